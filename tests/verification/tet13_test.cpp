// The nodal-pressure tetrahedron (*SECTION_SOLID ELFORM 13, element/tet13_block.cpp) against
// references that do not come from our code:
//  - the patch test: a homogeneous deformation of an irregular tetrahedral mesh, driven on the
//    boundary only, must leave the interior nodes on the homogeneous motion and give every
//    element the stress of the hypoelastic law integrated in closed form (any nu, 0.4999 too);
//  - volumetric locking: a thick-walled cylinder under internal pressure in plane strain
//    against Lame's solution (Timoshenko & Goodier, Theory of Elasticity, sec. 28), nu = 0.499:
//    the constant-strain tetrahedron (ELFORM 10) locks, ELFORM 13 does not, and converges;
//  - locking in plastic flow: the same cylinder, elastic-perfectly-plastic, expanded far into
//    full plasticity, against the limit pressure (2 / sqrt 3) sigma_y ln(b / a) (Hill);
//  - conservation: a free body with an internal impact keeps its momentum and angular momentum
//    to round-off, glstat's balance closes, and the internal work equals Bonet & Burton's
//    stored energy (deviatoric per element, volumetric per node) of the final configuration;
//  - input errors naming the element or the material.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "deck_builder.hpp"
#include "element/tet13_block.hpp"
#include "model/error.hpp"
#include "tet_mesh.hpp"

namespace rf::test {
namespace {

// --- Patch test -----------------------------------------------------------------------------

// Velocity gradient of the homogeneous motion: v = G X, G diagonal (no spin), so the stretch
// is I + G t and the log strain ln(1 + g_i t), which the hypoelastic law integrates exactly.
constexpr double kRate[3] = {0.25, -0.1, 0.0625};

std::string patch_deck(int elform, const std::string& material, double end_time) {
  const TetGrid grid = tet_box(3, 3, 3, 1.0, 1.0, 1.0, 0.15);
  std::string deck = "*KEYWORD\n" + grid.text();
  deck += fmt::format("*PART\npatch\n1,1,1\n*SECTION_SOLID\n1,{}\n", elform) + material;
  deck += "*DEFINE_CURVE\n1\n0.0,1.0\n100.0,1.0\n*INITIAL_VELOCITY_NODE\n";
  std::string prescribed = "*BOUNDARY_PRESCRIBED_MOTION_NODE\n";
  for (int k = 0; k <= grid.nk; ++k)
    for (int j = 0; j <= grid.nj; ++j)
      for (int i = 0; i <= grid.ni; ++i) {
        const Eigen::Vector3d p = grid.position(i, j, k);
        const int id = grid.node(i, j, k);
        deck += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", id, kRate[0] * p.x(), kRate[1] * p.y(),
                            kRate[2] * p.z());
        if (!grid.on_boundary(i, j, k)) continue;
        for (int d = 0; d < 3; ++d)
          prescribed += fmt::format("{},{},0,1,{:.17g}\n", id, d + 1, kRate[d] * p[d]);
      }
  deck += prescribed;
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},0\n*END\n", end_time);
  return deck;
}

struct PatchResult {
  double stress_error = 0.0;    // max over elements and components, / max |sigma|
  double position_error = 0.0;  // interior nodes, / max |G X| t
  double plastic_strain = 0.0;  // mean effective plastic strain (J2 materials)
  std::vector<double> stress;
};

