// The eigen analysis' stiffness must be the explicit solver's: K u equals the assembled internal
// force of one kernel pass over the whole (shared-node) mesh for a small displacement u. The
// comparison goes through the solver's own assembly, not the stiffness assembly, so it checks
// the probing, the sparsity pattern and the scatter together. Also: rigid-body motions give no
// force, the lumped mass is the solver's, and modes.h5 round-trips.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <type_traits>

#include "../verification/deck_builder.hpp"
#include "../verification/shell_builder.hpp"
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

// Shells on a curved surface (quads and a triangle; flat elements, or warped ones with the
// Belytschko-Wong-Chiang correction BWC 1) and beams of ELFORM 1 and 2: each element's
// probed matrix (without the drilling penalty) times the element's small displacement and
// rotation equals the kernel's forces and moments for that motion; the assembled K (with the
// drilling penalty) gives no force for a rigid translation and an infinitesimal rigid rotation
// (translations and nodal rotations together).
std::string shell_and_beam_deck(bool warped) {
  test::ShellPlate plate;
  plate.nx = 3;
  plate.ny = 2;
  plate.lx = 3.0;
  plate.ly = 2.0;
  plate.place = [warped](double u, double v) {
    return Eigen::Vector3d(u, v, 0.15 * std::sin(1.1 * u) + (warped ? 0.1 * u * v : 0.0));
  };
  std::string deck = "*KEYWORD\n" + plate.text();
  // Warped BLT elements need the Belytschko-Wong-Chiang correction to be free of force under
  // an infinitesimal rigid rotation (the kernel's property, docs/eigen.md).
  if (warped) deck += "*CONTROL_SHELL\n20,0,0,0,2,1\n";
  // A triangle on the edge v = 2 (nodes 9, 10 and a new node 101 above the plate).
  deck += "*NODE\n101,1.5,2.6,0.3\n*ELEMENT_SHELL\n100,1,9,10,101,101\n";
  deck += test::shell_part(1, 0.05, 7.8e-9, 2.1e5, 0.3, 3, 4, 0.1);
  // Beams from node 1 along a bent line, ELFORM 2 (part 2) and 1 (part 3).
  deck += "*NODE\n201,-0.5,-0.3,0.2\n202,-1.1,-0.2,0.5\n";
  deck += "*ELEMENT_BEAM_ORIENTATION\n201,2,1,201\n0,0,1\n202,3,201,202\n0,0,1\n";
  deck += "*PART\nresultant\n2,2,2\n*SECTION_BEAM\n2,2,0.8333\n1e-2,8e-6,1.2e-5,0\n";
  deck += "*MAT_ELASTIC\n2,7.8e-9,2.1e5,0.3\n";
  deck += "*PART\nintegrated\n3,3,3\n*SECTION_BEAM\n3,1,0.8333,2,0\n0.1,0.1,0.08,0.08\n";
  deck += "*MAT_ELASTIC\n3,7.8e-9,2.1e5,0.3\n*END\n";
  return deck;
}

