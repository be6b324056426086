// The 10-node quadratic tetrahedron (*SECTION_SOLID ELFORM 16, element/tet10_block.cpp) against
// references that do not come from our code:
//  - the patch test: a homogeneous deformation of an irregular mesh, driven on the boundary
//    only, must leave every interior node (corners and mid-side nodes) on the homogeneous motion
//    and give every integration point the stress of the hypoelastic law in closed form;
//  - frequencies (`rigidflex eigen`'s modal::compute_modes): the axial mode of a free-free bar
//    with nu = 0 against c / (2 L), with the convergence order under refinement; the first
//    bending mode against Euler-Bernoulli with Timoshenko's correction, where the constant-strain
//    tetrahedron (ELFORM 10) on the same mesh locks in shear (too stiff) and ELFORM 16 does not;
//  - conservation: a free body with an internal impact keeps its momentum and angular momentum
//    to round-off and glstat's energy balance closes, for every material ELFORM 16 runs;
//  - a *MAT_RIGID ELFORM 16 part: mass exact, inertia against the box's m (b^2 + c^2) / 12;
//  - *ELEMENT_SOLID_TET4TOTET10 gives the same model as the 10-node cards;
//  - the same results for 1 and 3 threads, bit for bit;
//  - input errors naming the file, line, element and field.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "deck_builder.hpp"
#include "element/tet10_block.hpp"
#include "modal/eigen_analysis.hpp"
#include "model/error.hpp"
#include "tet_mesh.hpp"

namespace rf::test {
namespace {

std::string elastic_card(double rho, double young, double nu) {
  return fmt::format("*MAT_ELASTIC\n1,{:.17g},{:.17g},{:.17g}\n", rho, young, nu);
}

// --- Patch test -----------------------------------------------------------------------------

// v = G X with G diagonal: the stretch is I + G t, the log strain ln(1 + g_i t), which the
// hypoelastic law integrates exactly.
constexpr double kRate[3] = {0.25, -0.1, 0.0625};

struct PatchResult {
  double stress_error = 0.0;    // max over points and components, / max |sigma|
  double position_error = 0.0;  // interior nodes, / max |G X| t
  int interior_midside = 0;     // interior mid-side nodes checked
};

PatchResult run_patch(double young, double nu, double end_time) {
  const TetGrid grid = tet_box(3, 3, 3, 1.0, 1.0, 1.0, 0.15);
  std::string deck = "*KEYWORD\n" + grid.text10();
  deck += "*PART\npatch\n1,1,1\n*SECTION_SOLID\n1,16\n" + elastic_card(7850.0, young, nu);
  deck += "*DEFINE_CURVE\n1\n0.0,1.0\n100.0,1.0\n";
  // Boundary nodes: those on the faces of the unit box (a mid-side node of an edge through the
  // interior is interior: its position is).
  const model::Model mesh = read(deck + "*END\n");
  std::string velocities = "*INITIAL_VELOCITY_NODE\n";
  std::string prescribed = "*BOUNDARY_PRESCRIBED_MOTION_NODE\n";
  auto on_face = [](const std::array<double, 3>& x) {
    for (const double c : x)
      if (std::abs(c) < 1e-12 || std::abs(c - 1.0) < 1e-12) return true;
    return false;
  };
  for (const auto& node : mesh.nodes) {
    velocities += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", node.id, kRate[0] * node.x[0],
                              kRate[1] * node.x[1], kRate[2] * node.x[2]);
    if (!on_face(node.x)) continue;
    for (int d = 0; d < 3; ++d)
      prescribed += fmt::format("{},{},0,1,{:.17g}\n", node.id, d + 1, kRate[d] * node.x[d]);
  }
  deck += velocities + prescribed;
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},0\n*END\n", end_time);
  solver::Simulation sim(read(deck), {});
  while (!sim.finished()) sim.cycle();
  const solver::State& s = sim.state();
  const double t = s.time;
  PatchResult r;
  const double lambda = young * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double mu = young / (2.0 * (1.0 + nu));
  double eps[3], trace = 0.0;
  for (int d = 0; d < 3; ++d) trace += eps[d] = std::log1p(kRate[d] * t);
  double exact[6] = {0, 0, 0, 0, 0, 0};
  for (int d = 0; d < 3; ++d) exact[d] = lambda * trace + 2.0 * mu * eps[d];
  const double scale = std::max({std::abs(exact[0]), std::abs(exact[1]), std::abs(exact[2])});
  const auto& block = s.hex_blocks.front();
  EXPECT_EQ(block.stress.size(), 6u * 4u * block.size());
  for (std::size_t k = 0; k < block.stress.size(); ++k)
    r.stress_error = std::max(r.stress_error, std::abs(block.stress[k] - exact[k % 6]) / scale);
  const auto& n = s.nodes;
  double motion = 0.0, worst = 0.0;
  const auto first_midside = static_cast<model::Id>(grid.first_node + grid.node_count());
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::array<double, 3> x0{n.x0.x[i], n.x0.y[i], n.x0.z[i]};
    const double x[3] = {n.x.x[i], n.x.y[i], n.x.z[i]};
    if (!on_face(x0) && n.id[i] >= first_midside) ++r.interior_midside;
    for (int d = 0; d < 3; ++d) {
      motion = std::max(motion, std::abs(kRate[d] * x0[d] * t));
      worst = std::max(worst, std::abs(x[d] - x0[d] * (1.0 + kRate[d] * t)));
    }
  }
  r.position_error = worst / motion;
  return r;
}

