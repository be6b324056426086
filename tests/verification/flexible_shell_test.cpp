// Flexible rigid bodies made of shells (*PART_MODES on a *MAT_RIGID shell part; modes with
// rotational components, docs/flexible_bodies.md section 9), against references that do not
// come from the modal code:
// * the free-free bending of a shell strip: the body oscillates exactly at the eigenvalue of a
//   dense eigen solve of the kernel-probed stiffness (flexible_body_modes.hpp's method, with the
//   rotations), which itself lies within 3 % of the Euler-Bernoulli free-free frequency (the
//   explicit solver's scaled rotary inertia lowers it by 2.2 %);
//   momentum and angular momentum stay zero;
// * the seed paper's plate (003, section 4.1, option (i)): a plate whose corner elements are
//   deformable and carry the supports while the rest is a flexible body, struck by a short
//   transverse pulse at its centre. With every mode of the flexible part the centre deflection
//   equals the fully deformable linear-elastic run; with 10 / 40 / 100 modes the error of the
//   peak falls monotonically; energy ratio 1.
// Numbers quoted in docs/flexible_bodies.md and docs/verification.md.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "deck_builder.hpp"
#include "flexible_body_modes.hpp"
#include "modal/stiffness_assembly.hpp"
#include "model/error.hpp"
#include "shell_builder.hpp"
#include "solver/simulation.hpp"

namespace rf::test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRho = 7.8e-9;  // t/mm^3
constexpr double kE = 2.1e5;     // MPa

// All modes of part 1 of `deck` (free-free), densely from the kernel-probed K (drilling penalty
// of docs/eigen.md included) and the explicit solver's lumped mass and rotary inertia; the
// six lowest are flagged rigid.
modal::ModeSet dense_shell_modes(const std::string& deck) {
  const model::Model model = read(deck);
  const modal::StructuralMatrices sm =
      modal::assemble_structural_matrices(model, {1}, modal::RotaryInertia::kExplicit);
  const Eigen::MatrixXd k = Eigen::MatrixXd(sm.stiffness);
  const Eigen::MatrixXd ks = 0.5 * (k + k.transpose());
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(
      ks, sm.mass.asDiagonal().toDenseMatrix());
  const solver::NodalState& nodes = sm.state.nodes;
  const std::size_t n = nodes.size();
  const std::size_t r = sm.state.rotations.size();
  modal::ModeSet set;
  for (std::size_t i = 0; i < n; ++i) {
    set.node_ids.push_back(nodes.id[i]);
    set.node_parts.push_back(1);
    set.coordinates.push_back(nodes.x0.x[i]);
    set.coordinates.push_back(nodes.x0.y[i]);
    set.coordinates.push_back(nodes.x0.z[i]);
    set.mass.push_back(nodes.mass[i]);
  }
  for (std::size_t j = 0; j < r; ++j) {
    set.rotation_nodes.push_back(sm.state.rotations.node[j]);
    set.rotational_inertia.push_back(sm.mass[static_cast<Eigen::Index>(3 * n + 3 * j)]);
  }
  for (Eigen::Index m = 0; m < eig.eigenvalues().size(); ++m) {
    set.eigenvalues.push_back(eig.eigenvalues()[m]);
    set.generalized_mass.push_back(1.0);
    set.residual.push_back(0.0);
    set.rigid.push_back(m < 6 ? 1 : 0);
    const Eigen::VectorXd phi = eig.eigenvectors().col(m);
    for (std::size_t d = 0; d < 3 * n; ++d) set.shapes.push_back(phi[static_cast<Eigen::Index>(d)]);
    for (std::size_t d = 0; d < 3 * r; ++d) {
      set.rotation_shapes.push_back(phi[static_cast<Eigen::Index>(3 * n + d)]);
    }
  }
  set.rigid_mode_count = 6;
  return set;
}

