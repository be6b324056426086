// Part switching of a deformable part named by *PART_MODES (a flexible body while rigid),
// against references that do not come from the modal or switching code: the eigenvalues and
// modes of a dense eigen solve of the mesh's stiffness (flexible_body_modes.hpp), the exact
// eigen-vibration of a linear elastic body, and conservation laws. Numbers quoted in
// docs/flexible_bodies.md section 6 and docs/verification.md.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "deck_builder.hpp"
#include "flexible_body_modes.hpp"
#include "model/error.hpp"

namespace rf::test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRho = kSteelDensity, kYoung = kSteelYoung, kNu = kSteelPoisson;

BoxMesh beam() {
  return steel_beam_mesh();
}

// ELFORM 2, or ELFORM 1 with the stiffness hourglass control IHQ 4 (both linear elastic).
int hourglass_of(int elform) {
  return elform == 1 ? 4 : 1;
}

std::string deck(const std::string& extra, double end_time, double dtinit, int nmfb, int form,
                 int elform = 2) {
  return "*KEYWORD\n" + beam().keyword_text() +
         elastic_part(kRho, kYoung, kNu, elform, hourglass_of(elform)) +
         fmt::format("*PART_MODES\n1,{},{},0,3,0\nbeam_modes.h5\n", nmfb, form) +
         fmt::format("*CONTROL_TIMESTEP\n{:.17g},0.9\n*CONTROL_TERMINATION\n{:.17g},0\n", dtinit,
                     end_time) +
         extra + "*END\n";
}

// The dense modes of the beam with the element formulation the run uses, computed once each.
const modal::ModeSet& beam_modes(int elform = 2) {
  auto compute = [](int e) {
    solver::Simulation sim(read("*KEYWORD\n" + beam().keyword_text() +
                                elastic_part(kRho, kYoung, kNu, e, hourglass_of(e)) +
                                "*CONTROL_TERMINATION\n1e-3,0\n*END\n"),
                           {});
    return dense_modes(sim, dense_stiffness(sim));
  };
  if (elform == 1) {
    static const modal::ModeSet modes = compute(1);
    return modes;
  }
  static const modal::ModeSet modes = compute(2);
  return modes;
}

solver::SimulationOptions with_modes(int elform = 2) {
  solver::SimulationOptions options;
  options.write_fields = false;
  options.mode_loader = [elform](const std::filesystem::path&) { return beam_modes(elform); };
  return options;
}

// *INITIAL_VELOCITY_NODE: v0 + w0 x x + a phi_k (database mode k, 0-based) at every node.
std::string initial_velocity(int mode, double a, const Eigen::Vector3d& v0,
                             const Eigen::Vector3d& w0, int elform = 2) {
  const auto& modes = beam_modes(elform);
  std::string s = "*INITIAL_VELOCITY_NODE\n";
  const double* phi = modes.shape(static_cast<std::size_t>(mode));
  for (std::size_t i = 0; i < modes.node_count(); ++i) {
    const Eigen::Vector3d x(modes.coordinates[3 * i], modes.coordinates[3 * i + 1],
                            modes.coordinates[3 * i + 2]);
    const Eigen::Vector3d v =
        v0 + w0.cross(x) + a * Eigen::Vector3d(phi[3 * i], phi[3 * i + 1], phi[3 * i + 2]);
    s += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", modes.node_ids[i], v.x(), v.y(), v.z());
  }
  return s;
}

// Modal amplitude of database mode k in the nodal field u (3 per node): phi_k^T M u.
double project(int mode, const std::vector<double>& u, int elform = 2) {
  const auto& modes = beam_modes(elform);
  const double* phi = modes.shape(static_cast<std::size_t>(mode));
  double sum = 0.0;
  for (std::size_t i = 0; i < modes.node_count(); ++i) {
    for (int d = 0; d < 3; ++d) sum += modes.mass[i] * phi[3 * i + d] * u[3 * i + d];
  }
  return sum;
}

Eigen::Vector3d momentum(const solver::Simulation& sim) {
  const auto& e = sim.energy();
  return {e.momentum[0], e.momentum[1], e.momentum[2]};
}
Eigen::Vector3d angular_momentum(const solver::Simulation& sim) {
  const auto& e = sim.energy();
  return {e.angular_momentum[0], e.angular_momentum[1], e.angular_momentum[2]};
}