TEST(Tet10Patch, HomogeneousDeformationOfAnIrregularMeshGivesTheExactStress) {
  for (const double nu : {0.3, 0.49}) {
    const PatchResult r = run_patch(2.1e11, nu, 4e-3);
    std::printf(
        "[measured] ELFORM 16 patch, nu %.2f: stress error %.3e of |sigma| (4 points per "
        "element), interior positions %.3e of the motion (%d interior mid-side nodes)\n",
        nu, r.stress_error, r.position_error, r.interior_midside);
    EXPECT_GT(r.interior_midside, 50);
    EXPECT_LT(r.stress_error, 1e-7);
    EXPECT_LT(r.position_error, 1e-9);
  }
}

// --- Frequencies ----------------------------------------------------------------------------

constexpr double kE = 2.1e11, kRho = 7850.0;

struct Modes {
  std::vector<double> frequency;    // elastic modes, Hz
  std::vector<double> axial_share;  // sum m u_x^2 / sum m |u|^2 of each
  int rigid = 0;
};

// Free-free square bar along x, length l, side h, nx x nyz x nyz cells of 6 tetrahedra.
Modes bar_modes(double l, double h, int nx, int nyz, int elform, double nu, int count) {
  TetGrid grid = tet_box(nx, nyz, nyz, l, h, h);
  std::string deck = "*KEYWORD\n" + (elform == 16 ? grid.text10() : grid.text());
  deck +=
      fmt::format("*PART\nbar\n1,1,1\n*SECTION_SOLID\n1,{}\n", elform) + elastic_card(kRho, kE, nu);
  deck += "*CONTROL_IMPLICIT_GENERAL\n1,0.001\n";
  deck += fmt::format("*CONTROL_IMPLICIT_EIGENVALUE\n{},0.0\n*END\n", count);
  const model::Model model = read(deck);
  modal::EigenReport report;
  const modal::ModeSet modes = modal::compute_modes(model, modal::request_from_deck(model), report);
  Modes out;
  for (std::size_t k = 0; k < modes.mode_count(); ++k) {
    if (modes.rigid[k]) {
      ++out.rigid;
      continue;
    }
    out.frequency.push_back(std::sqrt(modes.eigenvalues[k]) / (2.0 * std::numbers::pi));
    const double* u = modes.shape(k);
    double ux = 0.0, all = 0.0;
    for (std::size_t i = 0; i < modes.node_count(); ++i) {
      ux += modes.mass[i] * u[3 * i] * u[3 * i];
      for (int d = 0; d < 3; ++d) all += modes.mass[i] * u[3 * i + d] * u[3 * i + d];
    }
    out.axial_share.push_back(ux / all);
  }
  return out;
}

TEST(Tet10Frequency, AxialBarModeConvergesToTheOneDimensionalFrequency) {
  // nu = 0: the axial mode of a prism is exactly the 1-D one, f = c / (2 L), c = sqrt(E / rho).
  // Cubic cells of 1/4, 1/8, 1/16 of the length.
  const double l = 1.0, h = 0.25;
  const double exact = std::sqrt(kE / kRho) / (2.0 * l);
  double previous = 0.0;
  for (const int nx : {4, 8, 16}) {
    const Modes m = bar_modes(l, h, nx, nx / 4, 16, 0.0, 30);
    EXPECT_EQ(m.rigid, 6);
    double f = 0.0;
    for (std::size_t k = 0; k < m.frequency.size(); ++k)
      if (m.axial_share[k] > 0.85) {  // the first mode mostly along the bar
        f = m.frequency[k];
        break;
      }
    ASSERT_GT(f, 0.0) << "no axial mode among the first modes, nx " << nx;
    const double error = std::abs(f / exact - 1.0);
    const double order = previous > 0.0 ? std::log2(previous / error) : 0.0;
    std::printf(
        "[measured] ELFORM 16 free-free bar, %d cells along: axial frequency %.6g Hz, exact "
        "%.6g Hz, error %.3e, order %.2f\n",
        nx, f, exact, error, order);
    // The lumped mass makes the frequency error O(h^2) (the consistent mass of the quadratic
    // element would give O(h^4)); the coarse meshes are pre-asymptotic: 1.29, 1.73 measured.
    if (nx == 8) EXPECT_GT(order, 1.1);
    if (nx == 16) EXPECT_GT(order, 1.6);
    previous = error;
  }
  EXPECT_LT(previous, 1e-3);
}

