// The rubber materials' updates at one point (material/mooney_rivlin.hpp, ogden.hpp,
// hyperelastic.hpp), against references computed here:
//  - the left Cauchy-Green update reproduces b = F F^T of a prescribed deformation path exactly
//    (to round-off), for any step size, and a rigid rotation of a stretched point turns its
//    stress as Q sigma Q^T (objectivity);
//  - the stress equals the derivative of the LS-DYNA strain energy (numerical, in principal
//    stretches) in arbitrary rotated frames;
//  - small strain: shear modulus 2 (A + B) or sum(mu alpha)/2 and Poisson's ratio PR;
//  - the SIMD-lane instantiation gives the same bits as the scalar one.
// Bad *MAT_027 / *MAT_077_O input: each refused field is named with file, line and keyword.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "io/keyword/reader.hpp"
#include "material/hyperelastic_setup.hpp"
#include "material/mooney_rivlin.hpp"
#include "material/ogden.hpp"
#include "model/error.hpp"
#include "solver/build_state.hpp"

namespace rf::test {
namespace {

using material::HyperelasticParameters;

HyperelasticParameters mooney(double a, double b, double nu) {
  model::Material m;
  m.kind = model::MaterialKind::MooneyRivlinRubber;
  m.pr = nu;
  m.rubber.a = a;
  m.rubber.b = b;
  return material::make_hyperelastic_parameters(m);
}

HyperelasticParameters ogden(std::vector<double> mu, std::vector<double> alpha, double nu) {
  model::Material m;
  m.kind = model::MaterialKind::OgdenRubber;
  m.pr = nu;
  for (std::size_t i = 0; i < mu.size(); ++i) {
    m.rubber.mu[i] = mu[i];
    m.rubber.alpha[i] = alpha[i];
  }
  m.rubber.terms = static_cast<int>(mu.size());
  return material::make_hyperelastic_parameters(m);
}

Eigen::Matrix3d from_voigt(const double* s) {
  Eigen::Matrix3d m;
  m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  return m;
}

// One step of the update driven by the velocity gradient of F0 -> F1 on the mid configuration.
template <class M>
void step(const HyperelasticParameters& p, const Eigen::Matrix3d& f0, const Eigen::Matrix3d& f1,
          double dt, double s[6], double h[6]) {
  const Eigen::Matrix3d l = (f1 - f0) / dt * (0.5 * (f0 + f1)).inverse();
  double lv[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) lv[3 * i + j] = l(i, j);
  double d[6], w[3];
  material::split_velocity_gradient(lv, d, w);
  M::update(material::ElasticConstants{}, p, d, w, dt, s, h);
}

// A deformation path with stretch, shear and rotation.
Eigen::Matrix3d path(double t) {
  Eigen::Matrix3d u;
  u << 1.0 + 1.5 * t, 0.4 * t, 0.1 * t, 0.0, 1.0 - 0.3 * t, 0.2 * t, 0.0, 0.0, 1.0 / (1.0 + t);
  return Eigen::AngleAxisd(2.0 * t, Eigen::Vector3d(1.0, 2.0, 3.0).normalized())
             .toRotationMatrix() *
         u;
}

TEST(RubberKinematics, LeftCauchyGreenIsExactForAHomogeneousPath) {
  for (int steps : {3, 50, 1000}) {
    double s[6] = {}, h[6] = {};
    const auto p = mooney(0.4, 0.1, 0.49);
    for (int n = 0; n < steps; ++n)
      step<material::MooneyRivlinMaterial>(p, path(double(n) / steps), path(double(n + 1) / steps),
                                           1.0 / steps, s, h);
    const Eigen::Matrix3d f = path(1.0);
    const Eigen::Matrix3d b = f * f.transpose() - Eigen::Matrix3d::Identity();
    EXPECT_LT((from_voigt(h) - b).norm(), 1e-12 * steps) << steps << " steps";
  }
}

// sigma_a = lambda_a / J dW/dlambda_a (central differences) in the eigenframe of b.
template <class W>
Eigen::Matrix3d reference_stress(W energy, const Eigen::Matrix3d& f) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(f * f.transpose());
  double l[3];
  for (int a = 0; a < 3; ++a) l[a] = std::sqrt(es.eigenvalues()[a]);
  const double jac = l[0] * l[1] * l[2];
  Eigen::Vector3d s;
  for (int a = 0; a < 3; ++a) {
    const double h = 1e-5 * l[a];
    double lp[3] = {l[0], l[1], l[2]}, lm[3] = {l[0], l[1], l[2]};
    lp[a] += h;
    lm[a] -= h;
    s[a] = l[a] / jac * (energy(lp) - energy(lm)) / (2.0 * h);
  }
  return es.eigenvectors() * s.asDiagonal() * es.eigenvectors().transpose();
}

template <class M, class W>
void expect_stress_from_energy(const HyperelasticParameters& p, W energy, double tol) {
  for (int k = 1; k <= 8; ++k) {
    const Eigen::Matrix3d f = path(0.2 * k);
    const Eigen::Matrix3d b = f * f.transpose() - Eigen::Matrix3d::Identity();
    const double h[6] = {b(0, 0), b(1, 1), b(2, 2), b(0, 1), b(1, 2), b(2, 0)};
    double s[6];
    if constexpr (std::is_same_v<M, material::OgdenMaterial>)
      material::ogden_stress(p, h, s);
    else
      M::stress(p, h, s);
    const Eigen::Matrix3d ref = reference_stress(energy, f);
    EXPECT_LT((from_voigt(s) - ref).norm() / ref.norm(), tol) << "t = " << 0.2 * k;
  }
}

TEST(RubberStress, MooneyRivlinIsTheDerivativeOfTheManualsEnergy) {
  const double a = 0.4, b = 0.1, nu = 0.45;
  const auto energy = [&](const double* l) {
    const double c = 0.5 * a + b;
    const double d = (a * (5 * nu - 2) + b * (11 * nu - 5)) / (2 * (1 - 2 * nu));
    const double s1 = l[0] * l[0], s2 = l[1] * l[1], s3 = l[2] * l[2];
    const double i3 = s1 * s2 * s3;
    return a * (s1 + s2 + s3 - 3) + b * (s1 * s2 + s2 * s3 + s3 * s1 - 3) +
           c * (1 / (i3 * i3) - 1) + d * (i3 - 1) * (i3 - 1);
  };
  expect_stress_from_energy<material::MooneyRivlinMaterial>(mooney(a, b, nu), energy, 1e-8);
}

TEST(RubberStress, OgdenIsTheDerivativeOfTheManualsEnergy) {
  const std::vector<double> mu = {0.63, 0.0012, -0.01}, alpha = {1.3, 5.0, -2.0};
  const double nu = 0.49;
  const auto p = ogden(mu, alpha, nu);
  const double g = 0.5 * (0.63 * 1.3 + 0.0012 * 5.0 + 0.01 * 2.0);
  const double k = 2 * g * (1 + nu) / (3 * (1 - 2 * nu));
  EXPECT_NEAR(p.bulk, k, 1e-15 * k);
  const auto energy = [&](const double* l) {
    const double jac = l[0] * l[1] * l[2];
    double w = k * (jac - 1 - std::log(jac));
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i)
        w += mu[j] / alpha[j] * (std::pow(l[i] / std::cbrt(jac), alpha[j]) - 1);
    return w;
  };
  expect_stress_from_energy<material::OgdenMaterial>(p, energy, 1e-8);
}