PatchResult run_patch(int elform, const std::string& material, double young, double nu,
                      double end_time) {
  solver::Simulation sim(read(patch_deck(elform, material, end_time)), {});
  while (!sim.finished()) sim.cycle();
  const solver::State& s = sim.state();
  const double t = s.time;
  PatchResult r;
  // Closed form: sigma = lambda tr(eps) I + 2 mu eps, eps_i = ln(1 + g_i t).
  const double lambda = young * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double mu = young / (2.0 * (1.0 + nu));
  double eps[3], trace = 0.0;
  for (int d = 0; d < 3; ++d) trace += eps[d] = std::log1p(kRate[d] * t);
  double exact[6] = {0, 0, 0, 0, 0, 0};
  for (int d = 0; d < 3; ++d) exact[d] = lambda * trace + 2.0 * mu * eps[d];
  const double scale = std::max({std::abs(exact[0]), std::abs(exact[1]), std::abs(exact[2])});
  const auto& block = s.hex_blocks.front();
  for (std::size_t e = 0; e < block.size(); ++e)
    for (int c = 0; c < 6; ++c)
      r.stress_error =
          std::max(r.stress_error, std::abs(block.stress[6 * e + c] - exact[c]) / scale);
  r.stress = block.stress;
  if (const auto* h = element::find_history(block, "effective_plastic_strain")) {
    for (const double v : h->values) r.plastic_strain += v;
    r.plastic_strain /= static_cast<double>(h->values.size());
  }
  const auto& n = s.nodes;
  double motion = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const double x0[3] = {n.x0.x[i], n.x0.y[i], n.x0.z[i]};
    const double x[3] = {n.x.x[i], n.x.y[i], n.x.z[i]};
    for (int d = 0; d < 3; ++d) {
      motion = std::max(motion, std::abs(kRate[d] * x0[d] * t));
      worst = std::max(worst, std::abs(x[d] - x0[d] * (1.0 + kRate[d] * t)));
    }
  }
  r.position_error = worst / motion;
  return r;
}

std::string elastic_card(double rho, double young, double nu) {
  return fmt::format("*MAT_ELASTIC\n1,{:.17g},{:.17g},{:.17g}\n", rho, young, nu);
}

TEST(Tet13Patch, HomogeneousDeformationOfAnIrregularMeshGivesTheExactStress) {
  for (const double nu : {0.3, 0.4999}) {
    const PatchResult r = run_patch(13, elastic_card(7850.0, 2.1e11, nu), 2.1e11, nu, 4e-3);
    std::printf(
        "[measured] ELFORM 13 patch, nu %.4f: stress error %.3e of |sigma|, interior "
        "positions %.3e of the motion\n",
        nu, r.stress_error, r.position_error);
    EXPECT_LT(r.stress_error, 1e-7);
    EXPECT_LT(r.position_error, 1e-9);
  }
}

TEST(Tet13Patch, PlasticPatchEqualsTheConstantStrainTetrahedron) {
  // A homogeneous field has the same volumetric rate at every node: ELFORM 13 must then be the
  // verified ELFORM 10 in every element, here in J2 plastic flow.
  const std::string mat024 = "*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,7850.0,2.1e11,0.3,2.0e8,1.0e9\n";
  const PatchResult tet13 = run_patch(13, mat024, 2.1e11, 0.3, 4e-2);
  const PatchResult tet10 = run_patch(10, mat024, 2.1e11, 0.3, 4e-2);
  ASSERT_EQ(tet13.stress.size(), tet10.stress.size());
  double scale = 0.0, diff = 0.0;
  for (std::size_t k = 0; k < tet13.stress.size(); ++k) {
    scale = std::max(scale, std::abs(tet10.stress[k]));
    diff = std::max(diff, std::abs(tet13.stress[k] - tet10.stress[k]));
  }
  std::printf(
      "[measured] plastic patch: mean plastic strain %.4g, ELFORM 13 - ELFORM 10 stress "
      "%.3e of |sigma|, interior positions %.3e\n",
      tet13.plastic_strain, diff / scale, tet13.position_error);
  EXPECT_GT(tet13.plastic_strain, 1e-3);
  EXPECT_NEAR(tet13.plastic_strain, tet10.plastic_strain, 1e-9);
  EXPECT_LT(diff, 1e-9 * scale);
  EXPECT_LT(tet13.position_error, 1e-9);
}

// --- Thick-walled cylinder (Lame) -----------------------------------------------------------

constexpr double kInner = 1.0, kOuter = 2.0, kYoung = 1.0e7, kRho = 1000.0, kPressure = 1.0e3;

