// Control, output, parameters and file structure.
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "io/keyword/handlers.hpp"
#include "io/keyword/number.hpp"

namespace rf::io::handlers {

namespace {

const Layout kEightByTen = uniform_layout(8, 10);

// Control cards are optional in LS-DYNA: an absent card means all defaults.
std::optional<Card> single_card(const Block& block, CardCursor& cursor) {
  auto card = cursor.next_optional(1, kEightByTen);
  return card;
}

double non_negative(const Card& card, std::size_t i, const char* name, double fallback) {
  const double v = card.real(i, name, fallback);
  if (v < 0.0) throw card.error(name, fmt::format("value {} must not be negative", v));
  return v;
}

}  // namespace

void control_termination(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  auto& t = context.model.termination;
  context.termination_where = block.location();
  if (const auto card = single_card(block, cursor)) {
    t.endtim = non_negative(*card, 0, "ENDTIM", 0.0);
    t.endcyc = card->flag(1, "ENDCYC", 0);
    if (t.endcyc < 0) throw card->error("ENDCYC", "value must not be negative");
    t.dtmin = non_negative(*card, 2, "DTMIN", 0.0);
    if (card->real(3, "ENDENG", 0.0) != 0.0 || card->real(4, "ENDMAS", 0.0) != 0.0) {
      context.warn(card->location(),
                   "ENDENG/ENDMAS ignored: only ENDTIM, ENDCYC and DTMIN "
                   "end a run");
    }
  }
  warn_unread_lines(block, cursor, context);
}

void control_timestep(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  auto& ts = context.model.timestep;
  ts.where = block.location();
  if (const auto card = single_card(block, cursor)) {
    ts.dtinit = non_negative(*card, 0, "DTINIT", 0.0);
    ts.tssfac = card->real(1, "TSSFAC", 0.9);
    if (ts.tssfac == 0.0) ts.tssfac = 0.9;  // LS-DYNA: 0 means the default
    if (ts.tssfac < 0.0 || ts.tssfac > 1.0) {
      throw card->error("TSSFAC", fmt::format("value {} must lie in (0, 1]", ts.tssfac));
    }
    // Mass scaling (solver/mass_scaling.hpp): DT2MS < 0 adds mass only where an element's step
    // is below TSSFAC |DT2MS|; DT2MS > 0 adds or removes mass so that every element's step is
    // TSSFAC DT2MS at the start. MS1ST 1 scales at the first step only.
    ts.dt2ms = card->real(4, "DT2MS", 0.0);
    if (!std::isfinite(ts.dt2ms)) throw card->error("DT2MS", "value must be finite");
    ts.ms1st = card->flag(7, "MS1ST", 0);
    if (ts.ms1st != 0 && ts.ms1st != 1) {
      throw card->error("MS1ST", fmt::format("value {} is not 0 or 1", ts.ms1st));
    }
    ts.lctm = card->id(5, "LCTM");
    if (ts.lctm < 0) throw card->error("LCTM", "curve ID must not be negative");
    context.lctm_where = card->location();
    // ERODE (docs/materials.md, "Failure and erosion"): elements whose step brings the run below
    // TSMIN erode; the digits 1, 10, 100 name solids, shells, beams (LS-DYNA's values).
    ts.erode = card->flag(6, "ERODE", 0);
    if (ts.erode < 0 || ts.erode > 111 || ts.erode % 10 > 1 || ts.erode / 10 % 10 > 1) {
      throw card->error("ERODE", fmt::format("value {} is not one of 0, 1, 10, 11, 100, 101, 110, "
                                             "111 (solids 1, shells 10, beams 100)",
                                             ts.erode));
    }
    // ISDO and TSLIMT concern shells (ISDO 0: LS-DYNA's shell length; TSLIMT a lower bound on
    // the shell step by mass scaling, not supported); MS1ST mass scaling.
    ts.isdo = card->flag(2, "ISDO", 0);
    if (ts.isdo != 0) {
      throw card->error("ISDO",
                        fmt::format("shell step option ISDO {} is not supported (0)", ts.isdo));
    }
    if (card->real(3, "TSLIMT", 0.0) != 0.0) {
      throw card->error("TSLIMT", "TSLIMT (shell mass scaling) is not supported (leave 0)");
    }
  }
  // Card 2 (optional): DT2MSF DT2MSLC IMSCL - - RMSCL EMSCL IHDO. Each changes the mass scaling
  // or the solid step; only their defaults are supported.
  if (const auto card = cursor.next_optional(2, kEightByTen)) {
    if (card->real(0, "DT2MSF", 0.0) != 0.0) {
      throw card->error("DT2MSF",
                        "DT2MSF (mass scaling from the initial step) is not supported "
                        "(give DT2MS on card 1)");
    }
    if (card->id(1, "DT2MSLC") != 0) {
      throw card->error("DT2MSLC", "a curve of DT2MS over time is not supported (leave 0)");
    }
    if (card->id(2, "IMSCL") != 0) {
      throw card->error("IMSCL", "selective mass scaling is not supported (leave 0)");
    }
    if (card->real(5, "RMSCL", 0.0) != 0.0) {
      throw card->error("RMSCL", "selective mass scaling is not supported (leave 0)");
    }
    if (card->real(6, "EMSCL", 0.0) != 0.0) {
      throw card->error("EMSCL",
                        "gravity on added mass is not supported (leave 0: body loads act on the "
                        "physical mass only)");
    }
    if (card->flag(7, "IHDO", 0) != 0) {
      throw card->error("IHDO", "the modified solid step (IHDO 1) is not supported (leave 0)");
    }
  }
  warn_unread_lines(block, cursor, context);
}

// *CONTROL_DYNAMIC_RELAXATION NRCYCK DRTOL DRFCTR DRTERM TSSFDR IRELAL EDTTL IDRFLG: the
// dynamic relaxation of LS-DYNA's IDRFLG 0, 1, -1 and -999 (solver/simulation.cpp,
// relax_dynamically). The automatic control (IRELAL), prescribed-geometry and implicit
// initialisation (IDRFLG 2, 3, 5, 6, -3) are errors.
void control_dynamic_relaxation(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  auto& dr = context.model.dynamic_relaxation;
  dr.where = block.location();
  if (const auto card = single_card(block, cursor)) {
    dr.where = card->location();
    dr.nrcyck = card->flag(0, "NRCYCK", 250);
    if (dr.nrcyck == 0) dr.nrcyck = 250;
    if (dr.nrcyck < 0) throw card->error("NRCYCK", "value must be a positive cycle count");
    dr.drtol = non_negative(*card, 1, "DRTOL", 1e-3);
    if (dr.drtol == 0.0) dr.drtol = 1e-3;
    if (dr.drtol >= 1.0) {
      throw card->error("DRTOL", fmt::format("value {} must lie in (0, 1)", dr.drtol));
    }
    dr.drfctr = non_negative(*card, 2, "DRFCTR", 0.995);
    if (dr.drfctr == 0.0) dr.drfctr = 0.995;
    if (dr.drfctr >= 1.0) {
      throw card->error("DRFCTR", fmt::format("value {} must lie in (0, 1): it scales the "
                                              "velocities every cycle",
                                              dr.drfctr));
    }
    dr.drterm = non_negative(*card, 3, "DRTERM", 0.0);
    dr.tssfdr = non_negative(*card, 4, "TSSFDR", 0.0);
    if (dr.tssfdr > 1.0) {
      throw card->error("TSSFDR", fmt::format("value {} must lie in (0, 1]", dr.tssfdr));
    }
    if (card->flag(5, "IRELAL", 0) != 0) {
      throw card->error("IRELAL",
                        "the automatic control of dynamic relaxation (Papadrakakis) is "
                        "not supported (leave 0: DRFCTR damps the velocities)");
    }
    dr.idrflg = card->flag(7, "IDRFLG", 0);
    if (dr.idrflg != 0 && dr.idrflg != 1 && dr.idrflg != -1 && dr.idrflg != -999) {
      throw card->error("IDRFLG", fmt::format("value {} is not supported (0, 1, -1 or -999; "
                                              "prescribed-geometry and implicit initialisation "
                                              "are not)",
                                              dr.idrflg));
    }
  }
  warn_unread_lines(block, cursor, context);
}

void control_hourglass(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  auto& h = context.model.hourglass_control;
  if (const auto card = single_card(block, cursor)) {
    h.ihq = card->flag(0, "IHQ", 1);
    if (h.ihq == 0) h.ihq = 1;
    if (h.ihq < 1 || h.ihq > 10) {
      throw card->error("IHQ", fmt::format("value {} is not a hourglass type 1..10", h.ihq));
    }
    h.qh = non_negative(*card, 1, "QH", 0.1);
  }
  warn_unread_lines(block, cursor, context);
}

// *CONTROL_BULK_VISCOSITY Q1 Q2 TYPE BTYPE TSTYPE (docs/keywords.md). TYPE -1/-2 add the
// shells (element/shell_block.cpp, section 10); BTYPE 1/2 (beams) is accepted only for models
// without beams (checked when the model is built). TYPE 2 (2-D solids) is an error.
void control_bulk_viscosity(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  auto& b = context.model.bulk_viscosity;
  b.where = block.location();
  if (const auto card = single_card(block, cursor)) {
    b.where = card->location();
    b.q1 = non_negative(*card, 0, "Q1", 1.5);
    b.q2 = non_negative(*card, 1, "Q2", 0.06);
    b.type = card->flag(2, "TYPE", 1);
    if (b.type == 0) b.type = 1;
    if (b.type != 1 && b.type != -1 && b.type != -2) {
      throw card->error("TYPE", fmt::format("bulk viscosity type {} is not supported (1: solids; "
                                            "-1, -2: solids and shells; 2 is for 2-D solids)",
                                            b.type));
    }
    b.btype = card->flag(3, "BTYPE", 0);
    if (b.btype < 0 || b.btype > 2) {
      throw card->error("BTYPE",
                        fmt::format("value {} is not a beam bulk viscosity type 0..2", b.btype));
    }
    const int tstype = card->flag(4, "TSTYPE", 0);
    if (tstype != 0 && tstype != 1) {
      throw card->error("TSTYPE", fmt::format("value {} is not 0 or 1", tstype));
    }
  }
  warn_unread_lines(block, cursor, context);
}

// *CONTROL_SHELL: the fields that change the shell physics are read and checked; values this
// solver does not implement are errors (docs/keywords.md).
void control_shell(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  auto& c = context.model.shell_control;
  c.where = block.location();
  if (const auto card = cursor.next_optional(1, kEightByTen)) {
    card->real(0, "WRPANG", 20.0);  // a warning threshold in LS-DYNA's printout
    const int esort = card->flag(1, "ESORT", 0);
    if (esort != 0 && esort != 1) {
      throw card->error("ESORT", "ESORT 2 (DKT triangles) is not supported (0 or 1)");
    }
    const int irnxx = card->flag(2, "IRNXX", -1);
    if (irnxx != 0 && irnxx != -1) {
      throw card->error("IRNXX", "only IRNXX -1 (normals recomputed every cycle) is supported");
    }
    // ISTUPD (LS-DYNA Keyword User's Manual, *CONTROL_SHELL): 1 membrane straining changes the
    // thickness of 3- and 4-node shells, 4 the same with the elastic strains neglected; 2 and 3
    // concern 8-node thick shells (*SECTION_TSHELL), which this solver does not have.
    c.istupd = card->flag(3, "ISTUPD", 0);
    if (c.istupd == 2 || c.istupd == 3) {
      throw card->error("ISTUPD", fmt::format("ISTUPD {} (thickness change of thick shells, "
                                              "*SECTION_TSHELL) is not supported: 0 constant "
                                              "thickness, 1 thickness update of the 3- and "
                                              "4-node shells, 4 the same without elastic strains",
                                              c.istupd));
    }
    if (c.istupd != 0 && c.istupd != 1 && c.istupd != 4) {
      throw card->error("ISTUPD", fmt::format("ISTUPD {} is not a thickness change option (0 "
                                              "constant thickness, 1 thickness update of the 3- "
                                              "and 4-node shells, 4 the same without elastic "
                                              "strains)",
                                              c.istupd));
    }
    c.theory = card->flag(4, "THEORY", 2);
    if (c.theory == 0) c.theory = 2;
    if (c.theory != 2 && c.theory != 16) {
      throw card->error("THEORY", fmt::format("default shell theory {} is not supported (2, "
                                              "Belytschko-Lin-Tsay; 16, fully integrated)",
                                              c.theory));
    }
    c.bwc = card->flag(5, "BWC", 2);
    if (c.bwc == 0) c.bwc = 2;
    if (c.bwc != 1 && c.bwc != 2) throw card->error("BWC", "BWC must be 1 or 2");
    c.miter = card->flag(6, "MITER", 1);
    if (c.miter == 0) c.miter = 1;
    if (c.miter != 1 && c.miter != 2) {
      throw card->error("MITER",
                        "MITER 3 (non-iterative radial return) is not supported: "
                        "plane stress is iterated (1 or 2)");
    }
    c.proj = card->flag(7, "PROJ", 0);
    if (c.proj != 0 && c.proj != 1) throw card->error("PROJ", "PROJ must be 0 or 1");
  }
  if (const auto card = cursor.next_optional(2, kEightByTen)) {
    c.rotascl = card->real(0, "ROTASCL", 1.0);
    if (c.rotascl == 0.0) c.rotascl = 1.0;
    if (c.rotascl < 0.0) throw card->error("ROTASCL", "must be positive");
    c.intgrd = card->flag(1, "INTGRD", 0);
    if (c.intgrd != 0 && c.intgrd != 1) throw card->error("INTGRD", "INTGRD must be 0 or 1");
    if (card->flag(2, "LAMSHT", 0) != 0) {
      throw card->error("LAMSHT", "laminated shell theory is not supported");
    }
    if (card->flag(4, "THSHEL", 0) != 0) {
      throw card->error("THSHEL", "thermal shells are not supported");
    }
  }
  // Cards 3-5 (thickness update sets, failure and deletion options, drilling control): only
  // their defaults are supported.
  static const char* const kLater[][8] = {
      {"PSSTUPD", "SIDT4TU", "CNTCO", "ITSFLG", "IRQUAD", "W-MODE", "STRETCH", "ICRQ"},
      {"NFAIL1", "NFAIL4", "PSNFAIL", "KEEPCS", "DELFR", "DRCPSID", "DRCPRM", "INTPERR"},
      {"DRCMTH", "LISPSID", "NLOCDT", nullptr, nullptr, nullptr, nullptr, nullptr}};
  for (int k = 0; k < 3; ++k) {
    const auto card = cursor.next_optional(3 + k, kEightByTen);
    if (!card) break;
    for (std::size_t i = 0; i < 8 && kLater[k][i]; ++i) {
      const std::string_view name = kLater[k][i];
      const double fallback = name == "IRQUAD" ? 3.0 : name == "DRCPRM" ? 1.0 : 0.0;
      const double v = card->real(i, kLater[k][i], fallback);
      // IRQUAD concerns ELFORM 16's in-plane rule; W-MODE and STRETCH are warning thresholds.
      if (name == "IRQUAD" || name == "W-MODE" || name == "STRETCH") continue;
      if (v != fallback) {
        throw card->error(
            kLater[k][i],
            fmt::format("value {} is not supported (only the default {})", v, fallback));
      }
    }
  }
  warn_unread_lines(block, cursor, context);
}

void database_ascii(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  double dt = 0.0;
  if (const auto card = single_card(block, cursor)) {
    dt = non_negative(*card, 0, "DT", 0.0);
    // BINARY and IOOPT are ignored, but read: a fixed-format DT too long for its 10 columns
    // spills into BINARY, and that must be an error, not a silently truncated interval.
    card->integer(1, "BINARY", 0);
    card->integer(3, "IOOPT", 0);
    if (card->id(2, "LCUR") != 0) {
      context.warn(card->location(), "LCUR ignored: output intervals come from DT");
    }
  }
  if (block.base == "*DATABASE_GLSTAT") {
    context.model.output.glstat_dt = dt;
  } else if (block.base == "*DATABASE_RBDOUT") {
    context.model.output.rbdout_dt = dt;
    context.model.output.rbdout = true;
  } else if (block.base == "*DATABASE_RWFORC") {
    context.model.output.rwforc_dt = dt;
  } else if (block.base == "*DATABASE_RCFORC") {
    context.model.output.rcforc_dt = dt;
  } else if (block.base == "*DATABASE_MATSUM") {
    context.model.output.matsum_dt = dt;
    context.model.output.matsum = true;
  } else if (block.base == "*DATABASE_SPCFORC") {
    context.model.output.spcforc_dt = dt;
    context.model.output.spcforc = true;
  } else if (block.base == "*DATABASE_ELOUT") {
    context.model.output.elout_dt = dt;
  } else if (block.base == "*DATABASE_SECFORC") {
    context.model.output.secforc_dt = dt;
  } else if (block.base == "*DATABASE_SWFORC") {
    context.model.output.swforc_dt = dt;
  } else if (block.base == "*DATABASE_JNTFORC") {
    context.model.output.jntforc_dt = dt;
    context.model.output.jntforc = true;
  } else {
    context.model.output.nodout_dt = dt;
  }
  warn_unread_lines(block, cursor, context);
}

void database_binary_d3plot(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  if (const auto card = single_card(block, cursor)) {
    context.model.output.d3plot_dt = non_negative(*card, 0, "DT", 0.0);
    if (card->id(1, "LCDT") != 0) {
      context.warn(card->location(), "LCDT ignored: d3plot intervals come from DT or NPLTC");
    }
    context.d3plot_npltc = card->flag(3, "NPLTC", 0);
    if (context.d3plot_npltc < 0) throw card->error("NPLTC", "value must not be negative");
  }
  // Card 2 (IOOPT and others) does not affect what is written here.
  while (cursor.next_optional(2, kEightByTen)) {
  }
}

void database_history_node(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const bool sets = block.base.ends_with("_SET");
  const char* field = sets ? "NSID" : "NID";
  int n = 0;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(++n, kEightByTen, field);
    for (std::size_t i = 0; i < card.field_count(); ++i) {
      const model::Id id = card.id(i, field);
      if (id < 0) throw card.error(field, fmt::format("ID {} must not be negative", id));
      if (id == 0) continue;
      if (sets)
        context.history_node_sets.push_back({id, card.location()});
      else {
        context.model.output.history_nodes.push_back(id);
        context.history_nodes.push_back({id, card.location()});
      }
    }
  }
}

