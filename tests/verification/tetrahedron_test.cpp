// One-point tetrahedra (*SECTION_SOLID ELFORM 10, *ELEMENT_SOLID with 4 nodes) against the
// elementary theory of a free-free bar (Timoshenko & Goodier; Graff, Wave Motion in Elastic
// Solids, sec. 2.1): at PR 0 the first axial mode v = v0 cos(pi x / L) has the period
// T = 2 L / c, c = sqrt(E / rho). The lumped-mass, constant-strain discretisation of a bar
// lengthens the period by about (pi h / L)^2 / 24 (the dispersion of the discrete chain,
// w_h = (2 c / h) sin(k h / 2)), and the error must fall as h^2 with the mesh. Every velocity
// field of a tetrahedron is linear, so the hourglass forces (IHQ 1 by default) must do no work.
// TSSFAC 0.6: the bar is one cell across, every node on the surface, and the step rule (smallest
// altitude / c, as LS-DYNA) is then above the stable step (docs/theory.md, "Tetrahedra").
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "deck_builder.hpp"
#include "model/error.hpp"

namespace rf::test {
namespace {

constexpr double kRho = 7850.0, kE = 2.1e11, kLength = 1.0, kWidth = 0.1, kV0 = 1.0;

// nx cells of kLength / nx x kWidth x kWidth along x, each split into the six Kuhn tetrahedra
// about its diagonal (0,0,0)-(1,1,1) (conforming from cell to cell), written as 4-node
// *ELEMENT_SOLID cards, ordered so that every volume is positive.
std::string tetrahedral_bar(int nx, int elform) {
  auto node = [nx](int i, int j, int k) { return 1 + i + (nx + 1) * (j + 2 * k); };
  auto position = [nx](int i, int j, int k) {
    return Eigen::Vector3d(kLength * i / nx, kWidth * j, kWidth * k);
  };
  std::string deck = "*KEYWORD\n*NODE\n";
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= 1; ++j)
      for (int i = 0; i <= nx; ++i) {
        const Eigen::Vector3d p = position(i, j, k);
        deck += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", node(i, j, k), p.x(), p.y(), p.z());
      }
  deck += "*ELEMENT_SOLID\n";
  const std::array<std::array<int, 3>, 6> orders{
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  int eid = 0;
  for (int c = 0; c < nx; ++c) {
    for (const auto& order : orders) {
      std::array<std::array<int, 3>, 4> v{};
      v[0] = {c, 0, 0};
      for (int s = 1; s < 4; ++s) {
        v[s] = v[s - 1];
        v[s][order[s - 1]] += 1;
      }
      auto at = [&](int s) { return position(v[s][0], v[s][1], v[s][2]); };
      if ((at(1) - at(0)).cross(at(2) - at(0)).dot(at(3) - at(0)) < 0.0) std::swap(v[1], v[2]);
      deck += fmt::format("{},1,{},{},{},{}\n", ++eid, node(v[0][0], v[0][1], v[0][2]),
                          node(v[1][0], v[1][1], v[1][2]), node(v[2][0], v[2][1], v[2][2]),
                          node(v[3][0], v[3][1], v[3][2]));
    }
  }
  deck +=
      fmt::format("*PART\nbar\n1,1,1\n*SECTION_SOLID\n1,{}\n*MAT_ELASTIC\n1,{:.17g},{:.17g},0.0\n",
                  elform, kRho, kE);
  // The first free-free mode as the initial velocity, node by node.
  deck += "*INITIAL_VELOCITY_NODE\n";
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= 1; ++j)
      for (int i = 0; i <= nx; ++i) {
        deck += fmt::format("{},{:.17g},0,0\n", node(i, j, k),
                            kV0 * std::cos(std::numbers::pi * i / nx));
      }
  // No bulk viscosity: the reference is the undamped bar.
  deck += "*CONTROL_BULK_VISCOSITY\n0.0,0.0\n";
  return deck;
}

struct Vibration {
  double period = 0.0, hourglass = 0.0, kinetic0 = 0.0, energy_ratio = 0.0;
};

// Period from the zero crossings of the end face's mean velocity (at T/4 and 3T/4).
Vibration vibrate(int nx) {
  const double period = 2.0 * kLength / std::sqrt(kE / kRho);
  solver::Simulation sim(
      read(tetrahedral_bar(nx, 10) + fmt::format("*CONTROL_TERMINATION\n{:.17g},0\n"
                                                 "*CONTROL_TIMESTEP\n0.0,0.6\n*END\n",
                                                 0.9 * period)),
      {});
  const auto& v = sim.state().nodes.v;
  std::vector<std::int32_t> end;  // the four nodes at x = 0
  const auto& x0 = sim.state().nodes.x0;
  for (std::size_t i = 0; i < x0.size(); ++i)
    if (x0.x[i] == 0.0) end.push_back(static_cast<std::int32_t>(i));
  EXPECT_EQ(end.size(), 4u);
  auto mean_velocity = [&] {
    double s = 0.0;
    for (const std::int32_t i : end) s += v.x[i];
    return s / static_cast<double>(end.size());
  };
  std::vector<double> crossings;
  double t_prev = 0.0, v_prev = kV0;
  Vibration r;
  bool first = true;
  while (!sim.finished()) {
    sim.cycle();
    if (first) r.kinetic0 = sim.energy().kinetic;
    first = false;
    // Velocities are at t^{n+1/2}.
    const double t = sim.state().time - 0.5 * sim.state().dt_prev, vt = mean_velocity();
    if ((v_prev > 0.0) != (vt > 0.0))
      crossings.push_back(t_prev + (t - t_prev) * v_prev / (v_prev - vt));
    t_prev = t;
    v_prev = vt;
  }
  EXPECT_EQ(crossings.size(), 2u);
  if (crossings.size() >= 2) r.period = 2.0 * (crossings[1] - crossings[0]);
  r.hourglass = sim.energy().hourglass;
  r.energy_ratio = sim.energy().ratio();
  return r;
}

TEST(Tetrahedron, Elform10BarVibratesAtTheAxialPeriodWithSecondOrderConvergence) {
  const double exact = 2.0 * kLength / std::sqrt(kE / kRho);
  double previous_error = 0.0;
  for (const int nx : {10, 20, 40}) {
    const Vibration r = vibrate(nx);
    const double error = r.period / exact - 1.0;
    const double chain = std::pow(std::numbers::pi / nx, 2) / 24.0;  // discrete-chain estimate
    std::printf(
        "ELFORM 10 bar, %d cells (%d tetrahedra): period %.7g s vs 2L/c %.7g s: error %.3e "
        "(chain estimate %.3e); hourglass energy %.3g J of %.3g J; energy ratio %.12f\n",
        nx, 6 * nx, r.period, exact, error, chain, r.hourglass, r.kinetic0, r.energy_ratio);
    // Lumped mass makes the discrete bar slower; the chain estimate is the 1D leading term
    // (measured 0.99, 0.88, 0.71 of it: the time integration shortens the period by
    // (w dt)^2 / 24 and the cross-section is not a 1D chain).
    EXPECT_GT(error, 0.0);
    EXPECT_LT(error, 1.5 * chain);
    if (previous_error > 0.0) {  // second order: measured 2.18 and 2.30
      const double order = std::log2(previous_error / error);
      std::printf("  observed order of convergence %.3f\n", order);
      EXPECT_GT(order, 1.8);
      EXPECT_LT(order, 2.6);
    }
    previous_error = error;
    EXPECT_LT(std::abs(r.hourglass), 1e-12 * r.kinetic0);
    EXPECT_NEAR(r.energy_ratio, 1.0, 1e-6);
  }
}

TEST(TetrahedronInput, Elform10RefusesOtherShapesAndOtherTetrahedronFormulationsAreNamed) {
  // A hexahedron in an ELFORM 10 part.
  const std::string hexahedron =
      "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
      "*ELEMENT_SOLID\n7,1,1,2,3,4,5,6,7,8\n*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,10\n"
      "*MAT_ELASTIC\n1,7850.0,2.1e11,0.3\n*CONTROL_TERMINATION\n1e-5\n*END\n";
  try {
    solver::Simulation sim(read(hexahedron), {});
    ADD_FAILURE() << "a hexahedron in an ELFORM 10 part must be refused";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("element 7"), std::string::npos) << what;
    EXPECT_NE(what.find("8 distinct nodes"), std::string::npos) << what;
    EXPECT_NE(what.find("ELFORM 10"), std::string::npos) << what;
    EXPECT_NE(what.find("verification.k:"), std::string::npos) << what;
  }
  // ELFORM 16 reads (10-node tetrahedra); its 4-node elements are refused when the model is
  // built (Tet10Input in tet10_test.cpp). 17 and 3 are refused at the card.
  for (const int elform : {17, 3}) {
    try {
      read(tetrahedral_bar(2, elform) + "*CONTROL_TERMINATION\n1e-5\n*END\n");
      ADD_FAILURE() << "ELFORM " << elform << " must be refused";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("field ELFORM"), std::string::npos) << what;
      EXPECT_NE(what.find("10"), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace rf::test
