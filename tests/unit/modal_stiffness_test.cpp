// The eigen analysis' stiffness must be the explicit solver's: K u equals the assembled internal
// force of one kernel pass over the whole (shared-node) mesh for a small displacement u. The
// comparison goes through the solver's own assembly, not the stiffness assembly, so it checks
// the probing, the sparsity pattern and the scatter together. Also: rigid-body motions give no
// force, the lumped mass is the solver's, and modes.h5 round-trips.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "../verification/deck_builder.hpp"
#include "element/kernels.hpp"
#include "modal/mode_set.hpp"
#include "modal/stiffness_assembly.hpp"
#include "model/error.hpp"
#include "solver/build_state.hpp"

namespace rf {
namespace {

std::string distorted_block_deck(int elform, int ihq, const std::string& extra = "") {
  test::BoxMesh mesh;
  mesh.nx = 4;
  mesh.ny = 2;
  mesh.nz = 3;
  mesh.lx = 2.0;
  mesh.ly = 0.7;
  mesh.lz = 1.1;
  mesh.distort = [](double& x, double& y, double& z) {
    const double x0 = x, y0 = y, z0 = z;
    x = x0 + 0.07 * std::sin(3.1 * y0 + 1.3 * z0);
    y = y0 + 0.05 * std::cos(2.3 * x0 - 0.7 * z0);
    z = z0 + 0.06 * std::sin(1.7 * x0 + 2.9 * y0);
  };
  return "*KEYWORD\n" + mesh.keyword_text() +
         test::elastic_part(7.8e-9, 2.1e5, 0.3, elform, ihq, 1.0) + extra + "*END\n";
}

// f_int of one kernel pass at x0 + u (assembled by the explicit solver) versus K u.
void expect_stiffness_matches_kernel(int elform, int ihq, const std::string& extra = "") {
  const model::Model model = test::read(distorted_block_deck(elform, ihq, extra));
  modal::StructuralMatrices sm = modal::assemble_structural_matrices(model, {});
  solver::State& state = sm.state;
  const std::size_t n = state.nodes.size();
  ASSERT_EQ(static_cast<std::size_t>(sm.stiffness.rows()), 3 * n);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pick(-1.0, 1.0);
  Eigen::VectorXd u(static_cast<Eigen::Index>(3 * n));
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = 1e-8 * pick(rng);
  for (std::size_t i = 0; i < n; ++i) {
    state.nodes.x.x[i] = state.nodes.x0.x[i] + u[3 * i];
    state.nodes.x.y[i] = state.nodes.x0.y[i] + u[3 * i + 1];
    state.nodes.x.z[i] = state.nodes.x0.z[i] + u[3 * i + 2];
    state.nodes.v.x[i] = u[3 * i];  // dt = 1: the step's displacement is u
    state.nodes.v.y[i] = u[3 * i + 1];
    state.nodes.v.z[i] = u[3 * i + 2];
  }
  const element::NodalView view{state.nodes.x.x.data(), state.nodes.x.y.data(),
                                state.nodes.x.z.data(), state.nodes.v.x.data(),
                                state.nodes.v.y.data(), state.nodes.v.z.data()};
  for (auto& block : state.hex_blocks) element::compute_block_forces(block, view, 1.0);
  solver::assemble_internal_forces(state);
  const Eigen::VectorXd ku = sm.stiffness * u;
  double largest = 0.0, difference = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double f[3] = {state.nodes.f_int.x[i], state.nodes.f_int.y[i], state.nodes.f_int.z[i]};
    for (int d = 0; d < 3; ++d) {
      largest = std::max(largest, std::abs(f[d]));
      difference = std::max(difference, std::abs(f[d] - ku[static_cast<Eigen::Index>(3 * i + d)]));
    }
  }
  ASSERT_GT(largest, 0.0);
  // Second-order terms of the kernel are ~1e-8 relative for |u| ~ 1e-8.
  EXPECT_LT(difference / largest, 1e-6) << "ELFORM " << elform << " IHQ " << ihq;
  EXPECT_LT(sm.element_asymmetry, 1e-6);

