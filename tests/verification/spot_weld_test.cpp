// Spot welds (*CONSTRAINED_SPOTWELD) and constrained node sets (*CONSTRAINED_NODE_SET) against
// references that do not come from the solver:
//  - two elastic blocks joined by four spot welds, spinning and translating freely: linear and
//    angular momentum are conserved to round-off (no external force or moment acts), the weld
//    links keep their length and the blocks turn together;
//  - the same blocks pulled at B's far face by a force ramp F(t) = R t: the assembly moves as
//    one body, so each of the four welds carries the force that accelerates a quarter of block
//    A, F_A / 4 = M_A / (M_A + M_B) F(t) / 4 (Newton's second law for A); with a normal
//    strength SN the welds fail at t_f = 4 SN (M_A + M_B) / (M_A R), after which A coasts;
//  - TF: a weld fails at its time;
//  - *CONSTRAINED_NODE_SET DOF 1 on two loaded blocks: the x velocities are those of one
//    mass M_A + M_B under the summed x force, the y and z velocities those of each block alone
//    (two-mass answer, exact for uniform nodal loads, which strain nothing);
//  - *CONSTRAINED_NODE_SET DOF 7 on the coincident nodes of a bar cut in two: the same motion
//    as the uncut bar (the tie is the node merge);
//  - NCSF = 1 on a switch deletes the welds (A stops being pulled), NCSF = 2 activates them
//    again (A is pulled again; momentum is carried exactly).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "deck_builder.hpp"
#include "model/error.hpp"

namespace rf::test {
namespace {

constexpr double kRho = 1.0, kE = 1.0e5, kNu = 0.3;
constexpr double kGap = 0.2;  // between the blocks' facing sides

// Block A over [0,1]^3 (nodes 1..8), block B over [1.2,2.2] x [0,1]^2 (nodes 101..108).
Block block_a() {
  Block b;
  b.pid = 1;
  return b;
}
Block block_b() {
  Block b;
  b.pid = 2;
  b.first_node = 101;
  b.first_element = 101;
  b.shift = Eigen::Vector3d(1.0 + kGap, 0.0, 0.0);
  return b;
}

// Four welds from A's face x = 1 to B's face x = 1.2 (card options and strengths as given).
std::string welds(double sn, double tf = 0.0, bool with_id = false) {
  const Block a = block_a(), b = block_b();
  std::string s = with_id ? "*CONSTRAINED_SPOTWELD_ID\n" : "*CONSTRAINED_SPOTWELD\n";
  int id = 0;
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= 1; ++j) {
      if (with_id) s += fmt::format("{}\n", 11 + id);
      s += fmt::format("{},{},{:.17g},0.0,1.0,1.0,{:.17g}\n", a.node(1, j, k), b.node(0, j, k), sn,
                       tf);
      ++id;
    }
  return s;
}

std::string two_blocks() {
  return "*KEYWORD\n" + block_a().text() + block_b().text() + elastic(1, kRho, kE, kNu) +
         elastic(2, kRho, kE, kNu);
}

std::int32_t dense(const solver::Simulation& sim, model::Id id) {
  const auto& ids = sim.state().nodes.id;
  return static_cast<std::int32_t>(std::find(ids.begin(), ids.end(), id) - ids.begin());
}

double distance(const solver::Simulation& sim, model::Id a, model::Id b) {
  const auto& x = sim.state().nodes.x;
  const auto i = dense(sim, a), j = dense(sim, b);
  return std::hypot(x.x[i] - x.x[j], x.y[i] - x.y[j], x.z[i] - x.z[j]);
}

TEST(SpotWeld, WeldedBlocksSpinTogetherConservingMomenta) {
  // Spin about z through the assembly's centre plus a drift: centrifugal loads strain both
  // blocks and the welds carry them.
  std::string deck = two_blocks() + welds(0.0);
  deck += "*INITIAL_VELOCITY_GENERATION\n0,2,20.0,3.0,-1.0,0.5\n1.1,0.5,0.5,0.0,0.0,1.0\n";
  deck += "*CONTROL_TERMINATION\n0.3,0\n*CONTROL_TIMESTEP\n0,0.5\n*END\n";
  solver::Simulation sim(read(deck), {});
  sim.cycle();
  const auto p0 = sim.energy().momentum, h0 = sim.energy().angular_momentum;
  const double gap0 = distance(sim, block_a().node(1, 0, 0), block_b().node(0, 0, 0));
  double worst_gap = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    for (int k = 0; k <= 1; ++k)
      for (int j = 0; j <= 1; ++j) {
        const double d = distance(sim, block_a().node(1, j, k), block_b().node(0, j, k));
        worst_gap = std::max(worst_gap, std::abs(d - gap0) / gap0);
      }
  }
  const auto p1 = sim.energy().momentum, h1 = sim.energy().angular_momentum;
  const double p_scale = std::hypot(p0[0], p0[1], p0[2]);
  const double h_scale = std::hypot(h0[0], h0[1], h0[2]);
  double dp = 0.0, dh = 0.0;
  for (int k = 0; k < 3; ++k) {
    dp = std::max(dp, std::abs(p1[k] - p0[k]) / p_scale);
    dh = std::max(dh, std::abs(h1[k] - h0[k]) / h_scale);
  }
  // The blocks turned about 6 rad together: B's far corner still faces A's across the welds.
  const double turned = distance(sim, block_a().node(0, 0, 0), block_b().node(1, 0, 0));
  std::printf(
      "welded spin: %lld cycles, momentum drift %.3g, angular momentum drift %.3g, weld length "
      "change %.3g, corner distance %.6f (initial %.6f), energy ratio %.9f\n",
      static_cast<long long>(sim.state().cycle), dp, dh, worst_gap, turned,
      std::hypot(2.0 + kGap, 0.0, 0.0), sim.energy().ratio());
  EXPECT_LT(dp, 1e-12);
  EXPECT_LT(dh, 1e-12);
  EXPECT_LT(worst_gap, 1e-3);  // linear node update: O((w dt)^2) per step
  EXPECT_NEAR(turned, 2.0 + kGap, 0.05 * (2.0 + kGap));
  for (const auto& w : sim.nodal_constraints().welds) {
    EXPECT_EQ(w.status, solver::ConstraintStatus::kActive);
  }
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-3);
}

