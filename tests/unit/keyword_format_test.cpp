// Fixed and free card formats, number spellings, long format and unknown keywords.
#include <gtest/gtest.h>

#include "io/keyword/number.hpp"
#include "keyword_test_util.hpp"

using rf::io::read_deck;
using rf::io::read_deck_text;
using rf::model::Model;

namespace {

void expect_same_location_free(const Model& a, const Model& b) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    EXPECT_EQ(a.nodes[i].id, b.nodes[i].id);
    for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(a.nodes[i].x[k], b.nodes[i].x[k]);
    EXPECT_EQ(a.nodes[i].tc, b.nodes[i].tc);
    EXPECT_EQ(a.nodes[i].rc, b.nodes[i].rc);
  }
  ASSERT_EQ(a.solids.size(), b.solids.size());
  for (std::size_t i = 0; i < a.solids.size(); ++i) {
    EXPECT_EQ(a.solids[i].id, b.solids[i].id);
    EXPECT_EQ(a.solids[i].pid, b.solids[i].pid);
    EXPECT_EQ(a.solids[i].nodes, b.solids[i].nodes);
  }
  ASSERT_EQ(a.parts.size(), b.parts.size());
  for (const auto& [id, p] : a.parts) {
    const auto& q = b.parts.at(id);
    EXPECT_EQ(p.title, q.title);
    EXPECT_EQ(p.secid, q.secid);
    EXPECT_EQ(p.mid, q.mid);
    EXPECT_EQ(p.hgid, q.hgid);
  }
  ASSERT_EQ(a.solid_sections.size(), b.solid_sections.size());
  for (const auto& [id, s] : a.solid_sections) EXPECT_EQ(s.elform, b.solid_sections.at(id).elform);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (const auto& [id, m] : a.materials) {
    const auto& n = b.materials.at(id);
    EXPECT_EQ(m.kind, n.kind);
    EXPECT_DOUBLE_EQ(m.rho, n.rho);
    EXPECT_DOUBLE_EQ(m.e, n.e);
    EXPECT_DOUBLE_EQ(m.pr, n.pr);
    EXPECT_DOUBLE_EQ(m.cmo, n.cmo);
    EXPECT_DOUBLE_EQ(m.con1, n.con1);
    EXPECT_DOUBLE_EQ(m.con2, n.con2);
  }
  ASSERT_EQ(a.hourglass.size(), b.hourglass.size());
  for (const auto& [id, h] : a.hourglass) {
    EXPECT_EQ(h.ihq, b.hourglass.at(id).ihq);
    EXPECT_DOUBLE_EQ(h.qm, b.hourglass.at(id).qm);
  }
  ASSERT_EQ(a.curves.size(), b.curves.size());
  for (const auto& [id, c] : a.curves) {
    const auto& d = b.curves.at(id);
    EXPECT_EQ(c.abscissa, d.abscissa);
    EXPECT_EQ(c.ordinate, d.ordinate);
    EXPECT_DOUBLE_EQ(c.sfa, d.sfa);
    EXPECT_DOUBLE_EQ(c.sfo, d.sfo);
  }
  ASSERT_EQ(a.node_sets.size(), b.node_sets.size());
  for (const auto& [id, s] : a.node_sets) EXPECT_EQ(s.nodes, b.node_sets.at(id).nodes);
  ASSERT_EQ(a.part_sets.size(), b.part_sets.size());
  for (const auto& [id, s] : a.part_sets) EXPECT_EQ(s.parts, b.part_sets.at(id).parts);
  ASSERT_EQ(a.segment_sets.size(), b.segment_sets.size());
  for (const auto& [id, s] : a.segment_sets) EXPECT_EQ(s.segments, b.segment_sets.at(id).segments);
  ASSERT_EQ(a.spcs.size(), b.spcs.size());
  for (std::size_t i = 0; i < a.spcs.size(); ++i) {
    EXPECT_EQ(a.spcs[i].target, b.spcs[i].target);
    EXPECT_EQ(a.spcs[i].id, b.spcs[i].id);
    EXPECT_EQ(a.spcs[i].fix, b.spcs[i].fix);
  }
  ASSERT_EQ(a.prescribed_motions.size(), b.prescribed_motions.size());
  for (std::size_t i = 0; i < a.prescribed_motions.size(); ++i) {
    const auto& p = a.prescribed_motions[i];
    const auto& q = b.prescribed_motions[i];
    EXPECT_EQ(p.target, q.target);
    EXPECT_EQ(p.id, q.id);
    EXPECT_EQ(p.dof, q.dof);
    EXPECT_EQ(p.vad, q.vad);
    EXPECT_EQ(p.lcid, q.lcid);
    EXPECT_DOUBLE_EQ(p.sf, q.sf);
    EXPECT_DOUBLE_EQ(p.death, q.death);
    EXPECT_DOUBLE_EQ(p.birth, q.birth);
  }
  ASSERT_EQ(a.initial_velocities.size(), b.initial_velocities.size());
  for (std::size_t i = 0; i < a.initial_velocities.size(); ++i) {
    const auto& v = a.initial_velocities[i];
    const auto& w = b.initial_velocities[i];
    EXPECT_EQ(v.target, w.target);
    EXPECT_EQ(v.id, w.id);
    EXPECT_EQ(v.v, w.v);
    EXPECT_DOUBLE_EQ(v.omega, w.omega);
    EXPECT_EQ(v.point, w.point);
    EXPECT_EQ(v.axis, w.axis);
  }
  ASSERT_EQ(a.nodal_loads.size(), b.nodal_loads.size());
  for (std::size_t i = 0; i < a.nodal_loads.size(); ++i) {
    EXPECT_EQ(a.nodal_loads[i].id, b.nodal_loads[i].id);
    EXPECT_EQ(a.nodal_loads[i].dof, b.nodal_loads[i].dof);
    EXPECT_DOUBLE_EQ(a.nodal_loads[i].sf, b.nodal_loads[i].sf);
  }
  ASSERT_EQ(a.body_loads.size(), b.body_loads.size());
  for (std::size_t i = 0; i < a.body_loads.size(); ++i) {
    EXPECT_EQ(a.body_loads[i].direction, b.body_loads[i].direction);
    EXPECT_DOUBLE_EQ(a.body_loads[i].sf, b.body_loads[i].sf);
  }
  EXPECT_DOUBLE_EQ(a.termination.endtim, b.termination.endtim);
  EXPECT_DOUBLE_EQ(a.timestep.tssfac, b.timestep.tssfac);
  EXPECT_EQ(a.hourglass_control.ihq, b.hourglass_control.ihq);
  EXPECT_DOUBLE_EQ(a.output.glstat_dt, b.output.glstat_dt);
  EXPECT_DOUBLE_EQ(a.output.nodout_dt, b.output.nodout_dt);
  EXPECT_DOUBLE_EQ(a.output.d3plot_dt, b.output.d3plot_dt);
  EXPECT_EQ(a.output.history_nodes, b.output.history_nodes);
  EXPECT_EQ(a.title, b.title);
}

}  // namespace