// Bending frequency of a slender square beam: Euler-Bernoulli, first free-free root, with
// Timoshenko's first-order correction for shear and rotary inertia (eigen_test.cpp has the
// same reference: Han, Benaroya & Wei, J. Sound Vib. 225 (1999) 935; Cowper's kappa).
double bending_frequency(double l, double h, double nu) {
  const double beta_l = 4.730040745;
  const double area = h * h, inertia = h * h * h * h / 12.0;
  const double omega = beta_l * beta_l * std::sqrt(kE * inertia / (kRho * area)) / (l * l);
  const double r2 = inertia / area;
  const double kappa = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);
  const double g = kE / (2.0 * (1.0 + nu));
  const double beta2 = (beta_l / l) * (beta_l / l);
  return omega * std::sqrt(1.0 - beta2 * r2 * (1.0 + kE / (kappa * g))) / (2.0 * std::numbers::pi);
}

TEST(Tet10Frequency, BendingDoesNotLockWhereTheConstantStrainTetrahedronDoes) {
  const double l = 2.0, h = 0.1, nu = 0.3;
  const double reference = bending_frequency(l, h, nu);
  double previous = 0.0;
  for (const int nx : {10, 20}) {
    const Modes quadratic = bar_modes(l, h, nx, 1, 16, nu, 8);
    const Modes linear = bar_modes(l, h, nx, 1, 10, nu, 8);
    ASSERT_FALSE(quadratic.frequency.empty());
    ASSERT_FALSE(linear.frequency.empty());
    const double e16 = quadratic.frequency[0] / reference - 1.0;
    const double e10 = linear.frequency[0] / reference - 1.0;
    std::printf(
        "[measured] free-free beam %g x %g, %d x 1 x 1 cells: first bending %.6g Hz "
        "(Timoshenko-corrected Euler-Bernoulli); ELFORM 16 %.6g Hz (%+.3e), ELFORM 10 %.6g Hz "
        "(%+.3e)\n",
        l, h, nx, reference, quadratic.frequency[0], e16, linear.frequency[0], e10);
    EXPECT_EQ(quadratic.rigid, 6);
    EXPECT_LT(std::abs(e16), nx >= 20 ? 0.01 : 0.03);
    EXPECT_GT(e10, 0.3);  // shear locking: far too stiff on one cell through the depth
    if (previous > 0.0) EXPECT_LT(std::abs(e16), std::abs(previous));
    previous = e16;
  }
}

// --- Conservation ---------------------------------------------------------------------------

// A free 2 x 1 x 1 block of irregular 10-node tetrahedra whose half x < 1 moves at v0 (and
// spreads in y) into the other half, at rest.
std::string impact_deck(const std::string& material, double v0, bool bulk_viscosity) {
  const TetGrid grid = tet_box(4, 2, 2, 2.0, 1.0, 1.0, 0.15);
  std::string deck = "*KEYWORD\n" + grid.text10();
  deck += "*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,16\n" + material;
  const model::Model mesh = read(deck + "*END\n");
  deck += "*INITIAL_VELOCITY_NODE\n";
  for (const auto& node : mesh.nodes)
    if (node.x[0] < 1.0 + 1e-9)
      deck += fmt::format("{},{:.17g},{:.17g},0\n", node.id, node.x[0] < 1.0 - 1e-9 ? v0 : 0.5 * v0,
                          0.2 * v0 * (node.x[1] - 0.5));
  if (!bulk_viscosity) deck += "*CONTROL_BULK_VISCOSITY\n0.0,0.0\n";
  deck += "*CONTROL_TERMINATION\n1.0e3\n*END\n";
  return deck;
}

struct Conservation {
  double momentum_error = 0.0, angular_error = 0.0, energy_ratio = 0.0, internal = 0.0,
         kinetic0 = 0.0;
  std::vector<double> final_state;
};

Conservation run_impact(const std::string& deck, int cycles = 400) {
  solver::Simulation sim(read(deck), {});
  Conservation c;
  double p0[3] = {}, l0[3] = {};
  double p_scale = 0.0, l_scale = 0.0;
  for (int cycle = 0; cycle < cycles; ++cycle) {
    sim.cycle();
    const auto& e = sim.energy();
    if (cycle == 0) {
      for (int d = 0; d < 3; ++d) {
        p0[d] = e.momentum[d];
        l0[d] = e.angular_momentum[d];
      }
      p_scale = std::hypot(p0[0], p0[1], p0[2]);
      l_scale = std::hypot(l0[0], l0[1], l0[2]);
      c.kinetic0 = e.kinetic;
    }
    for (int d = 0; d < 3; ++d) {
      c.momentum_error = std::max(c.momentum_error, std::abs(e.momentum[d] - p0[d]) / p_scale);
      c.angular_error =
          std::max(c.angular_error, std::abs(e.angular_momentum[d] - l0[d]) / l_scale);
    }
  }
  c.energy_ratio = sim.energy().ratio();
  c.internal = sim.energy().internal();
  const auto& n = sim.state().nodes;
  const auto& block = sim.state().hex_blocks.at(0);
  c.final_state = n.x.x;
  c.final_state.insert(c.final_state.end(), n.v.y.begin(), n.v.y.end());
  c.final_state.insert(c.final_state.end(), block.stress.begin(), block.stress.end());
  return c;
}