// Radial displacement of the inner surface in plane strain (Timoshenko & Goodier):
// u(r) = (1 + nu) p a^2 / (E (b^2 - a^2)) ((1 - 2 nu) r + b^2 / r).
double lame_inner_displacement(double nu) {
  const double a = kInner, b = kOuter;
  return (1.0 + nu) * kPressure * a * a / (kYoung * (b * b - a * a)) *
         ((1.0 - 2.0 * nu) * a + b * b / a);
}

// A quarter of the cylinder, nr x nt cells in r and theta, one layer of thickness (b - a) / nr
// along z; every node fixed in z (plane strain), symmetry planes x = 0 and y = 0. The pressure
// rises over `ramp` and is held; mass-proportional damping (*DAMPING_GLOBAL) brings the
// breathing mode to rest.
std::string cylinder_deck(int nr, int elform, double nu, double ramp, double end_time,
                          double damping) {
  TetGrid grid;
  grid.ni = nr;
  grid.nj = nr;
  grid.nk = 1;
  const double thickness = (kOuter - kInner) / nr;
  grid.position = [=](int i, int j, int k) {
    const double r = kInner + (kOuter - kInner) * i / nr;
    const double theta = 0.5 * std::numbers::pi * j / nr;
    return Eigen::Vector3d(r * std::cos(theta), r * std::sin(theta), thickness * k);
  };
  std::string deck = "*KEYWORD\n" + grid.text();
  deck += fmt::format("*PART\ncylinder\n1,1,1\n*SECTION_SOLID\n1,{}\n", elform) +
          elastic_card(kRho, kYoung, nu);
  deck += "*BOUNDARY_SPC_NODE\n";
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= nr; ++j)
      for (int i = 0; i <= nr; ++i)
        deck += fmt::format("{},0,{},{},1\n", grid.node(i, j, k), j == nr ? 1 : 0, j == 0 ? 1 : 0);
  // The inner face i = 0, two triangles per cell face (split along the Kuhn diagonal), ordered
  // with the normal into the hole: positive pressure pushes the wall outward.
  deck += "*LOAD_SEGMENT\n";
  for (int j = 0; j < nr; ++j) {
    const int a = grid.node(0, j, 0), b = grid.node(0, j + 1, 0), c = grid.node(0, j + 1, 1),
              d = grid.node(0, j, 1);
    for (const auto& tri : {std::array<int, 3>{a, b, c}, std::array<int, 3>{a, c, d}}) {
      auto at = [&](int id) {
        const int jj = (id - grid.first_node) / (nr + 1) % (nr + 1);
        const int kk = (id - grid.first_node) / ((nr + 1) * (nr + 1));
        return grid.position(0, jj, kk);
      };
      const Eigen::Vector3d n = (at(tri[1]) - at(tri[0])).cross(at(tri[2]) - at(tri[0]));
      const Eigen::Vector3d radial(at(tri[0]).x(), at(tri[0]).y(), 0.0);
      if (n.dot(radial) < 0.0)
        deck += fmt::format("1,{:.17g},0,{},{},{},{}\n", kPressure, tri[0], tri[1], tri[2], tri[2]);
      else
        deck += fmt::format("1,{:.17g},0,{},{},{},{}\n", kPressure, tri[0], tri[2], tri[1], tri[1]);
    }
  }
  deck += fmt::format("*DEFINE_CURVE\n1\n0.0,0.0\n{:.17g},1.0\n1000.0,1.0\n", ramp);
  deck += fmt::format("*DAMPING_GLOBAL\n0,{:.17g}\n", damping);
  deck += "*CONTROL_BULK_VISCOSITY\n0.0,0.0\n";
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},0\n*END\n", end_time);
  return deck;
}

struct CylinderResult {
  double inner = 0.0;          // mean radial displacement of the nodes at r = a
  double inner_earlier = 0.0;  // the same at 80 % of the run (settled?)
  std::int64_t cycles = 0;
};

