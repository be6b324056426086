// Rigid-body keywords: the same deck in fixed and in free format must give the same,
// fully checked model (tests/decks/rigid_fixed.k and rigid_free.k).
#include <gtest/gtest.h>

#include <cmath>

#include "keyword_test_util.hpp"

using rf::model::Model;
using rf::model::Target;

namespace {

using Vec = std::array<double, 3>;

void expect_vec(const Vec& actual, const Vec& expected, const char* what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(actual[k], expected[k], 1e-12) << what << "[" << k << "]";
}

class KeywordRigid : public ::testing::TestWithParam<const char*> {
 protected:
  Model read() { return rf::io::read_deck(rf::test::deck_path(GetParam())); }
};

TEST_P(KeywordRigid, CoordinateSystemsAndVectors) {
  const Model m = read();
  const double h = 1.0 / std::sqrt(2.0);
  ASSERT_EQ(m.coordinate_systems.size(), 3u);
  const auto& system = m.coordinate_systems.at(5);
  EXPECT_EQ(system.kind, rf::model::CoordinateKind::System);
  expect_vec(system.origin, {1, 1, 1}, "system origin");
  expect_vec(system.axes[0], {0, 1, 0}, "system x");
  expect_vec(system.axes[1], {-1, 0, 0}, "system y");
  expect_vec(system.axes[2], {0, 0, 1}, "system z");
  EXPECT_EQ(system.where.keyword, "*DEFINE_COORDINATE_SYSTEM");
  EXPECT_EQ(system.where.line, 58);

  const auto& vector = m.coordinate_systems.at(6);
  EXPECT_EQ(vector.kind, rf::model::CoordinateKind::Vector);
  expect_vec(vector.origin, {0, 0, 0}, "vector origin");
  expect_vec(vector.axes[0], {h, h, 0}, "vector x");
  expect_vec(vector.axes[1], {-h, h, 0}, "vector y");
  expect_vec(vector.axes[2], {0, 0, 1}, "vector z");

  const auto& nodes = m.coordinate_systems.at(7);
  EXPECT_EQ(nodes.kind, rf::model::CoordinateKind::Nodes);
  EXPECT_EQ(nodes.nodes, (std::array<rf::model::Id, 3>{1, 2, 4}));
  EXPECT_EQ(nodes.dir, 'Y');
  expect_vec(nodes.origin, {0, 0, 0}, "nodes origin");
  expect_vec(nodes.axes[0], {0, 0, 1}, "nodes x");
  expect_vec(nodes.axes[1], {1, 0, 0}, "nodes y (N1 -> N2)");
  expect_vec(nodes.axes[2], {0, 1, 0}, "nodes z");

  ASSERT_EQ(m.vectors.size(), 2u);
  expect_vec(m.vectors.at(1).direction, {0, 0, 1}, "vector 1");
  expect_vec(m.vectors.at(1).head, {0, 0, 2}, "vector 1 head");
  EXPECT_EQ(m.vectors.at(2).cid, 6);
  expect_vec(m.vectors.at(2).direction, {h, h, 0}, "vector 2 in system 6");
}

TEST_P(KeywordRigid, RigidMaterials) {
  const Model m = read();
  const auto& local = m.materials.at(1);
  EXPECT_EQ(local.kind, rf::model::MaterialKind::Rigid);
  EXPECT_EQ(local.cmo, -1.0);
  EXPECT_EQ(local.con1, 5.0);
  EXPECT_EQ(local.cmo_cid, 5);
  EXPECT_EQ(local.cmo_local_fix, (std::array<bool, 6>{true, true, false, false, false, true}));
  EXPECT_EQ(local.lco, 5);
  EXPECT_FALSE(local.has_output_vectors);

  const auto& global = m.materials.at(3);
  EXPECT_EQ(global.keyword, "*MAT_RIGID_TITLE");
  EXPECT_EQ(global.cmo, 1.0);
  EXPECT_EQ(global.con1, 4.0);
  EXPECT_EQ(global.con2, 7.0);
  EXPECT_EQ(global.cmo_cid, 0);
  EXPECT_TRUE(global.has_output_vectors);
  expect_vec(global.output_a, {1, 0, 0}, "A");
  expect_vec(global.output_v, {0, 1, 0}, "V");
  EXPECT_EQ(global.lco, 0);
}

TEST_P(KeywordRigid, PartInertia) {
  const Model m = read();
  EXPECT_FALSE(m.parts.at(1).inertia.has_value());
  const auto& p = m.parts.at(2);
  EXPECT_EQ(p.title, "flywheel");
  EXPECT_EQ(p.mid, 3);
  ASSERT_TRUE(p.inertia.has_value());
  const auto& in = *p.inertia;
  expect_vec(in.xc, {2.5, 0.5, 0.5}, "xc");
  EXPECT_EQ(in.tm, 10.0);
  EXPECT_EQ(in.ircs, 1);
  EXPECT_EQ(in.nodeid, 0);
  EXPECT_EQ(in.inertia, (std::array<double, 6>{1.0, 0.0, 0.0, 2.0, 0.0, 3.0}));
  expect_vec(in.vt, {1, 0, 0}, "vt");
  expect_vec(in.vr, {0, 0, 6}, "vr");
  expect_vec(in.xl, {0, 1, 0}, "xl");
  expect_vec(in.xlip, {-1, 0, 0}, "xlip");
  expect_vec(in.principal_axes[0], {0, 1, 0}, "principal 1");
  expect_vec(in.principal_axes[1], {-1, 0, 0}, "principal 2");
  expect_vec(in.principal_axes[2], {0, 0, 1}, "principal 3");
  EXPECT_EQ(in.where.keyword, "*PART_INERTIA");
  EXPECT_EQ(in.where.line, 40);
}

TEST_P(KeywordRigid, ConstraintsAndNodalRigidBodies) {
  const Model m = read();
  ASSERT_EQ(m.rigid_body_merges.size(), 1u);
  EXPECT_EQ(m.rigid_body_merges[0].lead, 1);
  EXPECT_EQ(m.rigid_body_merges[0].constrained, 2);
  EXPECT_EQ(m.rigid_body_merges[0].iflag, 1);
  EXPECT_EQ(m.rigid_body_merges[0].where.line, 69);

  ASSERT_EQ(m.extra_nodes.size(), 2u);
  EXPECT_EQ(m.extra_nodes[0].pid, 1);
  EXPECT_EQ(m.extra_nodes[0].target, Target::Node);
  EXPECT_EQ(m.extra_nodes[0].id, 24);
  EXPECT_EQ(m.extra_nodes[0].iflag, 0);
  EXPECT_EQ(m.extra_nodes[1].pid, 2);
  EXPECT_EQ(m.extra_nodes[1].target, Target::NodeSet);
  EXPECT_EQ(m.extra_nodes[1].id, 11);
  EXPECT_EQ(m.extra_nodes[1].iflag, 1);

  ASSERT_EQ(m.nodal_rigid_bodies.size(), 2u);
  const auto& b = m.nodal_rigid_bodies.at(10);
  EXPECT_EQ(b.nsid, 10);
  EXPECT_EQ(b.cid, 0);
  EXPECT_EQ(b.pnode, 0);
  EXPECT_EQ(b.iprt, 1);
  EXPECT_EQ(b.cmo, 1.0);
  EXPECT_EQ(b.con1, 7.0);
  EXPECT_EQ(b.con2, 0.0);
  ASSERT_TRUE(b.inertia.has_value());
  expect_vec(b.inertia->xc, {5, 1, 0}, "xc from NODEID 19");
  EXPECT_EQ(b.inertia->nodeid, 19);
  EXPECT_EQ(b.inertia->tm, 0.5);
  EXPECT_EQ(b.inertia->ircs, 0);
  EXPECT_EQ(b.inertia->inertia, (std::array<double, 6>{0.1, 0.0, 0.0, 0.2, 0.0, 0.3}));
  expect_vec(b.inertia->vr, {0, 0, 1}, "vr");
  expect_vec(b.inertia->principal_axes[0], {1, 0, 0}, "identity axes");
  EXPECT_EQ(b.where.keyword, "*CONSTRAINED_NODAL_RIGID_BODY_SPC_INERTIA");

  const auto& plain = m.nodal_rigid_bodies.at(12);
  EXPECT_EQ(plain.nsid, 12);  // NSID blank -> PID
  EXPECT_EQ(plain.pnode, -23);
  EXPECT_FALSE(plain.inertia.has_value());
  EXPECT_EQ(plain.cmo, 0.0);
}

TEST_P(KeywordRigid, MotionsLoadsAndControls) {
  const Model m = read();
  ASSERT_EQ(m.rigid_prescribed_motions.size(), 2u);
  const auto& rot = m.rigid_prescribed_motions[0];
  EXPECT_EQ(rot.pid, 1);
  EXPECT_EQ(rot.dof, 5);
  EXPECT_EQ(rot.vad, 2);
  EXPECT_EQ(rot.lcid, 1);
  EXPECT_EQ(rot.sf, 0.5);
  EXPECT_EQ(rot.vid, 0);
  EXPECT_EQ(rot.death, 1e28);
  EXPECT_EQ(rot.where.keyword, "*BOUNDARY_PRESCRIBED_MOTION_RIGID_ID");
  const auto& about = m.rigid_prescribed_motions[1];
  EXPECT_EQ(about.pid, 10);  // a nodal rigid body
  EXPECT_EQ(about.dof, 8);
  EXPECT_EQ(about.vad, 0);
  EXPECT_EQ(about.sf, 1.0);
  EXPECT_EQ(about.vid, 1);
  EXPECT_EQ(about.death, 2.0);
  EXPECT_EQ(about.birth, 0.1);

  ASSERT_EQ(m.rigid_loads.size(), 1u);
  EXPECT_EQ(m.rigid_loads[0].pid, 1);
  EXPECT_EQ(m.rigid_loads[0].dof, 6);
  EXPECT_EQ(m.rigid_loads[0].lcid, 1);
  EXPECT_EQ(m.rigid_loads[0].sf, 2.0);

  ASSERT_EQ(m.initial_velocities.size(), 1u);
  const auto& v = m.initial_velocities[0];
  EXPECT_EQ(v.target, Target::Part);
  EXPECT_EQ(v.id, 2);  // a rigid part
  EXPECT_EQ(v.omega, 10.0);
  expect_vec(v.axis, {0, 0, 1}, "axis");
  EXPECT_EQ(v.irigid, 1);

  EXPECT_EQ(m.rigid_body_update, 1);
  EXPECT_TRUE(m.output.rbdout);
  EXPECT_DOUBLE_EQ(m.output.rbdout_dt, 1e-4);
  bool control_rigid_warned = false;
  for (const auto& w : m.warnings) {
    control_rigid_warned |=
        w.where.keyword == "*CONTROL_RIGID" && w.message.find("ignored") != std::string::npos;
  }
  EXPECT_TRUE(control_rigid_warned);
}

INSTANTIATE_TEST_SUITE_P(Formats, KeywordRigid, ::testing::Values("rigid_fixed.k", "rigid_free.k"),
                         [](const auto& info) {
                           return std::string(info.param).find("free") != std::string::npos
                                      ? std::string("Free")
                                      : std::string("Fixed");
                         });

TEST(KeywordRigidDefaults, NoRigidKeywordsMeansEmpty) {
  const Model m = rf::io::read_deck(rf::test::deck_path("block_fixed.k"));
  EXPECT_TRUE(m.coordinate_systems.empty());
  EXPECT_TRUE(m.rigid_body_merges.empty());
  EXPECT_TRUE(m.nodal_rigid_bodies.empty());
  EXPECT_EQ(m.rigid_body_update, 0);
  EXPECT_FALSE(m.output.rbdout);
}

}  // namespace