// Momenta and kinetic energy of the free nodes (x^n, v^{n-1/2}), and the kinetic energy of
// the velocity field that no rigid motion with those momenta carries (the test's own least-
// squares rigid fit).
struct NodalMotion {
  Eigen::Vector3d p = Eigen::Vector3d::Zero(), h = Eigen::Vector3d::Zero();
  double kinetic = 0.0, non_rigid = 0.0;
};
NodalMotion nodal_motion(const solver::State& s) {
  NodalMotion out;
  double mass = 0.0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  const auto& n = s.nodes;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const Eigen::Vector3d x(n.x.x[i], n.x.y[i], n.x.z[i]), v(n.v.x[i], n.v.y[i], n.v.z[i]);
    out.p += n.mass[i] * v;
    out.h += x.cross(n.mass[i] * v);
    out.kinetic += 0.5 * n.mass[i] * v.squaredNorm();
    mass += n.mass[i];
    c += n.mass[i] * x;
  }
  c /= mass;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < n.size(); ++i) {
    const Eigen::Vector3d r = Eigen::Vector3d(n.x.x[i], n.x.y[i], n.x.z[i]) - c;
    inertia += n.mass[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  const Eigen::Vector3d vc = out.p / mass;
  const Eigen::Vector3d w = inertia.ldlt().solve(out.h - c.cross(out.p));
  out.non_rigid = out.kinetic - 0.5 * mass * vc.squaredNorm() - 0.5 * w.dot(inertia * w);
  return out;
}

// ---------------------------------------------------------------------------------------
// (i) A deformable part with *PART_MODES switched rigid at the start is a flexible body: the
// initial modal velocities are recovered from the nodal field, the modes oscillate at the
// dense eigenfrequencies, the energy ratio is 1 and the momenta are constant.

TEST(SwitchingFlexible, SwitchedRigidAtStartMovesAsAFlexibleBody) {
  const auto& modes = beam_modes();
  const double w7 = std::sqrt(modes.eigenvalues[6]);
  const double a7 = 0.05;  // modal velocity (sqrt(kg) m/s)
  const Eigen::Vector3d v0(2.0, -1.0, 0.5), w0(0.0, 0.0, 0.0);
  const double end = 10.0 * 2.0 * kPi / w7, dt = 2e-6;
  solver::Simulation sim(
      read(deck(initial_velocity(6, a7, v0, w0) + "*DEFORMABLE_TO_RIGID\n1\n", end, dt, 14, 0)),
      with_modes());
  ASSERT_EQ(sim.rigid_bodies().flexible.size(), 1u);
  const auto& f = sim.rigid_bodies().flexible[0];
  EXPECT_EQ(f.file_modes[0], 7);
  EXPECT_NEAR(f.s[0], a7, 1e-10 * a7);
  for (std::size_t k = 1; k < f.mode_count; ++k) EXPECT_NEAR(f.s[k], 0.0, 1e-10 * a7);
  // Nothing but the modes' share was non-rigid: no switch energy (round-off of the whole
  // kinetic energy, 309 J).
  EXPECT_NEAR(sim.energy().switch_energy, 0.0, 1e-14 * sim.energy().kinetic);
  const Eigen::Vector3d p0 = momentum(sim), h0 = angular_momentum(sim);
  std::vector<double> t, q7;
  double worst_ratio = 0.0, worst_p = 0.0, worst_h = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    if (sim.finished()) break;
    t.push_back(sim.state().time);
    q7.push_back(sim.rigid_bodies().flexible[0].q[0]);
    worst_ratio = std::max(worst_ratio, std::abs(sim.energy().ratio() - 1.0));
    worst_p = std::max(worst_p, (momentum(sim) - p0).norm() / p0.norm());
    worst_h = std::max(worst_h, (angular_momentum(sim) - h0).norm() / h0.norm());
  }
  const double f7 = zero_crossing_frequency(t, q7);
  std::printf("D2R at start: f7 %.6f Hz (dense eigen %.6f), |ratio - 1| %.2e, dP %.2e, dH %.2e\n",
              f7, w7 / (2 * kPi), worst_ratio, worst_p, worst_h);
  EXPECT_NEAR(f7, w7 / (2 * kPi), 1e-5 * w7 / (2 * kPi));
  EXPECT_LT(worst_ratio, 1e-12);
  EXPECT_LT(worst_p, 1e-13);
  EXPECT_LT(worst_h, 1e-12);
}

// ---------------------------------------------------------------------------------------
// (ii) A flexible body (all 291 elastic modes) vibrating in mode 7 and translating is switched
// to deformable (ELFORM 2) at t_s: the elastic beam goes on vibrating in the same eigenmode at
// the same frequency and amplitude (q(t) = a / w sin(w t), the exact eigen-vibration), the
// total energy is continuous (the modal elastic energy became element strain energy; the
// switch books almost nothing), and P, H are continuous to round-off.