std::string shell_section(int id, double thickness, int elform = 2) {
  return fmt::format("*SECTION_SHELL\n{0},{2},0.8333333333333334,2\n{1},{1},{1},{1}\n", id,
                     thickness, elform);
}

// ---------------------------------------------------------------------------------------
// Free-free strip, 200 x 20 x 2 mm, 20 x 2 shells, NU = 0 (EI = E b t^3 / 12 exactly).

struct StripDeck {
  ShellPlate plate() const {
    ShellPlate p;
    p.nx = 20;
    p.ny = 2;
    p.lx = 200.0;
    p.ly = 20.0;
    return p;
  }
  std::string text(bool rigid, const std::string& extra, double end, double dt) const {
    std::string d = "*KEYWORD\n" + plate().text() + "*PART\nstrip\n1,1,1,0,1\n" +
                    shell_section(1, 2.0) +
                    (rigid ? fmt::format("*MAT_RIGID\n1,{:.17g},{:.17g},0\n0,0,0\n", kRho, kE)
                           : fmt::format("*MAT_ELASTIC\n1,{:.17g},{:.17g},0\n", kRho, kE)) +
                    "*HOURGLASS\n1,4,0.05\n";
    if (rigid) d += "*PART_MODES\n1,12,0,0,3,0\nstrip_modes.h5\n";
    d += fmt::format("*CONTROL_TIMESTEP\n{:.17g},0.9\n*CONTROL_TERMINATION\n{:.17g},0\n", dt, end);
    return d + extra + "*END\n";
  }
};

