#include "modal/shift_invert.hpp"

#include <fmt/format.h>

#include <Eigen/SparseCholesky>
#include <cstring>

#include "model/error.hpp"

#ifdef RIGIDFLEX_HAVE_CHOLMOD
#include <cholmod.h>
#endif

namespace rf::modal {

namespace {

class EigenFactor final : public SparseFactor {
 public:
  EigenFactor(const Eigen::SparseMatrix<double>& upper, bool positive_definite)
      : positive_definite_(positive_definite) {
    if (positive_definite) {
      llt_.compute(upper.selfadjointView<Eigen::Upper>());
      if (llt_.info() != Eigen::Success) {
        throw SolverError(
            "eigen analysis: K - sigma M is not positive definite (Eigen simplicial LL^T)");
      }
    } else {
      ldlt_.compute(upper.selfadjointView<Eigen::Upper>());
      if (ldlt_.info() != Eigen::Success) {
        throw SolverError("eigen analysis: K - sigma M is singular (Eigen simplicial LDL^T)");
      }
    }
  }
  void solve(const double* b, double* x) override {
    const Eigen::Map<const Eigen::VectorXd> rhs(b, size());
    Eigen::Map<Eigen::VectorXd> out(x, size());
    if (positive_definite_)
      out = llt_.solve(rhs);
    else
      out = ldlt_.solve(rhs);
  }
  std::string name() const override { return "eigen-simplicial"; }

 private:
  Eigen::Index size() const { return positive_definite_ ? llt_.rows() : ldlt_.rows(); }
  bool positive_definite_;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> llt_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt_;
};

#ifdef RIGIDFLEX_HAVE_CHOLMOD
class CholmodFactor final : public SparseFactor {
 public:
  CholmodFactor(const Eigen::SparseMatrix<double>& upper, bool positive_definite) {
    cholmod_start(&common_);
    common_.print = 0;
    common_.error_handler = nullptr;
    if (!positive_definite) {
      // Indefinite shifts: simplicial LDL^T (supernodal CHOLMOD is LL^T only).
      common_.supernodal = CHOLMOD_SIMPLICIAL;
      common_.final_ll = 0;
    }
    cholmod_sparse a{};
    a.nrow = static_cast<std::size_t>(upper.rows());
    a.ncol = static_cast<std::size_t>(upper.cols());
    a.nzmax = static_cast<std::size_t>(upper.nonZeros());
    a.p = const_cast<int*>(upper.outerIndexPtr());
    a.i = const_cast<int*>(upper.innerIndexPtr());
    a.x = const_cast<double*>(upper.valuePtr());
    a.stype = 1;  // upper triangle stored
    a.itype = CHOLMOD_INT;
    a.xtype = CHOLMOD_REAL;
    a.dtype = CHOLMOD_DOUBLE;
    a.sorted = 1;
    a.packed = 1;
    factor_ = cholmod_analyze(&a, &common_);
    if (!factor_) fail("symbolic analysis failed");
    cholmod_factorize(&a, factor_, &common_);
    if (common_.status == CHOLMOD_NOT_POSDEF) {
      fail(positive_definite
               ? fmt::format("K - sigma M is not positive definite (column {} of {}): a negative "
                             "stiffness or a shift above the lowest eigenvalue",
                             factor_->minor, a.ncol)
               : fmt::format("K - sigma M is singular at column {}: the CENTER shift is an "
                             "eigenvalue; move it slightly",
                             factor_->minor));
    }
    if (common_.status < CHOLMOD_OK) fail("numeric factorization failed");
    rhs_ = cholmod_allocate_dense(a.nrow, 1, a.nrow, CHOLMOD_REAL, &common_);
  }
  ~CholmodFactor() override {
    if (rhs_) cholmod_free_dense(&rhs_, &common_);
    if (x_) cholmod_free_dense(&x_, &common_);
    if (y_) cholmod_free_dense(&y_, &common_);
    if (e_) cholmod_free_dense(&e_, &common_);
    if (factor_) cholmod_free_factor(&factor_, &common_);
    cholmod_finish(&common_);
  }
  void solve(const double* b, double* x) override {
    const std::size_t n = rhs_->nrow;
    std::memcpy(rhs_->x, b, n * sizeof(double));
    if (!cholmod_solve2(CHOLMOD_A, factor_, rhs_, nullptr, &x_, nullptr, &y_, &e_, &common_)) {
      fail("solve failed");
    }
    std::memcpy(x, x_->x, n * sizeof(double));
  }
  std::string name() const override { return "cholmod"; }

 private:
  [[noreturn]] void fail(const std::string& what) {
    throw SolverError("eigen analysis (CHOLMOD): " + what);
  }
  cholmod_common common_{};
  cholmod_factor* factor_ = nullptr;
  cholmod_dense* rhs_ = nullptr;
  cholmod_dense* x_ = nullptr;
  cholmod_dense* y_ = nullptr;
  cholmod_dense* e_ = nullptr;
};
#endif

}  // namespace

std::unique_ptr<SparseFactor> factorize(const Eigen::SparseMatrix<double>& upper,
                                        bool positive_definite, bool prefer_cholmod) {
#ifdef RIGIDFLEX_HAVE_CHOLMOD
  if (prefer_cholmod) return std::make_unique<CholmodFactor>(upper, positive_definite);
#else
  (void)prefer_cholmod;
#endif
  return std::make_unique<EigenFactor>(upper, positive_definite);
}

}  // namespace rf::modal
