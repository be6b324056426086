// Shell thickness update (*CONTROL_SHELL ISTUPD 1 and 4; element/shell_block.cpp, section 12)
// through the whole deck path. One square shell stretched in its plane to large strain, the
// logarithmic thickness strain ln(t / t0) against closed forms that do not come from our code:
//  - plane stress with isotropic elasticity and plastically incompressible flow, additive
//    logarithmic strains (elastic strains small): e_t = e_t^e + e_t^p with
//    e_t^e = -nu (s_1 + s_2) / E and e_t^p = -(e_1^p + e_2^p), e_i^p = e_i - (s_i - nu s_j) / E
//    (e.g. Hill, The Mathematical Theory of Plasticity, 1950, ch. II; Marciniak, Duncan & Hu,
//    Mechanics of Sheet Metal Forming, 2002, ch. 2-3):
//      uniaxial  (s_2 = 0):      e_t = -e_1 / 2 + (1/2 - nu) s / E        (isotropic, J2)
//      uniaxial, R-value R:      e_t^p = -e_1^p / (1 + R)                 (Lankford)
//      equi-biaxial (s_1 = s_2): e_t = -(e_1 + e_2) + 2 (1 - 2 nu) s / E
//      ISTUPD 4 (elastic strains neglected): e_t = -(e_1^p + e_2^p) alone;
//  - elastic plane stress: e_t = -nu / (1 - nu) (e_1 + e_2) (hypoelastic rate form integrated
//    along fixed principal axes: exact in logarithmic strains);
//  - the stress from the linear hardening law of *MAT_024 (SIGY, ETAN: plastic modulus
//    H = E ETAN / (E - ETAN), LS-DYNA Keyword User's Manual), not read back from the solver;
//  - the work of a uniaxial tension test, W = int V s de_1 with V = V0 exp((1 - 2 nu) s / E)
//    (volume changes only elastically), against the solver's internal energy.
#include <gtest/gtest.h>

#include <cmath>

#include "deck_builder.hpp"
#include "shell_builder.hpp"