// Small strain: sigma = lambda tr(e) I + 2 G e with G = 2 (A + B) (or sum mu alpha / 2) and
// Poisson's ratio PR, from a uniaxial strain e_xx = 1e-6 and a shear e_xy = 1e-6.
template <class M>
void expect_small_strain(const HyperelasticParameters& p, double g, double nu) {
  const double e = 1e-6;
  double s[6];
  const double h_axial[6] = {(1 + e) * (1 + e) - 1, 0, 0, 0, 0, 0};
  if constexpr (std::is_same_v<M, material::OgdenMaterial>)
    material::ogden_stress(p, h_axial, s);
  else
    M::stress(p, h_axial, s);
  const double lambda_2mu = s[0] / e, lambda = s[1] / e;
  EXPECT_NEAR(lambda_2mu - lambda, 2 * g, 1e-5 * g);
  EXPECT_NEAR(lambda / (2 * (lambda + 0.5 * (lambda_2mu - lambda))), nu, 1e-5);
  const double h_shear[6] = {e * e, e * e, 0, 2 * e, 0, 0};  // F = I + e (x y^T + y x^T)
  if constexpr (std::is_same_v<M, material::OgdenMaterial>)
    material::ogden_stress(p, h_shear, s);
  else
    M::stress(p, h_shear, s);
  EXPECT_NEAR(s[3] / (2 * e), g, 1e-5 * g);
}

TEST(RubberStress, SmallStrainModuliAreTheCardsShearModulusAndPoissonsRatio) {
  expect_small_strain<material::MooneyRivlinMaterial>(mooney(0.4, 0.1, 0.45), 1.0, 0.45);
  expect_small_strain<material::MooneyRivlinMaterial>(mooney(0.4, 0.1, 0.4995), 1.0, 0.4995);
  expect_small_strain<material::OgdenMaterial>(ogden({0.8, -0.1}, {2.0, -2.0}, 0.45), 0.9, 0.45);
}

