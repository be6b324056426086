// Flexible rigid bodies (*PART_MODES) through the deck path, against references that do not
// come from the modal code: the eigenvalues of a dense eigen solve of the mesh's stiffness
// (flexible_body_modes.hpp), conservation laws, and the fully deformable run of the same mesh.
// Numbers quoted in docs/flexible_bodies.md and docs/verification.md.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "deck_builder.hpp"
#include "flexible_body_modes.hpp"
#include "io/keyword/reader.hpp"
#include "modal/eigen_analysis.hpp"
#include "model/error.hpp"

namespace rf::test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRho = kSteelDensity, kYoung = kSteelYoung, kNu = kSteelPoisson;

BoxMesh beam_mesh() {
  return steel_beam_mesh();
}

std::string deformable_deck(const BoxMesh& mesh, const std::string& extra, double end_time,
                            double tssfac = 0.9) {
  return "*KEYWORD\n" + mesh.keyword_text() + elastic_part(kRho, kYoung, kNu, 2, 1) +
         fmt::format("*CONTROL_TIMESTEP\n0,{}\n*CONTROL_TERMINATION\n{:.17g},0\n", tssfac,
                     end_time) +
         extra + "*END\n";
}

std::string flexible_deck(const BoxMesh& mesh, int nmfb, int form, const std::string& extra,
                          double end_time, double dt, const std::string& mode_cards = "") {
  return "*KEYWORD\n" + mesh.keyword_text() + "*PART\nbeam\n1,1,1\n*SECTION_SOLID\n1,2\n" +
         fmt::format("*MAT_RIGID\n1,{:.17g},{:.17g},{}\n0,0,0\n", kRho, kYoung, kNu) +
         fmt::format(
             "*PART_MODES\n1,{},{},0,3,{}\nbeam_modes.h5\n{}", nmfb, form,
             mode_cards.empty() || mode_cards[0] != 'K' ? 0 : 1,
             mode_cards.empty() || mode_cards[0] != 'K' ? mode_cards : mode_cards.substr(1)) +
         fmt::format("*CONTROL_TIMESTEP\n{:.17g},0.9\n*CONTROL_TERMINATION\n{:.17g},0\n", dt,
                     end_time) +
         extra + "*END\n";
}

// The beam's dense modes, computed once.
const modal::ModeSet& beam_modes() {
  static const modal::ModeSet modes = [] {
    solver::Simulation sim(read(deformable_deck(beam_mesh(), "", 1e-3)), {});
    return dense_modes(sim, dense_stiffness(sim));
  }();
  return modes;
}

solver::SimulationOptions with_modes(const std::filesystem::path& out = {}) {
  solver::SimulationOptions options;
  options.output_directory = out;
  options.write_fields = false;
  options.mode_loader = [](const std::filesystem::path&) { return beam_modes(); };
  return options;
}

// *INITIAL_VELOCITY_NODE with velocity v0 + w0 x x + sum_k a_k phi_k at every node.
std::string initial_velocity(const modal::ModeSet& modes, const std::vector<int>& mode_index,
                             const std::vector<double>& amplitude, const Eigen::Vector3d& v0,
                             const Eigen::Vector3d& w0) {
  std::string s = "*INITIAL_VELOCITY_NODE\n";
  for (std::size_t i = 0; i < modes.node_count(); ++i) {
    const Eigen::Vector3d x(modes.coordinates[3 * i], modes.coordinates[3 * i + 1],
                            modes.coordinates[3 * i + 2]);
    Eigen::Vector3d v = v0 + w0.cross(x);
    for (std::size_t m = 0; m < mode_index.size(); ++m) {
      const double* phi = modes.shape(static_cast<std::size_t>(mode_index[m]));
      for (int d = 0; d < 3; ++d) v[d] += amplitude[m] * phi[3 * i + d];
    }
    s += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", modes.node_ids[i], v.x(), v.y(), v.z());
  }
  return s;
}

// ---------------------------------------------------------------------------------------
// Free beam, initial modal velocity in two modes, no load: each mode oscillates at its own
// eigenfrequency (the dense eigenvalue), the energy is constant, and the step is 20 times the
// element stable step: the modes do not limit it.

