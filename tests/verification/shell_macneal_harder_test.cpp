// MacNeal-Harder shell problems brought to their static answer by an explicit run: the load is
// ramped slowly and held while mass-proportional damping (*DAMPING_GLOBAL, near critical for the
// lowest mode) takes the motion out, or applied in a dynamic relaxation phase
// (*CONTROL_DYNAMIC_RELAXATION) where the nodal spins must be damped too. References that do not
// come from our code:
//  - MacNeal & Harder, "A proposed standard set of problems to test finite element accuracy",
//    Finite Elements in Analysis and Design 1 (1985) 3-20: geometry, material, loads and
//    supports of the Scordelis-Lo roof, the pinched hemisphere with an 18 degree hole and the
//    twisted beam, and the twisted beam's answers 5.424e-3 (load along the root's normal) and
//    1.754e-3 (load along the root's width) for t = 0.32;
//  - Belytschko, Stolarski, Liu, Carpenter & Ong, "Stress projection for membrane and shear
//    locking in shell finite elements", CMAME 51 (1985) 221-258: the normalisations 0.3024
//    (roof, midside of the free edge, vertical) and 0.0924 (hemisphere, radial under the load)
//    that shell papers since use (MacNeal & Harder give 0.3086 and 0.094).
// Confirmed against public restatements of the problems (e.g. the Altair OptiStruct and
// SkyCiv verification manuals, which cite MacNeal & Harder).
//
// Linear answers from a nonlinear (co-rotational) code: the loads are scaled down so that the
// displacements stay about 1 % of the thickness, and the normalised value is u / (s u_ref). The
// static answer does not depend on the density; it only sets the time scale, and the damping
// constant is chosen against the lowest mode the density gives (measured from the period of
// the undamped response to a step load on the same mesh).
//
// Every test checks that the run has come to rest (expect_at_rest), so that a test cannot pass
// on a still-oscillating answer.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numbers>

#include "deck_builder.hpp"
#include "shell_builder.hpp"