TEST(Tet10Conservation, InternalImpactConservesMomentumAndClosesTheEnergyBalance) {
  struct Material {
    const char* name;
    std::string card;
    double v0;
    bool bulk_viscosity;
  };
  const Material materials[] = {
      {"*MAT_ELASTIC", elastic_card(7850.0, 2.1e11, 0.3), 60.0, false},
      {"*MAT_ELASTIC nu 0.49, bulk viscosity", elastic_card(7850.0, 2.1e11, 0.49), 60.0, true},
      {"*MAT_024", "*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,7850.0,2.1e11,0.3,1.0e8,1.0e9\n", 60.0,
       true},
      {"*MAT_003", "*MAT_PLASTIC_KINEMATIC\n1,7850.0,2.1e11,0.3,1.0e8,1.0e9,0.5\n", 60.0, true},
      {"*MAT_027", "*MAT_MOONEY-RIVLIN_RUBBER\n1,1100.0,0.499,2.0e6,0.5e6\n0,0,0,0\n", 5.0, true},
      {"*MAT_077_O", "*MAT_OGDEN_RUBBER\n1,1100.0,0.499,0\n3.0e6,1.0e5\n2.0,4.0\n", 5.0, true},
  };
  for (const Material& m : materials) {
    const Conservation c = run_impact(impact_deck(m.card, m.v0, m.bulk_viscosity));
    std::printf(
        "[measured] ELFORM 16 internal impact, %s: momentum %.2e, angular momentum %.2e, "
        "energy ratio %.10f, internal energy %.4g J of %.4g J\n",
        m.name, c.momentum_error, c.angular_error, c.energy_ratio, c.internal, c.kinetic0);
    EXPECT_LT(c.momentum_error, 1e-12) << m.name;
    EXPECT_LT(c.angular_error, 1e-12) << m.name;
    EXPECT_NEAR(c.energy_ratio, 1.0, 1e-6) << m.name;
    EXPECT_GT(c.internal, 1e-3 * c.kinetic0) << m.name;
  }
}

TEST(Tet10Conservation, ResultsDoNotDependOnTheThreadCount) {
  const std::string deck = impact_deck(
      "*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,7850.0,2.1e11,0.3,1.0e8,1.0e9\n", 60.0, true);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const Conservation one = run_impact(deck, 150);
  omp_set_num_threads(3);
  const Conservation three = run_impact(deck, 150);
  omp_set_num_threads(saved);
  ASSERT_EQ(one.final_state.size(), three.final_state.size());
  for (std::size_t k = 0; k < one.final_state.size(); ++k)
    ASSERT_EQ(one.final_state[k], three.final_state[k]) << "value " << k;
}

TEST(Tet10Conservation, Tet4ToTet10CardsGiveTheSameModelAsTenNodeCards) {
  // *ELEMENT_SOLID_TET4TOTET10: the same tetrahedra written with 4 nodes; the mid-side nodes it
  // creates (one per edge, IDs above the deck's) must give the explicit 10-node model's run.
  const TetGrid grid = tet_box(4, 2, 2, 2.0, 1.0, 1.0, 0.15);
  const std::string material =
      "*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,7850.0,2.1e11,0.3,1.0e8,1.0e9\n";
  const std::string ten = impact_deck(material, 60.0, true);
  std::string four = "*KEYWORD\n" + grid.text();
  four.replace(four.find("*ELEMENT_SOLID\n"), 15, "*ELEMENT_SOLID_TET4TOTET10\n");
  four += "*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,16\n" + material;
  // The same initial velocities in both, on the corner nodes x < 1 only.
  std::string ten_no_velocity = ten.substr(0, ten.find("*INITIAL_VELOCITY_NODE"));
  std::string velocity = "*INITIAL_VELOCITY_NODE\n";
  for (int k = 0; k <= grid.nk; ++k)
    for (int j = 0; j <= grid.nj; ++j)
      for (int i = 0; i < grid.ni / 2; ++i)
        velocity += fmt::format("{},60.0,{:.17g},0\n", grid.node(i, j, k), 3.0 * (j - 1));
  ten_no_velocity += velocity + "*CONTROL_TERMINATION\n1.0e3\n*END\n";
  four += velocity + "*CONTROL_TERMINATION\n1.0e3\n*END\n";
  solver::Simulation a(read(ten_no_velocity), {}), b(read(four), {});
  EXPECT_EQ(b.state().generated_node_count,
            static_cast<std::int64_t>(b.state().nodes.size()) - grid.node_count());
  EXPECT_EQ(a.state().nodes.size(), b.state().nodes.size());
  model::Id largest = 0;
  for (std::size_t i = 0; i < static_cast<std::size_t>(grid.node_count()); ++i)
    largest = std::max(largest, b.state().nodes.id[i]);
  for (std::size_t i = static_cast<std::size_t>(grid.node_count()); i < b.state().nodes.size(); ++i)
    EXPECT_GT(b.state().nodes.id[i], largest);
  for (int cycle = 0; cycle < 50; ++cycle) {
    a.cycle();
    b.cycle();
  }
  std::printf("[measured] TET4TOTET10: %lld nodes created; kinetic energy %.10g vs %.10g\n",
              static_cast<long long>(b.state().generated_node_count), a.energy().kinetic,
              b.energy().kinetic);
  EXPECT_EQ(a.state().time, b.state().time);
  EXPECT_NEAR(a.energy().kinetic, b.energy().kinetic, 1e-12 * a.energy().kinetic);
  EXPECT_NEAR(a.energy().internal(), b.energy().internal(), 1e-12 * a.energy().kinetic);
}