CylinderResult load_cylinder(int nr, int elform, double nu) {
  // Breathing mode of the incompressible cylinder: omega^2 = mu (1/a^2 - 1/b^2) / (rho ln(b/a)).
  const double mu = kYoung / (2.0 * (1.0 + nu));
  const double omega = std::sqrt(mu * (1.0 / (kInner * kInner) - 1.0 / (kOuter * kOuter)) /
                                 (kRho * std::log(kOuter / kInner)));
  const double period = 2.0 * std::numbers::pi / omega;
  const double damping = omega;  // half of critical
  const double end_time = period + 14.0 / damping;
  solver::Simulation sim(read(cylinder_deck(nr, elform, nu, period, end_time, damping)), {});
  const auto& n = sim.state().nodes;
  auto inner = [&] {
    double sum = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < n.size(); ++i) {
      const double r0 = std::hypot(n.x0.x[i], n.x0.y[i]);
      if (std::abs(r0 - kInner) > 1e-9) continue;
      sum += ((n.x.x[i] - n.x0.x[i]) * n.x0.x[i] + (n.x.y[i] - n.x0.y[i]) * n.x0.y[i]) / r0;
      ++count;
    }
    return sum / count;
  };
  CylinderResult r;
  bool marked = false;
  while (!sim.finished()) {
    sim.cycle();
    if (!marked && sim.state().time > 0.8 * end_time) {
      r.inner_earlier = inner();
      marked = true;
    }
  }
  r.inner = inner();
  r.cycles = sim.state().cycle;
  return r;
}

TEST(Tet13Locking, ThickCylinderUnderInternalPressureMatchesLameWhereElform10Locks) {
  // nu 0.499 (K / mu = 500). Locking shows as an error that does not go away with the mesh:
  // ELFORM 10 stays about 10 % too stiff, ELFORM 13 converges at second order. (nu 0.4999 was
  // measured once, docs/verification.md: the same picture at 3x the cycles.)
  const double nu = 0.499;
  const double exact = lame_inner_displacement(nu);
  double previous13 = 0.0, previous10 = 0.0;
  for (const int nr : {4, 8, 16}) {
    const CylinderResult t13 = load_cylinder(nr, 13, nu);
    const CylinderResult t10 = load_cylinder(nr, 10, nu);
    const double error13 = t13.inner / exact - 1.0, error10 = t10.inner / exact - 1.0;
    std::printf(
        "[measured] Lame cylinder nu %.3f, %d x %d cells (%d tetrahedra): u(a) exact "
        "%.6e; ELFORM 13 %.6e, error %+.3e (settled to %.1e, %lld cycles); ELFORM 10 "
        "%.6e, error %+.3e\n",
        nu, nr, nr, 6 * nr * nr, exact, t13.inner, error13,
        std::abs(t13.inner / t13.inner_earlier - 1.0), static_cast<long long>(t13.cycles),
        t10.inner, error10);
    EXPECT_LT(std::abs(t13.inner / t13.inner_earlier - 1.0), 1e-3);
    EXPECT_LT(std::abs(t10.inner / t10.inner_earlier - 1.0), 1e-3);
    EXPECT_LT(error10, -0.05);  // locked: far too stiff on every mesh
    if (nr >= 8) EXPECT_LT(std::abs(error13), 0.02);
    if (previous13 != 0.0) {
      const double order13 = std::log2(previous13 / error13),
                   order10 = std::log2(previous10 / error10);
      std::printf("[measured]   observed order: ELFORM 13 %.2f, ELFORM 10 %.2f\n", order13,
                  order10);
      EXPECT_GT(order13, 1.5);
      EXPECT_LT(order10, 0.8);
    }
    previous13 = error13;
    previous10 = error10;
  }
  // The same ELFORM 10 mesh at nu 0.3 is accurate: its error at 0.499 is volumetric locking.
  const double compressible = load_cylinder(8, 10, 0.3).inner / lame_inner_displacement(0.3) - 1.0;
  std::printf("[measured] ELFORM 10, 8 x 8 cells, nu 0.3: error %+.3e\n", compressible);
  EXPECT_LT(std::abs(compressible), 0.03);
}