// Pull on B's far face, F(t) = R t in total (R / 4 per node).
std::string pull(double rate) {
  const Block b = block_b();
  std::string s = node_set(7, {b.node(1, 0, 0), b.node(1, 1, 0), b.node(1, 0, 1), b.node(1, 1, 1)});
  s += fmt::format("*LOAD_NODE_SET\n7,1,9,{:.17g}\n*DEFINE_CURVE\n9\n0.0,0.0\n100.0,100.0\n",
                   rate / 4.0);
  return s;
}

TEST(SpotWeld, FailsWhenTheNormalForceReachesSn) {
  const double rate = 40.0, sn = 5.0;
  // Equal blocks: each weld carries F / 8, so it fails at t_f = 8 SN / R = 1.0.
  const double mass_a = kRho, mass_b = kRho;
  const double t_fail = 4.0 * sn * (mass_a + mass_b) / (mass_a * rate);
  std::string deck = two_blocks() + welds(sn, 0.0, true) + pull(rate);
  deck += "*DATABASE_SWFORC\n0.05\n";
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},0\n*CONTROL_TIMESTEP\n0,0.6\n*END\n",
                      1.4 * t_fail);
  solver::Simulation sim(read(deck), {});
  const auto far_a = dense(sim, block_a().node(0, 0, 0));
  double worst = 0.0, v_at_failure = -1.0, t_at_failure = -1.0;
  while (!sim.finished()) {
    sim.cycle();
    const double t = sim.state().time;
    const auto& welds_now = sim.nodal_constraints().welds;
    if (welds_now.front().status == solver::ConstraintStatus::kActive && t > 0.3 * t_fail) {
      // Quasi-static: the force of Newton's law for A, within the elastic ringing.
      const double expected = mass_a / (mass_a + mass_b) * rate * t / 4.0;
      for (const auto& w : welds_now) {
        worst = std::max(worst, std::abs(w.normal_force - expected) / expected);
        EXPECT_LT(std::abs(w.shear_force), 0.02 * expected);
      }
    }
    if (v_at_failure < 0.0 && welds_now.front().status == solver::ConstraintStatus::kFailed) {
      v_at_failure = sim.state().nodes.v.x[far_a];
      t_at_failure = welds_now.front().failure_time;
    }
  }
  ASSERT_GT(t_at_failure, 0.0) << "the welds did not fail";
  std::printf(
      "spot weld failure at t = %.6f vs %.6f (ratio %.5f); normal force within %.3g %% "
      "of M_A/M F / 4 while intact\n",
      t_at_failure, t_fail, t_at_failure / t_fail, 100.0 * worst);
  EXPECT_NEAR(t_at_failure / t_fail, 1.0, 0.02);
  EXPECT_LT(worst, 0.03);
  for (const auto& w : sim.nodal_constraints().welds) {
    EXPECT_EQ(w.status, solver::ConstraintStatus::kFailed);
    EXPECT_NEAR(w.failure_time, t_at_failure, 0.02 * t_fail);  // all four together
  }
  // Free of the welds, A coasts (its far face rings elastically about its mean velocity).
  const double v_a_expected = mass_a / (mass_a + mass_b) * rate * t_fail * t_fail / 2.0 / mass_a;
  EXPECT_NEAR(v_at_failure, v_a_expected, 0.05 * v_a_expected);
  double v_mean = 0.0;
  for (int c = 0; c < 8; ++c) {
    const auto i = dense(sim, block_a().node(c & 1, (c >> 1) & 1, (c >> 2) & 1));
    v_mean += sim.state().nodes.v.x[i] / 8.0;
  }
  EXPECT_NEAR(v_mean, v_a_expected, 0.02 * v_a_expected);
}