TEST(Tet10Conservation, SwitchedRigidAndBackKeepsMomentumAndDeformsAgain) {
  // Part switching (*DEFORMABLE_TO_RIGID_AUTOMATIC, time-paired) of an ELFORM 16 part: rigid
  // at 3 ms, deformable again at 6 ms; the stresses at the 4 points are frozen and restored.
  std::string deck = impact_deck(elastic_card(7850.0, 2.1e11, 0.3), 6.0, false);
  deck.insert(deck.rfind("*CONTROL_TERMINATION"),
              "*DEFORMABLE_TO_RIGID_AUTOMATIC\n10,0,0.003,0.004,0,0,20,1\n0,0,0,2.0e-5,1,0\n1\n"
              "*DEFORMABLE_TO_RIGID_AUTOMATIC\n20,0,0.006,0,0,0,10,-1\n0,0,0,0,0,1\n1\n");
  solver::Simulation sim(read(deck), {});
  double p0 = 0.0;
  std::vector<double> stress_at_release;
  double max_momentum_error = 0.0;
  while (sim.state().time < 0.009) {
    sim.cycle();
    if (sim.state().cycle == 1) p0 = sim.energy().momentum[0];
    max_momentum_error =
        std::max(max_momentum_error, std::abs(sim.energy().momentum[0] - p0) / std::abs(p0));
    if (stress_at_release.empty() && sim.switch_events().size() == 2)
      stress_at_release = sim.state().hex_blocks[0].stress;
  }
  ASSERT_EQ(sim.switch_events().size(), 2u);
  double change = 0.0, scale = 0.0;
  const auto& stress = sim.state().hex_blocks[0].stress;
  for (std::size_t k = 0; k < stress.size(); ++k) {
    scale = std::max(scale, std::abs(stress_at_release[k]));
    change = std::max(change, std::abs(stress[k] - stress_at_release[k]));
  }
  std::printf(
      "[measured] ELFORM 16 switched rigid and back: momentum %.2e, energy ratio %.10f, "
      "stress change after the release %.3g of %.3g\n",
      max_momentum_error, sim.energy().ratio(), change, scale);
  EXPECT_LT(max_momentum_error, 1e-12);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-6);
  EXPECT_GT(scale, 0.0);
  EXPECT_GT(change, 1e-3 * scale);
}

TEST(Tet10Conservation, MassScalingHoldsTheTargetStepAndTheBalanceCloses) {
  // *CONTROL_TIMESTEP DT2MS < 0: mass is added to the elements whose step is below TSSFAC |DT2MS|
  // (solver/mass_scaling.hpp) through the ELFORM 16 step and lumped shares; no bulk viscosity,
  // so the step is the scaled elastic one.
  double physical_step = 0.0;
  {
    solver::Simulation plain(read(impact_deck(elastic_card(7850.0, 2.1e11, 0.3), 6.0, false)), {});
    plain.cycle();
    physical_step = plain.state().dt;
  }
  const double target = 3.0 * physical_step / 0.9;  // TSSFAC |DT2MS| = three physical steps
  std::string deck = impact_deck(elastic_card(7850.0, 2.1e11, 0.3), 6.0, false);
  deck.insert(deck.rfind("*CONTROL_TERMINATION"),
              fmt::format("*CONTROL_TIMESTEP\n0.0,0.9,0,0.0,{:.17g}\n", -target));
  solver::Simulation sim(read(deck), {});
  double worst = 0.0;
  for (int cycle = 0; cycle < 200; ++cycle) {
    sim.cycle();
    worst = std::max(worst, std::abs(sim.state().dt / (0.9 * target) - 1.0));
  }
  std::printf(
      "[measured] ELFORM 16 mass scaling: step %.4g (target %.4g, physical %.4g), largest "
      "deviation %.2e, energy ratio %.10f\n",
      sim.state().dt, 0.9 * target, physical_step, worst, sim.energy().ratio());
  EXPECT_LT(physical_step, 0.9 * target);  // the scaling has work to do
  EXPECT_LT(worst, 1e-3);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-6);
}

