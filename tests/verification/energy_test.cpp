// Energy and momentum: conservation laws checked against quantities computed independently
// of the solver's own work bookkeeping (strain energy from element stresses).
#include <gtest/gtest.h>

#include <cmath>

#include "deck_builder.hpp"

namespace rf::test {
namespace {

constexpr double kRho = 7850.0, kE = 210e9;

// Mildly distorted 6x6x6 block (0.1 m) so that the elements are not all parallelepipeds.
// (Blocks of four or fewer elements across are unstable at TSSFAC 0.9 with the LS-DYNA
// characteristic length; see docs/theory.md.)
BoxMesh distorted_block() {
  BoxMesh mesh;
  mesh.nx = mesh.ny = mesh.nz = 6;
  mesh.lx = mesh.ly = mesh.lz = 0.1;
  mesh.distort = [](double& x, double& y, double& z) {
    const double s = 0.004;
    const double dx = s * std::sin(31.0 * y + 17.0 * z), dy = s * std::sin(23.0 * z + 11.0 * x),
                 dz = s * std::sin(13.0 * x + 29.0 * y);
    x += dx * x * (0.1 - x) * 400.0;
    y += dy * y * (0.1 - y) * 400.0;
    z += dz * z * (0.1 - z) * 400.0;
  };
  return mesh;
}

// Stretching initial velocity field v = a (x - x_c): no rigid motion, pure vibration.
std::string stretch_velocity(const BoxMesh& mesh, double a) {
  std::string s = "*INITIAL_VELOCITY_NODE\n";
  for (int k = 0; k <= mesh.nz; ++k)
    for (int j = 0; j <= mesh.ny; ++j)
      for (int i = 0; i <= mesh.nx; ++i) {
        double x, y, z;
        mesh.coordinates(i, j, k, x, y, z);
        s += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", mesh.node_id(i, j, k), a * (x - 0.05),
                         0.5 * a * (y - 0.05), -0.3 * a * (z - 0.05));
      }
  return s;
}

struct EnergyCase {
  int elform;
  int ihq;
};

class FreeVibrationEnergy : public ::testing::TestWithParam<EnergyCase> {};

// For central differences on a linear system the "shadow" energy
//   E^n = 1/2 v^{n-1/2} M v^{n+1/2} + U(x^n)
// is exactly conserved at constant dt; with U taken from the element stresses this checks
// that element forces are conservative and consistent with the stresses they report.
TEST_P(FreeVibrationEnergy, TotalEnergyFromStressesIsConserved) {
  const auto param = GetParam();
  const BoxMesh mesh = distorted_block();
  std::string deck = "*KEYWORD\n" + mesh.keyword_text() +
                     elastic_part(kRho, kE, 0.3, param.elform, param.ihq) +
                     stretch_velocity(mesh, 50.0) +
                     // Conservative forces are the subject: no bulk viscosity, whose damping
                     // (and rate-dependent step) the shadow-energy identity does not cover.
                     "*CONTROL_BULK_VISCOSITY\n0.0,0.0\n*CONTROL_TERMINATION\n5.0e-3\n*END\n";
  solver::Simulation sim(read(deck), {});
  const auto& nodes = sim.state().nodes;
  std::vector<double> vx_prev, vy_prev, vz_prev;
  double sigma_prev_energy = 0.0, hourglass_prev = 0.0;
  double e0 = -1.0, max_drift = 0.0;
  int steps = 0;
  // Stop short of the end: the last step is shortened to land on ENDTIM, and the shadow
  // energy is only conserved for a (nearly) constant step.
  while (sim.state().time < 0.9 * sim.end_time()) {
    sim.cycle();
    ++steps;
    if (!vx_prev.empty()) {
      double ke = 0.0;
      for (std::size_t i = 0; i < nodes.size(); ++i) {
        ke += 0.5 * nodes.mass[i] *
              (vx_prev[i] * nodes.v.x[i] + vy_prev[i] * nodes.v.y[i] + vz_prev[i] * nodes.v.z[i]);
      }
      // Stresses and hourglass energy of the previous cycle belong to x^n.
      const double e = ke + sigma_prev_energy + hourglass_prev;
      if (e0 < 0.0) e0 = e;
      max_drift = std::max(max_drift, std::abs(e - e0));
    }
    vx_prev = nodes.v.x;
    vy_prev = nodes.v.y;
    vz_prev = nodes.v.z;
    sigma_prev_energy = elastic_strain_energy(sim.state());
    hourglass_prev = sim.energy().hourglass;
  }
  ASSERT_GT(e0, 0.0);
  std::printf("free vibration ELFORM %d IHQ %d: %d cycles, max energy drift %.3g of initial\n",
              param.elform, param.ihq, steps, max_drift / e0);
  EXPECT_LT(max_drift / e0, 2e-3) << "energy drift over " << steps << " cycles";
  // The vibration must actually exchange energy, or the test proves nothing.
  EXPECT_GT(sigma_prev_energy, 0.01 * e0);
}

INSTANTIATE_TEST_SUITE_P(Elements, FreeVibrationEnergy,
                         ::testing::Values(EnergyCase{1, 6}, EnergyCase{1, 4}, EnergyCase{2, 1}),
                         [](const auto& info) {
                           return fmt::format("elform{}_ihq{}", info.param.elform, info.param.ihq);
                         });

// A free block spinning about a skew axis while translating, with a deforming kick:
// linear and angular momentum are conserved to round-off, whatever the deformation.
TEST(FreeSpinningBlock, MomentumAndAngularMomentumConservedToRoundOff) {
  const BoxMesh mesh = distorted_block();
  std::string deck = "*KEYWORD\n" + mesh.keyword_text() + elastic_part(kRho, kE, 0.3, 1, 6);
  std::vector<int> top;
  for (int j = 0; j <= mesh.ny; ++j)
    for (int i = 0; i <= mesh.nx; ++i) top.push_back(mesh.node_id(i, j, mesh.nz));
  deck += node_set(7, top);
  // Whole part: spin 400 rad/s about (1,1,1) through the centre plus translation.
  deck += "*INITIAL_VELOCITY_GENERATION\n1,2,400.0,1.0,2.0,3.0\n0.05,0.05,0.05,1.0,1.0,1.0\n";
  // Top face: extra upward velocity (deforms the block).
  deck += "*INITIAL_VELOCITY_GENERATION\n7,3,400.0,1.0,2.0,5.0\n0.05,0.05,0.05,1.0,1.0,1.0\n";
  deck += "*CONTROL_TERMINATION\n8.0e-3\n*END\n";
  solver::Simulation sim(read(deck), {});
  sim.cycle();
  const auto p0 = sim.energy();
  double mass = 0.0;
  for (double m : sim.state().nodes.mass) mass += m;
  const double p_scale = mass * (3.0 + 400.0 * 0.1);
  const double l_scale = p_scale * 0.2;
  while (!sim.finished()) sim.cycle();
  const auto& p1 = sim.energy();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(p1.momentum[k], p0.momentum[k], 1e-11 * p_scale) << "component " << k;
    EXPECT_NEAR(p1.angular_momentum[k], p0.angular_momentum[k], 1e-10 * l_scale)
        << "component " << k;
  }
  // The body really turned: about 3 rad in 8 ms.
  EXPECT_GT(sim.state().time * 400.0, 3.0);
  // Kinetic + strain + hourglass energy stays at its initial value (no dissipation).
  const double e_end = sim.energy().kinetic + elastic_strain_energy(sim.state()) + p1.hourglass;
  EXPECT_NEAR(e_end, p0.kinetic, 2e-3 * p0.kinetic);
}