// Elements whose stresses go to elout.csv (solids) and elout_shell.csv (shells): 8 IDs per card,
// 8 set IDs per card (_SET), or one ID and a heading per card (_ID). The IDs are checked
// against the mesh when the run starts.
void database_history_elements(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const bool shells = block.base.starts_with("*DATABASE_HISTORY_SHELL");
  const bool sets = block.base.ends_with("_SET");
  const bool with_heading = block.base.ends_with("_ID");
  const char* field = sets ? "SID" : (with_heading ? "ID" : "EID");
  model::OutputControl& output = context.model.output;
  std::vector<model::Id>& ids = shells ? (sets ? output.history_shell_sets : output.history_shells)
                                       : (sets ? output.history_solid_sets : output.history_solids);
  std::vector<model::SourceLocation>& where =
      shells ? (sets ? output.history_shell_set_where : output.history_shell_where)
             : (sets ? output.history_solid_set_where : output.history_solid_where);
  int n = 0;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    // _ID: the heading is a label for the user (not written to the CSV rows).
    const Card card = with_heading ? cursor.next(++n, Layout{10, 70}, "ID HEADING")
                                   : cursor.next(++n, kEightByTen, field);
    const std::size_t count = with_heading ? 1 : card.field_count();
    for (std::size_t i = 0; i < count; ++i) {
      const model::Id id = card.id(i, field);
      if (id < 0) throw card.error(field, fmt::format("ID {} must not be negative", id));
      if (id == 0) continue;
      ids.push_back(id);
      where.push_back(card.location());
    }
  }
}

