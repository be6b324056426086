#include "modal/eigen_analysis.hpp"

#include <fmt/format.h>

#include <Spectra/SymEigsShiftSolver.h>
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include "modal/shift_invert.hpp"
#include "modal/stiffness_assembly.hpp"
#include "model/error.hpp"
#include "model/error_context.hpp"

namespace rf::modal {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double frequency_of(double lambda) {
  // Negative round-off eigenvalues of rigid modes get a negative "frequency" so that they sort
  // and compare (LFTEND) in order.
  return std::copysign(std::sqrt(std::abs(lambda)), lambda) / (2.0 * M_PI);
}

// Union-find over the element connectivity: connected node groups.
struct NodeGroups {
  std::vector<std::int32_t> group;  // per node: 0..count-1, ordered by the lowest node index
  int count = 0;
};

NodeGroups connected_groups(const solver::State& state) {
  const std::size_t n = state.nodes.size();
  std::vector<std::int32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::int32_t i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
      parent[static_cast<std::size_t>(i)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
      i = parent[static_cast<std::size_t>(i)];
    }
    return i;
  };
  const auto join = [&](const std::vector<std::int32_t>& conn, std::size_t elements) {
    if (elements == 0) return;
    const std::size_t npe = conn.size() / elements;
    for (std::size_t e = 0; e < elements; ++e) {
      const std::int32_t* c = &conn[e * npe];
      for (std::size_t a = 1; a < npe; ++a) {
        const std::int32_t r0 = find(c[0]);
        const std::int32_t r = find(c[a]);
        if (r != r0) parent[static_cast<std::size_t>(std::max(r, r0))] = std::min(r, r0);
      }
    }
  };
  for (const auto& block : state.hex_blocks) join(block.conn, block.size());
  for (const auto& block : state.shell_blocks) join(block.conn, block.size());
  for (const auto& block : state.beam_blocks) join(block.conn, block.size());
  NodeGroups groups;
  groups.group.assign(n, -1);
  std::map<std::int32_t, std::int32_t> label;
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t r = find(static_cast<std::int32_t>(i));
    const auto [it, inserted] = label.emplace(r, static_cast<std::int32_t>(label.size()));
    groups.group[i] = it->second;
  }
  groups.count = static_cast<int>(label.size());
  return groups;
}

std::string describe_groups(const NodeGroups& groups, const StructuralMatrices& sm) {
  struct Info {
    std::size_t nodes = 0;
    model::Id lo = 0, hi = 0;
    std::set<model::Id> parts;
  };
  std::vector<Info> info(static_cast<std::size_t>(groups.count));
  for (std::size_t i = 0; i < groups.group.size(); ++i) {
    Info& g = info[static_cast<std::size_t>(groups.group[i])];
    const model::Id id = sm.state.nodes.id[i];
    g.lo = g.nodes == 0 ? id : std::min(g.lo, id);
    g.hi = g.nodes == 0 ? id : std::max(g.hi, id);
    ++g.nodes;
    g.parts.insert(sm.node_parts[i]);
  }
  std::string text;
  for (std::size_t k = 0; k < info.size(); ++k) {
    std::string parts;
    for (const model::Id p : info[k].parts) parts += (parts.empty() ? "" : ",") + std::to_string(p);
    text += fmt::format("{}group {}: {} nodes, node IDs {}..{}, part(s) {}", k == 0 ? "" : "; ",
                        k + 1, info[k].nodes, info[k].lo, info[k].hi, parts);
    if (k == 9 && info.size() > 10) {
      text += fmt::format("; ... {} more groups", info.size() - 10);
      break;
    }
  }
  return text;
}

