// Centrifugal stiffening of a flexible body against the published rotating-cantilever
// reference (not from our code). A symmetric two-blade rotor (slender steel blades on a short,
// 1000x stiffer and heavier hub, all one *PART_MODES body with free-free modes of the whole
// rotor) spins freely about the axis through its hub and vibrates in its first symmetric
// flapwise mode (both blades out of the plane of rotation together). The heavy, stiff hub
// clamps the blades at hub radius r, so each blade is the classic rotating cantilever:
//
//   EI w'''' - (T(x) w')' + rho A w_tt = 0,   T(x) = rho A Omega^2 int_x^{r+L} s ds,
//
// whose first flapwise frequency rises as omega^2 = omega0^2 + K(gamma, r/L) Omega^2 (K: the
// Southwell coefficient, e.g. Putter & Manor, J. Sound Vib. 56(2) 175-185, 1978, eq. (1)).
// The reference values come from a 1-D Hermite-cubic solution of that equation written here,
// which first reproduces the published table for r = 0 (dimensionless frequency
// omega sqrt(rho A L^4 / EI) against gamma = Omega sqrt(rho A L^4 / EI): Wright, Smith,
// Thresher & Wang, J. Appl. Mech. 49 (1982) 197-202; Hodges & Rutkowski, AIAA J. 19 (1981)
// 1459-1466; Yoo & Shin, J. Sound Vib. 212 (1998) 807-828).
// FORM 0 (inertia coupling + the cubic strain-energy invariants) must follow the reference
// rise; FORM 1 (uncoupled modes) must show none. Numbers quoted in docs/flexible_bodies.md and
// docs/verification.md.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "deck_builder.hpp"
#include "flexible_body_modes.hpp"
#include "modal/eigen_analysis.hpp"
#include "modal/mode_set.hpp"
#include "solver/simulation.hpp"

