// The processes of a run and the few collective operations the solver needs (docs/parallel.md).
// Without MPI in the build, or when the program was not started by an MPI launcher (mpirun), there
// is one process and no MPI call is made: a plain `rigidflex run` is the one-process program.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rf::parallel {

// What the ranks agree on once per cycle, in one reduction (Communicator::agree): the global
// element step with its controlling element, the lowest rank whose element failed, whether an
// interrupt arrived anywhere, whether rank 0 writes element output next.
struct StepAgreement {
  double dt = 1e300;         // min over ranks
  double element = 0.0;      // user ID of the element giving dt (lowest ID among ties)
  double failed_rank = 1e9;  // min over the ranks that report a failure (1e9: none)
  double interrupt = 0.0;    // max: the signal number, 0 none
  double output_due = 0.0;   // max: 1 when rank 0 writes element output at the next output pass
};

class Communicator {
 public:
  int rank() const { return rank_; }
  int size() const { return size_; }
  // More than one rank: the solver partitions elements and reduces across ranks.
  bool distributed() const { return size_ > 1; }

  // In-place sums over the ranks (MPI_Allreduce); every rank receives the same values.
  void sum(double* values, std::size_t count) const;
  // In-place min and max over ranks.
  double min(double value) const;
  double max(double value) const;
  void agree(StepAgreement& a) const;
  // From `root` to every rank.
  void broadcast(std::vector<std::int32_t>& values, int root) const;
  void broadcast(std::string& text, int root) const;
  // Every rank's bytes, concatenated in rank order, on every rank (MPI_Allgather of the lengths,
  // then MPI_Allgatherv when any rank has bytes). One process: `mine`.
  std::string all_gather(const std::string& mine) const;
  // Ends every rank of the run (MPI_Abort) with this exit status; one process: std::exit.
  [[noreturn]] void abort(int status) const;

 private:
  friend class Session;
  int rank_ = 0;
  int size_ = 1;
};

// The run's processes (one process until a Session started MPI).
const Communicator& world();

// Whether this build has MPI and METIS (CMake option RIGIDFLEX_MPI).
bool built_with_mpi();
// Whether an MPI launcher started this process (Open MPI, MPICH/Hydra and PMIx set these).
bool launched_by_mpi();

// MPI_Init / MPI_Finalize around main, only when launched by an MPI launcher.
class Session {
 public:
  Session(int* argc, char*** argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

 private:
  bool started_ = false;
};

}  // namespace rf::parallel
