// Sparse factorization of K - sigma M and the shift-invert operator Spectra iterates with.
//
// M is the diagonal lumped mass, so the generalized problem K phi = lambda M phi is reduced to
// the standard symmetric one A psi = lambda psi with A = M^-1/2 K M^-1/2 and phi = M^-1/2 psi
// at the cost of two diagonal scalings; Lanczos vectors orthonormal in the Euclidean sense are
// then M-orthonormal modes, with no B-inner products in the iteration. The operator is
// (A - sigma I)^-1 = M^1/2 (K - sigma M)^-1 M^1/2: one sparse triangular solve pair per step.
#pragma once

#include <Eigen/Sparse>
#include <memory>
#include <string>

namespace rf::modal {

// A factorization of the symmetric matrix S = K - sigma M (upper triangle given). Cholesky LL^T
// when S is positive definite (sigma below every eigenvalue), LDL^T without pivoting otherwise
// (CENTER shifts inside the spectrum).
class SparseFactor {
 public:
  virtual ~SparseFactor() = default;
  virtual void solve(const double* b, double* x) = 0;
  virtual std::string name() const = 0;
};

// Throws rf::SolverError when the matrix is not positive definite (LL^T) or singular (LDL^T).
// `prefer_cholmod` false (or no CHOLMOD in the build) uses Eigen's simplicial factorization.
std::unique_ptr<SparseFactor> factorize(const Eigen::SparseMatrix<double>& upper,
                                        bool positive_definite, bool prefer_cholmod);

// The operator for Spectra::SymEigsShiftSolver (its OpType concept).
class ShiftInvertOperator {
 public:
  using Scalar = double;
  // `sqrt_mass` = M^1/2 per DOF; `factor` of K - sigma M, sigma = `shift`.
  ShiftInvertOperator(const Eigen::VectorXd& sqrt_mass, SparseFactor& factor)
      : sqrt_mass_(sqrt_mass), factor_(factor), work_(sqrt_mass.size()), out_(sqrt_mass.size()) {}
  Eigen::Index rows() const { return sqrt_mass_.size(); }
  Eigen::Index cols() const { return sqrt_mass_.size(); }
  // The factor is built for one shift before the solver starts; Spectra passes the same value.
  void set_shift(double) {}
  void perform_op(const double* x_in, double* y_out) const {
    for (Eigen::Index i = 0; i < sqrt_mass_.size(); ++i) work_[i] = sqrt_mass_[i] * x_in[i];
    factor_.solve(work_.data(), out_.data());
    for (Eigen::Index i = 0; i < sqrt_mass_.size(); ++i) y_out[i] = sqrt_mass_[i] * out_[i];
    ++applications_;
  }
  int applications() const { return applications_; }

 private:
  const Eigen::VectorXd& sqrt_mass_;
  SparseFactor& factor_;
  mutable Eigen::VectorXd work_, out_;
  mutable int applications_ = 0;
};

}  // namespace rf::modal