namespace rf::test {
namespace {

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------
// 1-D reference: uniform Euler-Bernoulli cantilever clamped at radius r of a hub spinning at
// Omega, flapwise (out of the plane of rotation, so no centrifugal softening). Hermite cubic
// elements, consistent mass, the geometric stiffness int T N'^T N' dx by 3-point Gauss
// (T is quadratic). Dimensionless: EI = rho A = L = 1, delta = r / L. Returns the lowest
// dimensionless frequency lambda = omega sqrt(rho A L^4 / EI).
double rotating_cantilever_flap_frequency(double gamma, double delta, int elements = 60) {
  const int dofs = 2 * (elements + 1);
  Eigen::MatrixXd stiffness = Eigen::MatrixXd::Zero(dofs, dofs);
  Eigen::MatrixXd mass = Eigen::MatrixXd::Zero(dofs, dofs);
  const double h = 1.0 / elements;
  const double gauss_point[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double gauss_weight[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  for (int e = 0; e < elements; ++e) {
    Eigen::Matrix4d bending, consistent_mass, geometric = Eigen::Matrix4d::Zero();
    bending << 12, 6 * h, -12, 6 * h, 6 * h, 4 * h * h, -6 * h, 2 * h * h, -12, -6 * h, 12, -6 * h,
        6 * h, 2 * h * h, -6 * h, 4 * h * h;
    bending /= h * h * h;
    consistent_mass << 156, 22 * h, 54, -13 * h, 22 * h, 4 * h * h, 13 * h, -3 * h * h, 54, 13 * h,
        156, -22 * h, -13 * h, -3 * h * h, -22 * h, 4 * h * h;
    consistent_mass *= h / 420.0;
    for (int g = 0; g < 3; ++g) {
      const double xi = 0.5 * (gauss_point[g] + 1.0);
      const double x = (e + xi) * h;
      // T(x) / (rho A Omega^2 L^2) = delta (1 - x) + (1 - x^2) / 2
      const double tension = gamma * gamma * (delta * (1.0 - x) + 0.5 * (1.0 - x * x));
      Eigen::Vector4d slope;  // dN/dx of the four Hermite functions
      slope << 6.0 * (xi * xi - xi) / h, 1.0 - 4.0 * xi + 3.0 * xi * xi, 6.0 * (xi - xi * xi) / h,
          3.0 * xi * xi - 2.0 * xi;
      geometric += gauss_weight[g] * 0.5 * h * tension * slope * slope.transpose();
    }
    stiffness.block<4, 4>(2 * e, 2 * e) += bending + geometric;
    mass.block<4, 4>(2 * e, 2 * e) += consistent_mass;
  }
  // Clamped root: drop the two DOFs of node 0.
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(
      stiffness.bottomRightCorner(dofs - 2, dofs - 2), mass.bottomRightCorner(dofs - 2, dofs - 2));
  return std::sqrt(eig.eigenvalues()[0]);
}

// The published first flapwise frequencies of the rotating uniform cantilever, zero hub radius
// (Wright et al. 1982 table; the same values in Hodges & Rutkowski 1981 and Yoo & Shin 1998).
TEST(FlexibleSpin, RotatingCantileverReferenceReproducesPublishedTable) {
  const double gamma[] = {0, 1, 2, 3, 4, 5, 10};
  const double published[] = {3.5160, 3.6816, 4.1373, 4.7973, 5.5850, 6.4495, 11.2023};
  for (int k = 0; k < 7; ++k) {
    EXPECT_NEAR(rotating_cantilever_flap_frequency(gamma[k], 0.0), published[k], 1e-4)
        << "gamma " << gamma[k];
  }
  // The Southwell coefficient of the first mode at low spin: K -> 1.193 (r = 0); a hub radius
  // raises it by about 1.58 r / L (linear in r: the extra tension is proportional to r).
  const double l0 = rotating_cantilever_flap_frequency(0.0, 0.0);
  const double l1 = rotating_cantilever_flap_frequency(0.5, 0.0);
  EXPECT_NEAR((l1 * l1 - l0 * l0) / 0.25, 1.193, 2e-3);
}

// ---------------------------------------------------------------------------------------
// The rotor: x along the blades, y chord, z flap (thin direction). Spin about z through the
// centre. Hub: the middle kHubElements elements along x (part 2), blades: parts 1.
constexpr double kRho = 7850.0, kYoung = 2.0e11, kNu = 0.3;
constexpr double kHubFactor = 1000.0;  // hub E and rho: same wave speed, so the same step
constexpr int kBladeElements = 20, kHubElements = 4;
constexpr double kBladeLength = 1.0, kChord = 0.1, kThickness = 0.05;
constexpr double kElementLength = kBladeLength / kBladeElements;
constexpr double kHubRadius = 0.5 * kHubElements * kElementLength;

BoxMesh rotor_mesh() {
  BoxMesh mesh;
  mesh.nx = 2 * kBladeElements + kHubElements;
  mesh.ny = 2;
  mesh.nz = 2;
  mesh.lx = mesh.nx * kElementLength;
  mesh.ly = kChord;
  mesh.lz = kThickness;
  return mesh;
}

bool hub_element(int i) {
  return i >= kBladeElements && i < kBladeElements + kHubElements;
}

// Nodes and elements; elements of the hub are part 2.
std::string rotor_geometry(const BoxMesh& mesh) {
  std::string text = mesh.keyword_text(1);
  std::string out;
  std::size_t begin = 0;
  bool in_elements = false;
  int eid = 0;
  while (begin < text.size()) {
    const std::size_t end = text.find('\n', begin);
    std::string line = text.substr(begin, end - begin);
    begin = end + 1;
    if (line == "*ELEMENT_SOLID") {
      in_elements = true;
    } else if (in_elements) {
      // element eid (1-based) has x index (eid - 1) % nx
      const int i = eid % mesh.nx;
      ++eid;
      if (hub_element(i)) {
        const std::size_t comma = line.find(',');
        const std::size_t second = line.find(',', comma + 1);
        line = line.substr(0, comma + 1) + "2" + line.substr(second);
      }
    }
    out += line + "\n";
  }
  return out;
}

std::string controls(double end_time, double dt) {
  return fmt::format("*CONTROL_TIMESTEP\n{:.17g},0.9\n*CONTROL_TERMINATION\n{:.17g},0\n", dt,
                     end_time);
}

std::string deformable_rotor_deck(const std::string& extra, double end_time, double dt = 0.0,
                                  double hub_factor = kHubFactor) {
  return "*KEYWORD\n" + rotor_geometry(rotor_mesh()) +
         fmt::format(
             "*PART\nblades\n1,1,1\n*PART\nhub\n2,1,2\n*SECTION_SOLID\n1,2\n"
             "*MAT_ELASTIC\n1,{:.17g},{:.17g},{}\n*MAT_ELASTIC\n2,{:.17g},{:.17g},{}\n",
             kRho, kYoung, kNu, hub_factor * kRho, hub_factor * kYoung, kNu) +
         controls(end_time, dt) + extra + "*END\n";
}

// The whole rotor is one flexible body: blades (lead part 1) and hub (part 2) merged. The
// *MAT_RIGID E and PR of the lead part enter the geometric stiffening; the hub's strains are
// 1e-3 of the blades' so its share is negligible either way.
std::string flexible_rotor_deck(int nmfb, int form, const std::string& extra, double end_time,
                                double dt, double hub_factor = kHubFactor) {
  return "*KEYWORD\n" + rotor_geometry(rotor_mesh()) +
         fmt::format(
             "*PART\nblades\n1,1,1\n*PART\nhub\n2,1,2\n*SECTION_SOLID\n1,2\n"
             "*MAT_RIGID\n1,{:.17g},{:.17g},{}\n0,0,0\n"
             "*MAT_RIGID\n2,{:.17g},{:.17g},{}\n0,0,0\n"
             "*CONSTRAINED_RIGID_BODIES\n1,2\n",
             kRho, kYoung, kNu, hub_factor * kRho, kYoung, kNu) +
         fmt::format("*PART_MODES\n1,{},{},0,3,0\nrotor_modes.h5\n", nmfb, form) +
         controls(end_time, dt) + extra + "*END\n";
}

constexpr int kModeCount = 40;

const modal::ModeSet& rotor_modes() {
  static const modal::ModeSet modes = [] {
    modal::EigenRequest request;
    request.mode_count = kModeCount;
    request.remove_rigid_below = true;
    request.left_frequency = 1.0;
    return modal::compute_modes(read(deformable_rotor_deck("", 1e-3)), request);
  }();
  return modes;
}

// What a rotor mode is: its share of kinetic energy in z (flap) and its symmetry.
struct ModeClass {
  double flap = 0.0;       // share of the kinetic energy in z
  bool symmetric = false;  // invariant under the half turn about the spin axis
};

ModeClass classify(const modal::ModeSet& modes, std::size_t k) {
  const double* phi = modes.shape(k);
  double e[3] = {0, 0, 0};
  const std::size_t n = modes.node_count();
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) e[d] += modes.mass[i] * phi[3 * i + d] * phi[3 * i + d];
  }
  const double total = e[0] + e[1] + e[2];
  ModeClass c;
  c.flap = e[2] / total;
  // Half turn about z through the centre maps node (i, j, k) to (nx - i, ny - j, k) and the
  // displacement (ux, uy, uz) to (-ux, -uy, uz). Symmetric: phi maps onto itself.
  const BoxMesh mesh = rotor_mesh();
  double sym = 0.0, norm = 0.0;
  for (std::size_t r = 0; r < n; ++r) {
    const int id = modes.node_ids[r] - 1;
    const int i = id % (mesh.nx + 1), j = (id / (mesh.nx + 1)) % (mesh.ny + 1),
              kk = id / ((mesh.nx + 1) * (mesh.ny + 1));
    const int image = mesh.node_id(mesh.nx - i, mesh.ny - j, kk) - 1;
    std::size_t s = 0;
    while (modes.node_ids[s] - 1 != image) ++s;
    const double mapped[3] = {-phi[3 * s], -phi[3 * s + 1], phi[3 * s + 2]};
    for (int d = 0; d < 3; ++d) {
      sym += modes.mass[r] * phi[3 * r + d] * mapped[d];
      norm += modes.mass[r] * phi[3 * r + d] * phi[3 * r + d];
    }
  }
  c.symmetric = sym > 0.5 * norm;
  return c;
}

// *INITIAL_VELOCITY_NODE: spin about z through the centre plus the modal velocity a phi_k.
std::string initial_velocity(const modal::ModeSet& modes, std::size_t mode, double amplitude,
                             double spin) {
  const BoxMesh mesh = rotor_mesh();
  const Eigen::Vector3d centre(0.5 * mesh.lx, 0.5 * mesh.ly, 0.5 * mesh.lz);
  const Eigen::Vector3d w(0.0, 0.0, spin);
  std::string s = "*INITIAL_VELOCITY_NODE\n";
  const double* phi = modes.shape(mode);
  for (std::size_t i = 0; i < modes.node_count(); ++i) {
    const Eigen::Vector3d x(modes.coordinates[3 * i], modes.coordinates[3 * i + 1],
                            modes.coordinates[3 * i + 2]);
    const Eigen::Vector3d v =
        w.cross(x - centre) +
        amplitude * Eigen::Vector3d(phi[3 * i], phi[3 * i + 1], phi[3 * i + 2]);
    s += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", modes.node_ids[i], v.x(), v.y(), v.z());
  }
  return s;
}

// Nodes of the signal: the centre lines of both tips and of the hub (history nodes, so that a
// flexible body reconstructs them every cycle).
struct FlapNodes {
  int tip_a, tip_b, hub;
};

FlapNodes flap_nodes() {
  const BoxMesh mesh = rotor_mesh();
  return {mesh.node_id(0, 1, 1), mesh.node_id(mesh.nx, 1, 1), mesh.node_id(mesh.nx / 2, 1, 1)};
}

std::string history_cards() {
  const FlapNodes n = flap_nodes();
  return fmt::format("*DATABASE_HISTORY_NODE\n{},{},{}\n", n.tip_a, n.tip_b, n.hub);
}

// Angular frequency of the symmetric flap: mean z of the two tips relative to the hub, from
// its upward zero crossings (linear interpolation).
double symmetric_flap_frequency(solver::Simulation& sim) {
  const auto& nodes = sim.state().nodes;
  const FlapNodes ids = flap_nodes();
  std::size_t a = 0, b = 0, h = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes.id[i] == ids.tip_a) a = i;
    if (nodes.id[i] == ids.tip_b) b = i;
    if (nodes.id[i] == ids.hub) h = i;
  }
  const auto signal = [&] {
    return 0.5 * (nodes.x.z[a] + nodes.x.z[b]) - nodes.x.z[h] -
           (0.5 * (nodes.x0.z[a] + nodes.x0.z[b]) - nodes.x0.z[h]);
  };
  std::vector<double> crossings;
  double t_prev = sim.state().time, y_prev = signal();
  while (!sim.finished()) {
    sim.cycle();
    if (sim.finished()) break;
    const double t = sim.state().time, y = signal();
    if (y_prev < 0.0 && y >= 0.0)
      crossings.push_back(t_prev + (t - t_prev) * (-y_prev) / (y - y_prev));
    t_prev = t;
    y_prev = y;
  }
  if (crossings.size() < 2) return 0.0;
  return 2 * kPi * static_cast<double>(crossings.size() - 1) /
         (crossings.back() - crossings.front());
}

