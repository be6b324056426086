// Higher-order hexahedra through the whole pipeline (IMPETUS deck -> generator -> p-elevation ->
// solver state), against independent references:
//  - convergence: the fundamental axial frequency of a fixed-free bar with lateral motion held,
//    omega = (pi / 2L) sqrt((lambda + 2 mu) / rho) (1D wave equation, exact). Spatial error of
//    the frequency ~ h^(2p) with the GLL-lumped mass (order 2, 4, 6 for p = 1, 2, 3).
//  - stable time step: the step the solver takes from the element eigenvalue estimate is below
//    the stability limit measured by running the central-difference scheme, and not far below.
//  - geometry: a generated cylinder's volume converges to pi r^2 L (facets: O(h^2)); mantle
//    nodes smoothed onto the true surface make p = 3 exact to ~1e-7.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <set>

#include "element/kernels.hpp"
#include "io/keyword/reader.hpp"
#include "model/error.hpp"
#include "solver/boundary.hpp"
#include "solver/build_state.hpp"
#include "solver/simulation.hpp"

namespace rf {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRho = 7800.0, kYoung = 2.0e11, kNu = 0.3;

std::string bar_deck(int elements, int order) {
  return fmt::format(
      "*TIME\n1e-3\n*COMPONENT_BOX\n1, 1, {}, 1, 1\n0, 0, 0, 1, 0.1, 0.1\n"
      "*MAT_ELASTIC\n1, {}, {}, {}\n*PART\n1, 1\n*CHANGE_P-ORDER\nALL, 0, {}\n",
      elements, kRho, kYoung, kNu, order);
}

// Lowest eigenfrequency of K_xx phi = w^2 M phi for the bar (x-DOFs of nodes with x > 0; the
// y and z DOFs are held, as are all DOFs at x = 0). K columns by central differences of the
// solver's own internal forces (state, kernels, assembly) at amplitude eps.
double lowest_axial_frequency(int elements, int order, int elform) {
  model::Model m = io::read_deck_text(bar_deck(elements, order), "bar.k");
  solver::NodeIndex index(m);
  solver::State state = solver::build_state(m, index);
  auto& nodes = state.nodes;
  for (auto& block : state.hex_blocks) {
    if (order == 1) {
      block.elform = elform;
      block.hourglass.ihq = 6;  // physical (stiffness) hourglass control, no viscosity
      block.hourglass.qm = 0.1;
    }
  }
  std::vector<std::int32_t> dof;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes.x0.x[i] > 1e-12) dof.push_back(static_cast<std::int32_t>(i));
  }
  const int n = static_cast<int>(dof.size());
  Eigen::MatrixXd K(n, n);
  const double eps = 1e-9, dt = 1e-7;
  auto forces = [&](int column, double sign) {
    nodes.x = nodes.x0;
    std::fill(nodes.v.x.begin(), nodes.v.x.end(), 0.0);
    const element::NodalView reference{nodes.x.x.data(), nodes.x.y.data(), nodes.x.z.data(),
                                       nodes.v.x.data(), nodes.v.y.data(), nodes.v.z.data()};
    for (auto& block : state.hex_blocks) element::initialize_block(block, reference);
    nodes.x.x[static_cast<std::size_t>(dof[static_cast<std::size_t>(column)])] += sign * eps;
    nodes.v.x[static_cast<std::size_t>(dof[static_cast<std::size_t>(column)])] = sign * eps / dt;
    for (auto& block : state.hex_blocks) element::compute_block_forces(block, reference, dt);
    solver::assemble_internal_forces(state);
    std::vector<double> f(static_cast<std::size_t>(n));
    for (int r = 0; r < n; ++r) f[static_cast<std::size_t>(r)] = nodes.f_int.x[dof[r]];
    return f;
  };
  for (int c = 0; c < n; ++c) {
    const auto plus = forces(c, 1.0);
    const auto minus = forces(c, -1.0);
    for (int r = 0; r < n; ++r) K(r, c) = (plus[r] - minus[r]) / (2 * eps);
  }
  K = 0.5 * (K + K.transpose());
  Eigen::VectorXd s(n);
  for (int r = 0; r < n; ++r) s(r) = 1.0 / std::sqrt(nodes.mass[dof[r]]);
  const Eigen::MatrixXd A = s.asDiagonal() * K * s.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(A, Eigen::EigenvaluesOnly);
  return std::sqrt(solver.eigenvalues()(0));
}

double exact_axial_frequency() {
  const double lambda = kYoung * kNu / ((1 + kNu) * (1 - 2 * kNu));
  const double mu = kYoung / (2 * (1 + kNu));
  return kPi / 2.0 * std::sqrt((lambda + 2 * mu) / kRho);
}