TEST(FlexibleBody, FreeBeamModesOscillateAtTheirEigenfrequencies) {
  const auto& modes = beam_modes();
  // Modes 7 and 9 of the file (the first bending modes of the 0.1 x 0.15 section).
  const std::vector<int> chosen = {6, 8};
  const std::vector<double> amplitude = {0.05, 0.03};  // modal velocity (sqrt(kg) m/s)
  const double w7 = std::sqrt(modes.eigenvalues[6]), w9 = std::sqrt(modes.eigenvalues[8]);
  const double highest = std::sqrt(modes.eigenvalues[19]);
  const double end = 12.0 * 2.0 * kPi / w7;
  // (a) a step with w dt = 10 for the highest kept mode (5 times the leapfrog limit 2/w, and
  // 20 times TSSFAC x the element step): still the exact oscillation q = s0 / w sin(w t).
  // (b) a small step, the frequencies measured from zero crossings of the amplitude history.
  for (const double dt : {10.0 / highest, 2e-6}) {
    const auto out = std::filesystem::temp_directory_path() / "rigidflex_flex_free";
    std::filesystem::remove_all(out);
    solver::Simulation sim(
        read(flexible_deck(beam_mesh(), 14, 0,
                           initial_velocity(modes, chosen, amplitude, Eigen::Vector3d::Zero(),
                                            Eigen::Vector3d::Zero()) +
                               "*DATABASE_GLSTAT\n1e-4\n*DATABASE_RBDOUT\n1e-4\n",
                           end, dt)),
        with_modes(out));
    ASSERT_EQ(sim.rigid_bodies().flexible.size(), 1u);
    const auto& f = sim.rigid_bodies().flexible[0];
    ASSERT_EQ(f.mode_count, 14u);
    EXPECT_EQ(f.file_modes[0], 7);  // rigid modes skipped
    // Initial modal velocities recovered from the nodal velocity field.
    EXPECT_NEAR(f.s[0], amplitude[0], 1e-10);
    EXPECT_NEAR(f.s[2], amplitude[1], 1e-10);
    EXPECT_NEAR(f.s[1], 0.0, 1e-10);
    const double e0 = sim.energy().kinetic;
    EXPECT_NEAR(e0, 0.5 * (amplitude[0] * amplitude[0] + amplitude[1] * amplitude[1]), 1e-12);
    std::vector<double> t, q7, q9;
    double worst_ratio = 0.0, worst_q = 0.0;
    while (!sim.finished()) {
      sim.cycle();
      if (sim.finished()) break;  // the last cycle advances the modes, not the time
      t.push_back(sim.state().time);
      q7.push_back(f.q[0]);
      q9.push_back(f.q[2]);
      worst_ratio = std::max(worst_ratio, std::abs(sim.energy().ratio() - 1.0));
      worst_q = std::max(worst_q, std::abs(f.q[0] - amplitude[0] / w7 * std::sin(w7 * t.back())));
      worst_q = std::max(worst_q, std::abs(f.q[2] - amplitude[1] / w9 * std::sin(w9 * t.back())));
    }
    const double f7 = zero_crossing_frequency(t, q7), f9 = zero_crossing_frequency(t, q9);
    std::printf(
        "free beam, dt %.3g s (w_max dt %.2f): f7 %.4f Hz (eigen %.4f), f9 %.4f Hz "
        "(eigen %.4f), |ratio - 1| max %.2e, |q - exact| max %.2e (amplitude %.2e)\n",
        dt, highest * dt, f7, w7 / (2 * kPi), f9, w9 / (2 * kPi), worst_ratio, worst_q,
        amplitude[0] / w7);
    // FORM 0's cubic strain energy (geometric stiffening) makes the modes weakly nonlinear:
    // relative effects of the order of the strain, here 1e-7.
    EXPECT_LT(worst_q, 1e-6 * amplitude[0] / w7);
    EXPECT_LT(worst_ratio, 1e-12);
    if (dt < 1e-5) {
      EXPECT_NEAR(f7, w7 / (2 * kPi), 1e-5 * w7 / (2 * kPi));
      EXPECT_NEAR(f9, w9 / (2 * kPi), 1e-5 * w9 / (2 * kPi));
    }
    // modal.csv: header and one row per mode and output time.
    std::ifstream modal_csv(out / "modal.csv");
    std::string header;
    std::getline(modal_csv, header);
    EXPECT_EQ(header, "time,body,mode,amplitude,velocity");
    std::string first;
    std::getline(modal_csv, first);
    EXPECT_EQ(first.substr(0, 6), "0,1,7,");
  }
}

// ---------------------------------------------------------------------------------------
// A free spinning, translating beam with modal vibration: linear and angular momentum are
// exactly conserved, the mass centre of the reconstructed nodes moves uniformly (the modes do
// not move it), and the energy balance closes (FORM 0 inertia work booked as external work).