namespace {

// The ID of a cross section: the _ID card (CSID HEADING), else its position in the deck.
void read_cross_section_id(const Block& block, ReaderContext& context, CardCursor& cursor, int& n,
                           model::CrossSection& section) {
  if (block.has_option("ID")) {
    const Card card = cursor.next(++n, Layout{10, 70}, "CSID HEADING");
    section.id = card.id(0, "CSID");
    if (section.id <= 0) throw card.error("CSID", "must be a positive ID");
    section.title = std::string(card.text(1));
  } else {
    section.id = static_cast<model::Id>(context.model.output.cross_sections.size()) + 1;
  }
}

// ID (output in a rigid body's, accelerometer's or coordinate system's axes) is not supported.
void refuse_local_axes(const Card& card, std::size_t field) {
  if (card.id(field, "ID") != 0) {
    throw card.error("ID",
                     "section forces in the frame of a rigid body, accelerometer or "
                     "coordinate system are not supported: leave ID blank (global axes)");
  }
}

// Appends a cross section read from `card`; a second definition of its ID is an error at
// `field`.
void add_cross_section(const Block& block, CardCursor& cursor, ReaderContext& context,
                       const Card& card, const char* field, const model::CrossSection& section) {
  for (const model::CrossSection& other : context.model.output.cross_sections) {
    if (other.id == section.id) {
      throw card.error(block.has_option("ID") ? "CSID" : field,
                       fmt::format("cross section {} is defined twice", section.id));
    }
  }
  context.model.output.cross_sections.push_back(section);
  warn_unread_lines(block, cursor, context);
}

}  // namespace

