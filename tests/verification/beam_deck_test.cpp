// Beams and trusses through the whole deck path. References that do not come from our code:
// Euler-Bernoulli cantilever deflection P L^3 / (3 E I) (Timoshenko shear P L / (k G A) added
// where it matters) and the static stretch of a bar F L / (E A).
#include <gtest/gtest.h>

#include <cmath>

#include "deck_builder.hpp"
#include "model/error.hpp"

namespace rf::test {
namespace {

constexpr double kRho = 7800.0, kE = 2.0e11, kNu = 0.3;

// A straight line of `n` two-node elements along x from 0 to `length`, node 1 clamped, the tip
// (node n + 1) loaded in direction `dof` by a ramped force `load`, mass-proportional damping
// near critical for the first mode so that the run ends at the static answer.
std::string cantilever(const std::string& section, int n, double length, int dof, double load,
                       double damping, double end) {
  std::string deck = "*KEYWORD\n*NODE\n";
  for (int i = 0; i <= n; ++i) deck += fmt::format("{},{:.17g},0,0\n", i + 1, length * i / n);
  deck += "*ELEMENT_BEAM_ORIENTATION\n";
  for (int i = 0; i < n; ++i) deck += fmt::format("{},1,{},{}\n0,1,0\n", i + 1, i + 1, i + 2);
  deck += "*PART\nbeam\n1,1,1\n" + section;
  deck += fmt::format("*MAT_ELASTIC\n1,{},{},{}\n", kRho, kE, kNu);
  deck += "*BOUNDARY_SPC_NODE\n1,0,1,1,1,1,1,1\n";
  deck += fmt::format("*LOAD_NODE_POINT\n{},{},1,{:.17g}\n", n + 1, dof, load);
  deck += fmt::format("*DEFINE_CURVE\n1\n0,0\n{:.17g},1\n1e3,1\n", 0.3 * end);
  deck += fmt::format("*DAMPING_GLOBAL\n0,{:.17g}\n", damping);
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},\n*END\n", end);
  return deck;
}

double tip(const solver::Simulation& sim, int node, int axis) {
  const auto& x = sim.state().nodes.x;
  const std::size_t i = static_cast<std::size_t>(node - 1);
  return axis == 0 ? x.x[i] - sim.state().nodes.x0.x[i] : axis == 1 ? x.y[i] : x.z[i];
}

TEST(BeamDeck, ResultantBeamCantileverMatchesBeamTheory) {
  // 20 mm x 10 mm steel section, 1 m long; load in z bends about the section's weaker axis.
  const double a = 2e-4, i_weak = 0.02 * 1e-6 / 12.0, i_strong = 0.01 * 8e-6 / 12.0;
  const double j = 0.0;  // blank: ISS + ITT
  const std::string section = fmt::format(
      "*SECTION_BEAM\n1,2,0.8333\n{:.17g},{:.17g},{:.17g},{:.17g}\n", a, i_weak, i_strong, j);
  const double load = 2.0, length = 1.0;
  // With the orientation vector (0, 1, 0) the s axis is y: ISS bends about s, i.e. in the x-z
  // plane. First mode omega = 3.52 sqrt(EI / (rho A L^4)) = 51 rad/s; d = 80 is 0.78 of critical.
  const double ei = kE * i_weak;
  const double expected = load * std::pow(length, 3) / (3.0 * ei);
  solver::Simulation sim(read(cantilever(section, 10, length, 3, load, 80.0, 0.35)), {});
  sim.run();
  const double w = tip(sim, 11, 2);
  RecordProperty("tip_ratio", std::to_string(w / expected));
  EXPECT_NEAR(w / expected, 1.0, 0.01) << w << " vs " << expected;
}

TEST(BeamDeck, IntegratedBeamCantileverMatchesBeamTheory) {
  // ELFORM 1, rectangular 20 mm (TS, s) x 10 mm (TT, t) section integrated 2 x 2.
  const std::string section = "*SECTION_BEAM\n1,1,0.8333,2,0\n0.02,0.02,0.01,0.01\n";
  const double load = 2.0, length = 1.0;
  // Bending in z (across t, the 10 mm side): I = TS TT^3 / 12.
  const double ei = kE * 0.02 * 1e-6 / 12.0;
  const double expected = load * std::pow(length, 3) / (3.0 * ei);
  solver::Simulation sim(read(cantilever(section, 10, length, 3, load, 80.0, 0.35)), {});
  sim.run();
  const double w = tip(sim, 11, 2);
  RecordProperty("tip_ratio", std::to_string(w / expected));
  // One integration section per element: the tip deflection converges from below as
  // 1 - 1/(4 n^2) (0.9975 for n = 10); asserted within 1 %.
  EXPECT_NEAR(w / expected, 1.0, 0.01) << w << " vs " << expected;
}

TEST(BeamDeck, TrussBarStretchesAsFLOverEA) {
  const double a = 1e-4, length = 2.0, load = 1e4;
  std::string deck =
      "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,2,0,0\n*ELEMENT_BEAM\n1,1,1,2\n2,1,2,3\n";
  deck += fmt::format("*PART\ntruss\n1,1,1\n*SECTION_BEAM\n1,3\n{}\n*MAT_ELASTIC\n1,{},{},{}\n", a,
                      kRho, kE, kNu);
  deck += "*BOUNDARY_SPC_NODE\n1,0,1,1,1\n2,0,0,1,1\n3,0,0,1,1\n";
  deck += fmt::format("*LOAD_NODE_POINT\n3,1,1,{}\n*DEFINE_CURVE\n1\n0,0\n0.003,1\n1,1\n", load);
  // Axial mode omega = pi c / (2 L) = 4.0e3 rad/s: damping 1e3 1/s (13 % of critical) leaves
  // e^-10 of the transient by 0.02 s. (Stronger explicit damping lowers the stable step: with
  // d / (2 omega_max) = 0.25 a step of 0.9 L / c is no longer stable.)
  deck += "*DAMPING_GLOBAL\n0,1000\n*CONTROL_TERMINATION\n0.02\n*END\n";
  solver::Simulation sim(read(deck), {});
  sim.run();
  const double stretch = tip(sim, 3, 0);
  const double expected = load * length / (kE * a);
  RecordProperty("stretch_ratio", std::to_string(stretch / expected));
  // The truss uses the logarithmic strain: the stretch is F L / (E A) (1 + eps / 2) to first
  // order, 5e-4 above at this strain.
  EXPECT_NEAR(stretch / expected, 1.0, 2e-3);
}

TEST(BeamDeck, CheckListsBeamsAndRefusesBadSections) {
  auto error_of = [](const std::string& deck) -> std::string {
    try {
      solver::Simulation sim(read(deck), {});
    } catch (const InputError& e) {
      return e.what();
    }
    return {};
  };
  const std::string base =
      "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n*ELEMENT_BEAM\n1,1,1,2\n*PART\nb\n1,1,1\n"
      "*MAT_ELASTIC\n1,7800,2e11,0.3\n*CONTROL_TERMINATION\n0.001\n";
  EXPECT_NE(error_of(base + "*SECTION_BEAM\n1,4\n1e-4\n*END\n").find("ELFORM"), std::string::npos);
  EXPECT_NE(error_of(base + "*SECTION_BEAM\n1,2\n1e-4,0,1e-8\n*END\n").find("ISS"),
            std::string::npos);
  EXPECT_NE(error_of(base + "*SECTION_BEAM\n1,1,1,2,1\n0.02,0.02,0.03,0.03\n*END\n").find("TT1"),
            std::string::npos);
  EXPECT_EQ(error_of(base + "*SECTION_BEAM\n1,3\n1e-4\n*END\n"), "");
}

}  // namespace
}  // namespace rf::test