// K restricted to the free DOFs (fixed rows and columns removed), upper triangle of K - sigma M
// built alongside.
Eigen::SparseMatrix<double> restrict_to_free(const Eigen::SparseMatrix<double>& K,
                                             const std::vector<std::int64_t>& free_index) {
  std::int64_t nf = 0;
  for (const auto i : free_index) nf += i >= 0 ? 1 : 0;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(K.nonZeros()));
  for (Eigen::Index c = 0; c < K.outerSize(); ++c) {
    const std::int64_t fc = free_index[static_cast<std::size_t>(c)];
    if (fc < 0) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, c); it; ++it) {
      const std::int64_t fr = free_index[static_cast<std::size_t>(it.row())];
      if (fr >= 0) entries.emplace_back(static_cast<int>(fr), static_cast<int>(fc), it.value());
    }
  }
  Eigen::SparseMatrix<double> out(nf, nf);
  out.setFromTriplets(entries.begin(), entries.end());
  return out;
}

}  // namespace

bool deck_requests_eigen_analysis(const model::Model& model) {
  return model.implicit.eigenvalue && model.implicit.neig > 0 &&
         (!model.implicit.general || model.implicit.imflag == 1);
}

EigenRequest request_from_deck(const model::Model& model) {
  const model::ImplicitControl& c = model.implicit;
  EigenRequest request;
  request.mode_count = c.neig;
  request.center_frequency = c.center;
  request.remove_rigid_below = c.lflag == 1;
  request.left_frequency = c.lftend;
  request.limit_above = c.rflag == 1;
  request.right_frequency = c.rhtend;
  if (c.shfscl > 0.0) request.shift = -std::pow(2.0 * M_PI * c.shfscl, 2);
  return request;
}

ModeSet compute_modes(const model::Model& model, const EigenRequest& request) {
  EigenReport report;
  return compute_modes(model, request, report);
}