solver::SimulationOptions with_rotor_modes() {
  solver::SimulationOptions options;
  options.write_fields = false;
  options.mode_loader = [](const std::filesystem::path&) { return rotor_modes(); };
  return options;
}

// The first symmetric flapwise mode: both blades out of the plane of rotation together.
std::size_t first_symmetric_flap_mode(const modal::ModeSet& modes) {
  for (std::size_t k = 0; k < modes.mode_count(); ++k) {
    const ModeClass c = classify(modes, k);
    if (c.symmetric && c.flap > 0.9) return k;
  }
  return modes.mode_count();
}

// FORM 0 follows the reference rise of the Southwell coefficient K = (omega^2 - omega0^2) /
// Omega^2 (omega0: the rotor's own non-rotating eigenfrequency; absolute frequencies are not
// compared: the 2-element-thick ELFORM 2 blade is 15 % stiffer in bending than Euler-Bernoulli,
// which shifts omega0 but not the centrifugal term). Measured: within 0.5 % at Omega = 0.3, 0.6
// and 1.0 omega0. Tolerance 1.5 %: 3-D blade vs Euler-Bernoulli (shear, rotary inertia, h/L =
// 1/20: O(0.3 %)), the finite hub (1000x), the stretch carried by the two symmetric axial
// modes among the 40 kept, and the impulse splitting's quasi-static factor
// (theta/2) cot(theta/2) = 0.9986 on the axial stretch (theta = w_axial dt = 0.13). It catches
// a missing hub-radius term (K 1.19 instead of 1.34: -11 %), a factor error in the cubic
// invariants and missing stiffening (K = 0). With 16 modes (one axial mode) the stretch is
// represented less well: K about 2 % low, converging from below. FORM 1 (uncoupled modes)
// stays at omega0. The fully deformable run (geometrically nonlinear hexahedra, same mesh) at
// 0.6 omega0 agrees with both.
TEST(FlexibleSpin, RotorFlapStiffensAsRotatingCantilever) {
  const auto& modes = rotor_modes();
  const std::size_t flap = first_symmetric_flap_mode(modes);
  ASSERT_EQ(flap, 0u);
  const double w0 = std::sqrt(modes.eigenvalues[flap]);
  // gamma = Omega sqrt(rho A L^4 / EI), I = b h^3 / 12 (flapwise)
  const double gamma_per_spin =
      kBladeLength * kBladeLength * std::sqrt(12.0 * kRho / (kYoung * kThickness * kThickness));
  const double delta = kHubRadius / kBladeLength;
  const double lambda0 = rotating_cantilever_flap_frequency(0.0, delta);
  std::printf(
      "rotor: symmetric flap mode %.2f rad/s (Euler-Bernoulli cantilever %.2f), "
      "r/L %.2f\n",
      w0, lambda0 / gamma_per_spin, delta);
  // Tip amplitude about 0.5 mm (h / 100): linear flap.
  const double amplitude = 0.5e-3 * w0 / std::abs(modes.shape(flap)[2]);
  solver::Simulation probe(read(deformable_rotor_deck("", 1e-3)), {});
  const double dt_deformable = probe.state().dt;
  // The modes do not limit the step (docs/flexible_bodies.md section 3): 4 x the element step.
  const double dt_flexible = 4.0 * dt_deformable;
  for (const double ratio : {0.3, 0.6, 1.0}) {
    const double spin = ratio * w0;
    const double gamma = spin * gamma_per_spin;
    const double lambda = rotating_cantilever_flap_frequency(gamma, delta);
    const double k_ref = (lambda * lambda - lambda0 * lambda0) / (gamma * gamma);
    const double end = 6.0 * 2 * kPi / w0;
    const std::string extra = initial_velocity(modes, flap, amplitude, spin) + history_cards();
    const auto southwell = [&](double w) { return (w * w - w0 * w0) / (spin * spin); };
    double w_form[2];
    for (const int form : {0, 1}) {
      solver::Simulation flexible(
          read(flexible_rotor_deck(kModeCount, form, extra, end, dt_flexible)), with_rotor_modes());
      w_form[form] = symmetric_flap_frequency(flexible);
    }
    solver::Simulation sixteen(read(flexible_rotor_deck(16, 0, extra, end, dt_flexible)),
                               with_rotor_modes());
    const double w_sixteen = symmetric_flap_frequency(sixteen);
    std::printf(
        "spin %.1f w0 (gamma %.3f): w/w0 reference %.4f, FORM 0 %.4f (16 modes %.4f), "
        "FORM 1 %.4f; K reference %.4f, FORM 0 %.4f (%+.2f %%, 16 modes %.4f), FORM 1 "
        "%.4f\n",
        ratio, gamma, std::sqrt(1.0 + k_ref * ratio * ratio), w_form[0] / w0, w_sixteen / w0,
        w_form[1] / w0, k_ref, southwell(w_form[0]), 100 * (southwell(w_form[0]) / k_ref - 1),
        southwell(w_sixteen), southwell(w_form[1]));
    EXPECT_NEAR(southwell(w_form[0]), k_ref, 0.015 * k_ref) << "spin " << ratio;
    EXPECT_NEAR(w_form[1], w0, 1e-3 * w0) << "spin " << ratio;
    EXPECT_LT(southwell(w_sixteen), southwell(w_form[0]));
    EXPECT_NEAR(southwell(w_sixteen), k_ref, 0.04 * k_ref);
    if (ratio == 0.6) {
      solver::Simulation deformable(read(deformable_rotor_deck(extra, end, dt_deformable)), {});
      const double w_deformable = symmetric_flap_frequency(deformable);
      std::printf("  deformable w/w0 %.4f, K %.4f (%+.2f %%)\n", w_deformable / w0,
                  southwell(w_deformable), 100 * (southwell(w_deformable) / k_ref - 1));
      EXPECT_NEAR(southwell(w_deformable), k_ref, 0.015 * k_ref);
      EXPECT_NEAR(southwell(w_form[0]), southwell(w_deformable), 0.01 * southwell(w_deformable));
    }
  }
}