TEST(FlexibleShell, FreeStripBendingModeOscillatesAtItsEigenfrequency) {
  const StripDeck strip;
  const modal::ModeSet modes = dense_shell_modes(strip.text(false, "", 1e-3, 0.0));
  // The first out-of-plane bending mode: the lowest elastic mode with z motion.
  std::size_t bending = 0;
  for (std::size_t m = 6; m < modes.mode_count() && bending == 0; ++m) {
    double z = 0.0, all = 0.0;
    for (std::size_t i = 0; i < modes.node_count(); ++i) {
      for (int d = 0; d < 3; ++d) {
        const double v = modes.mass[i] * std::pow(modes.shape(m)[3 * i + d], 2);
        all += v;
        if (d == 2) z += v;
      }
    }
    if (z > 0.5 * all) bending = m;
  }
  ASSERT_GT(bending, 5u);
  const double omega = std::sqrt(modes.eigenvalues[bending]);
  // Euler-Bernoulli free-free: (4.730)^2 sqrt(EI / (rho A L^4)).
  const double ei = kE * 20.0 * 8.0 / 12.0, rho_a = kRho * 20.0 * 2.0;
  const double omega_eb = std::pow(4.730040745, 2) * std::sqrt(ei / (rho_a * std::pow(200.0, 4)));
  std::printf("strip: first bending mode %zu, omega %.6f rad/s, Euler-Bernoulli %.6f (%+.3f %%)\n",
              bending + 1, omega, omega_eb, 100.0 * (omega / omega_eb - 1.0));
  // The explicit solver's scaled rotary inertia (the mass the body is integrated with) lowers
  // bending frequencies by O(element size), docs/eigen.md: -2.2 % here.
  EXPECT_NEAR(omega / omega_eb, 1.0, 0.03);

  // Initial velocity a * (phi, psi) of that mode at every node (translations and rotations).
  const double a = 2.0;  // modal velocity, sqrt(t) mm/s
  std::string velocities = "*INITIAL_VELOCITY_NODE\n";
  for (std::size_t i = 0; i < modes.node_count(); ++i) {
    const double* phi = modes.shape(bending) + 3 * i;
    double w[3] = {0.0, 0.0, 0.0};
    for (std::size_t j = 0; j < modes.rotation_count(); ++j) {
      if (static_cast<std::size_t>(modes.rotation_nodes[j]) != i) continue;
      for (int d = 0; d < 3; ++d) w[d] = modes.rotation_shape(bending)[3 * j + d];
    }
    velocities +=
        fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", modes.node_ids[i],
                    a * phi[0], a * phi[1], a * phi[2], a * w[0], a * w[1], a * w[2]);
  }
  const double period = 2.0 * kPi / omega;
  // A step of a tenth of the period (the element step is about 4e-6 s, 50 times smaller): the
  // modes are advanced by their exact flow.
  const double dt = period / 10.0;
  solver::SimulationOptions options;
  options.write_fields = false;
  options.mode_loader = [&](const std::filesystem::path&) { return modes; };
  solver::Simulation sim(read(strip.text(true, velocities, 3.05 * period, dt)), options);
  ASSERT_EQ(sim.rigid_bodies().flexible.size(), 1u);
  const modal::FlexibleBody& f = sim.rigid_bodies().flexible[0];
  EXPECT_EQ(f.rotation_count, modes.rotation_count());
  // The mode is recovered from translations and rotations together: s = a in it, 0 elsewhere.
  const std::size_t kept = bending - 6;
  ASSERT_LT(kept, f.mode_count);
  double others = 0.0;
  for (std::size_t m = 0; m < f.mode_count; ++m) {
    if (m != kept) others = std::max(others, std::abs(f.s[m]));
  }
  std::printf("strip: s %.12f (given %.1f), largest other %.2e\n", f.s[kept], a, others);
  EXPECT_NEAR(f.s[kept], a, 1e-9 * a);
  EXPECT_LT(others, 1e-9 * a);
  // The given field's momentum (zero up to the dense eigenvectors' round-off) is conserved.
  const double mass = kRho * 200.0 * 20.0 * 2.0;
  const double p_scale = a * std::sqrt(mass);
  double p0[3], h0[3];
  for (int d = 0; d < 3; ++d) {
    p0[d] = sim.energy().momentum[d];
    h0[d] = sim.energy().angular_momentum[d];
    EXPECT_LT(std::abs(p0[d]), 1e-8 * p_scale);
  }
  double worst = 0.0, drift = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    // After a cycle the state's time is t^{n+1} and q = q(t^{n+1}); the last cycle stops after
    // the velocity update (time t^n, q_previous = q(t^n)).
    const double t = sim.state().time;
    const double q = sim.finished() ? f.q_previous[kept] : f.q[kept];
    worst = std::max(worst, std::abs(q - a / omega * std::sin(omega * t)));
    for (int d = 0; d < 3; ++d) {
      drift = std::max(drift, std::abs(sim.energy().momentum[d] - p0[d]) / p_scale);
      drift =
          std::max(drift, std::abs(sim.energy().angular_momentum[d] - h0[d]) / (p_scale * 200.0));
    }
  }
  std::printf("strip: momentum and angular momentum drift %.2e of a sqrt(M) (and x L)\n", drift);
  EXPECT_LT(drift, 1e-13);
  std::printf(
      "strip: q vs a/w sin(w t) over %.2f periods: %.2e of the amplitude; energy ratio "
      "- 1 = %.2e\n",
      sim.state().time / period, worst * omega / a, sim.energy().ratio() - 1.0);
  EXPECT_LT(worst * omega / a, 1e-9);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-12);
}

// ---------------------------------------------------------------------------------------
// The seed's plate: 200 x 200 x 2 mm, 8 x 8 shells. Part 2 = the four corner elements
// (deformable, the plate's corner nodes pinned), part 1 = the rest, a flexible body (or
// deformable for the reference run). A transverse half-sine pulse of 1 ms at the centre node.

