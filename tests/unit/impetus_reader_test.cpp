// IMPETUS dialect: detection, card syntax, the commands of the seed deck, and clear errors.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "io/keyword/reader.hpp"
#include "keyword_test_util.hpp"
#include "mesh/component.hpp"
#include "model/error.hpp"
#include "model/function.hpp"

namespace {

using rf::io::read_deck_text;
using rf::model::Target;
using rf::test::input_error_of;
using rf::test::read_text_file;

std::string seed_text() {
  return read_text_file(std::string(RIGIDFLEX_EXAMPLES) + "/seed_rigid_body_update.k");
}

TEST(ImpetusDialect, DetectedFromCommandsAndOverridable) {
  const auto m = read_deck_text(seed_text(), "seed.k");
  EXPECT_EQ(m.dialect, "impetus");
  EXPECT_NE(m.dialect_reason.find("*UNIT_SYSTEM"), std::string::npos) << m.dialect_reason;
  // Forced to LS-DYNA the same text is a list of unknown keywords, each reported (errors, as
  // unknown LS-DYNA keywords may change the physics; skipped here to look at the dialect).
  rf::io::ReadOptions lsdyna;
  lsdyna.dialect = rf::io::Dialect::LsDyna;
  lsdyna.ignore_unsupported = true;
  const auto forced = read_deck_text("*TIME\n0.01\n*OUTPUT\n0.002\n", "x.k", ".", lsdyna);
  EXPECT_EQ(forced.dialect, "lsdyna");
  EXPECT_EQ(forced.unknown_keywords.count("*TIME"), 1u);
  // %-parameters alone are enough.
  EXPECT_EQ(read_deck_text("*PARAMETER\n%a = 2, \"a\"\n", "p.k").dialect, "impetus");
  // An LS-DYNA deck stays LS-DYNA.
  EXPECT_EQ(read_deck_text("*KEYWORD\n*CONTROL_TERMINATION\n0.1\n*END\n", "k.k").dialect, "lsdyna");
}

TEST(ImpetusDialect, SeedDeckModel) {
  const auto m = read_deck_text(seed_text(), "seed.k");
  EXPECT_EQ(m.unit_system, "SI");
  EXPECT_DOUBLE_EQ(m.termination.endtim, 0.01);
  EXPECT_DOUBLE_EQ(m.output.d3plot_dt, 0.002);
  EXPECT_EQ(m.rigid_body_update, 2);
  EXPECT_NEAR(m.parameters.at("rot"), 4 * std::numbers::pi, 1e-15);
  // Two cylinders: 20 + 3 layers of 48 elements; 24 (not 25) layers of 57 nodes after merging
  // the shared end face.
  EXPECT_EQ(m.solids.size(), 23u * 48u);
  EXPECT_EQ(m.nodes.size(), 24u * 57u);
  EXPECT_EQ(m.merged_node_count, 57);
  ASSERT_EQ(m.parts.size(), 2u);
  EXPECT_DOUBLE_EQ(m.parts.at(1).smoothing_angle, 50.0);
  EXPECT_EQ(m.materials.at(2).kind, rf::model::MaterialKind::Rigid);
  ASSERT_EQ(m.p_order_changes.size(), 1u);
  EXPECT_EQ(m.p_order_changes[0].target, Target::All);
  EXPECT_EQ(m.p_order_changes[0].order, 3);
  // "G, 1, XYZ": a constraint on geometry 1, the seed point at the origin.
  ASSERT_EQ(m.spcs.size(), 1u);
  EXPECT_EQ(m.spcs[0].target, Target::Geometry);
  EXPECT_TRUE(m.spcs[0].fix[0] && m.spcs[0].fix[1] && m.spcs[0].fix[2]);
  EXPECT_DOUBLE_EQ(m.geometry_seeds.at(1).feature_angle_deg, 45.0);
  // "P, 2, Z" + "D, RZ, 2" on a rigid part: z held, rotation about z prescribed by function 2.
  ASSERT_EQ(m.rigid_prescribed_motions.size(), 2u);
  EXPECT_EQ(m.rigid_prescribed_motions[0].dof, 3);
  EXPECT_EQ(m.rigid_prescribed_motions[0].vad, 2);
  EXPECT_DOUBLE_EQ(m.rigid_prescribed_motions[0].sf, 0.0);
  EXPECT_EQ(m.rigid_prescribed_motions[1].dof, 7);
  EXPECT_EQ(m.rigid_prescribed_motions[1].function, 2);
  const auto& f = *m.functions.at(2).evaluator;
  EXPECT_NEAR(f(0.005), 2 * std::numbers::pi, 1e-12);
}

TEST(ImpetusDialect, OneLineCopyOfTheSeedReadsLikeTheOriginal) {
  // The seed document carries the deck with its line breaks turned into blanks.
  std::string flat;
  for (char c : seed_text()) flat += c == '\n' ? ' ' : c;
  const auto a = read_deck_text(seed_text(), "seed.k");
  const auto b = read_deck_text(flat, "flat.k");
  EXPECT_EQ(b.dialect, "impetus");
  EXPECT_EQ(a.nodes.size(), b.nodes.size());
  EXPECT_EQ(a.solids.size(), b.solids.size());
  EXPECT_EQ(a.rigid_prescribed_motions.size(), b.rigid_prescribed_motions.size());
  EXPECT_EQ(a.functions.at(2).expression, b.functions.at(2).expression);
  EXPECT_EQ(b.rigid_body_update, 2);
  EXPECT_TRUE(b.warnings.empty());
}

TEST(ImpetusDialect, ParameterOverrideSwitchesTheUpdateType) {
  for (const char* name : {"type", "%type", "TYPE"}) {
    rf::io::ReadOptions options;
    options.parameter_overrides[name] = 0;
    EXPECT_EQ(read_deck_text(seed_text(), "seed.k", ".", options).rigid_body_update, 0) << name;
  }
}

TEST(ImpetusDialect, ExpressionsUseDegreesAndParameters) {
  const auto m = read_deck_text(
      "*PARAMETER\n%a = 30, \"angle\"\n%b = [cos(%a)*2], \"c\"\n%c = sinr(pi/2) + ln(1)\n"
      "*TIME\n[%b*%c/2]\n*FUNCTION\n7\nsin(90*t) + %a\n",
      "e.k");
  EXPECT_NEAR(m.parameters.at("b"), std::sqrt(3.0), 1e-14);  // cos(30 deg) = sqrt(3)/2
  EXPECT_NEAR(m.parameters.at("c"), 1.0, 1e-15);
  EXPECT_NEAR(m.termination.endtim, std::sqrt(3.0) / 2, 1e-14);
  EXPECT_NEAR((*m.functions.at(7).evaluator)(1.0), 31.0, 1e-12);  // sin(90 deg) + 30
}

TEST(ImpetusDialect, SmallDeckWithNodesElementsSetsAndVelocity) {
  const auto m = read_deck_text(
      "*NODE\n1, 0, 0, 0, XYZ\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n5, 0, 0, 1\n6, 1, 0, 1\n"
      "7, 1, 1, 1\n8, 0, 1, 1\n"
      "*ELEMENT_SOLID\n1, 3, 1, 2, 3, 4, 5, 6, 7, 8\n"
      "*MAT_ELASTIC\n1, 7800, 2e11, 0.3\n*PART\n\"block\"\n3, 1\n"
      "*SET_NODE\n10\n5, 6, 7, 8\n*SET_PART\n20\n3..3\n"
      "*INITIAL_VELOCITY\nPS, 20, 1, 0, 0, 0, 0, 5\n0.5, 0.5, 0\n"
      "*OUTPUT_NODE\nNS, 10\n*TIME\n1e-3\n*OUTPUT\n1e-4, 1e-5\n",
      "small.k");
  EXPECT_EQ(m.nodes[0].tc, 7);
  EXPECT_EQ(m.parts.at(3).title, "block");
  EXPECT_EQ(m.part_sets.at(20).parts, std::vector<rf::model::Id>{3});
  ASSERT_EQ(m.initial_velocities.size(), 1u);
  EXPECT_EQ(m.initial_velocities[0].target, Target::PartSet);
  EXPECT_DOUBLE_EQ(m.initial_velocities[0].omega, 5.0);
  EXPECT_DOUBLE_EQ(m.initial_velocities[0].point[0], 0.5);
  EXPECT_EQ(m.output.history_nodes.size(), 4u);
  EXPECT_DOUBLE_EQ(m.output.glstat_dt, 1e-5);
}

TEST(ImpetusDialect, BadInputNamesFileLineCommandAndField) {
  const std::string e1 = input_error_of("*TIME\n[%undefined*2]\n", "t.k");
  EXPECT_NE(e1.find("t.k:2"), std::string::npos) << e1;
  EXPECT_NE(e1.find("*TIME"), std::string::npos) << e1;
  EXPECT_NE(e1.find("t_term"), std::string::npos) << e1;
  const std::string e2 =
      input_error_of("*COMPONENT_CYLINDER\n1, 1, 2.5, 4\n0,0,0,0,0,1,0.1\n", "c.k");
  EXPECT_NE(e2.find("c.k:2"), std::string::npos) << e2;
  EXPECT_NE(e2.find("N_1"), std::string::npos) << e2;
  const std::string e3 = input_error_of("*BC_MOTION\n1\nP, 1, XQ\n", "b.k");
  EXPECT_NE(e3.find("bc_tr"), std::string::npos) << e3;
  const std::string e4 = input_error_of("*BC_MOTION\n1\nP, 1, 0\nD, RW, 2\n", "b.k");
  EXPECT_NE(e4.find("b.k:4"), std::string::npos) << e4;
  EXPECT_NE(e4.find("direc"), std::string::npos) << e4;
  // Unsupported values that change the physics are errors, not silently dropped.
  const std::string e5 =
      input_error_of("*TIME\n1\n*MAT_ELASTIC\n1, 7800, 2e11, 0.3\n0, 0, 0.05\n", "m.k");
  EXPECT_NE(e5.find("damping"), std::string::npos) << e5;
  const std::string e6 = input_error_of("*FUNCTION\n3\nt + nosuchname\n", "f.k");
  EXPECT_NE(e6.find("f.k:3"), std::string::npos) << e6;
  EXPECT_NE(e6.find("expression"), std::string::npos) << e6;
  const std::string e7 = input_error_of("*CHANGE_P-ORDER\nALL, 0, 5\n", "o.k");
  EXPECT_NE(e7.find("order"), std::string::npos) << e7;
}

TEST(ImpetusDialect, UnknownCommandsAreListedAsWarnings) {
  const auto m = read_deck_text("*TIME\n1\n*CONTACT\n1, P, 1, P, 2\n", "u.k");
  ASSERT_EQ(m.unknown_keywords.count("*CONTACT"), 1u);
  ASSERT_FALSE(m.warnings.empty());
  EXPECT_NE(m.warnings[0].message.find("*CONTACT"), std::string::npos);
}

TEST(MeshGenerator, CylinderIsAnOGridWithPositiveJacobians) {
  const auto mesh = rf::mesh::generate_cylinder({0, 0, 0}, {0, 0, 2}, 0.5, {3, 4, 2});
  EXPECT_EQ(mesh.hexes.size(), 3u * (16u + 4u * 4u * 2u));
  // Every hexahedron: (n2 - n1) x (n4 - n1) points towards n5.
  for (const auto& h : mesh.hexes) {
    const auto& a = mesh.nodes[h[0]];
    const auto& b = mesh.nodes[h[1]];
    const auto& d = mesh.nodes[h[3]];
    const auto& e = mesh.nodes[h[4]];
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    const double vx = d[0] - a[0], vy = d[1] - a[1], vz = d[2] - a[2];
    const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    EXPECT_GT(nx * (e[0] - a[0]) + ny * (e[1] - a[1]) + nz * (e[2] - a[2]), 0.0);
  }
  // Nodes on the mantle lie on the circle.
  int mantle = 0;
  for (const auto& x : mesh.nodes) {
    const double r = std::hypot(x[0], x[1]);
    if (std::abs(r - 0.5) < 1e-12) ++mantle;
    EXPECT_LE(r, 0.5 + 1e-12);
  }
  EXPECT_EQ(mantle, 4 * 16);  // 16 around, 4 layers of nodes
}

}  // namespace