ModeSet compute_modes(const model::Model& model, const EigenRequest& request, EigenReport& report) {
  auto log = [&](const std::string& line) {
    if (request.log) request.log->push_back(line);
  };
  if (request.mode_count < 1) {
    throw InputError(InputErrorContext{}, fmt::format("eigen analysis: the number of modes must "
                                                      "be positive (got {})",
                                                      request.mode_count));
  }
  auto t0 = Clock::now();
  StructuralMatrices sm = assemble_structural_matrices(model, request.parts, request.rotary_inertia,
                                                       request.drilling_factor);
  report.seconds_assembly = seconds_since(t0);
  for (auto& w : sm.warnings) report.warnings.push_back(w);
  const std::size_t ndof = static_cast<std::size_t>(sm.mass.size());
  const std::size_t n = sm.state.nodes.size();
  const std::size_t tdof = sm.translation_dofs();
  const std::size_t rotations = sm.rotation_count();
  report.dof_count = ndof;
  report.stiffness_nonzeros = static_cast<std::size_t>(sm.stiffness.nonZeros());
  log(fmt::format(
      "eigen: {} nodes ({} with rotations), {} DOFs, K assembled in {:.3f} s ({} nonzeros, element "
      "asymmetry {:.1e})",
      n, rotations, ndof, report.seconds_assembly, report.stiffness_nonzeros,
      sm.element_asymmetry));

  // Free DOFs and the mass check.
  std::vector<std::int64_t> free_index(ndof, -1);
  std::vector<std::size_t> free_dofs;
  for (std::size_t i = 0; i < ndof; ++i) {
    if (sm.fixed[i]) continue;
    if (!(sm.mass[static_cast<Eigen::Index>(i)] > 0.0)) {
      throw InputError(InputErrorContext{},
                       fmt::format("eigen analysis: node {} has no {} (a part with RO = 0?); "
                                   "massless DOFs are not supported",
                                   sm.node_of_dof(i), i < tdof ? "mass" : "rotational inertia"));
    }
    free_index[i] = static_cast<std::int64_t>(free_dofs.size());
    free_dofs.push_back(i);
  }
  const std::size_t nf = free_dofs.size();
  report.free_dof_count = nf;
  if (nf < 2) throw InputError(InputErrorContext{}, "eigen analysis: fewer than two free DOFs");
  const bool constrained = nf != ndof;
  const Eigen::SparseMatrix<double> Kf =
      constrained ? restrict_to_free(sm.stiffness, free_index) : sm.stiffness;
  Eigen::VectorXd mass(static_cast<Eigen::Index>(nf));
  for (std::size_t k = 0; k < nf; ++k)
    mass[static_cast<Eigen::Index>(k)] = sm.mass[static_cast<Eigen::Index>(free_dofs[k])];
  const Eigen::VectorXd sqrt_mass = mass.cwiseSqrt();

  // The scale of the spectrum from the translational DOFs: in a shell or beam model the
  // rotational ones (drilling penalty over a small rotary inertia) reach 1e2 to 1e3 times
  // higher, far from the bending that governs the low modes, and a shift and a near-zero limit
  // taken from them were 1e5 times too large for a thin panel (docs/eigen.md: 4 of 6 rigid
  // modes found, real 3 and 8 Hz modes flagged as mechanisms). Models without translations in
  // the free DOFs fall back on all of them.
  double lambda_scale = 0.0;
  for (int pass = 0; pass < 2 && !(lambda_scale > 0.0); ++pass) {
    for (Eigen::Index k = 0; k < Kf.outerSize(); ++k) {
      if (pass == 0 && free_dofs[static_cast<std::size_t>(k)] >= tdof) continue;
      lambda_scale = std::max(lambda_scale, Kf.coeff(k, k) / mass[k]);
    }
  }
  report.lambda_scale = lambda_scale;
  const double rigid_limit = request.rigid_tolerance * lambda_scale;

  // Shift: CENTER inside the spectrum (LDL^T), else a negative shift below the rigid modes.
  // 1e-6 lambda_scale keeps cond(K - sigma M) near 1e6 while the rigid modes (1/|sigma| in the
  // inverted spectrum) and the elastic ones stay well separated.
  const bool center = request.center_frequency > 0.0;
  double sigma = request.shift < 0.0 ? request.shift : -1e-6 * lambda_scale;
  if (center) sigma = std::pow(2.0 * M_PI * request.center_frequency, 2);
  report.shift = sigma;

  t0 = Clock::now();
  Eigen::SparseMatrix<double> shifted = Kf;
  for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(nf); ++k) {
    shifted.coeffRef(k, k) -= sigma * mass[k];
  }
  const Eigen::SparseMatrix<double> upper = shifted.triangularView<Eigen::Upper>();
  const bool cholmod = request.backend != FactorizationBackend::EigenSimplicial;
  std::unique_ptr<SparseFactor> factor = factorize(upper, !center, cholmod);
  report.backend = factor->name();
  report.seconds_factorization = seconds_since(t0);
  log(fmt::format("eigen: shift sigma = {:.6g}, {} factorization in {:.3f} s", sigma,
                  report.backend, report.seconds_factorization));

  // Lanczos; with LFLAG the modes below LFTEND do not count, so ask for more until NEIG remain.
  t0 = Clock::now();
  std::vector<double> lambdas;
  Eigen::MatrixXd psi;
  int extra = request.remove_rigid_below ? 6 : 0;
  for (int attempt = 0;; ++attempt) {
    const Eigen::Index nev =
        std::min<Eigen::Index>(request.mode_count + extra, static_cast<Eigen::Index>(nf) - 1);
    const Eigen::Index ncv = std::min<Eigen::Index>(std::max<Eigen::Index>(2 * nev + 1, nev + 20),
                                                    static_cast<Eigen::Index>(nf));
    ShiftInvertOperator op(sqrt_mass, *factor);
    if (ncv <= nev) {
      throw InputError(InputErrorContext{},
                       fmt::format("eigen analysis: {} modes asked for a model with {} free DOFs",
                                   request.mode_count + extra, nf));
    }
    Spectra::SymEigsShiftSolver<ShiftInvertOperator> solver(op, nev, ncv, sigma);
    solver.init();
    const Eigen::Index converged =
        solver.compute(Spectra::SortRule::LargestMagn, request.max_iterations, request.tolerance,
                       Spectra::SortRule::SmallestAlge);
    report.iterations += static_cast<int>(solver.num_iterations());
    report.operator_applications += op.applications();
    if (solver.info() != Spectra::CompInfo::Successful) {
      throw SolverError(fmt::format(
          "eigen analysis: Lanczos did not converge ({} of {} modes after {} restarts, {} "
          "solves)",
          converged, nev, solver.num_iterations(), op.applications()));
    }
    log(fmt::format("eigen: Lanczos converged, {} modes, {} restarts, {} solves", nev,
                    solver.num_iterations(), op.applications()));
    const Eigen::VectorXd values = solver.eigenvalues();
    psi = solver.eigenvectors();
    lambdas.assign(values.data(), values.data() + values.size());
    if (!request.remove_rigid_below) break;
    int below = 0;
    for (const double l : lambdas) below += frequency_of(l) <= request.left_frequency ? 1 : 0;
    if (nev - below >= request.mode_count || nev >= static_cast<Eigen::Index>(nf) - 1 ||
        attempt == 3) {
      break;
    }
    extra = below + 6;
  }
  report.seconds_lanczos = seconds_since(t0);

  // Order: ascending eigenvalue, or distance from CENTER.
  std::vector<std::size_t> order(lambdas.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (center) return std::abs(lambdas[a] - sigma) < std::abs(lambdas[b] - sigma);
    return lambdas[a] < lambdas[b];
  });

  // Modes phi = M^-1/2 psi; Rayleigh quotients recomputed from K, residuals.
  struct Candidate {
    double lambda;
    Eigen::VectorXd phi;  // free DOFs
    double residual;
    bool rigid;
  };
  std::vector<Candidate> candidates;
  for (const std::size_t k : order) {
    Candidate c;
    c.phi = psi.col(static_cast<Eigen::Index>(k)).cwiseQuotient(sqrt_mass);
    const Eigen::VectorXd kphi = Kf * c.phi;
    const Eigen::VectorXd mphi = mass.cwiseProduct(c.phi);
    c.lambda = c.phi.dot(kphi) / c.phi.dot(mphi);
    c.rigid = std::abs(c.lambda) < rigid_limit;
    const double knorm = kphi.norm();
    const double denominator = c.rigid ? lambda_scale * mphi.norm() : knorm;
    c.residual = (kphi - c.lambda * mphi).norm() / denominator;
    candidates.push_back(std::move(c));
  }
  int rigid_found = 0;
  for (const auto& c : candidates) rigid_found += c.rigid ? 1 : 0;
  report.rigid_found = rigid_found;

  // Model-quality check (the seed's advice): more than six near-zero modes of an unconstrained
  // model, or any constrained model with rigid modes, means disconnected pieces or mechanisms.
  const NodeGroups groups = connected_groups(sm.state);
  report.connected_groups = groups.count;
  if (groups.count > 1) {
    report.warnings.push_back(fmt::format(
        "the analysed model is not one connected body: {} node groups are not joined by "
        "elements ({}); expect {} rigid-body modes for it free-free",
        groups.count, describe_groups(groups, sm), 6 * groups.count));
  }
  if ((!constrained && rigid_found > 6) || (constrained && rigid_found > 0)) {
    report.warnings.push_back(fmt::format(
        "{} near-zero modes found (|lambda| < {:.3g}){}: {}", rigid_found, rigid_limit,
        constrained ? " in a constrained model" : ", more than the six rigid-body modes",
        groups.count > 1 ? "badly connected model, node groups: " + describe_groups(groups, sm)
                         : std::string("the model is connected, so these are mechanisms "
                                       "(hourglass or hinge modes)")));
  }

  // LFLAG / RFLAG selection, then NEIG modes.
  ModeSet modes;
  modes.rigid_mode_count = rigid_found;
  std::vector<const Candidate*> kept;
  for (const auto& c : candidates) {
    const double f = frequency_of(c.lambda);
    if (request.remove_rigid_below && f <= request.left_frequency) {
      ++report.removed_by_lflag;
      continue;
    }
    if (request.limit_above && f > request.right_frequency) continue;
    if (static_cast<int>(kept.size()) < request.mode_count) kept.push_back(&c);
  }
  if (center) {
    std::stable_sort(kept.begin(), kept.end(),
                     [](const Candidate* a, const Candidate* b) { return a->lambda < b->lambda; });
  }
  if (request.remove_rigid_below && static_cast<int>(kept.size()) < request.mode_count) {
    report.warnings.push_back(
        fmt::format("only {} modes above LFTEND = {:g} were found of {} "
                    "asked for",
                    kept.size(), request.left_frequency, request.mode_count));
  }

  modes.node_ids = sm.state.nodes.id;
  modes.node_parts = sm.node_parts;
  modes.coordinates.resize(3 * n);
  modes.mass = sm.state.nodes.mass;
  for (std::size_t i = 0; i < n; ++i) {
    modes.coordinates[3 * i] = sm.state.nodes.x0.x[i];
    modes.coordinates[3 * i + 1] = sm.state.nodes.x0.y[i];
    modes.coordinates[3 * i + 2] = sm.state.nodes.x0.z[i];
  }
  modes.rotation_nodes.assign(sm.state.rotations.node.begin(), sm.state.rotations.node.end());
  modes.rotational_inertia.resize(rotations);
  for (std::size_t r = 0; r < rotations; ++r)
    modes.rotational_inertia[r] = sm.mass[static_cast<Eigen::Index>(tdof + 3 * r)];
  modes.shapes.assign(kept.size() * tdof, 0.0);
  modes.rotation_shapes.assign(kept.size() * 3 * rotations, 0.0);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const Candidate& c = *kept[k];
    double* shape = modes.shapes.data() + k * tdof;
    double* rotation_shape = modes.rotation_shapes.data() + k * 3 * rotations;
    double largest = 0.0;
    for (std::size_t j = 0; j < nf; ++j) {
      const double value = c.phi[static_cast<Eigen::Index>(j)];
      if (free_dofs[j] < tdof) {
        shape[free_dofs[j]] = value;
        largest = std::max(largest, std::abs(value));
      } else {
        rotation_shape[free_dofs[j] - tdof] = value;
      }
    }
    if (!(largest > 0.0)) largest = c.phi.cwiseAbs().maxCoeff();  // a pure rotation mode
    modes.eigenvalues.push_back(c.lambda);
    // Generalized mass of the mode scaled to a largest translation of 1 (its form before mass
    // normalisation, as eigout tables give it).
    modes.generalized_mass.push_back(1.0 / (largest * largest));
    modes.residual.push_back(c.residual);
    // With LFLAG the user's LFTEND decides what is rigid: every kept mode is elastic (the
    // file holds elastic modes only, docs/eigen.md), even one whose |lambda| is below the
    // rigid limit, as the lowest bending modes of a large thin shell are (1e-10 of a
    // lambda_scale set by its drilling and rotary stiffness). *PART_MODES skips modes flagged
    // rigid, so such a mode would silently be lost to the flexible body.
    modes.rigid.push_back(c.rigid && !request.remove_rigid_below ? 1 : 0);
    report.max_residual = std::max(report.max_residual, c.residual);
  }
  // Mass orthonormality of the kept modes: max |Phi^T M Phi - I| (one dense product).
  double ortho = 0.0;
  if (!kept.empty()) {
    Eigen::MatrixXd phi(static_cast<Eigen::Index>(nf), static_cast<Eigen::Index>(kept.size()));
    for (std::size_t k = 0; k < kept.size(); ++k)
      phi.col(static_cast<Eigen::Index>(k)) = kept[k]->phi;
    const Eigen::MatrixXd gram = phi.transpose() * (mass.asDiagonal() * phi);
    ortho = (gram - Eigen::MatrixXd::Identity(gram.rows(), gram.cols())).cwiseAbs().maxCoeff();
  }
  report.max_orthonormality_error = ortho;
  log(
      fmt::format("eigen: {} modes kept ({} rigid found, {} removed by LFLAG), max residual "
                  "{:.2e}, max |Phi^T M Phi - I| = {:.2e}",
                  kept.size(), rigid_found, report.removed_by_lflag, report.max_residual, ortho));
  for (const auto& w : report.warnings) log("warning: " + w);
  return modes;
}

}  // namespace rf::modal