// The same four welds written as *CONSTRAINED_GENERALIZED_WELD_SPOT_ID, each on a node set of
// its two nodes (sets 21..24; B's node first in two of them: the order of a set is the weld's).
std::string generalized_welds(double sn) {
  const Block a = block_a(), b = block_b();
  std::string s;
  int id = 0;
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= 1; ++j) {
      s += id % 2 == 0 ? node_set(21 + id, {a.node(1, j, k), b.node(0, j, k)})
                       : node_set(21 + id, {b.node(0, j, k), a.node(1, j, k)});
      s += fmt::format(
          "*CONSTRAINED_GENERALIZED_WELD_SPOT_ID\n{}\n{},0,0,0.0,0,1\n0.0,0.0,{:.17g},"
          "0.0,1.0,1.0\n",
          11 + id, 21 + id, sn);
      ++id;
    }
  return s;
}

TEST(SpotWeld, GeneralizedWeldOfTwoNodesFailsLikeTheSpotweld) {
  // Reference: the analytic failure time 8 SN / R of FailsWhenTheNormalForceReachesSn, and the
  // same run written with *CONSTRAINED_SPOTWELD (bitwise, up to the order of each pair).
  const double rate = 40.0, sn = 5.0, t_fail = 8.0 * sn / rate;
  const std::string tail = pull(rate) + fmt::format(
                                            "*CONTROL_TERMINATION\n{:.17g},0\n*CONTROL_TIMESTEP\n"
                                            "0,0.6\n*END\n",
                                            1.4 * t_fail);
  solver::Simulation plain(read(two_blocks() + welds(sn, 0.0, true) + tail), {});
  solver::Simulation general(read(two_blocks() + generalized_welds(sn) + tail), {});
  plain.run();
  general.run();
  const auto& wp = plain.nodal_constraints().welds;
  const auto& wg = general.nodal_constraints().welds;
  ASSERT_EQ(wg.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(wg[k].status, solver::ConstraintStatus::kFailed);
    EXPECT_NEAR(wg[k].failure_time / t_fail, 1.0, 0.02);
    EXPECT_EQ(wg[k].failure_time, wp[k].failure_time) << "weld " << k;
  }
  EXPECT_EQ(plain.state().nodes.x.x, general.state().nodes.x.x);
  EXPECT_EQ(plain.energy().kinetic, general.energy().kinetic);
}

TEST(SpotWeld, FailsAtItsTime) {
  std::string deck = two_blocks() + welds(0.0, 0.25) + pull(40.0);
  deck += "*CONTROL_TERMINATION\n0.4,0\n*CONTROL_TIMESTEP\n0,0.6\n*END\n";
  solver::Simulation sim(read(deck), {});
  sim.run();
  for (const auto& w : sim.nodal_constraints().welds) {
    EXPECT_EQ(w.status, solver::ConstraintStatus::kFailed);
    EXPECT_GE(w.failure_time, 0.25);
    EXPECT_LT(w.failure_time, 0.25 + 2.0 * sim.state().dt);
  }
}