TEST(KeywordFormat, FixedAndFreeFormatGiveTheSameModel) {
  const Model fixed = read_deck(rf::test::deck_path("block_fixed.k"));
  const Model free = read_deck(rf::test::deck_path("block_free.k"));
  expect_same_location_free(fixed, free);
  EXPECT_TRUE(fixed.warnings.empty()) << fixed.warnings.front().message;
  EXPECT_TRUE(free.warnings.empty()) << free.warnings.front().message;
}

TEST(KeywordFormat, FixedFormatValuesAreReadAsWritten) {
  const Model m = read_deck(rf::test::deck_path("block_fixed.k"));
  EXPECT_EQ(m.title, "two-block test deck");
  ASSERT_EQ(m.nodes.size(), 12u);
  EXPECT_DOUBLE_EQ(m.nodes[11].x[2], 1.0);
  ASSERT_EQ(m.solids.size(), 2u);
  EXPECT_EQ(m.solids[1].nodes[7], 11);  // two-card element form
  EXPECT_EQ(m.parts.at(1).title, "steel block");
  EXPECT_EQ(m.parts.at(1).hgid, 1);
  EXPECT_DOUBLE_EQ(m.materials.at(1).e, 2.1e5);  // written "2.1+5"
  EXPECT_EQ(m.materials.at(2).kind, rf::model::MaterialKind::Rigid);
  EXPECT_DOUBLE_EQ(m.materials.at(2).con1, 4.0);
  EXPECT_DOUBLE_EQ(m.hourglass.at(1).qb, 0.05);  // QB defaults to QM
  EXPECT_EQ(m.node_sets.at(1).nodes, (std::vector<rf::model::Id>{1, 2, 3, 4}));  // zero dropped
  EXPECT_DOUBLE_EQ(m.curves.at(1).sfa, 1.0);                                     // SFA 0 means 1
  EXPECT_DOUBLE_EQ(m.curves.at(1).sfo, 2.0);
  EXPECT_DOUBLE_EQ(m.curves.at(1).abscissa[1], 1.0e-3);
  ASSERT_EQ(m.prescribed_motions.size(), 2u);
  EXPECT_EQ(m.prescribed_motions[0].target, rf::model::Target::NodeSet);
  EXPECT_EQ(m.prescribed_motions[0].vad, 2);
  EXPECT_DOUBLE_EQ(m.prescribed_motions[0].sf, -1.0);
  EXPECT_DOUBLE_EQ(m.prescribed_motions[0].death, 1e28);  // DEATH 0 means never
  ASSERT_EQ(m.spcs.size(), 2u);
  EXPECT_EQ(m.spcs[1].fix, (std::array<bool, 3>{true, false, false}));
  ASSERT_EQ(m.initial_velocities.size(), 2u);
  EXPECT_EQ(m.initial_velocities[0].target, rf::model::Target::Part);
  EXPECT_DOUBLE_EQ(m.initial_velocities[0].omega, 10.0);
  EXPECT_DOUBLE_EQ(m.initial_velocities[0].axis[2], 1.0);
  EXPECT_EQ(m.body_loads.at(0).direction, 2);
  EXPECT_DOUBLE_EQ(m.timestep.tssfac, 0.9);           // TSSFAC 0 means 0.9
  EXPECT_DOUBLE_EQ(m.output.d3plot_dt, 1.0e-3 / 50);  // NPLTC resolved against ENDTIM
  EXPECT_DOUBLE_EQ(m.output.nodout_dt, 2.0e-5);
  EXPECT_EQ(m.output.history_nodes, (std::vector<rf::model::Id>{12, 9}));
}

