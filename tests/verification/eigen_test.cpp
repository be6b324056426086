// Eigen analysis against beam theory (docs/verification.md, "Eigen analysis"):
// * free-free slender beam: exactly six rigid modes, bending frequencies against Euler-Bernoulli
//   with the Timoshenko (shear + rotary inertia) correction; ELFORM 2 converges under refinement;
// * cantilever with SPCs: clamped-free Euler-Bernoulli frequencies, mass-orthonormal modes;
// * a part made of two unconnected halves: twelve near-zero modes and a warning naming them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "deck_builder.hpp"
#include "modal/eigen_analysis.hpp"
#include "model/error.hpp"

namespace rf {
namespace {

constexpr double kRho = 7.8e-9;  // t/mm^3
constexpr double kE = 2.1e5;     // MPa
constexpr double kNu = 0.3;

// Square-section beam along x: length l, side h, nx x nyz x nyz elements.
std::string beam_deck(double l, double h, int nx, int nyz, int elform, const std::string& extra) {
  test::BoxMesh mesh;
  mesh.nx = nx;
  mesh.ny = nyz;
  mesh.nz = nyz;
  mesh.lx = l;
  mesh.ly = h;
  mesh.lz = h;
  return "*KEYWORD\n" + mesh.keyword_text() + test::elastic_part(kRho, kE, kNu, elform, 6, 1.0) +
         extra + "*END\n";
}

// Bending frequency (Hz) of a slender square beam: Euler-Bernoulli with beta_n L from the
// characteristic equation, corrected for shear deformation and rotary inertia to first order
// (Timoshenko: omega^2 ~ omega_EB^2 [1 - (beta r)^2 (1 + E / (kappa G))], Han, Benaroya & Wei,
// J. Sound Vib. 225 (1999) 935, eq. for slender beams; kappa of a square section
// 10 (1 + nu) / (12 + 11 nu), Cowper 1966).
double bending_frequency(double beta_l, double l, double h) {
  const double area = h * h, inertia = h * h * h * h / 12.0;
  const double omega = beta_l * beta_l * std::sqrt(kE * inertia / (kRho * area)) / (l * l);
  const double r2 = inertia / area;
  const double kappa = 10.0 * (1.0 + kNu) / (12.0 + 11.0 * kNu);
  const double g = kE / (2.0 * (1.0 + kNu));
  const double beta2 = (beta_l / l) * (beta_l / l);
  const double factor = 1.0 - beta2 * r2 * (1.0 + kE / (kappa * g));
  return omega * std::sqrt(factor) / (2.0 * M_PI);
}

// Free-free roots of cos(bL) cosh(bL) = 1.
constexpr double kFreeFree[3] = {4.730040745, 7.853204624, 10.995607838};
// Clamped-free roots of cos(bL) cosh(bL) = -1.
constexpr double kClampedFree[3] = {1.875104069, 4.694091133, 7.854757438};

struct BeamResult {
  modal::ModeSet modes;
  modal::EigenReport report;
  std::vector<double> bending;  // elastic frequencies, each bending pair (y, z) once
};

BeamResult free_free_beam(int nx, int nyz, int elform, int neig, bool lflag) {
  const double l = 500.0, h = 10.0;
  std::string extra = "*CONTROL_IMPLICIT_GENERAL\n1,0.001\n";
  extra += fmt::format("*CONTROL_IMPLICIT_EIGENVALUE\n{},0.0,{},{}\n", neig, lflag ? 1 : 0,
                       lflag ? 1.0 : 0.0);
  const model::Model model = test::read(beam_deck(l, h, nx, nyz, elform, extra));
  BeamResult r;
  EXPECT_TRUE(modal::deck_requests_eigen_analysis(model));
  r.modes = modal::compute_modes(model, modal::request_from_deck(model), r.report);
  std::vector<double> elastic;
  for (std::size_t k = 0; k < r.modes.mode_count(); ++k) {
    if (!r.modes.rigid[k]) elastic.push_back(std::sqrt(r.modes.eigenvalues[k]) / (2.0 * M_PI));
  }
  // Square section: bending in y and z come in pairs of equal frequency; torsion and axial modes
  // lie between them. Keep one of each pair of (nearly) equal frequencies.
  for (std::size_t k = 0; k + 1 < elastic.size(); ++k) {
    if (std::abs(elastic[k + 1] - elastic[k]) < 1e-6 * elastic[k]) {
      r.bending.push_back(elastic[k]);
      ++k;
    }
  }
  return r;
}

TEST(EigenFreeFreeBeam, SixRigidModesAndBendingFrequenciesIhq6) {
  const BeamResult r = free_free_beam(100, 2, 1, 16, false);
  EXPECT_EQ(r.report.rigid_found, 6);
  EXPECT_EQ(r.modes.rigid_mode_count, 6);
  EXPECT_TRUE(r.report.warnings.empty()) << r.report.warnings.front();
  for (int k = 0; k < 6; ++k) EXPECT_EQ(r.modes.rigid[static_cast<std::size_t>(k)], 1) << k;
  EXPECT_EQ(r.modes.rigid[6], 0);
  ASSERT_GE(r.bending.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    const double reference = bending_frequency(kFreeFree[k], 500.0, 10.0);
    std::printf("free-free IHQ6 bending %d: %.4f Hz, reference %.4f Hz, error %+.3f%%\n", k + 1,
                r.bending[static_cast<std::size_t>(k)], reference,
                100.0 * (r.bending[static_cast<std::size_t>(k)] / reference - 1.0));
    EXPECT_NEAR(r.bending[static_cast<std::size_t>(k)] / reference, 1.0, 0.01) << "mode " << k;
  }
  std::printf("max residual %.2e, orthonormality %.2e, %d solves\n", r.report.max_residual,
              r.report.max_orthonormality_error, r.report.operator_applications);
  // The residual relative to ||K phi|| cannot fall below about eps * lambda_max / lambda (the
  // terms of K phi cancel down to lambda M phi): ~1e-9 for the first bending mode here.
  EXPECT_LT(r.report.max_residual, 1e-6);
  EXPECT_LT(r.report.max_orthonormality_error, 1e-10);
}

TEST(EigenFreeFreeBeam, LflagRemovesExactlyTheSixRigidModes) {
  const BeamResult r = free_free_beam(100, 2, 1, 10, true);
  EXPECT_EQ(r.report.rigid_found, 6);
  EXPECT_EQ(r.report.removed_by_lflag, 6);
  ASSERT_EQ(r.modes.mode_count(), 10u);
  for (std::size_t k = 0; k < 10; ++k) EXPECT_EQ(r.modes.rigid[k], 0);
  // The first kept mode is the first bending mode.
  EXPECT_NEAR(std::sqrt(r.modes.eigenvalues[0]) / (2.0 * M_PI) /
                  bending_frequency(kFreeFree[0], 500.0, 10.0),
              1.0, 0.01);
}

TEST(EigenFreeFreeBeam, Elform2ConvergesUnderRefinement) {
  const double reference = bending_frequency(kFreeFree[0], 500.0, 10.0);
  double previous_error = 1e300;
  for (const auto& [nx, nyz] : {std::pair{25, 1}, std::pair{50, 2}, std::pair{100, 4}}) {
    const BeamResult r = free_free_beam(nx, nyz, 2, 8, false);
    ASSERT_GE(r.bending.size(), 1u);
    const double error = std::abs(r.bending[0] / reference - 1.0);
    std::printf("ELFORM 2 %dx%dx%d: first bending %.4f Hz, reference %.4f Hz, error %.3f%%\n", nx,
                nyz, nyz, r.bending[0], reference, 100.0 * error);
    EXPECT_EQ(r.report.rigid_found, 6);
    // Second-order convergence of the parasitic shear stiffness of the fully integrated
    // deviatoric part: the error falls by about 4 per halving (measured 2.8 and 3.7).
    EXPECT_LT(error, previous_error / 2.5);
    previous_error = error;
  }
  EXPECT_LT(previous_error, 0.05);
}

TEST(EigenFreeFreeBeam, BackendsAgreeAndCenterFindsTheNearestModes) {
  const model::Model model = test::read(beam_deck(500.0, 10.0, 50, 2, 1, ""));
  modal::EigenRequest request;
  request.mode_count = 12;
  modal::EigenReport cholmod, simplicial;
  const modal::ModeSet a = modal::compute_modes(model, request, cholmod);
  request.backend = modal::FactorizationBackend::EigenSimplicial;
  const modal::ModeSet b = modal::compute_modes(model, request, simplicial);
  EXPECT_EQ(simplicial.backend, "eigen-simplicial");
  ASSERT_EQ(a.mode_count(), b.mode_count());
  for (std::size_t k = 6; k < a.mode_count(); ++k) {
    EXPECT_NEAR(b.eigenvalues[k] / a.eigenvalues[k], 1.0, 1e-9) << k;
  }
  // CENTER just above the tenth mode's frequency: that mode (or its equal-frequency partner)
  // is the nearest; LDL^T of the indefinite K - sigma M.
  const double f9 = std::sqrt(a.eigenvalues[9]) / (2.0 * M_PI);
  modal::EigenRequest centred;
  centred.mode_count = 1;
  centred.center_frequency = f9 * (1.0 + 1e-3);
  const modal::ModeSet c = modal::compute_modes(model, centred);
  ASSERT_EQ(c.mode_count(), 1u);
  EXPECT_NEAR(c.eigenvalues[0] / a.eigenvalues[9], 1.0, 1e-8);
}

TEST(EigenFreeFreeBeam, SecondOrderElementsOnACoarseMesh) {
  // 25 x 1 x 1 hexahedra raised to p = 2 (27 nodes each): the first bending frequency against
  // the same Timoshenko-corrected reference.
  const BeamResult r = [] {
    const model::Model model =
        test::read(beam_deck(500.0, 10.0, 25, 1, 1, "*CHANGE_P-ORDER\nALL,0,2\n"));
    BeamResult out;
    modal::EigenRequest request;
    request.mode_count = 12;
    // The total-Lagrangian p = 2 kernel forms x - X, so its probed stiffness carries more
    // round-off: its rigid eigenvalues measure up to ~1e-10 lambda_scale (docs/eigen.md).
    request.rigid_tolerance = 1e-8;
    out.modes = modal::compute_modes(model, request, out.report);
    std::vector<double> elastic;
    for (std::size_t k = 0; k < out.modes.mode_count(); ++k) {
      if (!out.modes.rigid[k]) elastic.push_back(std::sqrt(out.modes.eigenvalues[k]) / (2 * M_PI));
    }
    for (std::size_t k = 0; k + 1 < elastic.size(); ++k) {
      if (std::abs(elastic[k + 1] - elastic[k]) < 1e-6 * elastic[k]) {
        out.bending.push_back(elastic[k]);
        ++k;
      }
    }
    return out;
  }();
  EXPECT_EQ(r.report.rigid_found, 6);
  ASSERT_GE(r.bending.size(), 1u);
  const double reference = bending_frequency(kFreeFree[0], 500.0, 10.0);
  std::printf("p = 2, 25x1x1: first bending %.4f Hz, reference %.4f Hz, error %+.3f%%\n",
              r.bending[0], reference, 100.0 * (r.bending[0] / reference - 1.0));
  EXPECT_NEAR(r.bending[0] / reference, 1.0, 0.02);
}

TEST(EigenCantilever, ClampedFreeFrequenciesAndMassOrthonormality) {
  const double l = 500.0, h = 10.0;
  test::BoxMesh mesh;
  mesh.nx = 100;
  mesh.ny = mesh.nz = 2;
  mesh.lx = l;
  mesh.ly = mesh.lz = h;
  const std::string deck = "*KEYWORD\n" + mesh.keyword_text() +
                           test::elastic_part(kRho, kE, kNu, 1, 6, 1.0) +
                           test::node_set(1, mesh.face_x(0)) +
                           "*BOUNDARY_SPC_SET\n1,0,1,1,1\n"
                           "*CONTROL_IMPLICIT_GENERAL\n1,0.001\n"
                           "*CONTROL_IMPLICIT_EIGENVALUE\n8\n*END\n";
  const model::Model model = test::read(deck);
  modal::EigenReport report;
  const modal::ModeSet modes = modal::compute_modes(model, modal::request_from_deck(model), report);
  EXPECT_EQ(report.rigid_found, 0);
  EXPECT_EQ(report.free_dof_count, report.dof_count - 27);
  // Fixed DOFs are zero in every mode.
  for (std::size_t k = 0; k < modes.mode_count(); ++k) {
    for (std::size_t i = 0; i < modes.node_count(); ++i) {
      if (modes.coordinates[3 * i] == 0.0) {
        for (int d = 0; d < 3; ++d) EXPECT_EQ(modes.shape(k)[3 * i + d], 0.0);
      }
    }
  }
  std::vector<double> bending;
  for (std::size_t k = 0; k + 1 < modes.mode_count(); ++k) {
    const double f0 = std::sqrt(modes.eigenvalues[k]) / (2.0 * M_PI);
    const double f1 = std::sqrt(modes.eigenvalues[k + 1]) / (2.0 * M_PI);
    if (std::abs(f1 - f0) < 1e-6 * f0) {
      bending.push_back(f0);
      ++k;
    }
  }
  ASSERT_GE(bending.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const double reference = bending_frequency(kClampedFree[k], l, h);
    std::printf("cantilever bending %d: %.4f Hz, reference %.4f Hz, error %+.3f%%\n", k + 1,
                bending[static_cast<std::size_t>(k)], reference,
                100.0 * (bending[static_cast<std::size_t>(k)] / reference - 1.0));
    EXPECT_NEAR(bending[static_cast<std::size_t>(k)] / reference, 1.0, 0.015);
  }
  // Mass orthonormality computed here from the written shapes and masses.
  double worst = 0.0;
  for (std::size_t a = 0; a < modes.mode_count(); ++a) {
    for (std::size_t b = 0; b < modes.mode_count(); ++b) {
      double dot = 0.0;
      for (std::size_t i = 0; i < modes.node_count(); ++i) {
        for (int d = 0; d < 3; ++d) {
          dot += modes.mass[i] * modes.shape(a)[3 * i + d] * modes.shape(b)[3 * i + d];
        }
      }
      worst = std::max(worst, std::abs(dot - (a == b ? 1.0 : 0.0)));
    }
  }
  std::printf("cantilever: max |Phi^T M Phi - I| = %.2e, max residual %.2e\n", worst,
              report.max_residual);
  EXPECT_LT(worst, 1e-10);
  EXPECT_LT(report.max_residual, 1e-6);  // round-off floor ~1e-8 here, see the free-free test
}

TEST(EigenDisconnectedPart, TwelveNearZeroModesAndAWarningNamingTheGroups) {
  // Two 4x2x2 blocks of part 1, side by side with a gap: no shared nodes.
  test::BoxMesh left;
  left.nx = 4;
  left.ny = left.nz = 2;
  left.lx = 40.0;
  left.ly = left.lz = 10.0;
  std::string nodes = "*NODE\n", elements = "*ELEMENT_SOLID\n";
  int eid = 0;
  for (int half = 0; half < 2; ++half) {
    const int offset = half * 1000;
    const double shift = half * 50.0;
    for (int k = 0; k <= 2; ++k)
      for (int j = 0; j <= 2; ++j)
        for (int i = 0; i <= 4; ++i) {
          double x, y, z;
          left.coordinates(i, j, k, x, y, z);
          nodes += fmt::format("{},{},{},{}\n", offset + left.node_id(i, j, k), x + shift, y, z);
        }
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 4; ++i) {
          auto id = [&](int a, int b, int c) { return offset + left.node_id(a, b, c); };
          elements +=
              fmt::format("{},1,{},{},{},{},{},{},{},{}\n", ++eid, id(i, j, k), id(i + 1, j, k),
                          id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
                          id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1));
        }
  }
  const model::Model model = test::read("*KEYWORD\n" + nodes + elements +
                                        test::elastic_part(kRho, kE, kNu, 1, 6, 1.0) + "*END\n");
  modal::EigenRequest request;
  request.mode_count = 16;
  modal::EigenReport report;
  const modal::ModeSet modes = modal::compute_modes(model, request, report);
  EXPECT_EQ(report.rigid_found, 12);
  EXPECT_EQ(report.connected_groups, 2);
  for (std::size_t k = 0; k < 12; ++k) EXPECT_EQ(modes.rigid[k], 1);
  EXPECT_EQ(modes.rigid[12], 0);
  bool named = false;
  for (const auto& w : report.warnings) {
    named |= w.find("12 near-zero modes") != std::string::npos &&
             w.find("node IDs 1..45") != std::string::npos &&
             w.find("node IDs 1001..1045") != std::string::npos;
  }
  EXPECT_TRUE(named) << (report.warnings.empty() ? "" : report.warnings.back());
}

TEST(EigenRequestChecks, BadInputIsAnInputError) {
  const model::Model model = test::read(beam_deck(100.0, 10.0, 4, 1, 1, ""));
  modal::EigenRequest request;
  request.mode_count = 0;
  EXPECT_THROW(modal::compute_modes(model, request), InputError);
  request.mode_count = 4;
  request.parts = {9};
  EXPECT_THROW(modal::compute_modes(model, request), InputError);
}

}  // namespace
}  // namespace rf