// A constant force F on one node of a free block: the impulse gives the momentum exactly
// (P^{n+1/2} = F (t^n + dt/2)) and the external work equals F times the node's travel.
TEST(ConstantNodalForce, ImpulseAndExternalWork) {
  BoxMesh mesh;
  mesh.nx = mesh.ny = mesh.nz = 2;
  mesh.lx = mesh.ly = mesh.lz = 0.1;
  const double force = 1000.0;
  std::string deck =
      "*KEYWORD\n" + mesh.keyword_text() + elastic_part(kRho, kE, 0.3, 1, 6) +
      fmt::format("*LOAD_NODE_POINT\n{},1,1,{}\n", mesh.node_id(2, 2, 2), force) +
      "*DEFINE_CURVE\n1\n0.0,1.0\n1.0,1.0\n*CONTROL_TERMINATION\n2.0e-4\n"
      // A constant step (LCTM curve below the stable step): the sum of
      // half-step increments then telescopes to the node's travel exactly.
      "*CONTROL_TIMESTEP\n0.0,0.9,0,0.0,0.0,2\n*DEFINE_CURVE\n2\n0.0,5.0e-6\n1.0,5.0e-6\n"
      "*END\n";
  solver::Simulation sim(read(deck), {});
  const auto& nodes = sim.state().nodes;
  std::size_t loaded = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes.id[i] == mesh.node_id(2, 2, 2)) loaded = i;
  const double x0 = nodes.x0.x[loaded];
  while (!sim.finished()) sim.cycle();
  // After the final cycle the step was not taken: v is v^{n+1/2} at t^n.
  const double t = sim.state().time;
  EXPECT_NEAR(sim.energy().momentum[0], force * (t + 0.5 * sim.state().dt), 1e-6 * force * t);
  EXPECT_NEAR(sim.energy().momentum[1], 0.0, 1e-9 * force * t);
  // Work of the force up to the last half step: F (x^{n+1/2} - x0) with x^{n+1/2} from x^n and
  // v, less the first half step's F dt/4 v^{1/2} (the scheme starts from v^0 = 0).
  const double dt = sim.state().dt;
  const double v_half_first = 0.5 * dt * force / nodes.mass[loaded];
  const double travel = nodes.x.x[loaded] + 0.5 * dt * nodes.v.x[loaded] - x0;
  EXPECT_NEAR(sim.energy().external_work, force * (travel - 0.25 * dt * v_half_first),
              1e-9 * force * travel);
}