namespace rf::test {
namespace {

constexpr double kSide = 0.01, kT0 = 0.001;
constexpr double kRho = 7800.0, kE = 2.0e11, kNu = 0.3, kSigy = 2.0e8, kEtan = 2.0e9;
constexpr double kH = kE * kEtan / (kE - kEtan);  // plastic modulus of SIGY/ETAN

const std::string kJ2 = fmt::format("*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,{},{},{},{},{}\n", kRho,
                                    kE, kNu, kSigy, kEtan);
const std::string kElastic = fmt::format("*MAT_ELASTIC\n1,{},{},{}\n", kRho, kE, kNu);
// *MAT_036 with the exponent M 6 and R00 1.8 (AOPT 0: rolling direction along the
// element's side 1-2, here x), the same linear hardening.
const std::string kBarlat = fmt::format(
    "*MAT_3-PARAMETER_BARLAT\n1,{},{},{},1,{},{},0\n6,1.8,1.4,2.1,0,0,0,0\n"
    "0,0,0,0,0,0,0,0\n0,0,0,0,0,0,0,0\n0,0,0,0,0,0,0,0\n",
    kRho, kE, kNu, kEtan, kSigy);

// The square shell (nodes 1-4 at (0,0), (S,0), (S,S), (0,S); z and rotations fixed, node 1
// fixed) pulled along x at `vx` (nodes 2, 3) and, if `vy` != 0, along y at `vy` (nodes 3, 4),
// after a ramp of 2e-4 s; with vy = 0 the sides are free in y (uniaxial stress).
std::string stretched_sheet(const std::string& material, double vx, double vy, int istupd,
                            int elform, double end_time) {
  std::string s = fmt::format(
      "*KEYWORD\n*NODE\n1,0,0,0\n2,{0},0,0\n3,{0},{0},0\n4,0,{0},0\n*ELEMENT_SHELL\n"
      "1,1,1,2,3,4\n*PART\nsheet\n1,1,1,0,1\n*SECTION_SHELL\n1,{1},0.8333333,3\n"
      "{2},{2},{2},{2}\n*HOURGLASS\n1,4,0.05\n",
      kSide, elform, kT0);
  s += material;
  s += fmt::format("*CONTROL_SHELL\n20,0,-1,{}\n", istupd);
  const bool biaxial = vy != 0.0;
  s += fmt::format(
      "*BOUNDARY_SPC_NODE\n1,0,1,1,1,1,1,1\n2,0,0,{},1,1,1,1\n3,0,0,0,1,1,1,1\n4,0,1,0,1,1,1,1\n",
      biaxial ? 1 : 0);
  s += fmt::format("*BOUNDARY_PRESCRIBED_MOTION_NODE\n2,1,0,1,{0}\n3,1,0,1,{0}\n", vx);
  if (biaxial) s += fmt::format("3,2,0,1,{0}\n4,2,0,1,{0}\n", vy);
  s +=
      fmt::format("*DEFINE_CURVE\n1\n0,0\n2e-4,1\n1,1\n*CONTROL_TERMINATION\n{}\n*END\n", end_time);
  return s;
}

struct SheetState {
  double e1, e2, et;    // logarithmic strains: x, y, thickness
  double s1, s2;        // mean stresses xx, yy over the points (co-rotational = global here)
  double force_x;       // internal force on nodes 2 and 3 along x
  double width;         // current width (mean of the sides along y)
  double thickness;     // current element thickness
  double internal;      // the solver's internal energy
  double energy_ratio;  // glstat's total / (initial + external work)
};

SheetState run(const std::string& deck) {
  solver::Simulation sim(read(deck), {});
  sim.run();
  const auto& nodes = sim.state().nodes;
  const auto& b = sim.state().shell_blocks.at(0);
  SheetState r{};
  const double length = 0.5 * ((nodes.x.x[1] - nodes.x.x[0]) + (nodes.x.x[2] - nodes.x.x[3]));
  r.width = 0.5 * ((nodes.x.y[3] - nodes.x.y[0]) + (nodes.x.y[2] - nodes.x.y[1]));
  r.e1 = std::log(length / kSide);
  r.e2 = std::log(r.width / kSide);
  r.thickness = b.element_thickness[0];
  r.et = std::log(r.thickness / kT0);
  const int points = b.points_per_element();
  for (int q = 0; q < points; ++q) {
    r.s1 += b.stress[static_cast<std::size_t>(q) * element::kShellStress] / points;
    r.s2 += b.stress[static_cast<std::size_t>(q) * element::kShellStress + 1] / points;
  }
  r.force_x = nodes.f_int.x[1] + nodes.f_int.x[2];
  r.internal = sim.energy().internal();
  r.energy_ratio = sim.energy().ratio();
  return r;
}

// Uniaxial stress of the linear-hardening law at total log strain e1: s = E e1 while elastic,
// else s = SIGY + H e_p with e_p = e1 - s / E.
double uniaxial_stress(double e1) {
  if (kE * e1 <= kSigy) return kE * e1;
  const double ep = (e1 - kSigy / kE) / (1.0 + kH / kE);
  return kSigy + kH * ep;
}

// (a) Uniaxial J2 to e_1 = 0.34: e_t = -e_1 / 2 + (1/2 - nu) s / E, s from the hardening law;
// the width strain is the same (isotropy), and the membrane force uses the thinned section.
void uniaxial_j2(int elform) {
  const SheetState r = run(stretched_sheet(kJ2, 1.0, 0.0, 1, elform, 4e-3));
  const double s = uniaxial_stress(r.e1);
  const double expected = -0.5 * r.e1 + (0.5 - kNu) * s / kE;
  ::testing::Test::RecordProperty("e1", fmt::format("{:.5f}", r.e1));
  ::testing::Test::RecordProperty("et_over_expected", fmt::format("{:.7f}", r.et / expected));
  std::printf(
      "ELFORM %d uniaxial: e1 %.5f e_t %.7f expected %.7f (ratio %.7f), e_w %.7f, "
      "stress / law %.6f\n",
      elform, r.e1, r.et, expected, r.et / expected, r.e2, r.s1 / s);
  ASSERT_GT(r.e1, 0.3);
  EXPECT_NEAR(r.et / expected, 1.0, 1e-4);
  EXPECT_NEAR(r.e2 / expected, 1.0, 1e-3);  // width strain: the same by isotropy
  EXPECT_NEAR(r.s1 / s, 1.0, 1e-3);
  // Forces with the current thickness: F = s_xx t w (t0 would give 1.18 times that).
  EXPECT_NEAR(r.force_x / (r.s1 * r.thickness * r.width), 1.0, 1e-3);
}

TEST(ShellThickness, UniaxialJ2ThinsAsIncompressibleFlowPlusElasticPart) {
  uniaxial_j2(2);
}

TEST(ShellThickness, UniaxialJ2FullyIntegratedShellThinsTheSame) {
  uniaxial_j2(16);
}

// Uniaxial tension along the rolling direction of a Barlat sheet (R00 = 1.8): the plastic
// thickness strain is -e_1^p / (1 + R00), the elastic part -nu s / E.
TEST(ShellThickness, UniaxialBarlatThinsByTheLankfordCoefficient) {
  const SheetState r = run(stretched_sheet(kBarlat, 1.0, 0.0, 1, 2, 4e-3));
  const double s = r.s1;  // the rolling-direction yield stress of HR 1 at e_p
  const double e1p = r.e1 - s / kE;
  const double expected = -e1p / (1.0 + 1.8) - kNu * s / kE;
  std::printf("Barlat uniaxial: e1 %.5f e_t %.7f expected %.7f (ratio %.7f)\n", r.e1, r.et,
              expected, r.et / expected);
  ::testing::Test::RecordProperty("et_over_expected", fmt::format("{:.7f}", r.et / expected));
  ASSERT_GT(r.e1, 0.3);
  EXPECT_NEAR(r.et / expected, 1.0, 2e-4);
  // The stress is the hardening law's (independent of the thickness).
  EXPECT_NEAR(s / uniaxial_stress(r.e1), 1.0, 2e-3);
}

// (b) Equi-biaxial J2 to e_1 = e_2 = 0.26: e_t = -(e_1 + e_2) + 2 (1 - 2 nu) s / E (ISTUPD 1),
// -(e_1 + e_2) + 2 (1 - nu) s / E (ISTUPD 4: the plastic part alone), with s from the law:
// equivalent plastic strain 2 e_1^p, e_1^p = e_1 - (1 - nu) s / E.
void equibiaxial_j2(int istupd, int elform) {
  const SheetState r = run(stretched_sheet(kJ2, 1.0, 1.0, istupd, elform, 3e-3));
  // s = SIGY + H 2 (e1 - (1 - nu) s / E), solved for s.
  const double s = (kSigy + 2.0 * kH * r.e1) / (1.0 + 2.0 * kH * (1.0 - kNu) / kE);
  const double elastic = istupd == 1 ? 2.0 * (1.0 - 2.0 * kNu) : 2.0 * (1.0 - kNu);
  const double expected = -(r.e1 + r.e2) + elastic * s / kE;
  std::printf(
      "ISTUPD %d ELFORM %d equi-biaxial: e1 %.5f e2 %.5f e_t %.7f expected %.7f "
      "(ratio %.7f), stress / law %.6f\n",
      istupd, elform, r.e1, r.e2, r.et, expected, r.et / expected, r.s1 / s);
  ::testing::Test::RecordProperty("et_over_expected", fmt::format("{:.7f}", r.et / expected));
  ASSERT_GT(r.e1, 0.25);
  EXPECT_NEAR(r.e2 / r.e1, 1.0, 1e-9);
  EXPECT_NEAR(r.et / expected, 1.0, 1e-4);
  EXPECT_NEAR(r.s1 / s, 1.0, 1e-3);
  EXPECT_NEAR(r.s2 / s, 1.0, 1e-3);
}

TEST(ShellThickness, EquibiaxialJ2ThinsByTheSumOfTheInPlaneStrains) {
  equibiaxial_j2(1, 2);
  equibiaxial_j2(1, 16);
}

TEST(ShellThickness, Istupd4NeglectsTheElasticStrains) {
  equibiaxial_j2(4, 2);
  equibiaxial_j2(4, 16);
}

// (c) Elastic plane stress, unequal stretches (10 % and 5 %): e_t = -nu / (1 - nu) (e_1 + e_2);
// with ISTUPD 4 the elastic strains are neglected and the thickness stays.
TEST(ShellThickness, ElasticSheetFollowsPlaneStressPoisson) {
  for (const int elform : {2, 16}) {
    const SheetState r = run(stretched_sheet(kElastic, 1.0, 0.5, 1, elform, 1e-3 + 1e-4));
    const double expected = -kNu / (1.0 - kNu) * (r.e1 + r.e2);
    std::printf("ELFORM %d elastic: e1 %.5f e2 %.5f e_t %.9f expected %.9f (ratio %.9f)\n", elform,
                r.e1, r.e2, r.et, expected, r.et / expected);
    ::testing::Test::RecordProperty(fmt::format("et_over_expected_{}", elform),
                                    fmt::format("{:.9f}", r.et / expected));
    ASSERT_GT(r.e1, 0.09);
    ASSERT_GT(r.e2, 0.045);
    EXPECT_NEAR(r.et / expected, 1.0, 1e-6);
    const SheetState kept = run(stretched_sheet(kElastic, 1.0, 0.5, 4, elform, 1e-3 + 1e-4));
    EXPECT_EQ(kept.thickness, kT0);
  }
}

// (d) The energy of a thinning run: glstat's balance closes, and the internal energy is the
// work of the tension test, int V s de_1 with the volume V = V0 exp((1 - 2 nu) s / E) (midpoint
// rule on a fine grid). Without the thickness update the sheet's volume grows with its area
// (V0 exp(e_1 + e_w)) and so does the work: the same comparison then misses by 10 %.
TEST(ShellThickness, InternalEnergyIsTheWorkOfTheTensionTest) {
  auto work = [](double e1) {
    const int n = 200000;
    double w = 0.0;
    for (int i = 0; i < n; ++i) {
      const double e = (i + 0.5) * e1 / n;
      const double s = uniaxial_stress(e);
      w += s * std::exp((1.0 - 2.0 * kNu) * s / kE) * (e1 / n);
    }
    return w * kSide * kSide * kT0;
  };
  const SheetState r = run(stretched_sheet(kJ2, 1.0, 0.0, 1, 2, 4e-3));
  const double expected = work(r.e1);
  std::printf(
      "ISTUPD 1: internal %.6f J, work of the test %.6f J (ratio %.6f), energy ratio "
      "%.8f\n",
      r.internal, expected, r.internal / expected, r.energy_ratio);
  ::testing::Test::RecordProperty("internal_over_work",
                                  fmt::format("{:.6f}", r.internal / expected));
  EXPECT_NEAR(r.internal / expected, 1.0, 1e-3);
  EXPECT_NEAR(r.energy_ratio, 1.0, 1e-4);
  const SheetState constant = run(stretched_sheet(kJ2, 1.0, 0.0, 0, 2, 4e-3));
  const double expected0 = work(constant.e1);
  std::printf("ISTUPD 0: internal %.6f J, work of the test %.6f J (ratio %.6f)\n",
              constant.internal, expected0, constant.internal / expected0);
  EXPECT_GT(constant.internal / expected0, 1.08);
  EXPECT_EQ(constant.thickness, kT0);
}

// Switching to rigid and back (*DEFORMABLE_TO_RIGID_AUTOMATIC, paired): a free sheet (in-plane
// only: z and rotations fixed) pulled apart by nodal forces (1300 N on each corner: 260 MPa on the
// initial section, beyond SIGY) yields and thins; while the part is rigid its thickness stays
// exactly what it was (frozen with the stresses, no kernel runs), after the release it thins
// on, and at the end the volume has changed only elastically, as without the switch.
TEST(ShellThickness, FrozenWhileRigidAndThinningOnAfterTheRelease) {
  std::string deck = fmt::format(
      "*KEYWORD\n*NODE\n1,0,0,0\n2,{0},0,0\n3,{0},{0},0\n4,0,{0},0\n*ELEMENT_SHELL\n"
      "1,1,1,2,3,4\n*PART\nsheet\n1,1,1,0,1\n*SECTION_SHELL\n1,2,0.8333333,3\n"
      "{1},{1},{1},{1}\n*HOURGLASS\n1,4,0.05\n",
      kSide, kT0);
  deck += kJ2 + "*CONTROL_SHELL\n20,0,-1,1\n";
  deck +=
      "*BOUNDARY_SPC_NODE\n1,0,0,0,1,1,1,1\n2,0,0,0,1,1,1,1\n3,0,0,0,1,1,1,1\n4,0,0,0,1,1,1,1\n";
  deck += "*LOAD_NODE_POINT\n1,1,1,-1300\n4,1,1,-1300\n2,1,1,1300\n3,1,1,1300\n";
  deck += "*DEFINE_CURVE\n1\n0,0\n5e-4,1\n1,1\n";
  deck +=
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n10,0,1.5e-3,1.6e-3,0,0,20,1\n0,0,0,1e-5,1,0\n1\n"
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n20,0,2.5e-3,0,0,0,10,-1\n0,0,0,0,0,1\n1\n";
  // A free single element needs TSSFAC <= 0.55 (docs/verification.md, time step of tiny meshes).
  deck += "*CONTROL_TIMESTEP\n0,0.5\n*CONTROL_TERMINATION\n4e-3\n*END\n";
  solver::Simulation sim(read(deck), {});
  const auto& b = sim.state().shell_blocks.at(0);
  bool was_rigid = false, released = false;
  double frozen = 0.0, at_release = 0.0;
  int rigid_cycles = 0;
  while (!sim.finished()) {
    sim.cycle();
    const double t = b.element_thickness[0];
    if (b.rigid) {
      if (!was_rigid) frozen = t;
      EXPECT_EQ(t, frozen) << "time " << sim.state().time;
      ++rigid_cycles;
    } else if (was_rigid) {
      released = true;
      at_release = t;
    }

    was_rigid = b.rigid;
  }
  ASSERT_GT(rigid_cycles, 10);
  ASSERT_TRUE(released);
  const double final_t = b.element_thickness[0];
  std::printf(
      "thickness frozen at %.9g (ln %.6f) over %d rigid cycles, after release %.9g, end "
      "%.9g\n",
      frozen, std::log(frozen / kT0), rigid_cycles, at_release, final_t);
  EXPECT_LT(frozen, 0.995 * kT0);      // thinned before the switch
  EXPECT_LT(final_t, 0.999 * frozen);  // and on after the release
  // The end state: the volume changed only elastically, e_1 + e_2 + e_t = (1 - 2 nu)(s_1 + s_2)/E
  // (the flow need not stay uniaxial in this dynamic pull), e_1, e_2 from the node positions.
  const auto& n = sim.state().nodes;
  auto distance = [&](int a, int c) {
    return std::hypot(n.x.x[a] - n.x.x[c], n.x.y[a] - n.x.y[c]);
  };
  const double e1 = std::log(0.5 * (distance(0, 1) + distance(3, 2)) / kSide);
  const double e2 = std::log(0.5 * (distance(0, 3) + distance(1, 2)) / kSide);
  double trace = 0.0;
  for (int q = 0; q < 3; ++q)
    for (int c = 0; c < 2; ++c)
      trace += b.stress[static_cast<std::size_t>(q) * element::kShellStress + c] / 3;
  const double expected = -(e1 + e2) + (1.0 - 2.0 * kNu) * trace / kE;
  std::printf("end: e1 %.6f e2 %.6f e_t %.7f expected %.7f (ratio %.8f)\n", e1, e2,
              std::log(final_t / kT0), expected, std::log(final_t / kT0) / expected);
  ::testing::Test::RecordProperty("et_over_expected",
                                  fmt::format("{:.8f}", std::log(final_t / kT0) / expected));
  EXPECT_NEAR(std::log(final_t / kT0) / expected, 1.0, 1e-4);
}

}  // namespace
}  // namespace rf::test