class SwitchingFlexibleRelease : public testing::TestWithParam<int> {};

TEST_P(SwitchingFlexibleRelease, VibratingFlexibleBodyKeepsVibratingInTheSameMode) {
  const int elform = GetParam();
  const auto& modes = beam_modes(elform);
  const double w7 = std::sqrt(modes.eigenvalues[6]);
  const double a7 = 0.05;
  const double period = 2.0 * kPi / w7;
  const Eigen::Vector3d v0(1.0, 0.5, -0.25);
  const double t_switch = 2.3 * period, end = 8.0 * period;
  const std::string switching =
      "*DEFORMABLE_TO_RIGID\n1\n" +
      fmt::format("*DEFORMABLE_TO_RIGID_AUTOMATIC\n20,0,{:.17g},0,0,0,0,0\n0,0,0,0,0,1\n1\n",
                  t_switch);
  solver::Simulation sim(
      read(deck(initial_velocity(6, a7, v0, Eigen::Vector3d::Zero(), elform) + switching, end, 2e-6,
                291, 1, elform)),
      with_modes(elform));
  ASSERT_EQ(sim.rigid_bodies().flexible.size(), 1u);
  const Eigen::Vector3d p0 = momentum(sim), h0 = angular_momentum(sim);
  const double e0 = sim.energy().total();
  const auto& n = sim.state().nodes;
  std::vector<double> u(3 * n.size());
  std::vector<double> t, q7;
  double worst_q = 0.0, worst_other = 0.0, worst_ratio = 0.0, worst_p = 0.0, worst_h = 0.0;
  double switch_energy = 0.0, dt_after = 0.0, t_top = 0.0, dt_top = 0.0;
  bool released = false;
  while (!sim.finished()) {
    if (!released) {
      t_top = sim.state().time;  // t^n of the cycle that may switch, and the step before it
      dt_top = sim.state().dt_prev;
    }
    sim.cycle();
    if (sim.finished()) break;
    const double time = sim.state().time;
    worst_p = std::max(worst_p, (momentum(sim) - p0).norm() / p0.norm());
    worst_h = std::max(worst_h, (angular_momentum(sim) - h0).norm() / h0.norm());
    worst_ratio = std::max(worst_ratio, std::abs(sim.energy().ratio() - 1.0));
    if (sim.rigid_bodies().flexible.empty()) {
      if (!released) {
        released = true;
        switch_energy = sim.energy().switch_energy;
        dt_after = sim.state().dt;
      }
      // Displacement relative to the translating reference: the modal amplitudes.
      for (std::size_t i = 0; i < n.size(); ++i) {
        u[3 * i] = n.x.x[i] - n.x0.x[i] - v0.x() * time;
        u[3 * i + 1] = n.x.y[i] - n.x0.y[i] - v0.y() * time;
        u[3 * i + 2] = n.x.z[i] - n.x0.z[i] - v0.z() * time;
      }
      t.push_back(time);
      q7.push_back(project(6, u, elform));
      worst_q = std::max(worst_q, std::abs(q7.back() - a7 / w7 * std::sin(w7 * time)));
      for (const int other : {7, 8, 12}) {
        worst_other = std::max(worst_other, std::abs(project(other, u, elform)));
      }
    }
  }
  ASSERT_TRUE(released);
  const double f7 = zero_crossing_frequency(t, q7);
  const double amplitude = a7 / w7;
  // The exact flexible-phase vibration q = a/w sin(w t) at the switch: elastic energy
  // 1/2 w^2 q^2 must become element strain energy; the kinetic energy 1/2 s(t^n)^2 becomes the
  // nodes' 1/2 s_half^2 with the secant s_half = (q^n - q^{n-1}) / dt (the leapfrog's v^{n-1/2}).
  const double elastic = 0.5 * a7 * a7 * std::pow(std::sin(w7 * t_top), 2);
  const double s_half =
      amplitude * (std::sin(w7 * t_top) - std::sin(w7 * (t_top - dt_top))) / dt_top;
  const double offset = 0.5 * a7 * a7 * std::pow(std::cos(w7 * t_top), 2) - 0.5 * s_half * s_half;
  const auto& events = sim.switch_events();
  ASSERT_EQ(events.size(), 2u);
  const auto& release = events[1];
  std::printf(
      "ELFORM %d, R2D: modal elastic %.9e (exact %.9e), strain energy restored %.9e (%.2e "
      "relative); "
      "switch energy %.6e, predicted half-step kinetic offset %.6e\n",
      elform, release.modal_elastic_released, elastic, release.strain_energy_restored,
      release.strain_energy_restored / release.modal_elastic_released - 1.0, switch_energy, offset);
  EXPECT_NEAR(release.modal_elastic_released, elastic, 1e-9 * 0.5 * a7 * a7);
  EXPECT_NEAR(release.strain_energy_restored, elastic, 1e-6 * elastic);
  EXPECT_NEAR(switch_energy, offset, 1e-6 * 0.5 * a7 * a7);
  std::printf(
      "ELFORM %d, R2D of a vibrating flexible body: switch %.4f periods, dt after %.3g (w dt "
      "%.3f); f7 "
      "%.6f Hz (eigen %.6f), |q7 - exact| max %.2e of the amplitude, other modes %.2e, switch "
      "energy %.2e of the vibration energy, |ratio - 1| %.2e, |E - E0| / E0 %.2e, dP %.2e, "
      "dH %.2e\n",
      elform, t_switch / period, dt_after, w7 * dt_after, f7, w7 / (2 * kPi), worst_q / amplitude,
      worst_other / amplitude, switch_energy / (0.5 * a7 * a7), worst_ratio,
      std::abs(sim.energy().total() - e0) / e0, worst_p, worst_h);
  // The leapfrog's own phase error over 5.7 periods at w dt ~ 0.03 is ~1e-3 of the amplitude.
  EXPECT_LT(worst_q, 5e-3 * amplitude);
  EXPECT_LT(worst_other, 1e-3 * amplitude);
  EXPECT_NEAR(f7, w7 / (2 * kPi), 1e-3 * w7 / (2 * kPi));
  EXPECT_LT(worst_ratio, 1e-9);
  EXPECT_LT(worst_p, 1e-12);
  EXPECT_LT(worst_h, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(SwitchingFlexible, SwitchingFlexibleRelease, testing::Values(2, 1),
                         [](const testing::TestParamInfo<int>& p) {
                           return "Elform" + std::to_string(p.param);
                         });

// ---------------------------------------------------------------------------------------
// (iii) A deformable beam translating, spinning and vibrating in eigenmode 7 is switched rigid
// at t_s (automatic D2R): P and H are conserved across the switch; the modal energy after the
// switch is the non-rigid kinetic energy the test computes from the nodes (nearly all of it in
// mode 7), the rest is switch energy.

TEST(SwitchingFlexible, VibratingDeformablePartSwitchedRigidKeepsItsVibrationInTheModes) {
  const auto& modes = beam_modes();
  const double w7 = std::sqrt(modes.eigenvalues[6]);
  const double a7 = 0.05;
  const double period = 2.0 * kPi / w7;
  const Eigen::Vector3d v0(1.0, 0.5, -0.25), w0(0.5, 2.0, 3.0);
  const double t_switch = 1.02 * period, end = 3.0 * period;
  const std::string switching = fmt::format(
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n10,0,{:.17g},0,0,0,0,0\n0,0,0,2e-6,1,0\n1\n", t_switch);
  solver::Simulation sim(read(deck(initial_velocity(6, a7, v0, w0) + switching, end, 0.0, 20, 1)),
                         with_modes());
  ASSERT_TRUE(sim.rigid_bodies().flexible.empty());
  NodalMotion before;
  double modal_after = 0.0, switch_energy = 0.0, ratio_before = 0.0, worst_ratio = 0.0;
  Eigen::Vector3d p_before, h_before;
  while (!sim.finished()) {
    if (sim.rigid_bodies().flexible.empty()) {
      before = nodal_motion(sim.state());
      p_before = momentum(sim);
      h_before = angular_momentum(sim);
      ratio_before = sim.energy().ratio();
    }
    const bool was_deformable = sim.rigid_bodies().flexible.empty();
    sim.cycle();
    if (sim.finished()) break;
    if (!sim.rigid_bodies().flexible.empty()) {
      worst_ratio = std::max(worst_ratio, std::abs(sim.energy().ratio() - 1.0));
      if (was_deformable) {
        const auto& f = sim.rigid_bodies().flexible[0];
        // FORM 1 and no force: the step conserves each mode's energy exactly.
        modal_after = f.kinetic_energy() + f.elastic_energy();
        switch_energy = sim.energy().switch_energy;
        ASSERT_EQ(f.file_modes[0], 7);
        std::printf(
            "D2R of a vibrating part: mode 7 energy %.6e of %.6e (the non-rigid kinetic "
            "energy)\n",
            0.5 * (f.s[0] * f.s[0] + f.omega[0] * f.omega[0] * f.q[0] * f.q[0]), before.non_rigid);
        EXPECT_GT(0.5 * (f.s[0] * f.s[0] + f.omega[0] * f.omega[0] * f.q[0] * f.q[0]),
                  0.99 * before.non_rigid);
        EXPECT_NEAR((momentum(sim) - p_before).norm() / p_before.norm(), 0.0, 1e-13);
        EXPECT_NEAR((angular_momentum(sim) - h_before).norm() / h_before.norm(), 0.0, 1e-12);
      }
    }
  }
  ASSERT_GT(modal_after, 0.0);
  std::printf(
      "D2R of a vibrating part at %.3f periods: non-rigid KE %.6e, modal energy after %.6e "
      "(%.6f), switch energy %.6e (non-rigid - modal %.6e), ratio before %.2e, |ratio - 1| "
      "after %.2e\n",
      t_switch / period, before.non_rigid, modal_after, modal_after / before.non_rigid,
      switch_energy, before.non_rigid - modal_after, ratio_before - 1.0, worst_ratio);
  EXPECT_LE(modal_after, before.non_rigid * (1.0 + 1e-9));
  EXPECT_GT(modal_after, 0.99 * before.non_rigid);
  EXPECT_NEAR(switch_energy, before.non_rigid - modal_after, 1e-9 * before.non_rigid);
  EXPECT_LT(worst_ratio, std::abs(ratio_before - 1.0) + 1e-9);
}

// ---------------------------------------------------------------------------------------
// Refusals: each names file, line, keyword and field.

void expect_input_error(const std::string& text, const std::string& keyword,
                        const std::string& field, const std::string& words) {
  try {
    solver::Simulation sim(read(text), with_modes());
    ADD_FAILURE() << "no error for " << keyword << " " << field;
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().keyword, keyword) << e.what();
    EXPECT_EQ(e.context().field, field) << e.what();
    EXPECT_GT(e.context().line, 0) << e.what();
    EXPECT_EQ(e.context().file, "verification.k") << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(SwitchingFlexible, RefusalsNameTheCardAndField) {
  const std::string body = "*KEYWORD\n" + beam().keyword_text() +
                           elastic_part(kRho, kYoung, kNu, 2, 1) +
                           "*PART_MODES\n1,10,1,0,3,0\nbeam_modes.h5\n"
                           "*CONTROL_TIMESTEP\n1e-6\n*CONTROL_TERMINATION\n1e-5,0\n";
  // A deformable *PART_MODES part that no card switches to rigid.
  expect_input_error(body + "*END\n", "*PART_MODES", "PID", "no *DEFORMABLE_TO_RIGID");
  // Merging it into another body (LRB).
  expect_input_error(body +
                         "*PART\nlead\n2,2,2\n*SECTION_SOLID\n2,1\n*MAT_RIGID\n2,7850,2e11,0.3\n"
                         "*NODE\n1001,5,0,0\n1002,6,0,0\n1003,6,1,0\n1004,5,1,0\n1005,5,0,1\n"
                         "1006,6,0,1\n1007,6,1,1\n1008,5,1,1\n*ELEMENT_SOLID\n"
                         "1001,2,1001,1002,1003,1004,1005,1006,1007,1008\n"
                         "*DEFORMABLE_TO_RIGID_AUTOMATIC\n10,0,0\n0,0,0,0,1,0\n1,2\n*END\n",
                     "*DEFORMABLE_TO_RIGID_AUTOMATIC", "LRB", "cannot be merged");
  // Switched together with a part it shares nodes with (they would form one body).
  const BoxMesh mesh = beam();
  expect_input_error(
      body + fmt::format("*PART\nend\n2,1,2\n*MAT_ELASTIC\n2,7850,2e11,0.3\n*NODE\n"
                         "2001,1.1,0,0\n2002,1.1,0.05,0\n2003,1.1,0.05,0.075\n2004,1.1,0,0.075\n"
                         "*ELEMENT_SOLID\n2001,2,{},2001,2002,{},{},2004,2003,{}\n"
                         "*DEFORMABLE_TO_RIGID\n1\n2\n*END\n",
                         mesh.node_id(10, 0, 0), mesh.node_id(10, 1, 0), mesh.node_id(10, 0, 1),
                         mesh.node_id(10, 1, 1)),
      "*DEFORMABLE_TO_RIGID", "PID", "shares node");
  // Its mass from an inertia card.
  expect_input_error(body +
                         "*DEFORMABLE_TO_RIGID\n1\n*DEFORMABLE_TO_RIGID_INERTIA\n1\n"
                         "0.5,0.05,0.075,117.75\n1,0,0,1,0,1\n*END\n",
                     "*DEFORMABLE_TO_RIGID_INERTIA", "PID", "nodal masses");
}

}  // namespace
}  // namespace rf::test