namespace rf::test {
namespace {

constexpr double kPi = std::numbers::pi;

struct QuasiStatic {
  double value = 0.0;          // probe displacement along the direction at the end
  double drift = 0.0;          // (max - min) of it over the last quarter, over |value|
  double kinetic_ratio = 0.0;  // kinetic / internal energy at the end
  double hourglass_ratio = 0.0;
  double seconds = 0.0;
  double energy_ratio = 0.0, internal = 0.0, external = 0.0;
  long cycles = 0;
};

// Runs `deck` to its end and follows node `probe` along `direction`.
QuasiStatic run_quasi_static(const std::string& deck, int probe, const Eigen::Vector3d& direction) {
  const auto start = std::chrono::steady_clock::now();
  if (const char* path = std::getenv("MH_DECK")) {  // by hand: keep the deck
    std::FILE* f = std::fopen(path, "w");
    if (f) {
      std::fputs(deck.c_str(), f);
      std::fclose(f);
    }
  }
  solver::Simulation sim(read(deck), {});
  if (sim.dynamic_relaxation().cycles > 0)
    std::printf("relaxation: %lld cycles, converged %d\n",
                static_cast<long long>(sim.dynamic_relaxation().cycles),
                sim.dynamic_relaxation().converged ? 1 : 0);
  const auto& n = sim.state().nodes;
  const auto i = static_cast<std::size_t>(
      std::distance(n.id.begin(), std::find(n.id.begin(), n.id.end(), probe)));
  QuasiStatic r;
  if (i >= n.size()) {
    ADD_FAILURE() << "no node " << probe;
    return r;
  }
  auto along = [&] {
    return (n.x.x[i] - n.x0.x[i]) * direction.x() + (n.x.y[i] - n.x0.y[i]) * direction.y() +
           (n.x.z[i] - n.x0.z[i]) * direction.z();
  };
  const double settle = 0.75 * sim.end_time();
  double lo = 1e300, hi = -1e300;
  double previous = 0.0;
  // MH_PEAK (by hand): the first peak under a step load is half the lowest period.
  bool peaked = std::getenv("MH_PEAK") == nullptr;
  while (!sim.finished()) {
    sim.cycle();
    ++r.cycles;
    if (!peaked) {
      const double u = along();
      if (std::abs(u) < std::abs(previous)) {
        peaked = true;
        std::printf("first peak %.6g at t %.6g (cycle %ld, dt %.3g)\n", previous, sim.state().time,
                    r.cycles, sim.state().time / r.cycles);
      }
      previous = u;
    }
    if (sim.state().time >= settle) {
      const double u = along();
      lo = std::min(lo, u);
      hi = std::max(hi, u);
    }
  }
  r.value = along();
  r.drift = (hi - lo) / std::abs(r.value);
  r.kinetic_ratio = sim.energy().kinetic / std::abs(sim.energy().internal_work);
  r.hourglass_ratio = sim.energy().hourglass / std::abs(sim.energy().internal_work);
  r.energy_ratio = sim.energy().ratio();
  r.internal = sim.energy().internal_work;
  r.external = sim.energy().external_work;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// At rest: the probe moves by less than 1e-3 of its value over the last quarter of the run
// (which spans at least half a period of the lowest mode), and the kinetic energy is below
// 1e-3 of the strain energy. The drift is the direct measure; the kinetic energy bound is loose
// because *DAMPING_GLOBAL leaves the nodal spins undamped and some rotational ringing stays
// that hardly moves the probe (measured: 1.6e-10 to 8e-5 of the strain energy).
void expect_at_rest(const QuasiStatic& r) {
  EXPECT_LT(r.drift, 1e-3) << "still moving over the last quarter of the run";
  EXPECT_LT(r.kinetic_ratio, 1e-3);
}

void report(const char* name, const QuasiStatic& r, double normalised) {
  std::printf(
      "%s: normalised %.4f, drift %.1e, kinetic/internal %.1e, hourglass/internal %.4f, "
      "%ld cycles, %.2f s (energy ratio %.6f, internal %.4g, external %.4g)\n",
      name, normalised, r.drift, r.kinetic_ratio, r.hourglass_ratio, r.cycles, r.seconds,
      r.energy_ratio, r.internal, r.external);
  ::testing::Test::RecordProperty("normalised", std::to_string(normalised));
}

// Node-by-node SPC cards from a flag table (x y z rx ry rz), so that nodes on two boundaries
// get the union of their constraints.
using DofFlags = std::array<int, 6>;
std::string spc_cards(const std::vector<std::pair<int, DofFlags>>& nodes) {
  std::map<int, DofFlags> merged;
  for (const auto& [id, f] : nodes) {
    DofFlags& m = merged.try_emplace(id, DofFlags{}).first->second;
    for (int k = 0; k < 6; ++k) m[k] = std::max(m[k], f[k]);
  }
  std::string s = "*BOUNDARY_SPC_NODE\n";
  for (const auto& [id, f] : merged)
    s += fmt::format("{},0,{},{},{},{},{},{}\n", id, f[0], f[1], f[2], f[3], f[4], f[5]);
  return s;
}

// Load curve 1: a smooth ramp (1 - cos) from 0 to 1 over `ramp`, then held.
std::string ramp_curve(double ramp, double end) {
  if (ramp <= 0.0) return fmt::format("*DEFINE_CURVE\n1\n0,1\n{:.17g},1\n", 10.0 * end);
  std::string s = "*DEFINE_CURVE\n1\n";
  for (int k = 0; k <= 16; ++k) {
    const double f = k / 16.0;
    s += fmt::format("{:.17g},{:.17g}\n", f * ramp, 0.5 * (1.0 - std::cos(kPi * f)));
  }
  return s + fmt::format("{:.17g},1\n", std::max(10.0 * end, 2.0 * ramp));
}

// How a case reaches its static state. Damping (drfctr 0): the load ramps (1 - cos) over
// `ramp` and is held to `end` with *DAMPING_GLOBAL `damping` on the translations. Dynamic
// relaxation (drfctr > 0): the full load on a constant curve flagged SIDR 2 (applied in the
// relaxation and kept in the transient), every velocity, the nodal spins included, scaled by
// `drfctr` each cycle until the kinetic energy is `drtol` of its peak; then a transient to
// `end` under the same load, in which a relaxed state must stay where it is.
struct Settle {
  double ramp = 0.0, end = 0.0, damping = 0.0;
  double drfctr = 0.0, drtol = 1e-6;
};

std::string tail(const Settle& s) {
  if (s.drfctr > 0.0)
    return fmt::format("*DEFINE_CURVE\n1,2\n0,1\n{:.17g},1\n", 10.0 * s.end) +
           fmt::format("*CONTROL_DYNAMIC_RELAXATION\n250,{:.17g},{:.17g}\n", s.drtol, s.drfctr) +
           fmt::format("*CONTROL_TERMINATION\n{:.17g},\n*END\n", s.end);
  return ramp_curve(s.ramp, s.end) + fmt::format("*DAMPING_GLOBAL\n0,{:.17g}\n", s.damping) +
         fmt::format("*CONTROL_TERMINATION\n{:.17g},\n*END\n", s.end);
}

// Shell options of the cases below.
struct Shell {
  int elform = 2;
  int ihq = 4;
  double qm = 0.1;
  bool bwc = false;
  double tssfac = 0.0;  // 0: the default 0.9
};

std::string part(const Shell& s, double t, double rho, double e, double nu) {
  std::string text = shell_part(1, t, rho, e, nu, 2, s.ihq, s.qm, s.elform);
  if (s.bwc) text += "*CONTROL_SHELL\n20,0,-1,0,2,1\n";
  if (s.tssfac > 0.0) text += fmt::format("*CONTROL_TIMESTEP\n0,{},\n", s.tssfac);
  return text;
}

// ---------------------------------------------------------------------------------------------
// Scordelis-Lo roof (MacNeal & Harder 1985, the roof problem): cylinder R 25, length 50, 80 degree
// arc, t 0.25, E 4.32e8, nu 0, self weight 90 per unit area, rigid diaphragms at the ends, straight
// edges free. Quarter model: x along the axis from the diaphragm (x = 0) to midspan (x = 25),
// phi from the crown (y = 0) to the free edge (40 degrees); point (x, R sin phi, R cos phi).
// Supports: diaphragm u_y = u_z = 0, and theta_x = 0, which the Kirchhoff solution has there
// too (it is the derivative along the edge of the normal displacement, zero on it); midspan
// symmetry u_x = theta_y = theta_z = 0; crown symmetry u_y = theta_x = theta_z = 0. Answer:
// vertical displacement at midspan of the free edge.
constexpr double kRoofReference = 0.3024;

struct RoofCase {
  int n = 8;  // n x n elements on the quarter
  double load_scale = 0.01;
  double rho = 1.0;
  // Lowest mode (rho 1, 8 x 8): half period 0.093 under a step load, omega_1 = 34 /s; damping
  // 66 /s is about critical for it, and the error decays as exp(-33 t) after the ramp.
  Settle settle{0.3, 0.8, 66.0};
};

double scordelis_lo(const Shell& shell, const RoofCase& c, QuasiStatic* out = nullptr) {
  constexpr double kR = 25.0, kHalfLength = 25.0, kAngle = 40.0 * kPi / 180.0;
  ShellPlate p;
  p.nx = p.ny = c.n;
  p.lx = kHalfLength;
  p.ly = kAngle;
  p.place = [](double x, double phi) {
    return Eigen::Vector3d(x, kR * std::sin(phi), kR * std::cos(phi));
  };
  std::string deck = "*KEYWORD\n" + p.text() + part(shell, 0.25, c.rho, 4.32e8, 0.0);
  std::vector<std::pair<int, DofFlags>> spc;
  for (int j = 0; j <= p.ny; ++j) {
    spc.push_back({p.node_id(0, j), {0, 1, 1, 1, 0, 0}});     // diaphragm
    spc.push_back({p.node_id(p.nx, j), {1, 0, 0, 0, 1, 1}});  // midspan symmetry
  }
  for (int i = 0; i <= p.nx; ++i) spc.push_back({p.node_id(i, 0), {0, 1, 0, 1, 0, 1}});  // crown
  deck += spc_cards(spc);
  // Self weight: 90 per unit area of the surface, lumped a quarter of each element's area to
  // each of its nodes (the area of the flat quadrilateral through the nodes).
  std::vector<double> force(static_cast<std::size_t>(p.node_count()), 0.0);
  for (int j = 0; j < p.ny; ++j)
    for (int i = 0; i < p.nx; ++i) {
      const Eigen::Vector3d d1 = p.position(i + 1, j + 1) - p.position(i, j);
      const Eigen::Vector3d d2 = p.position(i, j + 1) - p.position(i + 1, j);
      const double share = 0.25 * 0.5 * d1.cross(d2).norm() * 90.0 * c.load_scale;
      for (const int id :
           {p.node_id(i, j), p.node_id(i + 1, j), p.node_id(i + 1, j + 1), p.node_id(i, j + 1)})
        force[static_cast<std::size_t>(id - p.first_node)] += share;
    }
  for (int id = p.first_node; id < p.first_node + p.node_count(); ++id)
    deck += fmt::format("*LOAD_NODE_POINT\n{},3,1,{:.17g}\n", id,
                        -force[static_cast<std::size_t>(id - p.first_node)]);
  deck += tail(c.settle);
  const QuasiStatic r =
      run_quasi_static(deck, p.node_id(p.nx, p.ny), Eigen::Vector3d(0.0, 0.0, -1.0));
  if (out) *out = r;
  return r.value / (c.load_scale * kRoofReference);
}

// ---------------------------------------------------------------------------------------------
// Pinched hemisphere (MacNeal & Harder 1985, the spherical shell): R 10, t 0.04, E 6.825e7, nu 0.3,
// an 18 degree hole at the pole, equator free; radial point loads of 2 at 90 degree intervals on
// the equator, alternately outward and inward. Quarter model (x >= 0, y >= 0): outward load 1 at
// (R, 0, 0) along x, inward load 1 at (0, R, 0) along -y (half of each load on its symmetry
// plane); symmetry y = 0: u_y = theta_x = theta_z = 0, x = 0: u_x = theta_y = theta_z = 0; one
// equator node at 45 degrees holds u_z against the rigid drift. Answer: displacement under the
// load along it. Point (i, j): azimuth 90 i / n, latitude 72 j / n degrees.
constexpr double kHemisphereReference = 0.0924;

struct HemisphereCase {
  int n = 8;
  double load_scale = 0.01;
  double rho = 1.0;
  // Lowest mode (rho 1, 8 x 8): half period 0.75 under a step load, omega_1 = 4.2 /s; damping
  // 8 /s is about critical for it.
  Settle settle{2.5, 6.5, 8.0};
};

double hemisphere(const Shell& shell, const HemisphereCase& c, QuasiStatic* out = nullptr) {
  constexpr double kR = 10.0;
  ShellPlate p;
  p.nx = p.ny = c.n;
  p.lx = 0.5 * kPi;
  p.ly = 72.0 * kPi / 180.0;
  p.place = [](double azimuth, double latitude) {
    return Eigen::Vector3d(kR * std::cos(latitude) * std::cos(azimuth),
                           kR * std::cos(latitude) * std::sin(azimuth), kR * std::sin(latitude));
  };
  std::string deck = "*KEYWORD\n" + p.text() + part(shell, 0.04, c.rho, 6.825e7, 0.3);
  std::vector<std::pair<int, DofFlags>> spc;
  for (int j = 0; j <= p.ny; ++j) {
    spc.push_back({p.node_id(0, j), {0, 1, 0, 1, 0, 1}});
    spc.push_back({p.node_id(p.nx, j), {1, 0, 0, 0, 1, 1}});
  }
  spc.push_back({p.node_id(p.nx / 2, 0), {0, 0, 1, 0, 0, 0}});
  deck += spc_cards(spc);
  deck += fmt::format("*LOAD_NODE_POINT\n{},1,1,{:.17g}\n{},2,1,{:.17g}\n", p.node_id(0, 0),
                      c.load_scale, p.node_id(p.nx, 0), -c.load_scale);
  deck += tail(c.settle);
  const QuasiStatic r = run_quasi_static(deck, p.node_id(0, 0), Eigen::Vector3d(1.0, 0.0, 0.0));
  if (out) *out = r;
  return r.value / (c.load_scale * kHemisphereReference);
}

// ---------------------------------------------------------------------------------------------
// Twisted beam (MacNeal & Harder 1985, the twisted beam): length 12, width 1.1, t 0.32, twisted 90
// degrees root to tip, E 29e6, nu 0.22, root clamped; unit load at the tip. The mid-surface is
// (x, s cos a, s sin a), a = 90 x / 12 degrees, s in [-0.55, 0.55]: the width lies along y at
// the root and along z at the tip. Load along z (the root's normal, in the tip's plane):
// 5.424e-3; along y (the root's width, normal to the tip): 1.754e-3, displacement of the tip
// centre along the load. The unit load is spread over the three tip nodes as 1/4, 1/2, 1/4.
// 12 x 2 elements as in the paper.
struct TwistedCase {
  int nx = 12, ny = 2;
  double rho = 7.3e-4;
  // Dynamic relaxation (see TwistedBeam below): DRFCTR 0.9985 is (1 - d dt) with d = 600 /s at
  // the step 2.4e-6 (steel density in lbf s^2 / in^4).
  Settle settle{0.0, 0.01, 0.0, 0.9985, 1e-6};
  double twist = 0.5 * kPi;
};

double twisted_beam(const Shell& shell, const TwistedCase& c, bool load_along_z,
                    QuasiStatic* out = nullptr) {
  constexpr double kLength = 12.0, kWidth = 1.1;
  ShellPlate p;
  p.nx = c.nx;
  p.ny = c.ny;
  p.lx = kLength;
  p.ly = kWidth;
  const double twist = c.twist;
  p.place = [twist](double x, double v) {
    const double a = twist * x / kLength, s = v - 0.5 * kWidth;
    return Eigen::Vector3d(x, s * std::cos(a), s * std::sin(a));
  };
  std::string deck = "*KEYWORD\n" + p.text() + part(shell, 0.32, c.rho, 29.0e6, 0.22);
  deck += node_set(1, p.column(0)) + "*BOUNDARY_SPC_SET\n1,0,1,1,1,1,1,1\n";
  if (std::getenv("MH_FIX_ROTATIONS")) {
    std::vector<int> all;
    for (int id = p.first_node; id < p.first_node + p.node_count(); ++id) all.push_back(id);
    deck += node_set(2, all) + "*BOUNDARY_SPC_SET\n2,0,0,0,0,1,1,1\n";
  }
  const int dof = load_along_z ? 3 : 2;
  for (int j = 0; j <= p.ny; ++j) {
    const double w = (j == 0 || j == p.ny) ? 0.5 / p.ny : 1.0 / p.ny;
    deck += fmt::format("*LOAD_NODE_POINT\n{},{},1,{:.17g}\n", p.node_id(p.nx, j), dof, w);
  }
  deck += tail(c.settle);
  const Eigen::Vector3d direction =
      load_along_z ? Eigen::Vector3d(0.0, 0.0, 1.0) : Eigen::Vector3d(0.0, 1.0, 0.0);
  const QuasiStatic r = run_quasi_static(deck, p.node_id(p.nx, p.ny / 2), direction);
  if (out) *out = r;
  return r.value / (load_along_z ? 5.424e-3 : 1.754e-3);
}

// ELFORM 2 with the stiffness hourglass control a user would pick for a static-like answer
// (IHQ 4, QM 0.1): the viscous default (IHQ 1) resists hourglass modes only while they move,
// so at rest they carry nothing (measured below and in docs/elements.md).
Shell elform2() {
  Shell s;
  s.elform = 2;
  s.ihq = 4;
  s.qm = 0.1;
  return s;
}

Shell elform16() {
  Shell s;
  s.elform = 16;
  return s;
}

// Scordelis-Lo roof, 8 x 8 on the quarter. Fully integrated with MITC4 shear: measured 0.9744
// (slightly stiff, as bilinear elements with full membrane integration are on this coarse mesh;
// the 4 x 4 mesh gives less, 16 x 16 more, docs/verification.md). The band [0.96, 0.99] keeps
// that, and excludes a membrane- or shear-locked answer (well below 0.9 on this mesh) and any
// soft mode (above 1).
TEST(MacNealHarder, ScordelisLoRoofElform16) {
  QuasiStatic r;
  const double v = scordelis_lo(elform16(), RoofCase{}, &r);
  report("Scordelis-Lo 8x8 ELFORM 16", r, v);
  expect_at_rest(r);
  EXPECT_GT(v, 0.96);
  EXPECT_LT(v, 0.99);
}

// The one-point element with IHQ 4, QM 0.1: measured 1.0631 (the hourglass stiffness holds 3 %
// of the strain energy). Band [1.04, 1.085]: without the hourglass stiffness (IHQ 1) the roof
// goes to 1.60, with a locked membrane it would be below 1. This pins today's value on this
// mesh only: the answer is set by QM (16 x 16: 1.247, 1.110, 1.039, 0.996 for QM 0.03, 0.1,
// 0.3, 1) and moves away from the reference on refinement (open, DISABLED_MeshRefinement: no
// drilling stiffness).
TEST(MacNealHarder, ScordelisLoRoofElform2) {
  QuasiStatic r;
  const double v = scordelis_lo(elform2(), RoofCase{}, &r);
  report("Scordelis-Lo 8x8 ELFORM 2 IHQ 4", r, v);
  expect_at_rest(r);
  EXPECT_GT(v, 1.04);
  EXPECT_LT(v, 1.085);
  EXPECT_LT(r.hourglass_ratio, 0.05);
}

// Pinched hemisphere, 8 x 8 on the quarter. ELFORM 16: measured 1.0034. This is the problem in
// which bilinear shells without assumed shear strains lock (normalised values of 0.1-0.5 on
// this mesh); band [0.99, 1.02].
TEST(MacNealHarder, PinchedHemisphereElform16) {
  QuasiStatic r;
  const double v = hemisphere(elform16(), HemisphereCase{}, &r);
  report("hemisphere 8x8 ELFORM 16", r, v);
  expect_at_rest(r);
  EXPECT_GT(v, 0.99);
  EXPECT_LT(v, 1.02);
}

// ELFORM 2 with IHQ 4, QM 0.1, brought to rest by dynamic relaxation, chosen when
// *DAMPING_GLOBAL still damped translations only and the shells' nodal spins of this doubly
// curved mesh kept ringing (drift 2e-3 of the answer over the last quarter of a 10 s run; the
// spins are damped now, docs/theory.md). DRFCTR 0.99935 is (1 - d dt)
// with d = 8.4 /s (critical for the lowest mode) at the step 7.7e-5; the transient that follows
// (3 s, two periods of that mode) must not move. Measured 1.0205 (hourglass energy 0.8 % of the
// strain energy). Band [1.005, 1.035]: the viscous default IHQ 1 gives 2.28 and does not come
// to rest (w hourglass under the point loads).
TEST(MacNealHarder, PinchedHemisphereElform2) {
  HemisphereCase c;
  c.settle = Settle{0.0, 3.0, 0.0, 0.99935, 1e-5};
  QuasiStatic r;
  const double v = hemisphere(elform2(), c, &r);
  report("hemisphere 8x8 ELFORM 2 IHQ 4, dynamic relaxation", r, v);
  expect_at_rest(r);
  EXPECT_GT(v, 1.005);
  EXPECT_LT(v, 1.035);
  EXPECT_LT(r.hourglass_ratio, 0.03);
}

// OPEN (docs/elements.md, "Open defects"): the twisted beam, 12 x 2, both loads, both
// formulations, against MacNeal & Harder's answers within 5 %. Brought to rest by dynamic
// relaxation (the ramped, damped run does not come to rest: the nodal spins ring). Measured
// today: ELFORM 16 57.9 (load along z) and 103.8 (along y) times the reference, ELFORM 2 BWC 1
// 105 and 184, ELFORM 2 BWC 2 2.28 and 2.07 (hourglass 93 and 84 %); the same mesh
// untwisted is right (1.2116 of 5.424e-3, i.e. P L^3 / (3 E I) within 1 %), and a twist of 2
// degrees in all already gives 8.5. Not the time step (TSSFAC 0.3 gives the same). The shells
// have no drilling stiffness: on the twisted mesh a node's rotation about one element's normal
// is an in-plane rotation of its neighbour, and the bending finds a path through these nearly
// free rotations (the eigen analysis, with its drilling penalty 1e-3 G t A, puts the first mode
// at 64.6 Hz; with 1e-6 G t A at 8.46 Hz, an eigenvalue 58 times lower).
TEST(MacNealHarder, DISABLED_TwistedBeamMatchesMacNealHarder) {
  Shell bwc = elform2();
  bwc.bwc = true;
  for (const Shell& s : {elform16(), elform2(), bwc}) {
    for (const bool along_z : {true, false}) {
      QuasiStatic r;
      const double v = twisted_beam(s, TwistedCase{}, along_z, &r);
      report(fmt::format("twisted beam ELFORM {}{} load along {}", s.elform, s.bwc ? " BWC 1" : "",
                         along_z ? "z" : "y")
                 .c_str(),
             r, v);
      expect_at_rest(r);
      EXPECT_NEAR(v, 1.0, 0.05);
    }
  }
}

// By hand (docs/verification.md has the numbers): the roof and the hemisphere on 4 x 4, 8 x 8
// and 16 x 16 quarter meshes, both formulations, as the tests above. The hemisphere's
// relaxation factor follows the step (which scales with the element size) to keep d = 8.4 /s.
// OPEN (docs/elements.md, "Open defects"): on 16 x 16 every answer should be within 3 % of the
// reference; ELFORM 2's roof is not (1.110, and 1.259 on 32 x 32; ELFORM 16 1.061 there): the
// missing drilling stiffness, which the eigen analysis of the same decks shows (its drilling
// penalty taken from 1e-3 to 1e-6 G t A lowers the first eigenvalue by the same factors).
TEST(MacNealHarder, DISABLED_MeshRefinement) {
  for (const int n : {4, 8, 16}) {
    for (const Shell& s : {elform16(), elform2()}) {
      RoofCase roof;
      roof.n = n;
      QuasiStatic r;
      double v = scordelis_lo(s, roof, &r);
      report(fmt::format("Scordelis-Lo {0}x{0} ELFORM {1}", n, s.elform).c_str(), r, v);
      if (n == 16) EXPECT_NEAR(v, 1.0, 0.03) << "roof ELFORM " << s.elform;
      HemisphereCase hemi;
      hemi.n = n;
      if (s.elform == 2) hemi.settle = Settle{0.0, 3.0, 0.0, 1.0 - 8.4 * 7.7e-5 * 8.0 / n, 1e-5};
      v = hemisphere(s, hemi, &r);
      report(fmt::format("hemisphere {0}x{0} ELFORM {1}", n, s.elform).c_str(), r, v);
      if (n == 16) EXPECT_NEAR(v, 1.0, 0.03) << "hemisphere ELFORM " << s.elform;
    }
  }
}

double env(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v ? std::atof(v) : fallback;
}

Settle settle_from_env(Settle s) {
  s.ramp = env("MH_RAMP", s.ramp);
  s.end = env("MH_END", s.end);
  s.damping = env("MH_DAMP", s.damping);
  s.drfctr = env("MH_DRFCTR", s.drfctr);
  s.drtol = env("MH_DRTOL", s.drtol);
  return s;
}

// By hand: MH_PROBLEM=roof|hemi|twz|twy MH_ELFORM MH_IHQ MH_QM MH_BWC MH_N MH_RAMP MH_END
// MH_DAMP ... rigidflex_verification_tests --gtest_also_run_disabled_tests
// --gtest_filter='*Explore*'.
TEST(MacNealHarder, DISABLED_Explore) {
  const std::string problem = std::getenv("MH_PROBLEM") ? std::getenv("MH_PROBLEM") : "roof";
  Shell s;
  s.elform = static_cast<int>(env("MH_ELFORM", 2));
  s.ihq = static_cast<int>(env("MH_IHQ", 4));
  s.qm = env("MH_QM", 0.1);
  s.bwc = env("MH_BWC", 0) != 0;
  s.tssfac = env("MH_TSSFAC", 0.0);
  QuasiStatic r;
  double v = 0.0;
  if (problem == "roof") {
    RoofCase c;
    c.n = static_cast<int>(env("MH_N", c.n));
    c.settle = settle_from_env(c.settle);
    v = scordelis_lo(s, c, &r);
  } else if (problem == "hemi") {
    HemisphereCase c;
    c.n = static_cast<int>(env("MH_N", c.n));
    c.settle = settle_from_env(c.settle);
    v = hemisphere(s, c, &r);
  } else {
    TwistedCase c;
    c.nx = static_cast<int>(env("MH_N", c.nx));
    c.ny = static_cast<int>(env("MH_NY", c.ny));
    c.settle = settle_from_env(c.settle);
    c.twist = env("MH_TWIST", 90.0) * kPi / 180.0;
    v = twisted_beam(s, c, problem == "twz", &r);
  }
  report(problem.c_str(), r, v);
}

}  // namespace
}  // namespace rf::test