TEST(FlexibleBody, FreeSpinningBeamConservesMomentaAndCentreOfMass) {
  const auto& modes = beam_modes();
  const Eigen::Vector3d v0(3.0, -1.0, 2.0), w0(4.0, 10.0, 30.0);
  for (const int form : {0, 1}) {
    const double dt = 2e-5, end = 0.02;
    solver::Simulation sim(
        read(flexible_deck(beam_mesh(), 20, form,
                           initial_velocity(modes, {6, 7, 9}, {0.05, 0.04, 0.02}, v0, w0) +
                               "*DATABASE_HISTORY_NODE\n1,11,99\n",
                           end, dt)),
        with_modes());
    const auto& rigid = sim.rigid_bodies();
    const auto& body = rigid.bodies[0];
    const Eigen::Vector3d c0 = body.state.centre;
    const Eigen::Vector3d vc = body.state.velocity;
    const auto p0 = sim.energy().momentum;
    const double p_ref[3] = {p0[0], p0[1], p0[2]};
    const auto h0 = sim.energy().angular_momentum;
    const double h_ref[3] = {h0[0], h0[1], h0[2]};
    double worst_p = 0.0, worst_h = 0.0, worst_com = 0.0, worst_ratio = 0.0;
    const double mass = body.state.mass;
    auto& state = sim.mutable_state();
    while (!sim.finished()) {
      sim.cycle();
      for (int k = 0; k < 3; ++k) {
        worst_p = std::max(worst_p, std::abs(sim.energy().momentum[k] - p_ref[k]));
        worst_h = std::max(worst_h, std::abs(sim.energy().angular_momentum[k] - h_ref[k]));
      }
      worst_ratio = std::max(worst_ratio, std::abs(sim.energy().ratio() - 1.0));
      // Mass centre of all nodes reconstructed at t^{n+1} (body at n+1, q^{n+1}).
      Eigen::Vector3d com = Eigen::Vector3d::Zero();
      const auto& f = rigid.flexible[0];
      for (std::size_t k = 0; k < body.nodes.size(); ++k) {
        const Eigen::Vector3d x =
            body.state.centre +
            body.state.rotation * (Eigen::Vector3d(f.body_coords[3 * k], f.body_coords[3 * k + 1],
                                                   f.body_coords[3 * k + 2]) +
                                   f.displacement(k, f.q));
        com += state.nodes.mass[body.nodes[k]] * x;
      }
      com /= mass;
      // The last cycle advances the body but not the time (output at t^n, then stop).
      if (!sim.finished()) worst_com = std::max(worst_com, (com - (c0 + vc * state.time)).norm());
    }
    const double p_scale = mass * v0.norm();
    const double h_scale = std::abs(h_ref[0]) + std::abs(h_ref[1]) + std::abs(h_ref[2]);
    const auto& f = rigid.flexible[0];
    double q_max = 0.0;
    for (double q : f.q) q_max = std::max(q_max, std::abs(q));
    std::printf(
        "FORM %d spinning beam: |dp|/p %.2e, |dH|/H %.2e, |COM - uniform| %.2e m, "
        "|ratio - 1| %.2e, modal energy %.4g J, max |q| %.3g\n",
        form, worst_p / p_scale, worst_h / h_scale, worst_com, worst_ratio,
        f.kinetic_energy() + f.elastic_energy(), q_max);
    EXPECT_LT(worst_p, 1e-12 * p_scale);
    EXPECT_LT(worst_h, 1e-11 * h_scale);
    EXPECT_LT(worst_com, 1e-12);
    // The rigid rotation's splitting conserves energy to O(dt^2) only (docs/rigid_bodies.md):
    // the same drift with FORM 0 and 1 and without modes.
    EXPECT_LT(worst_ratio, 1e-8);
  }
}

// ---------------------------------------------------------------------------------------
// Modal damping (KMFLAG card 4): the amplitude decays as exp(-zeta w t), and the damping loss
// enters the internal energy so that the balance still closes.

TEST(FlexibleBody, ModalDampingDecaysAtTheGivenRatio) {
  const auto& modes = beam_modes();
  const double zeta = 0.02, w7 = std::sqrt(modes.eigenvalues[6]);
  const double end = 20.0 * 2.0 * kPi / w7, dt = 1e-5;
  solver::Simulation sim(
      read(flexible_deck(
          beam_mesh(), 4, 1,
          initial_velocity(modes, {6}, {0.05}, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
          end, dt, "1,2,0.02\n")),
      with_modes());
  const auto& f = sim.rigid_bodies().flexible[0];
  while (!sim.finished()) sim.cycle();
  const double t = sim.state().time;
  const double wd = w7 * std::sqrt(1.0 - zeta * zeta);
  const double exact = 0.05 / wd * std::exp(-zeta * w7 * t) * std::sin(wd * t);
  // The run stops after the velocity update of its last cycle: q_previous is q at that time.
  std::printf("damped mode: q(t) %.9e, exact %.9e, ratio - 1 = %.2e\n", f.q_previous[0], exact,
              sim.energy().ratio() - 1.0);
  EXPECT_NEAR(f.q_previous[0], exact, 1e-9 * 0.05 / w7);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-12);
}

