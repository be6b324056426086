// Eigen analysis of (usually free-free) parts: K phi = lambda M phi with the linear stiffness of
// the explicit solver's element kernels and its lumped mass (docs/eigen.md, design
// formulation.md section 5). Shift-invert Lanczos (Spectra) on the mass-scaled standard problem
// with a sparse Cholesky factorization (CHOLMOD, else Eigen's simplicial LL^T).
#pragma once

#include <string>
#include <vector>

#include "modal/mode_set.hpp"
#include "modal/stiffness_assembly.hpp"
#include "model/model.hpp"

namespace rf::modal {

enum class FactorizationBackend { Automatic, Cholmod, EigenSimplicial };

struct EigenRequest {
  // Number of modes wanted (NEIG). With remove_rigid_below (LFLAG 1) these are NEIG modes above
  // LFTEND, as in LS-DYNA's interval search.
  int mode_count = 20;
  // Parts whose elements form the analysed sub-model; empty: every part of the deck.
  std::vector<model::Id> parts;
  // Shift of the shift-invert operator, in eigenvalue units (omega^2). 0: automatic (a small
  // negative value below the rigid modes, see docs/eigen.md). Must be < 0 for a free-free part
  // because K - sigma M must be positive definite for the Cholesky factorization.
  double shift = 0.0;
  // CENTER (frequency, cycles per time unit): modes nearest this frequency. 0: the lowest.
  double center_frequency = 0.0;
  // LFLAG / LFTEND: drop modes with frequency <= LFTEND (the rigid modes of a free-free part).
  bool remove_rigid_below = false;
  double left_frequency = -1e29;
  // RFLAG / RHTEND: drop modes with frequency > RHTEND.
  bool limit_above = false;
  double right_frequency = 1e29;
  // Eigenvalues |lambda| below rigid_tolerance * lambda_scale count as rigid-body modes;
  // lambda_scale = max_i K_ii / M_ii (a lower bound of the largest eigenvalue).
  double rigid_tolerance = 1e-10;
  // Spectra convergence tolerance (relative, on the shift-inverted Ritz values).
  double tolerance = 1e-10;
  int max_iterations = 1000;
  FactorizationBackend backend = FactorizationBackend::Automatic;
  // Rotational inertia of shell and beam nodes (stiffness_assembly.hpp, docs/eigen.md).
  RotaryInertia rotary_inertia = RotaryInertia::kPhysical;
  // Drilling penalty of shells, k = drilling_factor G t A (docs/eigen.md): larger values move
  // the drilling modes (which the explicit shell does not have) above the band of interest.
  double drilling_factor = kDrillingFactor;
  // Where messages (convergence, warnings) go; null: nowhere.
  std::vector<std::string>* log = nullptr;
};

// Diagnostics of one analysis beyond the ModeSet (for the CLI, tests and eigout).
struct EigenReport {
  std::size_t dof_count = 0;       // 3 per node of the sub-model, 3 more per node with rotations
  std::size_t free_dof_count = 0;  // without SPC-fixed DOFs
  std::size_t stiffness_nonzeros = 0;
  double shift = 0.0;                     // sigma used
  double lambda_scale = 0.0;              // max K_ii / M_ii
  int rigid_found = 0;                    // near-zero modes among those computed
  int removed_by_lflag = 0;               // modes dropped below LFTEND
  int connected_groups = 1;               // node groups joined by elements
  int iterations = 0;                     // Spectra restarts
  int operator_applications = 0;          // factor solves
  std::string backend;                    // "cholmod" or "eigen-simplicial"
  double max_orthonormality_error = 0.0;  // max |Phi^T M Phi - I|
  double max_residual = 0.0;
  double seconds_assembly = 0.0, seconds_factorization = 0.0, seconds_lanczos = 0.0;
  std::vector<std::string> warnings;
};

// Runs the analysis. Throws rf::InputError for unusable input (no elements, massless DOFs,
// unknown parts) and rf::SolverError when the factorization or the iteration fails.
ModeSet compute_modes(const model::Model& model, const EigenRequest& request);
ModeSet compute_modes(const model::Model& model, const EigenRequest& request, EigenReport& report);

// The request a deck's *CONTROL_IMPLICIT_EIGENVALUE makes (NEIG, CENTER, LFLAG/LFTEND,
// RFLAG/RHTEND, SHFSCL); throws rf::InputError naming the card for unsupported values.
EigenRequest request_from_deck(const model::Model& model);

// True when the deck asks for an eigen analysis (IMFLAG 1 and *CONTROL_IMPLICIT_EIGENVALUE).
bool deck_requests_eigen_analysis(const model::Model& model);

}  // namespace rf::modal