// ---------------------------------------------------------------------------------------
// Prescribed spin-up (the profile of Kane, Ryan & Banerjee, J. Guidance 10(2) 139-151, 1987:
// Omega(t) = Omega_s / T_s (t - T_s / (2 pi) sin(2 pi t / T_s)), then Omega_s), scaled to the
// rotor: Omega_s = 1.58 and T_s = 57 / omega_c in units of the first symmetric chordwise
// (in-plane) frequency omega_c, as for their 10 m beam (omega_c = 3.80 rad/s, Omega_s = 6 rad/s,
// T_s = 15 s). The spin passes the chordwise frequency, where the in-plane motion of a model
// without stiffening diverges. Here it checks the Coriolis coupling of the chordwise and the
// axial stretch modes: taken explicitly (velocities before the kick) it drove the chordwise tip
// to a spurious +23 mm that did not come back; taken at the kick's midpoint (gyroscopic, no
// work) FORM 0 stays within about 1.2 mm and returns to zero. FORM 1 (no inertia terms) does
// not move. Not compared with the published curve (not available to us) nor with the
// hub-driven deformable run: *BOUNDARY_PRESCRIBED_MOTION_RIGID drives the body frame (mean
// axes), whose angular acceleration loads no mode (mean-axis conditions), while the published
// problem drives the hub (the deformable run with a rigid hub lags by up to 61 mm and comes
// back to about 1 mm). See docs/flexible_bodies.md, "What is left".
constexpr double kSpinUpHubFactor = 1.0e5;  // hub inertia 100 x the blades': mean axes ~ hub