// A mode database with rotational components at a node that has no rotations in the model (a
// solid part's node: the modes were computed for shells or beams) is refused at FILENAME.
TEST(FlexibleBodyDeck, DatabaseWithRotationsAtASolidNodeIsRefused) {
  solver::SimulationOptions options = with_modes();
  options.mode_loader = [](const std::filesystem::path&) {
    modal::ModeSet modes = beam_modes();
    modes.rotation_nodes = {0};
    modes.rotational_inertia = {1.0};
    modes.rotation_shapes.assign(3 * modes.mode_count(), 0.0);
    return modes;
  };
  try {
    solver::Simulation sim(read(flexible_deck(beam_mesh(), 10, 1, "", 1e-3, 1e-5)), options);
    ADD_FAILURE() << "no error for a database with rotations";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("has rotations in mode database"), std::string::npos) << message;
    EXPECT_NE(message.find("none in the model"), std::string::npos) << message;
    EXPECT_NE(message.find("FILENAME"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace rf::test

namespace rf::test {
namespace {

// ---------------------------------------------------------------------------------------
// Impact-like load on the free beam: a half-sine transverse force pulse on the middle node of
// the top face. With all elastic modes and the deformable run's step, the flexible body
// reproduces the fully deformable linear-elastic run (same mesh, ELFORM 2); with fewer modes the
// local peak displacement under the load converges as the seed's head-impact table does.

struct ImpactHistory {
  std::vector<double> load_z, tip_z;  // z displacement of the loaded node and of a tip node
  std::vector<double> indentation;    // loaded node minus the node below it (bottom face)
  std::vector<double> deflection;     // loaded node minus the mean of the two top end nodes
  double dt = 0.0;
};

constexpr double kPulse = 4e-4, kForce = 2e4, kImpactEnd = 1.2e-3;

std::string impact_cards(const BoxMesh& mesh) {
  return fmt::format(
      "*LOAD_NODE_POINT\n{},3,1,-1.0\n*DEFINE_CURVE\n1\n{}"
      "*DATABASE_HISTORY_NODE\n{},{},{}\n",
      mesh.node_id(5, 1, 2),
      [] {
        std::string c;
        for (int k = 0; k <= 40; ++k) {
          const double t = kPulse * k / 40.0;
          c += fmt::format("{:.17g},{:.17g}\n", t, kForce * std::sin(kPi * t / kPulse));
        }
        return c + fmt::format("{:.17g},0\n1,0\n", kPulse * 1.0001);
      }(),
      mesh.node_id(10, 1, 2), mesh.node_id(5, 1, 0), mesh.node_id(0, 1, 2));
}

ImpactHistory run_impact(solver::Simulation& sim, const BoxMesh& mesh) {
  ImpactHistory h;
  const auto& nodes = sim.state().nodes;
  std::int32_t load = -1, tip = -1, below = -1, root = -1;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes.id[i] == mesh.node_id(0, 1, 2)) root = static_cast<std::int32_t>(i);
    if (nodes.id[i] == mesh.node_id(5, 1, 0)) below = static_cast<std::int32_t>(i);
    if (nodes.id[i] == mesh.node_id(5, 1, 2)) load = static_cast<std::int32_t>(i);
    if (nodes.id[i] == mesh.node_id(10, 1, 2)) tip = static_cast<std::int32_t>(i);
  }
  h.dt = sim.state().dt;
  while (!sim.finished()) {
    sim.cycle();
    if (sim.finished()) break;
    h.load_z.push_back(nodes.x.z[load] - nodes.x0.z[load]);
    h.tip_z.push_back(nodes.x.z[tip] - nodes.x0.z[tip]);
    h.indentation.push_back(h.load_z.back() - (nodes.x.z[below] - nodes.x0.z[below]));
    h.deflection.push_back(h.load_z.back() -
                           0.5 * (h.tip_z.back() + nodes.x.z[root] - nodes.x0.z[root]));
  }
  return h;
}

double peak(const std::vector<double>& y) {
  double p = 0.0;
  for (double v : y) p = std::max(p, std::abs(v));
  return p;
}

TEST(FlexibleBody, AllModesMatchDeformableRunAndFewerModesConverge) {
  const BoxMesh mesh = beam_mesh();
  const auto& modes = beam_modes();
  const int elastic = static_cast<int>(modes.mode_count()) - 6;
  // (a) All modes against the deformable run, both with a step well below the stability
  // limit (TSSFAC 0.1): the leapfrog's own phase error in the highest modes, (w dt)^2 / 24,
  // is then below 0.2 % (at TSSFAC 0.9 it is the largest difference between the two runs).
  {
    // The modes are undamped: the deformable reference runs without bulk viscosity.
    solver::Simulation deformable(
        read(deformable_deck(mesh, impact_cards(mesh) + "*CONTROL_BULK_VISCOSITY\n0.0,0.0\n",
                             kImpactEnd, 0.1)),
        {});
    const ImpactHistory reference = run_impact(deformable, mesh);
    solver::Simulation flexible(
        read(flexible_deck(mesh, elastic, 0, impact_cards(mesh), kImpactEnd, reference.dt)),
        with_modes());
    const ImpactHistory h = run_impact(flexible, mesh);
    ASSERT_EQ(h.load_z.size(), reference.load_z.size());
    double history = 0.0, indentation = 0.0;
    for (std::size_t k = 0; k < h.load_z.size(); ++k) {
      history = std::max(history, std::abs(h.load_z[k] - reference.load_z[k]));
      history = std::max(history, std::abs(h.tip_z[k] - reference.tip_z[k]));
      indentation = std::max(indentation, std::abs(h.indentation[k] - reference.indentation[k]));
    }
    std::printf(
        "impact, all %d modes vs deformable (dt %.3g s, %zu steps): max |du_z| %.3e of "
        "the peak displacement, max |d indentation| %.3e of its peak\n",
        elastic, reference.dt, h.load_z.size(), history / peak(reference.load_z),
        indentation / peak(reference.indentation));
    EXPECT_LT(history, 1e-3 * peak(reference.load_z));
    EXPECT_LT(indentation, 5e-3 * peak(reference.indentation));
  }
  // (b) Fewer modes at the deformable run's own step (TSSFAC 0.9): relative errors of the peak
  // bending deflection under the load (against the beam's ends) and of the local indentation
  // (top minus bottom node under the load).
  solver::Simulation deformable(
      read(deformable_deck(mesh, impact_cards(mesh) + "*CONTROL_BULK_VISCOSITY\n0.0,0.0\n",
                           kImpactEnd)),
      {});
  const ImpactHistory reference = run_impact(deformable, mesh);
  const double ref_peak = peak(reference.deflection);
  std::printf(
      "impact: deformable dt %.4g s, %zu steps, peak deflection %.6e m, peak "
      "indentation %.6e m, peak |u_z| under the load %.6e m\n",
      reference.dt, reference.load_z.size(), ref_peak, peak(reference.indentation),
      peak(reference.load_z));
  std::vector<double> errors;
  for (const int nmfb : {5, 10, 20, 40, 80, 100, 160, elastic}) {
    solver::Simulation flexible(
        read(flexible_deck(mesh, nmfb, 0, impact_cards(mesh), kImpactEnd, reference.dt)),
        with_modes());
    const ImpactHistory h = run_impact(flexible, mesh);
    ASSERT_EQ(h.load_z.size(), reference.load_z.size());
    const double peak_error = std::abs(peak(h.deflection) - ref_peak) / ref_peak;
    const double indentation_error =
        std::abs(peak(h.indentation) - peak(reference.indentation)) / peak(reference.indentation);
    const double displacement_error =
        std::abs(peak(h.load_z) - peak(reference.load_z)) / peak(reference.load_z);
    std::printf(
        "impact: %3d modes: peak deflection error %7.2f %%, peak indentation error "
        "%7.2f %%, peak displacement error %6.3f %%\n",
        nmfb, 100.0 * peak_error, 100.0 * indentation_error, 100.0 * displacement_error);
    errors.push_back(indentation_error);
    // The bending deflection is carried by the lowest modes: right with any count.
    EXPECT_LT(peak_error, 0.01);
  }
  // The local peak error shrinks with the number of modes (the seed: 19 / 4.2 / 2.3 % for
  // 10 / 40 / 100 modes of its plate). With all modes the rest is the deformable run's own
  // leapfrog dispersion at TSSFAC 0.9 (see (a)).
  // errors: 5, 10, 20, 40, 80, 100, 160, all modes.
  EXPECT_GT(errors[1], errors[3]);  // 10 > 40
  EXPECT_GT(errors[3], errors[4]);  // 40 > 80
  EXPECT_GT(errors[3], errors[5]);  // 40 > 100
  EXPECT_GT(errors[5], errors[6]);  // 100 > 160
  EXPECT_GT(errors[6], errors[7]);  // 160 > all
  EXPECT_LT(errors[7], 0.05);
}

}  // namespace
}  // namespace rf::test

namespace rf::test {
namespace {

// ---------------------------------------------------------------------------------------
// The whole chain through files: the eigen analysis (modal::compute_modes, Lanczos) of the
// deformable beam writes modes.h5, a *PART_MODES deck reads it by relative path. Its modes
// reproduce the dense reference's frequencies, and a node missing from the database is an
// input error that names it.

TEST(FlexibleBody, ModeDatabaseFromTheEigenAnalysisDrivesTheBody) {
  const BoxMesh mesh = beam_mesh();
  const auto dir = std::filesystem::temp_directory_path() / "rigidflex_flex_db";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  modal::EigenRequest request;
  request.mode_count = 12;
  request.remove_rigid_below = true;
  request.left_frequency = 1.0;
  const modal::ModeSet lanczos =
      modal::compute_modes(read(deformable_deck(mesh, "", 1e-3)), request);
  modal::write_mode_database(dir / "beam_modes.h5", lanczos);
  const auto& dense = beam_modes();
  const double w7 = std::sqrt(dense.eigenvalues[6]);
  const double end = 4.0 * 2.0 * kPi / w7;
  {
    std::ofstream deck(dir / "flexible.k");
    deck << flexible_deck(
        mesh, 12, 0,
        initial_velocity(dense, {6}, {0.05}, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), end,
        2e-6);
  }
  solver::SimulationOptions options;
  solver::Simulation sim(io::read_deck(dir / "flexible.k"), options);
  const auto& f = sim.rigid_bodies().flexible.at(0);
  ASSERT_EQ(f.mode_count, 12u);
  for (std::size_t k = 0; k < 12; ++k) {
    EXPECT_NEAR(f.omega[k], std::sqrt(dense.eigenvalues[6 + k]),
                1e-6 * std::sqrt(dense.eigenvalues[6 + k]))
        << "mode " << k;
  }
  // The initial velocity (dense mode 7) lies in the span of the Lanczos modes: all of its
  // energy is recovered by the projection (possibly split within a degenerate pair).
  EXPECT_NEAR(f.kinetic_energy(), 0.5 * 0.05 * 0.05, 1e-9);
  while (!sim.finished()) sim.cycle();
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-12);

  // A database without node 5: the error names the node and the file.
  modal::ModeSet partial = lanczos;
  const std::size_t n = partial.node_count();
  std::size_t drop = 0;
  while (partial.node_ids[drop] != 5) ++drop;
  partial.node_ids.erase(partial.node_ids.begin() + drop);
  partial.node_parts.erase(partial.node_parts.begin() + drop);
  partial.mass.erase(partial.mass.begin() + drop);
  partial.coordinates.erase(partial.coordinates.begin() + 3 * drop,
                            partial.coordinates.begin() + 3 * drop + 3);
  std::vector<double> shapes;
  for (std::size_t k = 0; k < partial.mode_count(); ++k) {
    for (std::size_t r = 0; r < 3 * n; ++r) {
      if (r / 3 != drop) shapes.push_back(partial.shapes[k * 3 * n + r]);
    }
  }
  partial.shapes = shapes;
  modal::write_mode_database(dir / "beam_modes.h5", partial);
  try {
    solver::Simulation bad(io::read_deck(dir / "flexible.k"), options);
    ADD_FAILURE() << "no error for a node missing from the database";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("node(s) of flexible body 1: 5"), std::string::npos) << message;
    EXPECT_NE(message.find("beam_modes.h5"), std::string::npos) << message;
    EXPECT_NE(message.find("*PART_MODES"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace rf::test

namespace rf::test {
namespace {

// ---------------------------------------------------------------------------------------
// Centrifugal stiffening: the free beam spins about y (through its centre) at a quarter of its
// first bending frequency and vibrates in that mode (bending along y, out of the plane of
// rotation, where the frame's centrifugal softening does not act). The fully deformable run
// (geometrically nonlinear) shows the frequency rise; FORM 0, with the cubic strain-energy
// invariants, follows it; FORM 1 stays at the non-rotating frequency.

double flapping_frequency(solver::Simulation& sim, const BoxMesh& mesh) {
  const auto& nodes = sim.state().nodes;
  std::int32_t mid = -1, left = -1, right = -1;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes.id[i] == mesh.node_id(5, 1, 1)) mid = static_cast<std::int32_t>(i);
    if (nodes.id[i] == mesh.node_id(0, 1, 1)) left = static_cast<std::int32_t>(i);
    if (nodes.id[i] == mesh.node_id(10, 1, 1)) right = static_cast<std::int32_t>(i);
  }
  std::vector<double> t, y;
  while (!sim.finished()) {
    sim.cycle();
    if (sim.finished()) break;
    t.push_back(sim.state().time);
    y.push_back(nodes.x.y[mid] - 0.5 * (nodes.x.y[left] + nodes.x.y[right]) -
                (nodes.x0.y[mid] - 0.5 * (nodes.x0.y[left] + nodes.x0.y[right])));
  }
  return zero_crossing_frequency(t, y);
}

TEST(FlexibleBody, SpinningBeamStiffensWithForm0NotWithForm1) {
  const BoxMesh mesh = beam_mesh();
  const auto& modes = beam_modes();
  const double w7 = std::sqrt(modes.eigenvalues[6]);
  const double spin = 0.25 * w7;
  const Eigen::Vector3d axis = Eigen::Vector3d::UnitY() * spin;
  const Eigen::Vector3d centre(0.5, 0.05, 0.075);
  const std::string velocity =
      initial_velocity(modes, {6}, {0.2}, -axis.cross(centre), axis) +
      fmt::format("*DATABASE_HISTORY_NODE\n{},{},{}\n", mesh.node_id(5, 1, 1),
                  mesh.node_id(0, 1, 1), mesh.node_id(10, 1, 1));
  const double end = 10.0 * 2.0 * kPi / w7;
  solver::Simulation deformable(read(deformable_deck(mesh, velocity, end, 0.5)), {});
  const double dt = deformable.state().dt;
  const double f_deformable = flapping_frequency(deformable, mesh);
  double f_form[2] = {0.0, 0.0};
  for (const int form : {0, 1}) {
    solver::Simulation flexible(read(flexible_deck(mesh, 40, form, velocity, end, dt)),
                                with_modes());
    f_form[form] = flapping_frequency(flexible, mesh);
  }
  const double f0 = w7 / (2 * kPi);
  std::printf(
      "spinning beam (spin %.0f rad/s = 0.25 w7): flapping frequency deformable %.2f Hz "
      "(%+.2f %% vs non-rotating %.2f Hz), FORM 0 %.2f Hz (%+.2f %%), FORM 1 %.2f Hz "
      "(%+.2f %%)\n",
      spin, f_deformable, 100 * (f_deformable / f0 - 1), f0, f_form[0], 100 * (f_form[0] / f0 - 1),
      f_form[1], 100 * (f_form[1] / f0 - 1));
  // The deformable run stiffens clearly; FORM 0 recovers most of the rise, FORM 1 none.
  EXPECT_GT(f_deformable / f0 - 1, 0.01);
  EXPECT_NEAR(f_form[1], f0, 2e-3 * f0);
  EXPECT_NEAR(f_form[0], f_deformable, 0.25 * (f_deformable - f0));
}

}  // namespace
}  // namespace rf::test

namespace rf::test {
namespace {

// ---------------------------------------------------------------------------------------
// A flexible body bonded to deformable elements (shared nodes: the solver's masses there exceed
// the database's, so the modes are re-orthonormalised), spinning and vibrating: the energy
// balance closes and the momenta are conserved.

TEST(FlexibleBody, BondedToDeformablePartConservesEnergyAndMomenta) {
  BoxMesh mesh = beam_mesh();
  auto deck = [&](bool rigid, const std::string& extra) {
    std::string s = "*KEYWORD\n" + mesh.keyword_text(1);
    // Elements with x < 0.3 form part 1 (deformable), the rest part 2.
    std::string out;
    std::istringstream in(s);
    std::string line;
    bool elements = false;
    while (std::getline(in, line)) {
      if (line.starts_with("*")) elements = line == "*ELEMENT_SOLID";
      if (elements && !line.starts_with("*")) {
        const int eid = std::stoi(line.substr(0, line.find(',')));
        const int i = (eid - 1) % mesh.nx;
        line = fmt::format("{},{}{}", eid, i < 3 ? 1 : 2,
                           line.substr(line.find(',', line.find(',') + 1)));
      }
      out += line + "\n";
    }
    out += elastic_part(kRho, kYoung, kNu, 2, 1);
    out += "*PART\nflexible\n2,1,2\n";
    out += rigid ? fmt::format(
                       "*MAT_RIGID\n2,{},{},{}\n0,0,0\n*PART_MODES\n2,30,0,0,3\n"
                       "modes.h5\n",
                       kRho, kYoung, kNu)
                 : fmt::format("*MAT_ELASTIC\n2,{},{},{}\n", kRho, kYoung, kNu);
    return out + extra + "*CONTROL_TIMESTEP\n0,0.9\n*CONTROL_TERMINATION\n5e-3,0\n*END\n";
  };
  modal::EigenRequest request;
  request.mode_count = 30;
  request.parts = {2};
  request.remove_rigid_below = true;
  request.left_frequency = 1.0;
  const modal::ModeSet part_modes = modal::compute_modes(read(deck(false, "")), request);
  const std::string velocity =
      "*INITIAL_VELOCITY_GENERATION\n0,2,40,0,0,1\n0.5,0.05,0.075,0.3,1,0.2\n"
      "*INITIAL_VELOCITY_NODE\n" +
      fmt::format("{},0,3,0\n", mesh.node_id(10, 2, 2));
  solver::SimulationOptions options;
  options.write_fields = false;
  options.mode_loader = [&](const std::filesystem::path&) { return part_modes; };
  solver::Simulation sim(read(deck(true, velocity)), options);
  const auto& f = sim.rigid_bodies().flexible.at(0);
  EXPECT_GT(f.active.size(), 0u);   // the shared face
  EXPECT_GT(f.passive.size(), 0u);  // the rest waits for output
  const auto p0 = sim.energy().momentum;
  const double p_ref[3] = {p0[0], p0[1], p0[2]};
  const auto h0 = sim.energy().angular_momentum;
  const double h_ref[3] = {h0[0], h0[1], h0[2]};
  double worst_ratio = 0.0, worst_p = 0.0, worst_h = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    worst_ratio = std::max(worst_ratio, std::abs(sim.energy().ratio() - 1.0));
    for (int k = 0; k < 3; ++k) {
      worst_p = std::max(worst_p, std::abs(sim.energy().momentum[k] - p_ref[k]));
      worst_h = std::max(worst_h, std::abs(sim.energy().angular_momentum[k] - h_ref[k]));
    }
  }
  const double mass = 7850.0 * 0.015;
  std::printf(
      "bonded flexible body: |ratio - 1| max %.2e, |dp| %.2e, |dH| %.2e, modal "
      "energy %.3g J, kinetic %.3g J\n",
      worst_ratio, worst_p, worst_h, f.kinetic_energy() + f.elastic_energy(), sim.energy().kinetic);
  // 1e-7 of 7.6 kJ is 1e-4 of the modal energy: a modal bookkeeping error would show.
  EXPECT_LT(worst_ratio, 1e-7);
  EXPECT_LT(worst_p, 1e-10 * mass);
  EXPECT_LT(worst_h, 1e-10 * mass);
}

}  // namespace
}  // namespace rf::test

namespace rf::test {
namespace {

// ---------------------------------------------------------------------------------------
// Nodes that nothing reads every cycle are reconstructed only for output: right after each
// cycle that wrote a d3plot frame they sit exactly at x_c + R (X + Phi q); in between they are
// stale. The number of exact cycles equals the number of frames.

TEST(FlexibleBody, PassiveNodesAreReconstructedForEveryFrame) {
  const auto& modes = beam_modes();
  const auto out = std::filesystem::temp_directory_path() / "rigidflex_flex_frames";
  std::filesystem::remove_all(out);
  const double dt = 1e-5;
  solver::SimulationOptions options = with_modes(out);
  options.write_fields = true;
  solver::Simulation sim(
      read(flexible_deck(beam_mesh(), 10, 1,
                         initial_velocity(modes, {6, 8}, {0.5, 0.3}, Eigen::Vector3d(1, 0, 0),
                                          Eigen::Vector3d(0, 20, 5)) +
                             "*DATABASE_BINARY_D3PLOT\n1e-4\n",
                         1e-3, dt)),
      options);
  const auto& rigid = sim.rigid_bodies();
  const auto& body = rigid.bodies[0];
  const auto& f = rigid.flexible[0];
  ASSERT_EQ(f.active.size(), 0u);  // nothing loads or watches this beam
  const auto& nodes = sim.state().nodes;
  int exact = 0, stale = 0;
  while (!sim.finished()) {
    sim.cycle();
    if (sim.finished()) break;
    double worst = 0.0;
    for (const std::int32_t k : f.passive) {
      const Eigen::Vector3d x =
          body.state.centre +
          body.state.rotation * (Eigen::Vector3d(f.body_coords[3 * k], f.body_coords[3 * k + 1],
                                                 f.body_coords[3 * k + 2]) +
                                 f.displacement(k, f.q));
      const std::int32_t i = body.nodes[k];
      worst =
          std::max(worst, (x - Eigen::Vector3d(nodes.x.x[i], nodes.x.y[i], nodes.x.z[i])).norm());
    }
    (worst < 1e-13 ? exact : stale) += 1;
  }
  int frames = 0;
  for (const auto& entry : std::filesystem::directory_iterator(out)) {
    if (entry.path().extension() == ".vtu") ++frames;
  }
  std::printf("passive nodes: %d cycles exact (frames written: %d), %d stale\n", exact, frames,
              stale);
  // The last frame is written by the final (time-less) cycle, which is not sampled here.
  EXPECT_EQ(exact, frames - 1);
  EXPECT_GE(stale, 8 * exact);  // frames every 10 cycles
}

}  // namespace
}  // namespace rf::test

namespace rf::test {
namespace {

// KMFLAG 1: the listed modes are kept in the listed order, with their own frequencies; a
// listed rigid mode is an error naming it.
TEST(FlexibleBody, KeptModeListSelectsTheListedModes) {
  const auto& modes = beam_modes();
  solver::Simulation sim(read(flexible_deck(beam_mesh(), 2, 1, "", 1e-4, 1e-5, "K9,7\n")),
                         with_modes());
  const auto& f = sim.rigid_bodies().flexible.at(0);
  EXPECT_EQ(f.file_modes, (std::vector<int>{9, 7}));
  EXPECT_NEAR(f.omega[0], std::sqrt(modes.eigenvalues[8]), 1e-9 * f.omega[0]);
  EXPECT_NEAR(f.omega[1], std::sqrt(modes.eigenvalues[6]), 1e-9 * f.omega[1]);
  try {
    solver::Simulation bad(read(flexible_deck(beam_mesh(), 2, 1, "", 1e-4, 1e-5, "K3,7\n")),
                           with_modes());
    ADD_FAILURE() << "no error for a rigid mode in the list";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mode 3 of"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rf::test