TEST(ConstrainedNodeSet, Dof1SharesTheXMotionOnly) {
  const Block a = block_a(), b = block_b();
  std::string deck = two_blocks();
  std::vector<int> all, nodes_a, nodes_b;
  for (int c = 0; c < 8; ++c) {
    nodes_a.push_back(a.node(c & 1, (c >> 1) & 1, (c >> 2) & 1));
    nodes_b.push_back(b.node(c & 1, (c >> 1) & 1, (c >> 2) & 1));
  }
  all = nodes_a;
  all.insert(all.end(), nodes_b.begin(), nodes_b.end());
  const double fx = 3.0, fy = 2.0;  // totals on A (x) and on B (y), spread evenly
  deck += node_set(1, all) + node_set(2, nodes_a) + node_set(3, nodes_b);
  deck += "*CONSTRAINED_NODE_SET_ID\n5\n1,1\n";
  deck += fmt::format("*LOAD_NODE_SET\n2,1,9,{:.17g}\n3,2,9,{:.17g}\n", fx / 8.0, fy / 8.0);
  deck += "*DEFINE_CURVE\n9\n0.0,1.0\n100.0,1.0\n";
  deck += "*CONTROL_TERMINATION\n0.5,0\n*CONTROL_TIMESTEP\n0,0.6\n*END\n";
  solver::Simulation sim(read(deck), {});
  sim.run();
  // Every velocity is a constant acceleration times the same elapsed velocity time T (the
  // central-difference sum of dt_avg); T comes from one node of B in y and must be about t.
  const double ax = fx / (2.0 * kRho), ay_b = fy / kRho;
  const auto& v = sim.state().nodes.v;
  const double t_v = v.y[dense(sim, b.node(0, 0, 0))] / ay_b;
  EXPECT_NEAR(t_v, sim.state().time, 2.0 * sim.state().dt);
  double worst = 0.0;
  for (const int id : all) {
    const auto i = dense(sim, id);
    const bool in_b = id > 100;
    worst = std::max(worst, std::abs(v.x[i] - ax * t_v) / (ax * t_v));
    const double vy = in_b ? ay_b * t_v : 0.0;
    worst = std::max(worst, std::abs(v.y[i] - vy) / (ay_b * t_v));
    worst = std::max(worst, std::abs(v.z[i]) / (ay_b * t_v));
  }
  std::printf("node set DOF 1: largest deviation from the two-mass answer %.3g\n", worst);
  EXPECT_LT(worst, 1e-9);
}

TEST(ConstrainedNodeSet, Dof7OnACutBarMatchesTheUncutBar) {
  // Uncut: 2 elements along x. Cut: the same with the nodes at x = 1 doubled (ids 201..204 for
  // the second element) and tied pairwise.
  BoxMesh mesh;
  mesh.nx = 2;
  mesh.lx = 2.0;
  const std::string tail = "*CONTROL_TERMINATION\n0.05,0\n*CONTROL_TIMESTEP\n0,0.6\n*END\n";
  std::string velocity;
  {
    std::vector<int> left;
    for (int k = 0; k <= 1; ++k)
      for (int j = 0; j <= 1; ++j) left.push_back(mesh.node_id(0, j, k));
    velocity = node_set(8, left) + "*INITIAL_VELOCITY\n8\n5.0,1.0,0.0\n";
  }
  const std::string uncut =
      "*KEYWORD\n" + mesh.keyword_text(1) + elastic(1, kRho, kE, kNu) + velocity + tail;
  std::string cut = "*KEYWORD\n*NODE\n";
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= 1; ++j)
      for (int i = 0; i <= 2; ++i) {
        cut += fmt::format("{},{},{},{}\n", mesh.node_id(i, j, k), i, j, k);
        if (i == 1) cut += fmt::format("{},{},{},{}\n", 200 + mesh.node_id(i, j, k), i, j, k);
      }
  auto id = [&](int i, int j, int k, bool second) {
    return (i == 1 && second ? 200 : 0) + mesh.node_id(i, j, k);
  };
  cut += "*ELEMENT_SOLID\n";
  for (int e = 0; e < 2; ++e) {
    const bool second = e == 1;
    cut += fmt::format("{},1,{},{},{},{},{},{},{},{}\n", e + 1, id(e, 0, 0, second),
                       id(e + 1, 0, 0, second), id(e + 1, 1, 0, second), id(e, 1, 0, second),
                       id(e, 0, 1, second), id(e + 1, 0, 1, second), id(e + 1, 1, 1, second),
                       id(e, 1, 1, second));
  }
  cut += elastic(1, kRho, kE, kNu) + velocity;
  int sid = 20;
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= 1; ++j) {
      cut += node_set(++sid, {mesh.node_id(1, j, k), 200 + mesh.node_id(1, j, k)});
      cut += fmt::format("*CONSTRAINED_NODE_SET\n{},7\n", sid);
    }
  cut += tail;
  solver::Simulation a(read(uncut), {}), b(read(cut), {});
  a.run();
  b.run();
  ASSERT_EQ(a.state().cycle, b.state().cycle);
  double worst = 0.0;
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= 1; ++j)
      for (int i = 0; i <= 2; ++i) {
        const auto ia = dense(a, mesh.node_id(i, j, k)), ib = dense(b, mesh.node_id(i, j, k));
        worst = std::max({worst, std::abs(a.state().nodes.x.x[ia] - b.state().nodes.x.x[ib]),
                          std::abs(a.state().nodes.x.y[ia] - b.state().nodes.x.y[ib]),
                          std::abs(a.state().nodes.v.x[ia] - b.state().nodes.v.x[ib]) * 1e-2});
      }
  std::printf("cut bar tied by node sets vs uncut bar: largest difference %.3g\n", worst);
  EXPECT_LT(worst, 1e-12);
}

