#include "parallel/communicator.hpp"

#include <cstdlib>

#ifdef RIGIDFLEX_HAVE_MPI
#include <mpi.h>
#endif

namespace rf::parallel {

namespace {

Communicator& mutable_world() {
  static Communicator communicator;
  return communicator;
}

#ifdef RIGIDFLEX_HAVE_MPI
MPI_Op g_agree_op = MPI_OP_NULL;
MPI_Datatype g_agree_type = MPI_DATATYPE_NULL;

// The reduction of StepAgreement: commutative and associative on every field (min with a
// lowest-ID tie break, min, max, max), so every rank gets the same answer in any order.
void agree_op(void* in, void* inout, int* len, MPI_Datatype*) {
  const auto* a = static_cast<const StepAgreement*>(in);
  auto* b = static_cast<StepAgreement*>(inout);
  for (int k = 0; k < *len; ++k) {
    if (a[k].dt < b[k].dt || (a[k].dt == b[k].dt && a[k].element < b[k].element)) {
      b[k].dt = a[k].dt;
      b[k].element = a[k].element;
    }
    if (a[k].failed_rank < b[k].failed_rank) b[k].failed_rank = a[k].failed_rank;
    if (a[k].interrupt > b[k].interrupt) b[k].interrupt = a[k].interrupt;
    if (a[k].output_due > b[k].output_due) b[k].output_due = a[k].output_due;
  }
}
#endif

}  // namespace

const Communicator& world() {
  return mutable_world();
}

bool built_with_mpi() {
#ifdef RIGIDFLEX_HAVE_MPI
  return true;
#else
  return false;
#endif
}

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"}) {
    const char* v = std::getenv(name);
    if (v != nullptr && *v != '\0') return true;
  }
  return false;
}

Session::Session(int* argc, char*** argv) {
#ifdef RIGIDFLEX_HAVE_MPI
  if (!launched_by_mpi()) return;
  // The solver calls MPI from the main thread only, outside OpenMP regions (FUNNELED).
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  started_ = true;
  Communicator& w = mutable_world();
  MPI_Comm_rank(MPI_COMM_WORLD, &w.rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &w.size_);
  MPI_Type_contiguous(static_cast<int>(sizeof(StepAgreement) / sizeof(double)), MPI_DOUBLE,
                      &g_agree_type);
  MPI_Type_commit(&g_agree_type);
  MPI_Op_create(&agree_op, 1, &g_agree_op);
#else
  (void)argc;
  (void)argv;
#endif
}

Session::~Session() {
#ifdef RIGIDFLEX_HAVE_MPI
  if (!started_) return;
  MPI_Op_free(&g_agree_op);
  MPI_Type_free(&g_agree_type);
  MPI_Finalize();
#endif
}

void Communicator::sum(double* values, std::size_t count) const {
#ifdef RIGIDFLEX_HAVE_MPI
  if (size_ < 2 || count == 0) return;
  // In pieces below 2^31 values (MPI counts are int).
  constexpr std::size_t kPiece = std::size_t{1} << 30;
  for (std::size_t first = 0; first < count; first += kPiece) {
    const std::size_t n = count - first < kPiece ? count - first : kPiece;
    MPI_Allreduce(MPI_IN_PLACE, values + first, static_cast<int>(n), MPI_DOUBLE, MPI_SUM,
                  MPI_COMM_WORLD);
  }
#else
  (void)values;
  (void)count;
#endif
}

double Communicator::min(double value) const {
#ifdef RIGIDFLEX_HAVE_MPI
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
#endif
  return value;
}

double Communicator::max(double value) const {
#ifdef RIGIDFLEX_HAVE_MPI
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
#endif
  return value;
}

void Communicator::agree(StepAgreement& a) const {
#ifdef RIGIDFLEX_HAVE_MPI
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, &a, 1, g_agree_type, g_agree_op, MPI_COMM_WORLD);
#else
  (void)a;
#endif
}

void Communicator::broadcast(std::vector<std::int32_t>& values, int root) const {
#ifdef RIGIDFLEX_HAVE_MPI
  if (size_ < 2) return;
  long long n = static_cast<long long>(values.size());
  MPI_Bcast(&n, 1, MPI_LONG_LONG, root, MPI_COMM_WORLD);
  values.resize(static_cast<std::size_t>(n));
  if (n > 0) MPI_Bcast(values.data(), static_cast<int>(n), MPI_INT32_T, root, MPI_COMM_WORLD);
#else
  (void)values;
  (void)root;
#endif
}

void Communicator::broadcast(std::string& text, int root) const {
#ifdef RIGIDFLEX_HAVE_MPI
  if (size_ < 2) return;
  long long n = static_cast<long long>(text.size());
  MPI_Bcast(&n, 1, MPI_LONG_LONG, root, MPI_COMM_WORLD);
  text.resize(static_cast<std::size_t>(n));
  if (n > 0) MPI_Bcast(text.data(), static_cast<int>(n), MPI_CHAR, root, MPI_COMM_WORLD);
#else
  (void)text;
  (void)root;
#endif
}

std::string Communicator::all_gather(const std::string& mine) const {
#ifdef RIGIDFLEX_HAVE_MPI
  if (size_ < 2) return mine;
  // The lengths first (one small collective, all that is sent when every rank has nothing),
  // then the bytes of the ranks that have some.
  std::vector<long long> lengths(static_cast<std::size_t>(size_));
  long long n = static_cast<long long>(mine.size());
  MPI_Allgather(&n, 1, MPI_LONG_LONG, lengths.data(), 1, MPI_LONG_LONG, MPI_COMM_WORLD);
  std::vector<int> counts(static_cast<std::size_t>(size_)),
      offsets(static_cast<std::size_t>(size_));
  long long total = 0;
  for (std::size_t r = 0; r < lengths.size(); ++r) {
    counts[r] = static_cast<int>(lengths[r]);
    offsets[r] = static_cast<int>(total);
    total += lengths[r];
  }
  std::string all(static_cast<std::size_t>(total), '\0');
  if (total > 0) {
    MPI_Allgatherv(mine.data(), static_cast<int>(n), MPI_CHAR, all.data(), counts.data(),
                   offsets.data(), MPI_CHAR, MPI_COMM_WORLD);
  }
  return all;
#else
  return mine;
#endif
}

void Communicator::abort(int status) const {
#ifdef RIGIDFLEX_HAVE_MPI
  if (size_ > 1) MPI_Abort(MPI_COMM_WORLD, status);
#endif
  std::exit(status);
}

}  // namespace rf::parallel