  // Rigid translation and infinitesimal rotation about a point: no force.
  Eigen::VectorXd t = Eigen::VectorXd::Zero(u.size()), r = t;
  for (std::size_t i = 0; i < n; ++i) {
    t[3 * i + 1] = 1.0;
    const double y = state.nodes.x0.y[i] - 0.3, z = state.nodes.x0.z[i] - 0.2;
    r[3 * i + 1] = -z;  // rotation about x: (0, -z, y)
    r[3 * i + 2] = y;
  }
  const double scale = sm.stiffness.diagonal().cwiseAbs().maxCoeff();
  EXPECT_LT((sm.stiffness * t).cwiseAbs().maxCoeff() / scale, 1e-9);
  EXPECT_LT((sm.stiffness * r).cwiseAbs().maxCoeff() / scale, 1e-9);
}

TEST(ModalStiffness, Elform1Ihq6MatchesKernelForces) {
  expect_stiffness_matches_kernel(1, 6);
}
TEST(ModalStiffness, Elform1Ihq4MatchesKernelForces) {
  expect_stiffness_matches_kernel(1, 4);
}
TEST(ModalStiffness, Elform2MatchesKernelForces) {
  expect_stiffness_matches_kernel(2, 6);
}
TEST(ModalStiffness, SecondOrderLagrangeMatchesKernelForces) {
  expect_stiffness_matches_kernel(1, 6, "*CHANGE_P-ORDER\nALL,0,2\n");
}

TEST(ModalStiffness, MassIsTheExplicitLumpedMass) {
  const model::Model model = test::read(distorted_block_deck(1, 6));
  const modal::StructuralMatrices sm = modal::assemble_structural_matrices(model, {});
  const solver::State reference = solver::build_state(model, solver::NodeIndex(model));
  double total = 0.0, volume = 0.0;
  for (const auto& b : reference.hex_blocks)
    for (double v : b.volume0) volume += v;
  for (std::size_t i = 0; i < reference.nodes.size(); ++i) {
    EXPECT_EQ(sm.mass[static_cast<Eigen::Index>(3 * i)], reference.nodes.mass[i]);
    total += sm.mass[static_cast<Eigen::Index>(3 * i)];
  }
  EXPECT_NEAR(total, 7.8e-9 * volume, 1e-12 * total);  // rho V, independent of the lumping
}

TEST(ModalStiffness, ViscousHourglassIsReplacedWithAWarning) {
  const model::Model model = test::read(distorted_block_deck(1, 2));
  const modal::StructuralMatrices sm = modal::assemble_structural_matrices(model, {});
  ASSERT_FALSE(sm.warnings.empty());
  EXPECT_NE(sm.warnings.front().find("IHQ=2"), std::string::npos);
}

TEST(ModalStiffness, UnknownPartIsAnInputError) {
  const model::Model model = test::read(distorted_block_deck(1, 6));
  EXPECT_THROW(modal::assemble_structural_matrices(model, {42}), InputError);
}

TEST(ModeDatabase, RoundTrip) {
  modal::ModeSet modes;
  modes.node_ids = {10, 11};
  modes.node_parts = {1, 2};
  modes.coordinates = {0, 0, 0, 1, 0, 0};
  modes.mass = {0.5, 0.25};
  modes.eigenvalues = {0.0, 4.0};
  modes.generalized_mass = {1.0, 2.0};
  modes.residual = {1e-14, 2e-13};
  modes.rigid = {1, 0};
  modes.rigid_mode_count = 1;
  modes.shapes = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  const auto file = std::filesystem::temp_directory_path() / "rigidflex_modes_roundtrip.h5";
  modal::write_mode_database(file, modes);
  const modal::ModeSet back = modal::read_mode_database(file);
  EXPECT_EQ(back.node_ids, modes.node_ids);
  EXPECT_EQ(back.node_parts, modes.node_parts);
  EXPECT_EQ(back.coordinates, modes.coordinates);
  EXPECT_EQ(back.mass, modes.mass);
  EXPECT_EQ(back.eigenvalues, modes.eigenvalues);
  EXPECT_EQ(back.generalized_mass, modes.generalized_mass);
  EXPECT_EQ(back.residual, modes.residual);
  EXPECT_EQ(back.rigid, modes.rigid);
  EXPECT_EQ(back.shapes, modes.shapes);
  EXPECT_EQ(back.rigid_mode_count, 1);
  EXPECT_DOUBLE_EQ(back.shape(1)[0], 7.0);
  std::filesystem::remove(file);
  EXPECT_THROW(modal::read_mode_database(file), InputError);
}

}  // namespace
}  // namespace rf