TEST(RubberStress, ReferenceStateIsStressFree) {
  const double h[6] = {0, 0, 0, 0, 0, 0};
  double s[6];
  material::MooneyRivlinMaterial::stress(mooney(0.4, 0.1, 0.49), h, s);
  for (double v : s) EXPECT_EQ(v, 0.0);
  material::ogden_stress(ogden({0.63, 0.0012, -0.01}, {1.3, 5.0, -2.0}, 0.49), h, s);
  for (double v : s) EXPECT_EQ(v, 0.0);
}

// A point stretched, then turned rigidly by 3 rad in large steps: the stress turns with it.
template <class M>
void expect_objective(const HyperelasticParameters& p) {
  double s[6] = {}, h[6] = {};
  Eigen::Matrix3d u;
  u << 1.8, 0.3, 0.0, 0.3, 0.7, 0.1, 0.0, 0.1, 0.9;
  const int n = 20;
  for (int k = 0; k < n; ++k) {
    const Eigen::Matrix3d f0 =
        Eigen::Matrix3d::Identity() + (u - Eigen::Matrix3d::Identity()) * k / n;
    const Eigen::Matrix3d f1 =
        Eigen::Matrix3d::Identity() + (u - Eigen::Matrix3d::Identity()) * (k + 1) / n;
    step<M>(p, f0, f1, 1e-3, s, h);
  }
  const Eigen::Matrix3d s0 = from_voigt(s);
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -1.0, 0.5).normalized();
  for (int k = 0; k < 30; ++k) {
    const Eigen::Matrix3d r0 = Eigen::AngleAxisd(0.1 * k, axis).toRotationMatrix();
    const Eigen::Matrix3d r1 = Eigen::AngleAxisd(0.1 * (k + 1), axis).toRotationMatrix();
    step<M>(p, r0 * u, r1 * u, 1e-3, s, h);
  }
  const Eigen::Matrix3d q = Eigen::AngleAxisd(3.0, axis).toRotationMatrix();
  EXPECT_LT((from_voigt(s) - q * s0 * q.transpose()).norm(), 1e-12 * s0.norm());
  EXPECT_GT(s0.norm(), 0.1);
}

TEST(RubberKinematics, RigidRotationTurnsTheStress) {
  expect_objective<material::MooneyRivlinMaterial>(mooney(0.4, 0.1, 0.4995));
  expect_objective<material::OgdenMaterial>(ogden({0.63, 0.0012, -0.01}, {1.3, 5.0, -2.0}, 0.4995));
}

// The kernels run the update on GCC vectors of doubles: lane by lane the same bits as scalars.
TEST(RubberKinematics, VectorLanesEqualScalarPoints) {
  using V = double __attribute__((vector_size(2 * sizeof(double))));  // SSE2: any x86-64 build
  const auto p = ogden({0.63, 0.0012, -0.01}, {1.3, 5.0, -2.0}, 0.49);
  const auto pm = mooney(0.4, 0.1, 0.49);
  V d[6], w[3], s[6], h[6], sm[6], hm[6];
  double ds[2][6], ws[2][3];
  for (int l = 0; l < 2; ++l) {
    for (int c = 0; c < 6; ++c) {
      ds[l][c] = std::sin(1.0 + c + 7 * l);
      d[c][l] = ds[l][c];
      h[c][l] = hm[c][l] = 0.1 * std::cos(2.0 + c + 3 * l) + (c < 3 ? 0.2 : 0.0);
    }
    for (int c = 0; c < 3; ++c) w[c][l] = ws[l][c] = std::cos(0.5 + c + l);
  }
  material::OgdenMaterial::update(material::ElasticConstants{}, p, d, w, 0.01, s, h);
  material::MooneyRivlinMaterial::update(material::ElasticConstants{}, pm, d, w, 0.01, sm, hm);
  for (int l = 0; l < 2; ++l) {
    double hs[6], ss[6], hsm[6], ssm[6];
    for (int c = 0; c < 6; ++c)
      hs[c] = hsm[c] = 0.1 * std::cos(2.0 + c + 3 * l) + (c < 3 ? 0.2 : 0.0);
    material::OgdenMaterial::update(material::ElasticConstants{}, p, ds[l], ws[l], 0.01, ss, hs);
    material::MooneyRivlinMaterial::update(material::ElasticConstants{}, pm, ds[l], ws[l], 0.01,
                                           ssm, hsm);
    for (int c = 0; c < 6; ++c) {
      EXPECT_EQ(s[c][l], ss[c]);
      EXPECT_EQ(h[c][l], hs[c]);
      EXPECT_EQ(sm[c][l], ssm[c]);
    }
  }
}

// --- Bad input -------------------------------------------------------------------------------