// The same quarter cylinder, elastic-perfectly-plastic (*MAT_PLASTIC_KINEMATIC, ETAN 0, nu 0.3):
// the inner radius is driven outward at constant speed (after a short ramp) to u(a) = 0.04 a,
// far beyond full plasticity (yield strain 2e-3). Plastic flow is isochoric, so here locking
// comes from the plastic strain, not from nu. The pressure is the radial internal force on the
// inner nodes over the inner surface; the reference is the limit pressure of the fully plastic
// tube (Hill, The Mathematical Theory of Plasticity, ch. V; plane strain, von Mises),
// p_L = (2 / sqrt 3) sigma_y ln(b / a), on the current radii.
struct LimitResult {
  double pressure = 0.0, limit = 0.0;
};

LimitResult expand_plastic_cylinder(int nr, int elform) {
  constexpr double kYield = 2.0e4;  // E / 500
  const double nu = 0.3;
  const double mu = kYoung / (2.0 * (1.0 + nu));
  const double omega = std::sqrt(mu * (1.0 / (kInner * kInner) - 1.0 / (kOuter * kOuter)) /
                                 (kRho * std::log(kOuter / kInner)));
  const double period = 2.0 * std::numbers::pi / omega;
  const double end_time = 6.0 * period, ramp = period;
  const double speed = 0.04 * kInner / (end_time - 0.5 * ramp);
  std::string deck = cylinder_deck(nr, elform, nu, period, end_time, omega);
  // No damping: at constant speed it would add its force m d v to the pressure.
  const std::size_t damping = deck.find("*DAMPING_GLOBAL");
  deck.erase(damping, deck.find("*CONTROL_BULK_VISCOSITY") - damping);
  // Material, and prescribed inner motion instead of the pressure.
  const std::string elastic = elastic_card(kRho, kYoung, nu);
  deck.replace(deck.find(elastic), elastic.size(),
               fmt::format("*MAT_PLASTIC_KINEMATIC\n1,{:.17g},{:.17g},{:.17g},{:.17g},0.0,1.0\n",
                           kRho, kYoung, nu, kYield));
  const std::size_t load = deck.find("*LOAD_SEGMENT");
  deck.erase(load, deck.find("*DEFINE_CURVE") - load);
  std::string motion = "*BOUNDARY_PRESCRIBED_MOTION_NODE\n";
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= nr; ++j) {
      const double theta = 0.5 * std::numbers::pi * j / nr;
      const int id = 1 + (nr + 1) * (j + (nr + 1) * k);  // node (0, j, k) of the grid
      if (j < nr) motion += fmt::format("{},1,0,2,{:.17g}\n", id, speed * std::cos(theta));
      if (j > 0) motion += fmt::format("{},2,0,2,{:.17g}\n", id, speed * std::sin(theta));
    }
  motion += fmt::format("*DEFINE_CURVE\n2\n0.0,0.0\n{:.17g},1.0\n1000.0,1.0\n", ramp);
  deck.insert(deck.find("*DEFINE_CURVE"), motion);
  solver::Simulation sim(read(deck), {});
  while (!sim.finished()) sim.cycle();
  const auto& n = sim.state().nodes;
  double force = 0.0, inner = 0.0, outer = 0.0, thickness = 0.0;
  int inner_count = 0, outer_count = 0;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const double r0 = std::hypot(n.x0.x[i], n.x0.y[i]);
    const double r = std::hypot(n.x.x[i], n.x.y[i]);
    thickness = std::max(thickness, n.x.z[i]);
    if (std::abs(r0 - kInner) < 1e-9) {
      force += (n.f_int.x[i] * n.x.x[i] + n.f_int.y[i] * n.x.y[i]) / r;
      inner += r;
      ++inner_count;
    } else if (std::abs(r0 - kOuter) < 1e-9) {
      outer += r;
      ++outer_count;
    }
  }
  inner /= inner_count;
  outer /= outer_count;
  LimitResult result;
  result.pressure = force / (0.5 * std::numbers::pi * inner * thickness);
  result.limit = 2.0 / std::sqrt(3.0) * kYield * std::log(outer / inner);
  return result;
}