const modal::ModeSet& spin_up_modes() {
  static const modal::ModeSet modes = [] {
    modal::EigenRequest request;
    request.mode_count = kModeCount;
    request.remove_rigid_below = true;
    request.left_frequency = 1.0;
    return modal::compute_modes(read(deformable_rotor_deck("", 1e-3, 0.0, kSpinUpHubFactor)),
                                request);
  }();
  return modes;
}

// Load curve 1: the spin-up profile, 400 samples, then constant.
std::string spin_up_curve(double spin, double ramp, double end) {
  std::string s = "*DEFINE_CURVE\n1\n";
  const int samples = 400;
  for (int k = 0; k <= samples; ++k) {
    const double t = ramp * k / samples;
    s += fmt::format("{:.17g},{:.17g}\n", t,
                     spin / ramp * (t - ramp / (2 * kPi) * std::sin(2 * kPi * t / ramp)));
  }
  s += fmt::format("{:.17g},{:.17g}\n", 2 * end + ramp, spin);
  return s;
}

// Largest chordwise tip deflection in the hub frame (hub angle from the hub's two end nodes on
// the centre line, the tip rotated back by it), over the run and over its last third.
struct ChordwiseTip {
  double peak = 0.0, late = 0.0;
};

ChordwiseTip chordwise_tip(solver::Simulation& sim, double end) {
  const BoxMesh mesh = rotor_mesh();
  const auto& nodes = sim.state().nodes;
  const int ids[3] = {mesh.node_id(kBladeElements, 1, 1),
                      mesh.node_id(kBladeElements + kHubElements, 1, 1),
                      mesh.node_id(mesh.nx, 1, 1)};
  std::size_t index[3] = {0, 0, 0};
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (nodes.id[i] == ids[k]) index[k] = i;
    }
  }
  ChordwiseTip tip;
  while (!sim.finished()) {
    sim.cycle();
    if (sim.finished()) break;
    const double lag = std::abs(offset_across_hub_axis(nodes, index[0], index[1], index[2]));
    tip.peak = std::max(tip.peak, lag);
    if (sim.state().time > 2.0 / 3.0 * end) tip.late = std::max(tip.late, lag);
  }
  return tip;
}