std::string deck(const std::string& mat, int elform = 1) {
  return "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
         "*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n*PART\nblock\n1,1,1\n*SECTION_SOLID\n1," +
         std::to_string(elform) + "\n" + mat + "*END\n";
}

std::string error_of(const std::string& text) {
  try {
    const model::Model model = io::read_deck_text(text, "rubber.k");
    const solver::NodeIndex index(model);
    solver::build_state(model, index);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

struct Case {
  std::string name;
  std::string text;
  std::vector<std::string> expected;
};

class RubberInput : public ::testing::TestWithParam<Case> {};

TEST_P(RubberInput, ErrorNamesFileLineKeywordAndField) {
  const Case& c = GetParam();
  const std::string message = error_of(c.text);
  ASSERT_FALSE(message.empty()) << "no error for " << c.name;
  for (const auto& part : c.expected)
    EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "' in: " << message;
}

const std::string kMr = "*MAT_MOONEY-RIVLIN_RUBBER\n";
const std::string kOg = "*MAT_OGDEN_RUBBER\n";

std::vector<Case> cases() {
  return {
      {"mr_fit_from_curve",
       deck(kMr + "1,1000,0.499,0,0\n1,1,1,5\n"),
       {"rubber.k:20", "*MAT_MOONEY-RIVLIN_RUBBER", "LCID", "not supported"}},
      {"mr_fit_a_b_zero",
       deck(kMr + "1,1000,0.499,0,0\n1,1,1\n"),
       {"rubber.k:19", "*MAT_MOONEY-RIVLIN_RUBBER", "field A", "fit"}},
      {"mr_ref", deck("*MAT_027\n1,1000,0.499,4e5,1e5,1\n"), {"*MAT_027", "REF", "not supported"}},
      {"mr_pr_half",
       deck(kMr + "1,1000,0.5,4e5,1e5\n"),
       {"*MAT_MOONEY-RIVLIN_RUBBER", "PR", "[0, 0.5)"}},
      {"mr_no_density", deck(kMr + "1,0,0.49,4e5,1e5\n"), {"RO", "positive"}},
      {"mr_negative_shear", deck(kMr + "1,1000,0.49,-4e5,1e5\n"), {"field B", "positive"}},
      {"ogden_fit",
       deck(kOg + "1,1000,0.499,2\n1,1,1,5\n"),
       {"rubber.k:19", "*MAT_OGDEN_RUBBER", "field N", "fit"}},
      {"ogden_hysteresis", deck(kOg + "1,1000,-0.499,0\n"), {"field PR", "TBHYS"}},
      {"ogden_friction_g",
       deck(kOg + "1,1000,0.499,0,0,1e5,1e3\n1e6\n2\n"),
       {"field G", "not supported"}},
      {"ogden_friction_sigf", deck(kOg + "1,1000,0.499,0,0,0,1e3\n1e6\n2\n"), {"SIGF"}},
      {"ogden_ref", deck("*MAT_077_O\n1,1000,0.499,0,0,0,0,1\n1e6\n2\n"), {"*MAT_077_O", "REF"}},
      {"ogden_alpha_zero",
       deck(kOg + "1,1000,0.499,0\n1e6,2e5\n2\n"),
       {"rubber.k:21", "ALPHA2", "nonzero"}},
      {"ogden_no_mu", deck(kOg + "1,1000,0.499,0\n0\n2\n"), {"rubber.k:20", "MU1"}},
      {"ogden_negative_shear", deck(kOg + "1,1000,0.499,0\n-1e6\n2\n"), {"MU1", "positive"}},
      {"ogden_missing_alpha_card", deck(kOg + "1,1000,0.499,0\n1e6\n"), {"ALPHA1"}},
      {"ogden_prony",
       deck(kOg + "1,1000,0.499,0\n1e6\n2\n1e5,10.0\n"),
       {"rubber.k:22", "field GI", "viscoelastic"}},
      {"rubber_on_p_order",
       deck(kOg + "1,1000,0.499,0\n1e6\n2\n*CHANGE_P-ORDER\nP,1,2\n"),
       {"MID", "order 2"}},
  };
}

INSTANTIATE_TEST_SUITE_P(Rubber, RubberInput, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.name; });

TEST(RubberInput, ZeroPronyCardsAndTitleAreAccepted) {
  EXPECT_EQ(error_of(deck("*MAT_OGDEN_RUBBER_TITLE\nskin\n1,1000,0.499,0\n1e6\n2\n0,0,0\n")), "");
  EXPECT_EQ(error_of(deck("*MAT_027_TITLE\npad\n1,1000,0.499,4e5,1e5\n0,0,0,0\n", 2)), "");
}

}  // namespace
}  // namespace rf::test