// Switch sets at t1 (NCSF = 1) and t2 (NCSF = 2), switching a far-away third block only.
std::string ncsf_sets(double t1, double t2) {
  return fmt::format(
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n1,0,{0:.17g}\n0,1,0,0,1,0\n3\n"
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n2,0,{1:.17g}\n0,2,0,0,0,1\n3\n",
      t1, t2);
}

TEST(SpotWeld, NcsfDeletesThenActivatesTheWelds) {
  Block c;  // a third block far away, the part the sets switch
  c.pid = 3;
  c.first_node = 201;
  c.first_element = 201;
  c.shift = Eigen::Vector3d(0.0, 10.0, 0.0);
  const double rate = 4.0, t1 = 0.3, t2 = 0.6, t_end = 0.9;
  std::string deck = two_blocks() + c.text() + elastic(3, kRho, kE, kNu) + welds(0.0) + pull(rate) +
                     ncsf_sets(t1, t2);
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},0\n*CONTROL_TIMESTEP\n0,0.6\n*END\n", t_end);
  solver::Simulation sim(read(deck), {});
  // Mean x velocity of block A (its momentum over its mass).
  auto v_a = [&] {
    double v = 0.0;
    for (int n = 0; n < 8; ++n) {
      const auto i = dense(sim, block_a().node(n & 1, (n >> 1) & 1, (n >> 2) & 1));
      v += sim.state().nodes.v.x[i] / 8.0;
    }
    return v;
  };
  auto link = [&] { return distance(sim, block_a().node(1, 0, 0), block_b().node(0, 0, 0)); };
  double v_t1 = 0.0, v_before_t2 = 0.0, link_t2 = 0.0, worst_link = 0.0;
  bool deleted_seen = false;
  while (!sim.finished()) {
    const double t = sim.state().time;
    sim.cycle();
    const auto status = sim.nodal_constraints().welds.front().status;
    if (t < t1) v_t1 = v_a();
    if (t >= t1 && t < t2) {
      deleted_seen = deleted_seen || status == solver::ConstraintStatus::kDeleted;
      v_before_t2 = v_a();
    }
    if (t >= t2) {
      if (link_t2 == 0.0) link_t2 = link();
      worst_link = std::max(worst_link, std::abs(link() - link_t2) / link_t2);
    }
  }
  EXPECT_TRUE(deleted_seen);
  for (const auto& w : sim.nodal_constraints().welds) {
    EXPECT_EQ(w.status, solver::ConstraintStatus::kActive);
  }
  // Welded up to t1: A had half the impulse, R t1^2 / 2 / 2, over its mass; deleted from t1 to
  // t2 it coasts while B is pulled away; activated at t2 the welds hold the new distance. The
  // momentum is the total impulse R t^2 / 2 throughout (switches carry it exactly).
  const double v1 = rate * t1 * t1 / 4.0 / kRho;
  const double t = sim.state().time;
  const double impulse = rate * t * t / 2.0;
  std::printf(
      "NCSF: v_A at t1 %.6f (expected %.6f), before t2 %.6f; weld length %.6f after "
      "activation (initial %.3f), kept within %.3g; momentum %.9f vs impulse %.9f\n",
      v_t1, v1, v_before_t2, link_t2, kGap, worst_link, sim.energy().momentum[0], impulse);
  EXPECT_NEAR(v_t1, v1, 0.03 * v1);
  EXPECT_NEAR(v_before_t2, v1, 0.03 * v1);  // coasting: no weld pulls it
  EXPECT_GT(link_t2, kGap * 1.2);           // B went away while the welds were deleted
  EXPECT_LT(worst_link, 1e-3);              // and is held at that distance again
  EXPECT_NEAR(sim.energy().momentum[0], impulse, 0.02 * impulse);
}