// A cutting plane whose section force goes to secforc.csv. Card layouts from the LS-DYNA manual
// (*DATABASE_CROSS_SECTION): [CSID HEADING] with _ID; PSID XCT YCT ZCT XCH YCH ZCH RADIUS;
// XHEV YHEV ZHEV LENL LENM ID ITYPE.
void database_cross_section_plane(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  model::CrossSection section;
  int n = 0;
  read_cross_section_id(block, context, cursor, n, section);
  const Card plane = cursor.next(++n, kEightByTen, "PSID");
  section.where = plane.location();
  section.part_set = plane.id(0, "PSID");
  if (section.part_set < 0) throw plane.error("PSID", "must not be negative (0: every part)");
  const char* tail_names[3] = {"XCT", "YCT", "ZCT"};
  const char* head_names[3] = {"XCH", "YCH", "ZCH"};
  for (int k = 0; k < 3; ++k) {
    section.tail[k] = plane.real(1 + k, tail_names[k], 0.0);
    section.head[k] = plane.real(4 + k, head_names[k], 0.0);
  }
  section.radius = plane.real(7, "RADIUS", 0.0);
  if (section.radius < 0.0) {
    // XCT and XCH are node IDs.
    section.tail_node = static_cast<model::Id>(section.tail[0]);
    section.head_node = static_cast<model::Id>(section.head[0]);
    if (section.tail_node <= 0 || section.tail_node != section.tail[0]) {
      throw plane.error("XCT", "with RADIUS < 0 XCT must be a node ID");
    }
    if (section.head_node <= 0 || section.head_node != section.head[0]) {
      throw plane.error("XCH", "with RADIUS < 0 XCH must be a node ID");
    }
  }
  cursor.skip_blank_lines();
  if (!cursor.at_end()) {
    const Card edge = cursor.next(++n, kEightByTen, "XHEV");
    const char* edge_names[3] = {"XHEV", "YHEV", "ZHEV"};
    for (int k = 0; k < 3; ++k) section.edge_head[k] = edge.real(k, edge_names[k], 0.0);
    section.length_l = edge.real(3, "LENL", 0.0);
    section.length_m = edge.real(4, "LENM", 0.0);
    if (section.length_l < 0.0) throw edge.error("LENL", "must not be negative (0: unbounded)");
    if (section.length_m < 0.0) throw edge.error("LENM", "must not be negative (0: unbounded)");
    refuse_local_axes(edge, 5);
    edge.integer(6, "ITYPE", 0);
  }
  if (section.radius == 0.0) {
    double length = 0.0;
    for (int k = 0; k < 3; ++k) {
      length += (section.head[k] - section.tail[k]) * (section.head[k] - section.tail[k]);
    }
    if (length == 0.0) {
      throw plane.error("XCH",
                        "the head of the normal (XCH YCH ZCH) equals its tail (XCT YCT ZCT)");
    }
  }
  add_cross_section(block, cursor, context, plane, "PSID", section);
}