template <class Block>
void expect_element_matrices_match_kernel(Block block, const solver::State& state,
                                          std::vector<double> matrices, int npe) {
  const std::size_t n = state.nodes.size(), r = state.rotations.size();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pick(-1.0, 1.0);
  std::vector<double> u(3 * n), theta(3 * r);
  for (double& value : u) value = 1e-8 * pick(rng);
  for (double& value : theta) value = 1e-8 * pick(rng);
  solver::NodalState nodes = state.nodes;
  for (std::size_t i = 0; i < n; ++i) {
    nodes.x.x[i] = nodes.x0.x[i] + u[3 * i];
    nodes.x.y[i] = nodes.x0.y[i] + u[3 * i + 1];
    nodes.x.z[i] = nodes.x0.z[i] + u[3 * i + 2];
    nodes.v.x[i] = u[3 * i];  // dt = 1: the step's displacement is u
    nodes.v.y[i] = u[3 * i + 1];
    nodes.v.z[i] = u[3 * i + 2];
  }
  std::array<std::vector<double>, 3> w;
  for (int d = 0; d < 3; ++d) {
    w[d].resize(r);
    for (std::size_t j = 0; j < r; ++j) w[d][j] = theta[3 * j + d];
  }
  const element::NodalView view{nodes.x.x.data(), nodes.x.y.data(), nodes.x.z.data(),
                                nodes.v.x.data(), nodes.v.y.data(), nodes.v.z.data()};
  const element::RotationalView spin{w[0].data(), w[1].data(), w[2].data()};
  if constexpr (std::is_same_v<Block, element::ShellBlock>) {
    element::compute_shell_forces(block, view, spin, 1.0);
  } else {
    element::compute_beam_forces(block, view, spin, 1.0);
  }
  const std::size_t nd = 6 * static_cast<std::size_t>(npe);
  for (std::size_t e = 0; e < block.size(); ++e) {
    std::vector<double> ue(nd, 0.0);
    for (int a = 0; a < npe; ++a) {
      const std::size_t slot = e * static_cast<std::size_t>(npe) + static_cast<std::size_t>(a);
      if (a > 0 && block.conn[slot] == block.conn[slot - 1]) continue;  // triangle's node 4
      for (int d = 0; d < 3; ++d) {
        ue[6 * a + d] = u[3 * static_cast<std::size_t>(block.conn[slot]) + d];
        if (block.rotation_conn[slot] >= 0)
          ue[6 * a + 3 + d] = theta[3 * static_cast<std::size_t>(block.rotation_conn[slot]) + d];
      }
    }
    // The kernel's forces with a repeated node's slot added to its first occurrence (the
    // probed matrix folds those rows the same way).
    std::vector<double> fe(block.force.begin() + static_cast<std::ptrdiff_t>(e * nd),
                           block.force.begin() + static_cast<std::ptrdiff_t>((e + 1) * nd));
    for (int a = 1; a < npe; ++a) {
      const std::size_t slot = e * static_cast<std::size_t>(npe) + static_cast<std::size_t>(a);
      if (block.conn[slot] != block.conn[slot - 1]) continue;
      for (int d = 0; d < 6; ++d) {
        fe[6 * (a - 1) + d] += fe[6 * a + d];
        fe[6 * a + d] = 0.0;
      }
    }
    double largest = 0.0, difference = 0.0;
    for (std::size_t row = 0; row < nd; ++row) {
      double ku = 0.0;
      for (std::size_t c = 0; c < nd; ++c) ku += matrices[(e * nd + row) * nd + c] * ue[c];
      const double f = fe[row];
      largest = std::max(largest, std::abs(f));
      difference = std::max(difference, std::abs(f - ku));
    }
    ASSERT_GT(largest, 0.0);
    EXPECT_LT(difference / largest, 1e-6) << "part " << block.part_id << " element " << e;
  }
}

class ShellModalStiffness : public ::testing::TestWithParam<bool> {};

TEST_P(ShellModalStiffness, MatricesMatchKernelForcesAndMomentsAndRigidMotionsAreFree) {
  const model::Model model = test::read(shell_and_beam_deck(GetParam()));
  const modal::StructuralMatrices sm = modal::assemble_structural_matrices(model, {});
  const solver::State& state = sm.state;
  ASSERT_EQ(state.shell_blocks.size(), 1u);
  ASSERT_EQ(state.beam_blocks.size(), 2u);
  const auto& shells = state.shell_blocks.front();
  expect_element_matrices_match_kernel(
      shells, state, modal::element_stiffness_matrices(shells, state.nodes, 0, shells.size(), 0.0),
      4);
  for (const auto& beams : state.beam_blocks) {
    expect_element_matrices_match_kernel(
        beams, state, modal::element_stiffness_matrices(beams, state.nodes, 0, beams.size()), 2);
  }
  EXPECT_LT(sm.element_asymmetry, 1e-6);

  // Rigid motions of the assembled K, rotations included: translation along y, and the rotation
  // theta about the axis through c: u_i = theta x (X_i - c), every nodal rotation theta.
  const std::size_t n = state.nodes.size(), r = state.rotations.size();
  ASSERT_EQ(static_cast<std::size_t>(sm.stiffness.rows()), 3 * n + 3 * r);
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.5, 0.8).normalized(), c(0.4, 0.2, -0.1);
  Eigen::VectorXd t = Eigen::VectorXd::Zero(sm.stiffness.rows()), q = t;
  for (std::size_t i = 0; i < n; ++i) {
    t[static_cast<Eigen::Index>(3 * i + 1)] = 1.0;
    const Eigen::Vector3d x(state.nodes.x0.x[i], state.nodes.x0.y[i], state.nodes.x0.z[i]);
    const Eigen::Vector3d v = axis.cross(x - c);
    for (int d = 0; d < 3; ++d) q[static_cast<Eigen::Index>(3 * i + d)] = v[d];
  }
  for (std::size_t j = 0; j < r; ++j)
    for (int d = 0; d < 3; ++d) q[static_cast<Eigen::Index>(3 * n + 3 * j + d)] = axis[d];
  const double scale = sm.stiffness.diagonal().cwiseAbs().maxCoeff();
  EXPECT_LT((sm.stiffness * t).cwiseAbs().maxCoeff() / scale, 1e-9);
  EXPECT_LT((sm.stiffness * q).cwiseAbs().maxCoeff() / scale, 1e-9);
  // The physical rotary inertia: rho t^3 / 12 per unit area on the shells' nodes.
  double shell_inertia = 0.0;
  for (std::size_t j = 0; j < r; ++j)
    shell_inertia += sm.mass[static_cast<Eigen::Index>(3 * n + 3 * j)];
  EXPECT_GT(shell_inertia, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Surface, ShellModalStiffness, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "Warped" : "Curved"; });

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