TEST(Tet10Contact, TwoBarsCollideThroughTheirTriangulatedFaces) {
  // Bar A (part 1, x in [0, 1]) at 20 m/s into bar B (part 2, x in [1.001, 2.001]) at rest, both
  // ELFORM 16, *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE between the parts: each 6-node face is 4
  // triangle segments. Equal elastic bars: A stops and B leaves at v0 (1-D wave theory), the
  // momentum is exchanged through equal and opposite contact forces, the gap stays closed to a
  // small penetration.
  const double v0 = 20.0, gap = 0.001;
  TetGrid a = tet_box(4, 2, 2, 1.0, 0.5, 0.5);
  TetGrid b = tet_box(4, 2, 2, 1.0, 0.5, 0.5);
  b.first_node = 10001;
  b.first_element = 10001;
  b.pid = 2;
  const auto shifted = b.position;
  b.position = [=](int i, int j, int k) {
    return Eigen::Vector3d(shifted(i, j, k) + Eigen::Vector3d(1.0 + gap, 0.0, 0.0));
  };
  std::string deck = "*KEYWORD\n" + a.text10() + b.text10();
  deck += "*PART\nA\n1,1,1\n*PART\nB\n2,1,1\n*SECTION_SOLID\n1,16\n" +
          elastic_card(7850.0, 2.1e11, 0.0);
  deck += "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE\n1,2,3,3\n0,0\n1,1\n";
  const model::Model mesh = read(deck + "*END\n");
  deck += "*INITIAL_VELOCITY_NODE\n";
  for (const auto& node : mesh.nodes)
    if (node.x[0] < 1.0 + 0.5 * gap) deck += fmt::format("{},{:.17g},0,0\n", node.id, v0);
  deck += "*CONTROL_TERMINATION\n0.0006\n*END\n";
  solver::Simulation sim(read(deck), {});
  const auto& n = sim.state().nodes;
  double penetration = 0.0, p0 = 0.0, momentum_error = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    if (sim.state().cycle == 1) p0 = sim.energy().momentum[0];
    momentum_error = std::max(momentum_error, std::abs(sim.energy().momentum[0] - p0) / p0);
    double a_max = -1e300, b_min = 1e300;
    for (std::size_t i = 0; i < n.size(); ++i) {
      if (n.x0.x[i] < 1.0 + 0.5 * gap)
        a_max = std::max(a_max, n.x.x[i]);
      else
        b_min = std::min(b_min, n.x.x[i]);
    }
    penetration = std::max(penetration, a_max - b_min);
  }
  double pa = 0.0, pb = 0.0;
  for (std::size_t i = 0; i < n.size(); ++i)
    (n.x0.x[i] < 1.0 + 0.5 * gap ? pa : pb) += n.mass[i] * n.v.x[i];
  std::printf(
      "[measured] ELFORM 16 bars in contact: momentum %.2e, B carries %.4f of the momentum, A "
      "%.4f; largest penetration %.3e m (cell 0.25 m); energy ratio %.6f\n",
      momentum_error, pb / p0, pa / p0, penetration, sim.energy().ratio());
  EXPECT_LT(momentum_error, 1e-10);
  EXPECT_GT(pb / p0, 0.85);
  EXPECT_LT(std::abs(pa / p0), 0.15);
  EXPECT_LT(penetration, 0.01 * 0.25);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 0.02);
}

// --- Rigid part -----------------------------------------------------------------------------

TEST(Tet10Rigid, MassIsExactAndInertiaApproachesTheBox) {
  // A *MAT_RIGID box a x b x c of 10-node tetrahedra: mass rho a b c exactly; the inertia of
  // the lumped nodal masses (corners rho V / 36, mid-side nodes 4 rho V / 27) against the solid
  // box's m (b^2 + c^2) / 12, converging at second order under refinement.
  const double a = 2.0, b = 1.0, c = 0.5, rho = 1000.0;
  const double mass = rho * a * b * c;
  const double exact[3] = {mass * (b * b + c * c) / 12.0, mass * (a * a + c * c) / 12.0,
                           mass * (a * a + b * b) / 12.0};
  double previous = 0.0;
  for (const int n : {1, 2, 4}) {
    const TetGrid grid = tet_box(2 * n, n, n, a, b, c, 0.1);
    const std::string deck =
        "*KEYWORD\n" + grid.text10() + "*PART\nrigid\n1,1,1\n*SECTION_SOLID\n1,16\n*MAT_RIGID\n1," +
        fmt::format("{:.17g}", rho) +
        ",2.1e11,0.3\n*CONTROL_TIMESTEP\n1e-4\n*CONTROL_TERMINATION\n1e-3\n*END\n";
    solver::Simulation sim(read(deck), {});
    ASSERT_EQ(sim.rigid_bodies().bodies.size(), 1u);
    const auto& body = sim.rigid_bodies().bodies[0];
    EXPECT_NEAR(body.state.mass, mass, 1e-12 * mass);
    double worst = 0.0;
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, std::abs(body.state.principal_inertia[k] / exact[k] - 1.0));
    std::printf(
        "[measured] rigid ELFORM 16 box, %d x %d x %d cells: mass %.12g (exact %.12g), "
        "principal inertia %.6g %.6g %.6g vs %.6g %.6g %.6g, worst error %.3e\n",
        2 * n, n, n, body.state.mass, mass, body.state.principal_inertia[0],
        body.state.principal_inertia[1], body.state.principal_inertia[2], exact[0], exact[1],
        exact[2], worst);
    // The body's inertia is the second moment of the lumped nodal masses (what the nodes'
    // kinetic energy is, so that switching conserves energy); it converges as h^2.
    if (n > 1) EXPECT_GT(std::log2(previous / worst), 1.8);
    previous = worst;
  }
  EXPECT_LT(previous, 0.04);
}