TEST(Tet13Locking, FullyPlasticCylinderReachesTheLimitPressureWhereElform10Locks) {
  // Measured once on 16 x 16 cells as well: ELFORM 13 -0.11 %, ELFORM 10 +2.2 %.
  for (const int nr : {4, 8}) {
    const LimitResult t13 = expand_plastic_cylinder(nr, 13);
    const LimitResult t10 = expand_plastic_cylinder(nr, 10);
    const double error13 = t13.pressure / t13.limit - 1.0, error10 = t10.pressure / t10.limit - 1.0;
    std::printf(
        "[measured] plastic cylinder %d x %d cells: limit pressure %.5g; ELFORM 13 %.5g "
        "(%+.3e), ELFORM 10 %.5g (%+.3e)\n",
        nr, nr, t13.limit, t13.pressure, error13, t10.pressure, error10);
    EXPECT_LT(std::abs(error13), nr >= 8 ? 0.005 : 0.02);
    EXPECT_GT(error10, nr >= 8 ? 0.04 : 0.15);  // locked in plastic flow: too stiff
  }
}

// --- Conservation ---------------------------------------------------------------------------

// A free 2 x 1 x 1 block of irregular tetrahedra whose half x < 1 moves at v0 (and spreads in
// y) into the other half, at rest; no bulk viscosity unless asked: an internal impact with
// waves and, for the J2 materials, plastic flow. Runs `cycles` cycles.
std::string impact_deck(const std::string& material, double v0, bool bulk_viscosity) {
  const TetGrid grid = tet_box(8, 4, 4, 2.0, 1.0, 1.0, 0.15);
  std::string deck = "*KEYWORD\n" + grid.text();
  deck += "*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,13\n" + material;
  deck += "*INITIAL_VELOCITY_NODE\n";
  for (int k = 0; k <= grid.nk; ++k)
    for (int j = 0; j <= grid.nj; ++j)
      for (int i = 0; i <= grid.ni / 2; ++i)
        deck += fmt::format("{},{:.17g},{:.17g},0\n", grid.node(i, j, k),
                            i < grid.ni / 2 ? v0 : 0.5 * v0, 0.1 * v0 * (j - 2));
  if (!bulk_viscosity) deck += "*CONTROL_BULK_VISCOSITY\n0.0,0.0\n";
  deck += "*CONTROL_TERMINATION\n1.0e3\n*END\n";
  return deck;
}

struct Conservation {
  double momentum_error = 0.0, angular_error = 0.0, energy_ratio = 0.0, internal = 0.0,
         kinetic0 = 0.0, stored = 0.0, stored_per_element = 0.0;
  std::vector<double> final_state;
};

Conservation run_impact(const std::string& material, double v0, bool bulk_viscosity,
                        int cycles = 400) {
  solver::Simulation sim(read(impact_deck(material, v0, bulk_viscosity)), {});
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
  // Bonet & Burton's stored energy of the final configuration (meaningful for *MAT_ELASTIC):
  // sum_e V_e s:s / (4 mu) + sum_a V_a^0 K (ln J_a)^2 / 2, J_a = V_a / V_a^0, V_a = sum V_e / 4.
  const double mu = block.material.shear, k = block.material.bulk;
  const auto& avg = block.nodal_averaging;
  std::vector<double> va(avg.node_count(), 0.0), va0(avg.node_count(), 0.0);
  double deviatoric = 0.0;
  for (std::size_t e = 0; e < block.size(); ++e) {
    const double* s = &block.stress[6 * e];
    const double p = (s[0] + s[1] + s[2]) / 3.0;
    const double ss = (s[0] - p) * (s[0] - p) + (s[1] - p) * (s[1] - p) + (s[2] - p) * (s[2] - p) +
                      2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
    deviatoric += block.volume[e] * ss / (4.0 * mu);
    for (int a = 0; a < 4; ++a) {
      const auto node = static_cast<std::size_t>(avg.corner[4 * e + a]);
      va[node] += block.volume[e] / 4.0;
      va0[node] += block.volume0[e] / 4.0;
    }
  }
  double volumetric = 0.0, per_element = 0.0;
  for (std::size_t a = 0; a < va.size(); ++a) {
    const double lnj = std::log(va[a] / va0[a]);
    volumetric += va0[a] * 0.5 * k * lnj * lnj;
  }
  for (std::size_t e = 0; e < block.size(); ++e) {
    const double lnj = std::log(block.volume[e] / block.volume0[e]);
    per_element += block.volume0[e] * 0.5 * k * lnj * lnj;
  }
  c.stored = deviatoric + volumetric;
  c.stored_per_element = deviatoric + per_element;
  return c;
}