TEST(HigherOrder, AxialFrequencyConvergesAtOrderTwoP) {
  const double exact = exact_axial_frequency();
  for (int p = 1; p <= 3; ++p) {
    std::vector<double> errors;
    const std::vector<int> counts = p == 3 ? std::vector<int>{1, 2} : std::vector<int>{2, 4, 8};
    for (int n : counts) {
      const double w = lowest_axial_frequency(n, p, 2);
      errors.push_back(std::abs(w - exact) / exact);
      std::printf("p=%d elements=%d nodes along=%d frequency error %.3e\n", p, n, p * n + 1,
                  errors.back());
    }
    for (std::size_t k = 1; k < errors.size(); ++k) {
      const double rate = std::log(errors[k - 1] / errors[k]) / std::log(2.0);
      std::printf("p=%d observed rate %.2f (expected %d)\n", p, rate, 2 * p);
      EXPECT_NEAR(rate, 2.0 * p, 0.35) << "p " << p;
    }
  }
}

TEST(HigherOrder, BeatsEightNodeHexahedraWithTheSameNodes) {
  const double exact = exact_axial_frequency();
  // 13 nodes along the bar: 4 cubic, 6 quadratic or 12 linear elements.
  const double e3 = std::abs(lowest_axial_frequency(4, 3, 2) - exact) / exact;
  const double e2 = std::abs(lowest_axial_frequency(6, 2, 2) - exact) / exact;
  const double e1 = std::abs(lowest_axial_frequency(12, 1, 1) - exact) / exact;
  std::printf("13 nodes along: ELFORM 1 %.3e, p=2 %.3e, p=3 %.3e\n", e1, e2, e3);
  EXPECT_LT(e2, e1 / 50.0);
  EXPECT_LT(e3, e2 / 10.0);
  // ELFORM 1 itself: the lumped linear chain, omega_h = (2c/h) sin(pi h / 4L) (exact for it).
  const double h = 1.0 / 12.0;
  const double chain = 2.0 / h * std::sin(kPi * h / 4.0) * exact / (kPi / 2.0);
  EXPECT_NEAR(std::abs(chain - exact) / exact, e1, 1e-3 * e1);
}

// Runs `cycles` steps at `factor` times the solver's stability estimate from small random
// velocities; true when the kinetic energy stays bounded.
bool stable_at(int order, double factor) {
  model::Model m = io::read_deck_text(
      fmt::format("*TIME\n1\n*COMPONENT_BOX\n1, 1, 2, 2, 2\n0, 0, 0, 1, 0.8, 1.3\n"
                  "*MAT_ELASTIC\n1, 7800, 2e11, 0.3\n*PART\n1, 1\n*CHANGE_P-ORDER\nALL, 0, {}\n",
                  order),
      "box.k");
  m.timestep.tssfac = factor;
  m.termination.endtim = 0.0;
  m.termination.endcyc = 3000;
  solver::Simulation sim(m, {});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1e-3, 1e-3);
  auto& v = sim.mutable_state().nodes.v;
  for (std::size_t i = 0; i < v.size(); ++i) {
    v.x[i] = u(rng);
    v.y[i] = u(rng);
    v.z[i] = u(rng);
  }
  double ke0 = 0.0;
  const auto& mass = sim.state().nodes.mass;
  for (std::size_t i = 0; i < v.size(); ++i)
    ke0 += 0.5 * mass[i] * (v.x[i] * v.x[i] + v.y[i] * v.y[i] + v.z[i] * v.z[i]);
  try {
    while (!sim.finished()) sim.cycle();
  } catch (const SolverError&) {
    return false;
  }
  double ke = 0.0;
  const auto& w = sim.state().nodes.v;
  for (std::size_t i = 0; i < w.size(); ++i)
    ke += 0.5 * mass[i] * (w.x[i] * w.x[i] + w.y[i] * w.y[i] + w.z[i] * w.z[i]);
  return std::isfinite(ke) && ke < 10.0 * ke0;
}

TEST(HigherOrder, TimeStepEstimateIsBelowTheMeasuredStabilityLimit) {
  for (int p = 2; p <= 3; ++p) {
    double lo = 0.5, hi = 4.0;  // stable at lo, unstable at hi (checked)
    ASSERT_TRUE(stable_at(p, lo));
    ASSERT_FALSE(stable_at(p, hi));
    for (int it = 0; it < 7; ++it) {
      const double mid = 0.5 * (lo + hi);
      (stable_at(p, mid) ? lo : hi) = mid;
    }
    std::printf("p=%d measured stability limit: %.3f x the estimated step\n", p, lo);
    EXPECT_GE(lo, 1.0) << "the estimate must not exceed the measured limit";
    EXPECT_LE(lo, 2.0) << "the estimate should not waste more than half the step";
  }
}