// Prescribed motion and SPC reactions: a bar fixed at one end and stretched slowly at the
// other. All energy in the bar (kinetic + strain from stresses + hourglass) came from the
// reaction work at the moving end.
TEST(PrescribedMotionWork, ReactionWorkEqualsStoredEnergy) {
  BoxMesh mesh;
  mesh.nx = 20;
  mesh.ny = mesh.nz = 2;
  mesh.lx = 1.0;
  mesh.ly = mesh.lz = 0.1;
  std::string deck = "*KEYWORD\n" + mesh.keyword_text() + elastic_part(kRho, kE, 0.3, 1, 6);
  deck += node_set(1, mesh.face_x(0)) + node_set(2, mesh.face_x(mesh.nx));
  deck += "*BOUNDARY_SPC_SET\n1,0,1,1,1\n";
  // Velocity ramps from 0 to 0.5 m/s over 1 ms, then holds.
  deck += "*BOUNDARY_PRESCRIBED_MOTION_SET\n2,1,0,1,1.0\n";
  deck += "*DEFINE_CURVE\n1\n0.0,0.0\n1.0e-3,0.5\n1.0,0.5\n";
  deck += "*CONTROL_TERMINATION\n2.0e-3\n*END\n";
  solver::Simulation sim(read(deck), {});
  while (!sim.finished()) sim.cycle();
  const double stored =
      sim.energy().kinetic + elastic_strain_energy(sim.state()) + sim.energy().hourglass;
  ASSERT_GT(sim.energy().external_work, 0.0);
  EXPECT_NEAR(stored, sim.energy().external_work, 0.02 * sim.energy().external_work);
}

}  // namespace
}  // namespace rf::test