struct PlateDeck {
  static constexpr int kN = 8;
  static constexpr double kSize = 200.0;
  int elform = 2;  // of both parts
  int node(int i, int j) const { return 1 + i + (kN + 1) * j; }
  int centre() const { return node(kN / 2, kN / 2); }
  std::string text(bool flexible, int nmfb, int form, double end) const {
    std::string d = "*KEYWORD\n*NODE\n";
    for (int j = 0; j <= kN; ++j) {
      for (int i = 0; i <= kN; ++i) {
        d += fmt::format("{},{:.17g},{:.17g},0\n", node(i, j), kSize * i / kN, kSize * j / kN);
      }
    }
    d += "*ELEMENT_SHELL\n";
    int eid = 1;
    for (int j = 0; j < kN; ++j) {
      for (int i = 0; i < kN; ++i) {
        const bool corner = (i == 0 || i == kN - 1) && (j == 0 || j == kN - 1);
        d += fmt::format("{},{},{},{},{},{}\n", eid++, corner ? 2 : 1, node(i, j), node(i + 1, j),
                         node(i + 1, j + 1), node(i, j + 1));
      }
    }
    d += "*PART\nplate\n1,1,1,0,1\n" + shell_section(1, 2.0, elform) +
         (flexible ? fmt::format("*MAT_RIGID\n1,{:.17g},{:.17g},0.3\n0,0,0\n", kRho, kE)
                   : fmt::format("*MAT_ELASTIC\n1,{:.17g},{:.17g},0.3\n", kRho, kE)) +
         "*HOURGLASS\n1,4,0.05\n";
    if (elform != 2) d += shell_section(2, 2.0, elform);
    d += fmt::format("*PART\ncorners\n2,{},2,0,1\n", elform != 2 ? 2 : 1) +
         fmt::format("*MAT_ELASTIC\n2,{:.17g},{:.17g},0.3\n", kRho, kE);
    if (flexible) d += fmt::format("*PART_MODES\n1,{},{},0,3,0\nplate_modes.h5\n", nmfb, form);
    d += fmt::format("*SET_NODE_LIST\n1\n{},{},{},{}\n*BOUNDARY_SPC_SET\n1,0,1,1,1,0,0,0\n",
                     node(0, 0), node(kN, 0), node(0, kN), node(kN, kN));
    // Half-sine pulse of 1 ms, peak 20 N (about 0.1 mm of deflection: linear).
    d += "*DEFINE_CURVE\n1\n";
    for (int k = 0; k <= 20; ++k) {
      const double t = 1e-3 * k / 20.0;
      d += fmt::format("{:.17g},{:.17g}\n", t, std::sin(kPi * k / 20.0));
    }
    d += "0.5,0\n";
    d += fmt::format("*LOAD_NODE_POINT\n{},3,1,-20\n", centre());
    d += fmt::format("*CONTROL_TIMESTEP\n0,0.9\n*CONTROL_TERMINATION\n{:.17g},0\n", end);
    return d + "*END\n";
  }
};

struct PlateRun {
  std::vector<double> deflection;  // centre node z, every cycle
  double peak = 0.0;               // largest |z|
  double energy_ratio = 0.0;
};

PlateRun run_plate(const PlateDeck& plate, bool flexible, int nmfb, int form,
                   const modal::ModeSet* modes) {
  constexpr double kEnd = 4e-3;
  solver::SimulationOptions options;
  options.write_fields = false;
  if (modes) options.mode_loader = [modes](const std::filesystem::path&) { return *modes; };
  solver::Simulation sim(read(plate.text(flexible, nmfb, form, kEnd)), options);
  std::size_t centre = 0;
  for (std::size_t i = 0; i < sim.state().nodes.size(); ++i) {
    if (sim.state().nodes.id[i] == plate.centre()) centre = i;
  }
  PlateRun run;
  while (!sim.finished()) {
    sim.cycle();
    const double z = sim.state().nodes.x.z[centre];
    run.deflection.push_back(z);
    run.peak = std::max(run.peak, std::abs(z));
  }
  run.energy_ratio = sim.energy().ratio();
  return run;
}