// A cross section given by sets (LS-DYNA manual, *DATABASE_CROSS_SECTION_SET): [CSID HEADING]
// with _ID; NSID HSID BSID SSID TSID DSID ID ITYPE.
void database_cross_section_set(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  model::CrossSection section;
  section.from_sets = true;
  int n = 0;
  read_cross_section_id(block, context, cursor, n, section);
  const Card card = cursor.next(++n, kEightByTen, "NSID HSID BSID SSID");
  section.where = card.location();
  section.node_set = card.id(0, "NSID");
  section.solid_set = card.id(1, "HSID");
  section.beam_set = card.id(2, "BSID");
  section.shell_set = card.id(3, "SSID");
  if (section.node_set <= 0) throw card.error("NSID", "a node set is required");
  if (section.solid_set < 0 || section.beam_set < 0 || section.shell_set < 0) {
    throw card.error("HSID", "set IDs must not be negative");
  }
  if (section.solid_set == 0 && section.beam_set == 0 && section.shell_set == 0) {
    throw card.error("HSID", "give at least one element set (HSID, BSID or SSID)");
  }
  if (card.id(4, "TSID") != 0) throw card.error("TSID", "thick shells are not supported");
  if (card.id(5, "DSID") != 0) throw card.error("DSID", "discrete elements are not supported");
  refuse_local_axes(card, 6);
  card.integer(7, "ITYPE", 0);
  add_cross_section(block, cursor, context, card, "NSID", section);
}