TEST(SpotWeld, BadCardsAreRefusedWithTheField) {
  const std::string base = two_blocks() + "*CONTROL_TERMINATION\n0.1,0\n";
  auto error_of = [&](const std::string& cards) -> std::string {
    try {
      solver::Simulation sim(read(base + cards + "*END\n"), {});
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(error_of("*CONSTRAINED_SPOTWELD\n1,1\n").find("N2"), std::string::npos);
  EXPECT_NE(error_of("*CONSTRAINED_SPOTWELD\n2,999\n").find("999"), std::string::npos);
  EXPECT_NE(error_of("*CONSTRAINED_SPOTWELD\n2,101,-3.0\n").find("SN"), std::string::npos);
  EXPECT_NE(error_of("*CONSTRAINED_SPOTWELD\n2,101,0,0,0,0,0,0.3\n").find("EP"), std::string::npos);
  EXPECT_NE(error_of("*CONSTRAINED_SPOTWELD_FILTERED_FORCE\n2,101\n5,0.0\n").find("NF"),
            std::string::npos);
  // A node in two welds: it would move with two bodies.
  EXPECT_NE(error_of("*CONSTRAINED_SPOTWELD\n2,101\n2,103\n").find("node 2"), std::string::npos);
  // Coincident nodes: no normal direction.
  EXPECT_NE(error_of("*NODE\n500,1.0,0.0,0.0\n*CONSTRAINED_SPOTWELD\n2,500\n").find("coincide"),
            std::string::npos);
  EXPECT_NE(error_of("*CONSTRAINED_SPOTWELD_ID\n4\n2,101\n*CONSTRAINED_SPOTWELD_ID\n4\n3,103\n")
                .find("WID"),
            std::string::npos);
  EXPECT_NE(error_of("*SET_NODE_LIST\n1\n2\n*CONSTRAINED_NODE_SET\n1,1\n").find("at least two"),
            std::string::npos);
  EXPECT_NE(error_of("*SET_NODE_LIST\n1\n2,3\n*CONSTRAINED_NODE_SET\n1,8\n").find("DOF"),
            std::string::npos);
  EXPECT_NE(error_of("*CONSTRAINED_NODE_SET\n77,1\n").find("77"), std::string::npos);
  // Generalized spot welds: two nodes only, no filter, no node pairs, no plastic strain.
  const std::string weld = "*CONSTRAINED_GENERALIZED_WELD_SPOT\n";
  EXPECT_NE(error_of("*SET_NODE_LIST\n5\n2,101,103\n" + weld + "5\n0.0,0.0,5.0\n")
                .find("3 distinct nodes"),
            std::string::npos);
  EXPECT_NE(error_of(weld + "66\n0.0,0.0,5.0\n").find("node set 66"), std::string::npos);
  EXPECT_NE(error_of("*SET_NODE_LIST\n5\n2,101\n" + weld + "5,0,4\n0.0,0.0,5.0\n").find("FILTER"),
            std::string::npos);
  EXPECT_NE(
      error_of("*SET_NODE_LIST\n5\n2,101\n" + weld + "5,0,0,0.0,2\n0.0,0.0,5.0\n").find("NPR"),
      std::string::npos);
  EXPECT_NE(error_of("*SET_NODE_LIST\n5\n2,101\n" + weld + "5\n0.0,0.2,5.0\n").find("EPSF"),
            std::string::npos);
}

}  // namespace
}  // namespace rf::test