TEST(KeywordFormat, NumberSpellings) {
  using rf::io::parse_integer;
  using rf::io::parse_real;
  EXPECT_DOUBLE_EQ(*parse_real("2.1-3").value, 2.1e-3);
  EXPECT_DOUBLE_EQ(*parse_real("2.1+5").value, 2.1e5);
  EXPECT_DOUBLE_EQ(*parse_real("-1.5D2").value, -150.0);
  EXPECT_DOUBLE_EQ(*parse_real("+.5").value, 0.5);
  EXPECT_DOUBLE_EQ(*parse_real("1e-3").value, 1e-3);
  EXPECT_FALSE(parse_real("abc").value);
  EXPECT_FALSE(parse_real("nan").value);
  EXPECT_FALSE(parse_real("inf").value);
  EXPECT_FALSE(parse_real("1e999").value);
  EXPECT_FALSE(parse_real("1..2").value);
  EXPECT_FALSE(parse_real("1-2-3").value);
  EXPECT_FALSE(parse_real("-").value);
  EXPECT_EQ(*parse_integer("4.").value, 4);
  EXPECT_EQ(*parse_integer("+7").value, 7);
  EXPECT_EQ(*parse_integer("1e3").value, 1000);
  EXPECT_FALSE(parse_integer("1.5").value);
  EXPECT_FALSE(parse_integer("99999999999999999999").value);
  EXPECT_FALSE(parse_integer("+-3").value);
}

TEST(KeywordFormat, LongFormatAndCaseInsensitiveKeywords) {
  const std::string deck =
      "*keyword\n"
      "*node +\n"
      "                   1                 1.5                 2.5                 3.5\n"
      "*Node -\n"
      "       2             1.0             2.0             3.0\n";
  const Model m = read_deck_text(deck);
  ASSERT_EQ(m.nodes.size(), 2u);
  EXPECT_DOUBLE_EQ(m.nodes[0].x[2], 3.5);
  EXPECT_DOUBLE_EQ(m.nodes[1].x[1], 2.0);
}

TEST(KeywordFormat, KeywordLongYesSelectsLongFormatGlobally) {
  const std::string deck =
      "*KEYWORD LONG=Y\n"
      "*NODE\n"
      "                   1                 1.5                 2.5                 3.5\n";
  const Model m = read_deck_text(deck);
  ASSERT_EQ(m.nodes.size(), 1u);
  EXPECT_DOUBLE_EQ(m.nodes[0].x[0], 1.5);
}

// An output-only keyword the reader does not read (docs/keywords.md, "Unsupported keywords").
TEST(KeywordFormat, UnsupportedOutputKeywordWarnsAndIsCounted) {
  const std::string deck =
      "*NODE\n"
      "1,0,0,0\n"
      "*DATABASE_SBTOUT\n"
      "1,2,3\n"
      "$ comment\n"
      "*database_sbtout\n"
      "*NODE\n"
      "2,0,0,0\n";
  const Model m = read_deck_text(deck, "c.k");
  EXPECT_EQ(m.nodes.size(), 2u);  // cards of the unknown keyword were skipped
  ASSERT_EQ(m.unknown_keywords.count("*DATABASE_SBTOUT"), 1u);
  EXPECT_EQ(m.unknown_keywords.at("*DATABASE_SBTOUT"), 2);
  ASSERT_EQ(m.warnings.size(), 2u);
  EXPECT_EQ(m.warnings[0].where.file, "c.k");
  EXPECT_EQ(m.warnings[0].where.line, 3);
  EXPECT_EQ(m.warnings[1].where.line, 6);
  EXPECT_EQ(m.warnings[0].where.keyword, "*DATABASE_SBTOUT");
}

TEST(KeywordFormat, EmptyAndCommentOnlyDecksGiveEmptyModels) {
  EXPECT_TRUE(read_deck_text("").nodes.empty());
  EXPECT_TRUE(read_deck_text("$ nothing\n*KEYWORD\n*END\n").nodes.empty());
}