namespace {

// A parameter name field: a type letter (R, I or C) then the name, with or without blanks
// between them ("R rho", "Rrho").
std::pair<char, std::string> split_parameter_name(const Card& card, std::string_view field,
                                                  const char* name) {
  if (field.size() < 2) {
    throw card.error(name, fmt::format("'{}' is not a type letter (R, I or C) followed by a "
                                       "name",
                                       field));
  }
  const char type = static_cast<char>(std::toupper(static_cast<unsigned char>(field[0])));
  if (type != 'R' && type != 'I' && type != 'C') {
    throw card.error(name, fmt::format("type letter '{}' is not R, I or C", field[0]));
  }
  const std::string parameter(trim(field.substr(1)));
  if (parameter.empty()) throw card.error(name, "the parameter name is missing");
  for (char c : parameter) {
    const auto u = static_cast<unsigned char>(c);
    if (u <= 32 || u >= 127 || c == '&' || c == ',') {
      throw card.error(name, "the parameter name contains a blank or non-printable character");
    }
  }
  return {type, parameter};
}

// A parameter defined again: *PARAMETER_DUPLICATION DFLAG decides (LS-DYNA's default 1 keeps
// the first definition with a warning). Returns whether the new definition replaces the old.
bool accept_redefinition(const Card& card, const char* field, const std::string& name,
                         ReaderContext& context) {
  if (!context.parameters.contains(name)) return true;
  const int dflag = context.parameter_duplication;
  const std::string where = fmt::format("parameter {} is defined again", name);
  switch (dflag) {
    case 2:
      context.warn(card.location(), where +
                                        "; the new definition replaces the first "
                                        "(*PARAMETER_DUPLICATION DFLAG 2)");
      return true;
    case 3:
      context.report(kCardErrors, card.error(field, where + " (*PARAMETER_DUPLICATION DFLAG 3 "
                                                            "makes this an error)"));
      return false;
    case 4:
      return true;
    case 5:
      return false;
    default:
      context.warn(card.location(), where +
                                        "; the first definition is kept (LS-DYNA's rule; "
                                        "*PARAMETER_DUPLICATION DFLAG 2 or 4 keeps the new "
                                        "one)");
      return false;
  }
}

}  // namespace