// --- Input errors ---------------------------------------------------------------------------

const std::string kTetNodes =
    "*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n4,0,0,1\n5,0.5,0,0\n6,0.5,0.5,0\n7,0,0.5,0\n8,0,0,0.5\n"
    "9,0.5,0,0.5\n10,0,0.5,0.5\n";
const std::string kTail =
    "*PART\nblock\n1,1,1\n*MAT_ELASTIC\n1,7850.0,2.1e11,0.3\n*CONTROL_TERMINATION\n1e-5\n*END\n";

TEST(Tet10Input, WrongNodeCountsAndFormulationsAreRefusedByName) {
  // A 4-node tetrahedron on an ELFORM 16 part.
  std::string what = simulation_error_of(
      "*KEYWORD\n" + kTetNodes + "*ELEMENT_SOLID\n7,1,1,2,3,4\n*SECTION_SOLID\n1,16\n" + kTail);
  EXPECT_NE(what.find("element 7"), std::string::npos) << what;
  EXPECT_NE(what.find("ELFORM 16"), std::string::npos) << what;
  EXPECT_NE(what.find("verification.k:"), std::string::npos) << what;
  EXPECT_NE(what.find("TET4TOTET10"), std::string::npos) << what;
  // A 10-node tetrahedron on an ELFORM 10 part.
  what = simulation_error_of("*KEYWORD\n" + kTetNodes +
                             "*ELEMENT_SOLID\n7,1\n1,2,3,4,5,6,7,8,9,10\n*SECTION_SOLID\n1,10\n" +
                             kTail);
  EXPECT_NE(what.find("element 7"), std::string::npos) << what;
  EXPECT_NE(what.find("10 nodes"), std::string::npos) << what;
  EXPECT_NE(what.find("ELFORM 10"), std::string::npos) << what;
  EXPECT_NE(what.find("verification.k:"), std::string::npos) << what;
  // N10 missing.
  what =
      simulation_error_of("*KEYWORD\n" + kTetNodes +
                          "*ELEMENT_SOLID\n7,1\n1,2,3,4,5,6,7,8,9\n*SECTION_SOLID\n1,16\n" + kTail);
  EXPECT_NE(what.find("N10"), std::string::npos) << what;
  EXPECT_NE(what.find("10 positive node IDs"), std::string::npos) << what;
  // ELFORM 17 stays refused.
  what = simulation_error_of("*KEYWORD\n" + kTetNodes +
                             "*ELEMENT_SOLID\n7,1\n1,2,3,4,5,6,7,8,9,10\n*SECTION_SOLID\n1,17\n" +
                             kTail);
  EXPECT_NE(what.find("ELFORM"), std::string::npos) << what;
  EXPECT_NE(what.find("17"), std::string::npos) << what;
  EXPECT_NE(what.find("*SECTION_SOLID"), std::string::npos) << what;
}