// The flexible plate with each of `counts` modes (FORM 1) against the deformable run: the error
// of the centre deflection history never grows with the mode count, the energy balance closes,
// and with every mode (the last count) the flexible plate is the deformable one. Returns the RMS
// error per count.
std::vector<double> converge_to_deformable(const PlateDeck& plate, const modal::ModeSet& modes,
                                           const std::vector<int>& counts, const char* label) {
  const PlateRun reference = run_plate(plate, false, 0, 0, nullptr);
  std::printf(
      "%s: deformable peak centre deflection %.6f mm over %zu cycles, energy ratio - 1 = "
      "%.2e\n",
      label, reference.peak, reference.deflection.size(), reference.energy_ratio - 1.0);
  EXPECT_GT(reference.peak, 0.01);
  std::vector<double> errors;
  double previous_error = 1e30;
  for (const int count : counts) {
    const PlateRun run = run_plate(plate, true, count, 1, &modes);
    EXPECT_EQ(run.deflection.size(), reference.deflection.size());
    if (run.deflection.size() != reference.deflection.size()) return errors;
    double rms = 0.0;
    for (std::size_t c = 0; c < run.deflection.size(); ++c) {
      rms += std::pow(run.deflection[c] - reference.deflection[c], 2);
    }
    rms = std::sqrt(rms / static_cast<double>(run.deflection.size())) / reference.peak;
    std::printf(
        "%s: %3d modes: peak %.6f mm (%+.3f %%), RMS error of the history %.3e of the peak, "
        "energy ratio - 1 = %.2e\n",
        label, count, run.peak, 100.0 * (run.peak / reference.peak - 1.0), rms,
        run.energy_ratio - 1.0);
    EXPECT_NEAR(run.energy_ratio, 1.0, 1e-6) << count << " modes";
    EXPECT_LE(rms, previous_error * (1.0 + 1e-6))
        << count << " modes: the error must not grow with the mode count";
    previous_error = rms;
    errors.push_back(rms);
    if (count == counts.back()) {
      EXPECT_LT(std::abs(run.peak / reference.peak - 1.0), 2e-3);
      EXPECT_LT(rms, 3e-3);
    }
  }
  return errors;
}

TEST(FlexibleShell, SeedPlateWithDeformableCornersConvergesToTheDeformableRun) {
  const PlateDeck plate;
  // Modes of part 1 alone, free-free (the paper's two-step procedure): the eigen analysis sees
  // the *MAT_RIGID part as elastic with the card's RO, E, PR (modal::extract_parts).
  const modal::ModeSet modes = dense_shell_modes(plate.text(true, 10, 1, 1e-3));
  const int elastic = static_cast<int>(modes.mode_count()) - 6;
  // Modes 41 to 100 of this flat plate are in-plane and drilling modes that a transverse pulse
  // does not excite: 100 modes give the 40-mode error (docs/flexible_bodies.md).
  const std::vector<double> errors =
      converge_to_deformable(plate, modes, {10, 40, 100, elastic}, "plate");
  ASSERT_EQ(errors.size(), 4u);
  EXPECT_LT(errors[1], 0.5 * 1.642e-1);  // 40 modes: well below the 10-mode error
}

// The same plate of fully integrated shells (ELFORM 16: 2 x 2 points, MITC4 transverse shear, no
// hourglass control) in both parts: its own modes (kernel-probed stiffness of the ELFORM 16
// kernel), the flexible body with every mode equal to the deformable run, 40 modes between.
TEST(FlexibleShell, SeedPlateOfFullyIntegratedShellsConvergesToTheDeformableRun) {
  PlateDeck plate;
  plate.elform = 16;
  const modal::ModeSet modes = dense_shell_modes(plate.text(true, 10, 1, 1e-3));
  const int elastic = static_cast<int>(modes.mode_count()) - 6;
  EXPECT_EQ(converge_to_deformable(plate, modes, {10, 40, elastic}, "plate ELFORM 16").size(), 3u);
}

}  // namespace
}  // namespace rf::test