void parameter_duplication(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const Card card = cursor.next(1, kEightByTen, "DFLAG");
  const int dflag = card.flag(0, "DFLAG", 1);
  if (dflag < 1 || dflag > 5) {
    throw card.error("DFLAG", fmt::format("value {} is not 1, 2, 3, 4 or 5", dflag));
  }
  context.parameter_duplication = dflag;
}

void parameter(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  static const char* const kNames[] = {"PRMR1", "PRMR2", "PRMR3", "PRMR4"};
  static const char* const kValues[] = {"VAL1", "VAL2", "VAL3", "VAL4"};
  int n = 0;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(++n, kEightByTen, "PRMR1 VAL1");
    for (std::size_t pair = 0; pair < 4; ++pair) {
      const std::string_view name_field = card.text(2 * pair);
      if (name_field.empty()) continue;
      const auto [type, name] = split_parameter_name(card, name_field, kNames[pair]);
      if (!accept_redefinition(card, kNames[pair], name, context)) continue;
      if (type == 'C') {
        context.parameters.define_text(name, std::string(card.text(2 * pair + 1)));
        continue;
      }
      double value = type == 'I' ? static_cast<double>(card.integer(2 * pair + 1, kValues[pair], 0))
                                 : card.real(2 * pair + 1, kValues[pair], 0.0);
      context.parameters.define(name, value);
    }
  }
}