TEST(Tet13Conservation, InternalImpactConservesMomentumAndClosesTheEnergyBalance) {
  struct Material {
    const char* name;
    std::string card;
    double v0;
    bool bulk_viscosity;
  };
  const Material materials[] = {
      {"*MAT_ELASTIC", elastic_card(7850.0, 2.1e11, 0.3), 60.0, false},
      {"*MAT_ELASTIC nu 0.499", elastic_card(7850.0, 2.1e11, 0.499), 60.0, true},
      {"*MAT_024", "*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,7850.0,2.1e11,0.3,1.0e8,1.0e9\n", 60.0,
       true},
      {"*MAT_003", "*MAT_PLASTIC_KINEMATIC\n1,7850.0,2.1e11,0.3,1.0e8,1.0e9,0.5\n", 60.0, true},
      {"*MAT_027", "*MAT_MOONEY-RIVLIN_RUBBER\n1,1100.0,0.499,2.0e6,0.5e6\n0,0,0,0\n", 5.0, true},
      {"*MAT_077_O", "*MAT_OGDEN_RUBBER\n1,1100.0,0.499,0\n3.0e6,1.0e5\n2.0,4.0\n", 5.0, true},
  };
  for (const Material& m : materials) {
    const Conservation c = run_impact(m.card, m.v0, m.bulk_viscosity);
    std::printf(
        "[measured] ELFORM 13 internal impact, %s: momentum %.2e, angular momentum %.2e, "
        "energy ratio %.10f, internal energy %.4g J of %.4g J\n",
        m.name, c.momentum_error, c.angular_error, c.energy_ratio, c.internal, c.kinetic0);
    EXPECT_LT(c.momentum_error, 1e-12) << m.name;
    EXPECT_LT(c.angular_error, 1e-12) << m.name;
    EXPECT_NEAR(c.energy_ratio, 1.0, 1e-6) << m.name;
    EXPECT_GT(c.internal, 1e-3 * c.kinetic0) << m.name;
  }
}

TEST(Tet13Conservation, InternalWorkIsBonetBurtonsStoredEnergy) {
  // Elastic, no bulk viscosity: the work of the element forces must be the energy of the nodal
  // volumetric strains plus the elements' deviatoric energy (Bonet & Burton, eq. (2) of
  // tet13_block.cpp); a force that used the element's own pressure would not be.
  // The element-wise volumetric energy (each element's own ln J) is printed for contrast.
  for (const double v0 : {6.0, 0.6}) {
    const Conservation c = run_impact(elastic_card(7850.0, 2.1e11, 0.3), v0, false);
    std::printf(
        "[measured] ELFORM 13, v0 %.1f m/s: internal work %.8g J, Bonet-Burton energy "
        "%.8g J (%+.3e); element-wise volumetric energy %+.3e\n",
        v0, c.internal, c.stored, c.stored / c.internal - 1.0,
        c.stored_per_element / c.internal - 1.0);
    // The difference is the finite strain (hypoelastic rate vs ln J): it falls with v0.
    EXPECT_NEAR(c.stored / c.internal, 1.0, v0 > 1.0 ? 3e-3 : 5e-4);
    EXPECT_GT(std::abs(c.stored_per_element / c.internal - 1.0), 1e-2);
  }
}

TEST(Tet13Conservation, ResultsDoNotDependOnTheThreadCount) {
  const std::string card = "*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,7850.0,2.1e11,0.3,1.0e8,1.0e9\n";
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const Conservation one = run_impact(card, 60.0, true, 150);
  omp_set_num_threads(3);
  const Conservation three = run_impact(card, 60.0, true, 150);
  omp_set_num_threads(saved);
  ASSERT_EQ(one.final_state.size(), three.final_state.size());
  for (std::size_t k = 0; k < one.final_state.size(); ++k)
    ASSERT_EQ(one.final_state[k], three.final_state[k]) << "value " << k;
}