TEST(Tet10Input, InvertedAndMisorderedElementsAreRefused) {
  // N2 and N3 swapped: inverted.
  std::string what = simulation_error_of("*KEYWORD\n" + kTetNodes +
                                         "*ELEMENT_SOLID\n7,1\n1,3,2,4,7,6,5,8,10,9\n"
                                         "*SECTION_SOLID\n1,16\n" +
                                         kTail);
  EXPECT_NE(what.find("element 7"), std::string::npos) << what;
  EXPECT_NE(what.find("Jacobian"), std::string::npos) << what;
  EXPECT_NE(what.find("verification.k:"), std::string::npos) << what;
  // Mid-side nodes in the wrong order (N5 and N6 exchanged).
  what = simulation_error_of("*KEYWORD\n" + kTetNodes +
                             "*ELEMENT_SOLID\n7,1\n1,2,3,4,6,5,7,8,9,10\n*SECTION_SOLID\n1,16\n" +
                             kTail);
  EXPECT_NE(what.find("element 7"), std::string::npos) << what;
  EXPECT_NE(what.find("mid-side node N5"), std::string::npos) << what;
  EXPECT_NE(what.find("edge N1-N2"), std::string::npos) << what;
  // A material ELFORM 16 does not run.
  what = simulation_error_of(
      "*KEYWORD\n" + kTetNodes +
      "*ELEMENT_SOLID\n7,1\n1,2,3,4,5,6,7,8,9,10\n*SECTION_SOLID\n1,16\n*PART\nblock\n1,1,1\n"
      "*MAT_JOHNSON_COOK\n1,7850.0,8.0e10,2.1e11,0.3\n3.0e8,5.0e8,0.3,0.0,0.0,0.0,0.0,1.0\n"
      "*CONTROL_TERMINATION\n1e-5\n*END\n");
  EXPECT_NE(what.find("*MAT_JOHNSON_COOK"), std::string::npos) << what;
  EXPECT_NE(what.find("ELFORM 16"), std::string::npos) << what;
  EXPECT_NE(what.find("element 7"), std::string::npos) << what;
  // *PART_MODES flexible bodies of ELFORM 16 parts are refused (not verified).
  what = simulation_error_of("*KEYWORD\n" + kTetNodes +
                             "*ELEMENT_SOLID\n7,1\n1,2,3,4,5,6,7,8,9,10\n*SECTION_SOLID\n1,16\n"
                             "*PART\nblock\n1,1,1\n*MAT_RIGID\n1,7850.0,2.1e11,0.3\n"
                             "*PART_MODES\n1,3,0,0,3,0\nno_such_modes.h5\n"
                             "*CONTROL_TIMESTEP\n1e-4\n*CONTROL_TERMINATION\n1e-3\n*END\n");
  EXPECT_NE(what.find("part 1"), std::string::npos) << what;
  EXPECT_NE(what.find("*PART_MODES"), std::string::npos) << what;
  EXPECT_NE(what.find("ELFORM 16"), std::string::npos) << what;
  // Erosion (here *MAT_024 FAIL) is refused for ELFORM 16, naming the part and material.
  what = simulation_error_of(
      "*KEYWORD\n" + kTetNodes +
      "*ELEMENT_SOLID\n7,1\n1,2,3,4,5,6,7,8,9,10\n*SECTION_SOLID\n1,16\n*PART\nblock\n1,1,1\n"
      "*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,7850.0,2.1e11,0.3,1.0e8,1.0e9,0.01\n"
      "*CONTROL_TERMINATION\n1e-5\n*END\n");
  EXPECT_NE(what.find("part 1"), std::string::npos) << what;
  EXPECT_NE(what.find("do not erode"), std::string::npos) << what;
  EXPECT_NE(what.find("verification.k:"), std::string::npos) << what;
}

TEST(Tet10Conservation, NodeSetsReachTheMidsideNodesThatTet4ToTet10Creates) {
  // The deck's node sets cannot list the mid-side nodes *ELEMENT_SOLID_TET4TOTET10 creates; a
  // created node joins a set when both ends of its edge are in it (solver/boundary.cpp). So an
  // SPC set of the corner nodes on the face x = 0 holds the whole quadratic face, and an initial
  // velocity given to a set of corner nodes reaches the mid-side nodes between them.
  const TetGrid grid = tet_box(4, 2, 2, 2.0, 1.0, 1.0);
  std::string deck = "*KEYWORD\n" + grid.text();
  deck.replace(deck.find("*ELEMENT_SOLID\n"), 15, "*ELEMENT_SOLID_TET4TOTET10\n");
  deck += "*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,16\n" + elastic_card(7850.0, 2.1e11, 0.3);
  std::vector<int> face, corners;
  for (int k = 0; k <= grid.nk; ++k)
    for (int j = 0; j <= grid.nj; ++j) face.push_back(grid.node(0, j, k));
  for (int n = 1; n <= grid.node_count(); ++n) corners.push_back(n);
  deck += node_set(1, face) + node_set(2, corners);
  deck += "*BOUNDARY_SPC_SET\n1,0,1,1,1\n*INITIAL_VELOCITY\n2\n10.0,0.0,0.0\n";
  deck += "*CONTROL_TERMINATION\n1.0e3\n*END\n";
  solver::Simulation sim(read(deck), {});
  const solver::NodalState& n = sim.state().nodes;
  const auto first_created = static_cast<std::size_t>(grid.node_count());
  ASSERT_GT(n.size(), first_created);
  for (std::size_t i = first_created; i < n.size(); ++i)
    EXPECT_EQ(n.v.x[i], 10.0) << "created node " << n.id[i] << " between two set nodes";
  for (int cycle = 0; cycle < 50; ++cycle) sim.cycle();
  int on_face = 0, moved = 0;
  for (std::size_t i = first_created; i < n.size(); ++i) {
    if (n.x0.x[i] != 0.0) {
      moved += n.x.x[i] > n.x0.x[i] ? 1 : 0;
      continue;
    }
    ++on_face;
    EXPECT_EQ(n.x.x[i], 0.0) << "created node " << n.id[i] << " on the held face";
    EXPECT_EQ(n.x.y[i], n.x0.y[i]);
    EXPECT_EQ(n.x.z[i], n.x0.z[i]);
  }
  EXPECT_EQ(on_face, 16) << "the held face's 2 x 2 squares have 16 edges with created nodes";
  EXPECT_GT(moved, 0);
}

}  // namespace
}  // namespace rf::test