TEST(FlexibleSpin, PrescribedSpinUpPastTheChordwiseFrequencyStaysBounded) {
  const auto& modes = spin_up_modes();
  std::size_t chord = modes.mode_count();
  for (std::size_t k = 0; k < modes.mode_count() && chord == modes.mode_count(); ++k) {
    const ModeClass c = classify(modes, k);
    if (c.symmetric && c.flap < 0.1) chord = k;
  }
  ASSERT_LT(chord, modes.mode_count());
  const double omega_c = std::sqrt(modes.eigenvalues[chord]);
  const double spin = 1.58 * omega_c, ramp = 57.0 / omega_c, end = 1.6 * ramp;
  solver::Simulation probe(read(deformable_rotor_deck("", 1e-3)), {});
  const double dt = 4.0 * probe.state().dt;
  const BoxMesh mesh = rotor_mesh();
  const std::string cards =
      spin_up_curve(spin, ramp, end) + "*BOUNDARY_PRESCRIBED_MOTION_RIGID\n1,7,0,1,1.0\n" +
      fmt::format("*DATABASE_HISTORY_NODE\n{},{},{}\n", mesh.node_id(kBladeElements, 1, 1),
                  mesh.node_id(kBladeElements + kHubElements, 1, 1), mesh.node_id(mesh.nx, 1, 1));
  ChordwiseTip tip[2];
  for (const int form : {0, 1}) {
    solver::SimulationOptions options;
    options.write_fields = false;
    options.mode_loader = [](const std::filesystem::path&) { return spin_up_modes(); };
    solver::Simulation flexible(
        read(flexible_rotor_deck(kModeCount, form, cards, end, dt, kSpinUpHubFactor)), options);
    tip[form] = chordwise_tip(flexible, end);
    // The prescribed spin is reached (the frame follows the curve).
    const auto& body = flexible.rigid_bodies().bodies.at(
        static_cast<std::size_t>(flexible.rigid_bodies().flexible.at(0).body));
    EXPECT_NEAR(body.state.angular_velocity.z(), spin, 1e-6 * spin);
  }
  std::printf(
      "spin-up to %.1f rad/s = 1.58 omega_c (%.2f rad/s) in %.4f s: chordwise tip "
      "FORM 0 peak %.3e m, last third %.3e m; FORM 1 peak %.1e m\n",
      spin, omega_c, ramp, tip[0].peak, tip[0].late, tip[1].peak);
  EXPECT_LT(tip[0].peak, 2e-3);
  EXPECT_LT(tip[0].late, 5e-5);
  EXPECT_LT(tip[1].peak, 1e-12);
}

}  // namespace
}  // namespace rf::test
