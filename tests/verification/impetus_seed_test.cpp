// The IMPETUS *RIGID_BODY_UPDATE seed deck (examples/seed_rigid_body_update.k, the manual's
// example text unchanged), run for %type = 0, 1 and 2 (docs/verification.md, "IMPETUS seed").
//
// References, none from our own code:
//  - type 2 (curvilinear update): a rigid body's nodes keep their distance to the rotation axis
//    exactly, so after the 4 pi rotation every rigid node is at its initial radius and every
//    mantle node at D/2, to round-off; the body's rotation is 4 pi, i.e. the identity.
//  - type 0/1 (linear update): a rigid node at radius r moved along its tangent over a step with
//    rotation increment w dt lands at r sqrt(1 + (w dt)^2), i.e. outward by r (w dt)^2 / 2 to
//    leading order; summed over the steps actually taken, that predicts the radial error.
//  - energy: kinetic + internal energy equals the work of the prescribed motion and the
//    supports (the balance of docs/theory.md), for every type.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "io/keyword/reader.hpp"
#include "solver/simulation.hpp"

namespace rf {
namespace {

constexpr double kPi = std::numbers::pi;

struct SeedResult {
  double radial_error = 0.0;            // max | r_i(T) - r_i(0) | over rigid nodes
  double mantle_radius_error = 0.0;     // max | r_i(T) - D/2 | over rigid mantle nodes
  double predicted_linear_drift = 0.0;  // sum over steps of (D/2) (w dt)^2 / 2
  double angle = 0.0;                   // body rotation about z at the end, in (-pi, pi]
  double energy_ratio = 0.0;
  std::int64_t cycles = 0;
  bool normal_termination = false;
};

SeedResult run_seed(int type) {
  io::ReadOptions options;
  options.parameter_overrides["type"] = type;
  const model::Model model =
      io::read_deck(std::string(RIGIDFLEX_EXAMPLES) + "/seed_rigid_body_update.k", options);
  EXPECT_EQ(model.dialect, "impetus");
  EXPECT_EQ(model.rigid_body_update, type);
  solver::Simulation sim(model, {});
  const auto& body = sim.rigid_bodies().bodies.at(0);
  const auto& nodes = sim.state().nodes;
  const double radius = 0.05;  // D/2
  std::vector<double> r0;
  std::vector<char> on_mantle;
  for (const auto i : body.nodes) {
    r0.push_back(std::hypot(nodes.x.x[i], nodes.x.y[i]));
    on_mantle.push_back(std::abs(r0.back() - radius) < 1e-9 ? 1 : 0);
  }
  SeedResult result;
  const double omega = 4.0 * kPi / 0.01;  // %rot / %tend
  try {
    while (!sim.finished()) {
      sim.cycle();
      const double w_dt = omega * sim.state().dt_prev;
      result.predicted_linear_drift += radius * w_dt * w_dt / 2.0;
    }
    result.normal_termination = true;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "type " << type << ": " << e.what();
  }
  for (std::size_t k = 0; k < body.nodes.size(); ++k) {
    const auto i = body.nodes[k];
    const double r = std::hypot(nodes.x.x[i], nodes.x.y[i]);
    result.radial_error = std::max(result.radial_error, std::abs(r - r0[k]));
    if (on_mantle[k]) {
      result.mantle_radius_error = std::max(result.mantle_radius_error, std::abs(r - radius));
    }
  }
  const auto rel = body.state.previous_rotation * body.initial_rotation.transpose();
  result.angle = std::atan2(rel(1, 0), rel(0, 0));
  result.energy_ratio = sim.energy().ratio();
  result.cycles = sim.state().cycle;
  std::printf(
      "seed type %d: %lld cycles, rigid radial error %.3e m (linear-update prediction %.3e), "
      "mantle |r - D/2| %.3e m, final angle %.3e rad, energy ratio %.9f\n",
      type, static_cast<long long>(result.cycles), result.radial_error,
      result.predicted_linear_drift, result.mantle_radius_error, result.angle, result.energy_ratio);
  return result;
}

TEST(ImpetusSeed, Type2KeepsTheRigidCylinderRoundAfterFourPi) {
  const SeedResult r = run_seed(2);
  EXPECT_TRUE(r.normal_termination);
  EXPECT_LT(r.radial_error, 1e-14);         // 0.05 m radius: round-off is ~1e-17
  EXPECT_LT(r.mantle_radius_error, 1e-14);  // mantle nodes were placed on the exact circle
  EXPECT_LT(std::abs(r.angle), 1e-10);      // 4 pi: back to the start
  EXPECT_NEAR(r.energy_ratio, 1.0, 1e-9);
}

TEST(ImpetusSeed, Type0ShowsTheLinearUpdateGeometricError) {
  const SeedResult r = run_seed(0);
  EXPECT_TRUE(r.normal_termination);
  // The error the seed describes: visible (mm on a 50 mm radius) and as predicted from the
  // steps taken (the bound is the node's own tangent step; neighbours' forces change it little).
  EXPECT_GT(r.radial_error, 1e-3);
  EXPECT_NEAR(r.radial_error / r.predicted_linear_drift, 1.0, 0.1);
  EXPECT_NEAR(r.energy_ratio, 1.0, 1e-9);
}

TEST(ImpetusSeed, Type1MatchesType0WhenTheBodySharesNodes) {
  // The rigid cylinder shares its interface nodes with the deformable one: type 1's condition
  // holds throughout, so it updates linearly exactly like type 0.
  const SeedResult r = run_seed(1);
  EXPECT_TRUE(r.normal_termination);
  EXPECT_GT(r.radial_error, 1e-3);
  EXPECT_NEAR(r.radial_error / r.predicted_linear_drift, 1.0, 0.1);
  EXPECT_NEAR(r.energy_ratio, 1.0, 1e-9);
}

}  // namespace
}  // namespace rf