void parameter_expression(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 0;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    // The expression may itself contain commas (min(a,b)), so free format splits only at
    // the first comma; fixed format has the name in columns 1-10 and the rest after it.
    const Card card = cursor.next(++n, Layout{10}, "PRMR EXPRESSION");
    const DataLine& line = block.lines[block.lines.size() - cursor.remaining() - 1];
    std::string_view name_field, expression;
    if (const auto comma = line.text.find(','); comma != std::string_view::npos) {
      name_field = trim(line.text.substr(0, comma));
      expression = trim(line.text.substr(comma + 1));
    } else {
      name_field = trim(line.text.substr(0, std::min<std::size_t>(10, line.text.size())));
      expression = line.text.size() > 10 ? trim(line.text.substr(10)) : std::string_view{};
    }
    const auto [type, name] = split_parameter_name(card, name_field, "PRMR");
    if (type == 'C') throw card.error("PRMR", "text (C) parameters cannot be expressions");
    if (expression.empty()) throw card.error("EXPRESSION", "the expression is missing");
    double value = 0.0;
    try {
      value = context.parameters.evaluate(std::string(expression));
    } catch (const std::runtime_error& e) {
      throw card.error("EXPRESSION", fmt::format("cannot evaluate '{}': {}",
                                                 std::string(expression.substr(0, 80)), e.what()));
    }
    if (type == 'I') value = std::trunc(value);
    if (!accept_redefinition(card, "PRMR", name, context)) continue;
    context.parameters.define(name, value);
  }
}

void title(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const std::string text = cursor.next_text(1, "TITLE", false);
  if (context.model.title.empty()) context.model.title = text;
}

void include(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 0;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(++n, Layout{80}, "FILENAME");
    const DataLine& line = block.lines[block.lines.size() - cursor.remaining() - 1];
    context.include(std::string(trim(line.text)), card);
  }
  if (n == 0) throw block_error(block, 1, "FILENAME", "the file name card is missing");
}

// *INCLUDE_PATH and *INCLUDE_PATH_RELATIVE: folders searched for included files after the
// including file's folder and the main deck's (relative folders are taken from the main deck's).
void include_path(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 0;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const std::string folder = cursor.next_text(++n, "PATH");
    context.include_paths.push_back(folder);
  }
  if (n == 0) throw block_error(block, 1, "PATH", "the folder card is missing");
}

void ignore(const Block&, ReaderContext&) {}

}  // namespace rf::io::handlers