TEST(Tet13Conservation, ErodedElementsLeaveTheAveragesAndTheBalanceCloses) {
  // *MAT_024 with FAIL: elements erode during the impact; an eroded element contributes no
  // volume and no rate to its nodes' averages (tet13_block.cpp, pass (i)).
  solver::Simulation sim(
      read(impact_deck("*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,7850.0,2.1e11,0.3,1.0e8,1.0e9,0.01\n",
                       150.0, true)),
      {});
  for (int cycle = 0; cycle < 400; ++cycle) sim.cycle();
  const auto& block = sim.state().hex_blocks.at(0);
  const auto& avg = block.nodal_averaging;
  std::size_t eroded = 0;
  for (std::size_t e = 0; e < block.size(); ++e) {
    if (!block.erosion.is_eroded(e)) continue;
    ++eroded;
    EXPECT_EQ(avg.mid_volume[e], 0.0);
    EXPECT_EQ(avg.volume_rate[e], 0.0);
  }
  for (const double r : avg.node_rate) EXPECT_TRUE(std::isfinite(r));
  std::printf(
      "[measured] ELFORM 13 with FAIL 0.01: %zu of %zu elements eroded, energy ratio "
      "%.10f\n",
      eroded, block.size(), sim.energy().ratio());
  EXPECT_GT(eroded, 0u);
  EXPECT_LT(eroded, block.size());
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-6);
}

TEST(Tet13Conservation, SwitchedRigidAndBackKeepsMomentumAndDeformsAgain) {
  // Part switching (*DEFORMABLE_TO_RIGID_AUTOMATIC, time-paired) of an ELFORM 13 part: rigid
  // at 3 ms, deformable again at 6 ms; the averages restart from the motion after the release.
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
      "[measured] ELFORM 13 switched rigid and back: momentum %.2e, energy ratio %.10f, "
      "stress change after the release %.3g of %.3g\n",
      max_momentum_error, sim.energy().ratio(), change, scale);
  EXPECT_LT(max_momentum_error, 1e-12);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-6);
  EXPECT_GT(scale, 0.0);
  EXPECT_GT(change, 1e-3 * scale);
}

// --- Input errors ---------------------------------------------------------------------------

TEST(Tet13Input, HexahedronAndUnsupportedMaterialAreRefusedByName) {
  const std::string hexahedron =
      "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
      "*ELEMENT_SOLID\n7,1,1,2,3,4,5,6,7,8\n*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,13\n"
      "*MAT_ELASTIC\n1,7850.0,2.1e11,0.3\n*CONTROL_TERMINATION\n1e-5\n*END\n";
  std::string what = simulation_error_of(hexahedron);
  EXPECT_NE(what.find("element 7"), std::string::npos) << what;
  EXPECT_NE(what.find("8 distinct nodes"), std::string::npos) << what;
  EXPECT_NE(what.find("ELFORM 13"), std::string::npos) << what;
  EXPECT_NE(what.find("verification.k:"), std::string::npos) << what;

  const TetGrid grid = tet_box(1, 1, 1, 1.0, 1.0, 1.0);
  const std::string johnson_cook =
      "*KEYWORD\n" + grid.text() +
      "*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,13\n*MAT_JOHNSON_COOK\n1,7850.0,8.0e10,2.1e11,0.3\n"
      "3.0e8,5.0e8,0.3,0.0,0.0,0.0,0.0,1.0\n*CONTROL_TERMINATION\n1e-5\n*END\n";
  what = simulation_error_of(johnson_cook);
  EXPECT_NE(what.find("*MAT_JOHNSON_COOK"), std::string::npos) << what;
  EXPECT_NE(what.find("material 1"), std::string::npos) << what;
  EXPECT_NE(what.find("ELFORM 13"), std::string::npos) << what;
  EXPECT_NE(what.find("verification.k:"), std::string::npos) << what;
}

}  // namespace
}  // namespace rf::test