double cylinder_volume(int density, int order, int smoothing) {
  model::Model m = io::read_deck_text(
      fmt::format("*TIME\n1\n*COMPONENT_CYLINDER\n1, 1, 2, {}\n0, 0, 0, 0, 0, 2, 0.5\n"
                  "*MAT_ELASTIC\n1, 1, 2e11, 0.3\n*PART\n1, 1, , , {}\n*CHANGE_P-ORDER\n"
                  "ALL, 0, {}\n",
                  density, smoothing, order),
      "cyl.k");
  solver::NodeIndex index(m);
  const solver::State state = solver::build_state(m, index);
  double mass = 0.0;
  for (double v : state.nodes.mass) mass += v;
  return mass;  // rho = 1
}

TEST(HigherOrder, GeneratedCylinderVolumeConverges) {
  const double exact = kPi * 0.25 * 2.0;
  std::vector<double> errors;
  for (int n : {2, 4, 8}) {
    errors.push_back(std::abs(cylinder_volume(n, 1, 0) - exact) / exact);
    std::printf("cylinder N_2=%d linear facets: volume error %.3e\n", n, errors.back());
  }
  for (std::size_t k = 1; k < errors.size(); ++k) {
    EXPECT_NEAR(std::log(errors[k - 1] / errors[k]) / std::log(2.0), 2.0, 0.2);
  }
  // Smoothing (alpha_max 50 > facet angle) puts p = 2, 3 mantle nodes on the circle.
  const double e2 = std::abs(cylinder_volume(4, 2, 50) - exact) / exact;
  const double e3 = std::abs(cylinder_volume(4, 3, 50) - exact) / exact;
  const double e3_flat = std::abs(cylinder_volume(4, 3, 0) - exact) / exact;
  std::printf("cylinder N_2=4 smoothed: p=2 %.3e, p=3 %.3e; p=3 unsmoothed %.3e\n", e2, e3,
              e3_flat);
  EXPECT_LT(e2, 1e-3);
  EXPECT_LT(e3, 1e-5);
  EXPECT_NEAR(e3_flat, errors[1], 1e-12);  // no smoothing: the same facets as p = 1
}

}  // namespace
}  // namespace rf

namespace rf {
namespace {

TEST(HigherOrder, SeedMeshIsConformingAndTheSeedPointPicksTheEndFace) {
  const model::Model m =
      io::read_deck(std::string(RIGIDFLEX_EXAMPLES) + "/seed_rigid_body_update.k");
  solver::NodeIndex index(m);
  const solver::State state = solver::build_state(m, index);
  // A conforming cubic mesh of the two merged cylinders: 70 GLL layers (20 x 3 + 3 x 3 + 1)
  // of 457 nodes (57 corners, 2 per each of the 104 cross-section edges, 4 per each of the
  // 48 faces). Anything not shared across an element face or the merged interface adds nodes.
  EXPECT_EQ(state.nodes.size(), 70u * 457u);
  std::set<std::int32_t> deformable, rigid;
  for (const auto& block : state.hex_blocks) {
    (block.rigid ? rigid : deformable).insert(block.conn.begin(), block.conn.end());
  }
  std::vector<std::int32_t> shared;
  std::set_intersection(deformable.begin(), deformable.end(), rigid.begin(), rigid.end(),
                        std::back_inserter(shared));
  EXPECT_EQ(shared.size(), 457u);  // the whole interface face, every GLL node of it
  for (const auto i : shared) EXPECT_NEAR(state.nodes.x0.z[i], 1.0, 1e-12);
  // Geometry 1 (seed point at the origin): exactly the nodes of the z = 0 end face.
  std::vector<std::int32_t> end_face;
  for (std::size_t i = 0; i < state.nodes.size(); ++i) {
    if (std::abs(state.nodes.x0.z[i]) < 1e-12) end_face.push_back(static_cast<std::int32_t>(i));
  }
  EXPECT_EQ(solver::select_geometry(state, m.geometry_seeds.at(1)), end_face);
  // A seed on the mantle picks the whole deformable mantle (neighbouring facets turn by
  // 22.5 deg < 45) but neither end face (90 deg).
  model::GeometrySeed mantle = m.geometry_seeds.at(1);
  mantle.point = {0.05, 0.0, 0.5};
  mantle.pid = 1;
  const auto picked = solver::select_geometry(state, mantle);
  for (const auto i : picked) {
    EXPECT_NEAR(std::hypot(state.nodes.x0.x[i], state.nodes.x0.y[i]), 0.05, 1e-12);
  }
  EXPECT_EQ(picked.size(), 61u * 4u * 4u * 3u);  // 61 layers x 48 nodes around
}

}  // namespace
}  // namespace rf
