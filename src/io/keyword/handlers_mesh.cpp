// Mesh, parts, sections, materials and sets.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "io/keyword/definition_ids.hpp"
#include "io/keyword/handlers.hpp"
#include "io/keyword/number.hpp"
#include "material/hyperelastic_setup.hpp"

namespace rf::io::handlers {

namespace {

const Layout kEightByTen = uniform_layout(8, 10);

// Reads the title card of a _TITLE option, if present.
std::string read_title(const Block& block, CardCursor& cursor) {
  if (!block.has_option("TITLE")) return {};
  return cursor.next_text(1, "title");
}

bool only_blank_lines_left(const CardCursor& cursor, const Block& block) {
  for (std::size_t i = block.lines.size() - cursor.remaining(); i < block.lines.size(); ++i) {
    if (!trim(block.lines[i].text).empty()) return false;
  }
  return true;
}

}  // namespace

void node(const Block& block, ReaderContext& context) {
  static const Layout layout{8, 16, 16, 16, 8, 8};
  CardCursor cursor(block, context.parameters);
  auto& nodes = context.model.nodes;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(1, layout, "NID X Y Z TC RC");
    model::Node n;
    n.id = positive_id(card, 0, "NID", "node");
    n.x = {card.real(1, "X", 0.0), card.real(2, "Y", 0.0), card.real(3, "Z", 0.0)};
    n.tc = card.flag(4, "TC", 0);
    n.rc = card.flag(5, "RC", 0);
    if (n.tc < 0 || n.tc > 7) throw card.error("TC", fmt::format("value {} is not 0..7", n.tc));
    if (n.rc < 0 || n.rc > 7) throw card.error("RC", fmt::format("value {} is not 0..7", n.rc));
    const auto [it, inserted] = context.node_origin.try_emplace(
        n.id, std::pair{context.current_file_index, card.line_number()});
    if (!inserted) {
      throw card.error("NID", fmt::format("node {} is already defined at {}", n.id,
                                          context.origin_text(it->second)));
    }
    nodes.push_back(n);
  }
}

void element_solid(const Block& block, ReaderContext& context) {
  static const Layout layout = uniform_layout(10, 8);
  static const char* const kNodeFields[] = {"N1", "N2", "N3", "N4", "N5",
                                            "N6", "N7", "N8", "N9", "N10"};
  const bool convert = block.has_option("TET4TOTET10");
  CardCursor cursor(block, context.parameters);
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card first = cursor.next(1, layout, "EID PID N1..N8");
    model::SolidElement e;
    e.id = positive_id(first, 0, "EID", "element");
    e.pid = first.id(1, "PID");
    e.where = first.location();
    // The current manual puts EID PID on card 1 and the nodes on card 2; older decks put
    // all ten fields on one line. A card 1 with nothing after PID means the two-card form.
    bool nodes_on_first = false;
    for (std::size_t i = 2; i < first.field_count(); ++i) nodes_on_first |= !first.blank(i);
    std::optional<Card> second;
    if (!nodes_on_first) second.emplace(cursor.next(2, layout, "N1..N8"));
    const Card& nodes = second ? *second : first;
    const std::size_t offset = second ? 0 : 2;
    const bool ten_node =
        second && (nodes.id(8, kNodeFields[8]) != 0 || nodes.id(9, kNodeFields[9]) != 0);
    // Four nodes and N5..N8 blank: a tetrahedron written without repeated nodes, stored as
    // LS-DYNA's degenerate hexahedron N1 N2 N3 N4 N4 N4 N4 N4.
    bool tetrahedron = true;
    for (std::size_t k = 4; k < 8; ++k) tetrahedron &= nodes.id(offset + k, kNodeFields[k]) == 0;
    for (std::size_t k = 0; k < 8 && !ten_node; ++k) {
      e.nodes[k] = tetrahedron && k >= 4 ? e.nodes[3] : nodes.id(offset + k, kNodeFields[k]);
      if (e.nodes[k] <= 0) {
        throw nodes.error(kNodeFields[k],
                          "a solid needs 8 positive node IDs (repeat node IDs for wedges and "
                          "pyramids), or 4 with N5..N8 blank for a tetrahedron");
      }
    }
    if (second) {
      // N9 or N10 given: LS-DYNA's 10-node tetrahedron (*SECTION_SOLID ELFORM 16), corners
      // N1..N4, mid-side nodes N5 (edge 1-2), N6 (2-3), N7 (3-1), N8 (1-4), N9 (2-4), N10 (3-4).
      // Whether the part's section is ELFORM 16 is checked when the state is built (the section
      // may come later in the deck).
      if (nodes.id(8, kNodeFields[8]) != 0 || nodes.id(9, kNodeFields[9]) != 0) {
        for (std::size_t k = 0; k < 10; ++k) {
          if (nodes.id(k, kNodeFields[k]) <= 0) {
            throw nodes.error(kNodeFields[k],
                              "a 10-node tetrahedron needs 10 positive node IDs: corners N1..N4, "
                              "then the mid-side nodes of edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4");
          }
        }
        for (std::size_t k = 0; k < 8; ++k) e.nodes[k] = nodes.id(k < 4 ? k : 3, kNodeFields[k]);
        for (std::size_t k = 0; k < 6; ++k) e.midside[k] = nodes.id(4 + k, kNodeFields[4 + k]);
        e.ten_node = true;
        for (std::size_t a = 0; a < 10; ++a)
          for (std::size_t b = 0; b < a; ++b)
            if (nodes.id(a, kNodeFields[a]) == nodes.id(b, kNodeFields[b]))
              throw nodes.error(
                  kNodeFields[a],
                  fmt::format("node {} appears twice ({} and {}) in a 10-node "
                              "tetrahedron, whose 10 nodes must be distinct",
                              nodes.id(a, kNodeFields[a]), kNodeFields[b], kNodeFields[a]));
      }
      e.where.line = first.line_number();
    }
    if (convert) {
      // *ELEMENT_SOLID_TET4TOTET10: a 4-node tetrahedron that LS-DYNA raises to 10 nodes; the
      // mid-side nodes are created when the state is built (solver/build_state.cpp), midside
      // all 0 says so.
      if (e.ten_node) {
        throw nodes.error("N9",
                          "*ELEMENT_SOLID_TET4TOTET10 takes 4-node tetrahedra (N1..N4, "
                          "N5..N8 blank or equal to N4), not 10-node ones");
      }
      std::array<model::Id, 8> sorted = e.nodes;
      std::sort(sorted.begin(), sorted.end());
      const auto distinct = std::unique(sorted.begin(), sorted.end()) - sorted.begin();
      if (distinct != 4 || e.nodes[4] != e.nodes[3] || e.nodes[7] != e.nodes[3]) {
        throw nodes.error("N5", fmt::format("*ELEMENT_SOLID_TET4TOTET10 element {} is not a "
                                            "4-node tetrahedron N1 N2 N3 N4 (N5..N8 blank or "
                                            "N4): it has {} distinct nodes",
                                            e.id, distinct));
      }
      e.ten_node = true;
    }
    const auto [it, inserted] = context.element_origin.try_emplace(
        e.id, std::pair{context.current_file_index, first.line_number()});
    if (!inserted) {
      throw first.error("EID", fmt::format("element {} is already defined at {}", e.id,
                                           context.origin_text(it->second)));
    }
    context.model.solids.push_back(e);
  }
}

// *ELEMENT_SHELL(_THICKNESS/_BETA/_MCID): EID PID N1..N4 (N5..N8 blank: 4-node shells only);
// the options add a card with THIC1..THIC4 and BETA/MCID (angles matter only to anisotropic
// materials, which shells do not run yet: read and not used).
void element_shell(const Block& block, ReaderContext& context) {
  static const Layout layout = uniform_layout(10, 8);
  static const Layout thickness_layout{16, 16, 16, 16, 16};
  static const char* const kNodeFields[] = {"N1", "N2", "N3", "N4", "N5", "N6", "N7", "N8"};
  const bool thickness_card =
      block.has_option("THICKNESS") || block.has_option("BETA") || block.has_option("MCID");
  if (block.has_option("OFFSET")) {
    throw block_error(block, 1, "OFFSET",
                      "*ELEMENT_SHELL_OFFSET (shells offset from their nodes) is not supported");
  }
  CardCursor cursor(block, context.parameters);
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(1, layout, "EID PID N1 N2 N3 N4");
    model::ShellElement e;
    e.id = positive_id(card, 0, "EID", "element");
    e.pid = card.id(1, "PID");
    e.where = card.location();
    for (std::size_t k = 0; k < 4; ++k) {
      e.nodes[k] = card.id(2 + k, kNodeFields[k]);
      if (k == 3 && e.nodes[k] == 0) e.nodes[k] = e.nodes[2];  // three nodes: a triangle
      if (e.nodes[k] <= 0) {
        throw card.error(kNodeFields[k],
                         "a shell needs 4 positive node IDs (N3 = N4 or N4 "
                         "blank for a triangle)");
      }
    }
    for (std::size_t k = 4; k < 8; ++k) {
      if (card.id(2 + k, kNodeFields[k]) != 0) {
        throw card.error(kNodeFields[k], "8-node (quadratic) shells are not supported");
      }
    }
    if (e.nodes[0] == e.nodes[1] || e.nodes[1] == e.nodes[2] || e.nodes[0] == e.nodes[2] ||
        e.nodes[0] == e.nodes[3]) {
      throw card.error("N1",
                       "a shell repeats a node other than N3 = N4 (the only degenerate "
                       "form is the triangle N1 N2 N3 N3)");
    }
    if (thickness_card) {
      const Card t = cursor.next(2, thickness_layout, "THIC1 THIC2 THIC3 THIC4 BETA");
      static const char* const kThick[] = {"THIC1", "THIC2", "THIC3", "THIC4"};
      for (std::size_t k = 0; k < 4; ++k) {
        e.thickness[k] = t.real(k, kThick[k], 0.0);
        if (e.thickness[k] < 0.0) throw t.error(kThick[k], "a thickness must not be negative");
      }
      // Blank THIC2..4 take THIC1 (as LS-DYNA does for the section's T2..T4).
      for (std::size_t k = 1; k < 4; ++k) {
        if (e.thickness[k] == 0.0) e.thickness[k] = e.thickness[0];
      }
    }
    const auto [it, inserted] = context.element_origin.try_emplace(
        e.id, std::pair{context.current_file_index, card.line_number()});
    if (!inserted) {
      throw card.error("EID", fmt::format("element {} is already defined at {}", e.id,
                                          context.origin_text(it->second)));
    }
    context.model.shells.push_back(e);
  }
}

// *ELEMENT_BEAM(_ORIENTATION): EID PID N1 N2 N3 RT1 RR1 RT2 RR2 LOCAL; the option adds VX VY VZ.
void element_beam(const Block& block, ReaderContext& context) {
  static const Layout layout = uniform_layout(10, 8);
  static const Layout vector_layout{16, 16, 16};
  CardCursor cursor(block, context.parameters);
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(1, layout, "EID PID N1 N2 N3 RT1 RR1 RT2 RR2 LOCAL");
    model::BeamElement e;
    e.id = positive_id(card, 0, "EID", "element");
    e.pid = card.id(1, "PID");
    e.where = card.location();
    e.nodes = {card.id(2, "N1"), card.id(3, "N2"), card.id(4, "N3")};
    if (e.nodes[0] <= 0) throw card.error("N1", "a beam needs positive node IDs N1 and N2");
    if (e.nodes[1] <= 0) throw card.error("N2", "a beam needs positive node IDs N1 and N2");
    if (e.nodes[0] == e.nodes[1]) throw card.error("N2", "N2 repeats N1: the beam has no length");
    if (e.nodes[2] < 0) throw card.error("N3", "the orientation node must be positive or blank");
    static const char* const kReleases[] = {"RT1", "RR1", "RT2", "RR2"};
    for (std::size_t k = 0; k < 4; ++k) {
      if (card.flag(5 + k, kReleases[k], 0) != 0) {
        throw card.error(kReleases[k], "beam end releases are not supported (leave blank or 0)");
      }
    }
    const int local = card.flag(9, "LOCAL", 2);
    if (local != 0 && local != 2) {
      throw card.error("LOCAL", "releases in the global system (LOCAL 1) are not supported");
    }
    if (block.has_option("ORIENTATION")) {
      const Card v = cursor.next(2, vector_layout, "VX VY VZ");
      e.orientation =
          std::array<double, 3>{v.real(0, "VX", 0.0), v.real(1, "VY", 0.0), v.real(2, "VZ", 0.0)};
    }
    const auto [it, inserted] = context.element_origin.try_emplace(
        e.id, std::pair{context.current_file_index, card.line_number()});
    if (!inserted) {
      throw card.error("EID", fmt::format("element {} is already defined at {}", e.id,
                                          context.origin_text(it->second)));
    }
    context.model.beams.push_back(e);
  }
}

// *ELEMENT_DISCRETE: EID PID N1 N2 VID S PF OFFSET (I8 x5, E16, I8, E16 in standard format).
// Only VID 0 (the force acts along the current N1 -> N2 line) is supported; PF only concerns
// LS-DYNA's own print file and is read and ignored.
void element_discrete(const Block& block, ReaderContext& context) {
  static const Layout layout{8, 8, 8, 8, 8, 16, 8, 16};
  CardCursor cursor(block, context.parameters);
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(1, layout, "EID PID N1 N2 VID S PF OFFSET");
    model::DiscreteElement e;
    e.id = positive_id(card, 0, "EID", "element");
    e.pid = card.id(1, "PID");
    if (e.pid <= 0) throw card.error("PID", "a discrete element needs a positive part ID");
    e.where = card.location();
    e.nodes = {card.id(2, "N1"), card.id(3, "N2")};
    if (e.nodes[0] <= 0) throw card.error("N1", "a discrete element needs positive node IDs");
    if (e.nodes[1] <= 0) throw card.error("N2", "a discrete element needs positive node IDs");
    if (e.nodes[0] == e.nodes[1]) {
      throw card.error("N2", "N2 repeats N1: a spring or damper needs two different nodes");
    }
    if (card.id(4, "VID") != 0) {
      throw card.error("VID",
                       "orientation vectors (*DEFINE_SD_ORIENTATION) are not supported: "
                       "leave VID blank or 0 (the force acts along N1 -> N2)");
    }
    e.scale = card.real(5, "S", 1.0);
    if (!std::isfinite(e.scale)) throw card.error("S", "the scale factor must be finite");
    card.integer(6, "PF", 0);  // print flag: output selection of LS-DYNA's deforc only
    e.offset = card.real(7, "OFFSET", 0.0);
    const auto [it, inserted] = context.element_origin.try_emplace(
        e.id, std::pair{context.current_file_index, card.line_number()});
    if (!inserted) {
      throw card.error("EID", fmt::format("element {} is already defined at {}", e.id,
                                          context.origin_text(it->second)));
    }
    context.model.discretes.push_back(e);
  }
}

// *SECTION_DISCRETE: SECID DRO KD V0 CL FD, then (optional) CDL TDL. Only the translational
// spring/damper (DRO 0) without clearance, failure, deflection limits or dynamic magnification.
void section_discrete(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  do {
    read_title(block, cursor);
    const int first = block.has_option("TITLE") ? 2 : 1;
    const Card card = cursor.next(first, kEightByTen, "SECID DRO KD V0 CL FD");
    model::SectionDiscrete s;
    s.id = positive_id(card, 0, "SECID", "section");
    const int dro = card.flag(1, "DRO", 0);
    if (dro == 1) {
      throw card.error("DRO",
                       "torsional springs and dampers (DRO 1) are not supported yet "
                       "(supported: DRO 0, translational)");
    }
    if (dro != 0) throw card.error("DRO", fmt::format("value {} is not 0 or 1", dro));
    static const char* const kRefused[] = {"KD", "V0", "CL", "FD"};
    for (std::size_t k = 0; k < 4; ++k) {
      if (card.real(2 + k, kRefused[k], 0.0) != 0.0) {
        throw card.error(kRefused[k],
                         "dynamic magnification, clearance and failure deflection are not "
                         "supported (leave KD, V0, CL and FD blank or 0)");
      }
    }
    // The second card (CDL TDL) is optional in practice; a blank or zero limit means none.
    if (cursor.remaining() > 0 && !only_blank_lines_left(cursor, block)) {
      // A second card follows unless the next line starts another section (a SECID): the
      // second card has only two fields, so a line with more than two is a new first card.
      const std::optional<Card> limits = cursor.next_optional(first + 1, kEightByTen);
      if (limits) {
        if (!limits->blank(2)) {
          throw limits->error("CDL",
                              "expected the second card (CDL TDL), found a line with "
                              "more than two fields");
        }
        static const char* const kLimits[] = {"CDL", "TDL"};
        for (std::size_t k = 0; k < 2; ++k) {
          if (limits->real(k, kLimits[k], 0.0) != 0.0) {
            throw limits->error(kLimits[k],
                                "deflection limits (CDL, TDL) are not supported "
                                "(leave blank or 0)");
          }
        }
      }
    }
    s.where = card.location();
    check_unique(context.model.discrete_sections, s.id, card, "SECID", "section");
    context.model.discrete_sections.emplace(s.id, std::move(s));
  } while (!only_blank_lines_left(cursor, block));
}

void part(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int card_number = 1;
  do {
    const std::string heading = cursor.next_text(card_number, "HEADING");
    const Card card =
        cursor.next(card_number + 1, kEightByTen, "PID SECID MID EOSID HGID GRAV ADPOPT TMID");
    model::Part p;
    p.id = positive_id(card, 0, "PID", "part");
    p.title = heading;
    p.secid = card.id(1, "SECID");
    p.mid = card.id(2, "MID");
    p.eosid = card.id(3, "EOSID");
    p.hgid = card.id(4, "HGID");
    p.where = card.location();
    if (p.eosid < 0) throw card.error("EOSID", "equation of state ID must not be negative");
    card_number += 2;
    if (block.has_option("INERTIA")) {
      int cards = 0;
      p.inertia = read_rigid_inertia(cursor, card_number, cards);
      card_number += cards;
    }
    check_unique(context.model.parts, p.id, card, "PID", "part");
    context.model.parts.emplace(p.id, std::move(p));
  } while (!only_blank_lines_left(cursor, block));
}

void section_solid(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  do {
    read_title(block, cursor);
    const int card_number = block.has_option("TITLE") ? 2 : 1;
    const Card card = cursor.next(card_number, kEightByTen, "SECID ELFORM AET");
    model::SectionSolid s;
    s.id = positive_id(card, 0, "SECID", "section");
    s.elform = card.flag(1, "ELFORM", 1);
    if (s.elform == 0) s.elform = 1;  // LS-DYNA: 0 means the default formulation 1
    if (s.elform == 17) {
      throw card.error("ELFORM",
                       "tetrahedron formulation 17 (the 10-node composite tetrahedron) "
                       "is not supported (supported: 10, the one-point 4-node "
                       "tetrahedron; 13, the nodal-pressure tetrahedron; 16, the "
                       "10-node quadratic tetrahedron)");
    }
    if (s.elform != 1 && s.elform != 2 && s.elform != 10 && s.elform != 13 && s.elform != 16) {
      throw card.error(
          "ELFORM",
          fmt::format("value {} is not supported (supported: 1, 2, 10, 13, 16)", s.elform));
    }
    s.where = card.location();
    check_unique(context.model.solid_sections, s.id, card, "SECID", "section");
    context.model.solid_sections.emplace(s.id, std::move(s));
  } while (!only_blank_lines_left(cursor, block));
}

// *SECTION_SHELL: SECID ELFORM SHRF NIP PROPT QR/IRID ICOMP SETYP, then T1..T4 NLOC MAREA
// IDOF EDGSET. Values that would change the physics and are not supported are errors.
void section_shell(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  do {
    read_title(block, cursor);
    const int first = block.has_option("TITLE") ? 2 : 1;
    const Card card =
        cursor.next(first, kEightByTen, "SECID ELFORM SHRF NIP PROPT QR/IRID ICOMP SETYP");
    model::SectionShell s;
    s.id = positive_id(card, 0, "SECID", "section");
    s.elform = card.flag(1, "ELFORM", 0);  // 0: *CONTROL_SHELL THEORY (resolved when built)
    if (s.elform != 0 && s.elform != 2 && s.elform != 16) {
      throw card.error("ELFORM", fmt::format("shell formulation {} is not supported (supported: "
                                             "2, Belytschko-Lin-Tsay; 16, fully integrated)",
                                             s.elform));
    }
    s.shrf = card.real(2, "SHRF", 1.0);
    if (s.shrf == 0.0) s.shrf = 1.0;
    if (s.shrf < 0.0) throw card.error("SHRF", "the shear factor must be positive");
    s.nip = card.flag(3, "NIP", 2);
    if (s.nip == 0) s.nip = 2;
    if (s.nip < 1 || s.nip > 10) {
      throw card.error("NIP", fmt::format("{} points through the thickness: supported 1..10 "
                                          "(user rules are not supported)",
                                          s.nip));
    }
    const double propt = card.real(4, "PROPT", 1.0);
    if (propt != 0.0 && propt != 1.0 && propt != 2.0 && propt != 3.0) {
      throw card.error("PROPT", "printout option must be 1, 2 or 3");
    }
    const double qr = card.real(5, "QR/IRID", 0.0);
    if (qr != 0.0) {
      throw card.error("QR/IRID", fmt::format("quadrature rule {} is not supported (0: Gauss, or "
                                              "Lobatto through *CONTROL_SHELL INTGRD 1)",
                                              qr));
    }
    s.quadrature = 0;
    if (card.flag(6, "ICOMP", 0) != 0) {
      throw card.error("ICOMP", "composite layups (ICOMP 1) are not supported");
    }
    const int setyp = card.flag(7, "SETYP", 1);
    if (setyp != 0 && setyp != 1) {
      throw card.error("SETYP", "only 2D shells (SETYP 1) are supported");
    }
    const Card t = cursor.next(first + 1, kEightByTen, "T1 T2 T3 T4 NLOC MAREA IDOF EDGSET");
    static const char* const kT[] = {"T1", "T2", "T3", "T4"};
    for (std::size_t k = 0; k < 4; ++k) s.t[k] = t.real(k, kT[k], 0.0);
    if (!(s.t[0] > 0.0)) {
      throw t.error("T1", fmt::format("the shell thickness must be positive (got {})", s.t[0]));
    }
    for (std::size_t k = 1; k < 4; ++k) {
      if (s.t[k] < 0.0) throw t.error(kT[k], "a thickness must not be negative");
      if (s.t[k] == 0.0) s.t[k] = s.t[0];
    }
    s.nloc = t.real(4, "NLOC", 0.0);
    if (s.nloc != 0.0) {
      throw t.error("NLOC", "only the mid-surface as reference surface (NLOC 0) is supported");
    }
    if (t.real(5, "MAREA", 0.0) != 0.0) {
      throw t.error("MAREA", "non-structural mass per area (MAREA) is not supported");
    }
    if (t.real(6, "IDOF", 0.0) != 0.0) throw t.error("IDOF", "IDOF is not supported");
    if (t.id(7, "EDGSET") != 0) throw t.error("EDGSET", "EDGSET is not supported");
    s.where = card.location();
    check_unique(context.model.shell_sections, s.id, card, "SECID", "section");
    context.model.shell_sections.emplace(s.id, std::move(s));
  } while (!only_blank_lines_left(cursor, block));
}

// *SECTION_BEAM: SECID ELFORM SHRF QR/IRID CST SCOOR NSM, then the card of the formulation:
// ELFORM 1 TS1 TS2 TT1 TT2 NSLOC NTLOC; ELFORM 2 A ISS ITT J SA IST; ELFORM 3 A RAMPT STRESS.
void section_beam(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  do {
    read_title(block, cursor);
    const int first = block.has_option("TITLE") ? 2 : 1;
    const Card card = cursor.next(first, kEightByTen, "SECID ELFORM SHRF QR/IRID CST SCOOR NSM");
    model::SectionBeam s;
    s.id = positive_id(card, 0, "SECID", "section");
    s.elform = card.flag(1, "ELFORM", 1);
    if (s.elform == 0) s.elform = 1;
    if (s.elform < 1 || s.elform > 3) {
      throw card.error("ELFORM", fmt::format("beam formulation {} is not supported (supported: 1 "
                                             "Hughes-Liu, 2 Belytschko-Schwer, 3 truss)",
                                             s.elform));
    }
    s.shrf = card.real(2, "SHRF", 1.0);
    if (s.shrf == 0.0) s.shrf = 1.0;
    const double qr = card.real(3, "QR/IRID", 2.0);
    if (s.elform == 1 && qr != 2.0 && qr != 0.0) {
      throw card.error("QR/IRID", fmt::format("cross-section rule {} is not supported (2: 2x2 "
                                              "Gauss)",
                                              qr));
    }
    s.cst = static_cast<int>(card.real(4, "CST", 0.0));
    if (s.cst != 0 && s.cst != 1) {
      throw card.error("CST", "cross section type must be 0 (rectangular) or 1 (tubular)");
    }
    if (card.real(5, "SCOOR", 0.0) != 0.0) throw card.error("SCOOR", "SCOOR is not supported");
    if (card.real(6, "NSM", 0.0) != 0.0) {
      throw card.error("NSM", "non-structural mass per length (NSM) is not supported");
    }
    const Card c2 = cursor.next(first + 1, kEightByTen, "the formulation's section card");
    auto positive = [&](std::size_t i, const char* name) {
      const double v = c2.real(i, name, 0.0);
      if (!(v > 0.0)) throw c2.error(name, fmt::format("must be positive (got {})", v));
      return v;
    };
    if (s.elform == 1) {
      s.ts1 = positive(0, "TS1");
      s.ts2 = c2.real(1, "TS2", 0.0);
      if (s.ts2 == 0.0) s.ts2 = s.ts1;
      s.tt1 = c2.real(2, "TT1", 0.0);
      s.tt2 = c2.real(3, "TT2", 0.0);
      if (s.cst == 0) {
        if (!(s.tt1 > 0.0)) throw c2.error("TT1", "a rectangular section needs TT1 > 0");
        if (s.tt2 == 0.0) s.tt2 = s.tt1;
      }
      if (s.tt1 < 0.0 || s.tt2 < 0.0 || s.ts2 < 0.0) {
        throw c2.error("TT1", "section dimensions must not be negative");
      }
      if (s.cst == 1 && (s.tt1 >= s.ts1 || s.tt2 >= s.ts2)) {
        throw c2.error("TT1", "a tube's inner diameter must be smaller than its outer one");
      }
      if (c2.real(4, "NSLOC", 0.0) != 0.0 || c2.real(5, "NTLOC", 0.0) != 0.0) {
        throw c2.error("NSLOC", "beam offsets (NSLOC, NTLOC) are not supported");
      }
    } else if (s.elform == 2) {
      s.a = positive(0, "A");
      s.iss = positive(1, "ISS");
      s.itt = positive(2, "ITT");
      s.j = c2.real(3, "J", 0.0);
      if (s.j < 0.0) throw c2.error("J", "must not be negative");
      if (s.j == 0.0) s.j = s.iss + s.itt;  // LS-DYNA: J defaults to ISS + ITT
      s.sa = c2.real(4, "SA", 0.0);
      if (s.sa < 0.0) throw c2.error("SA", "must not be negative");
    } else {
      s.a = positive(0, "A");
      if (c2.real(1, "RAMPT", 0.0) != 0.0 || c2.real(2, "STRESS", 0.0) != 0.0) {
        throw c2.error("RAMPT", "truss initial stress ramps (RAMPT, STRESS) are not supported");
      }
    }
    s.where = card.location();
    check_unique(context.model.beam_sections, s.id, card, "SECID", "section");
    context.model.beam_sections.emplace(s.id, std::move(s));
  } while (!only_blank_lines_left(cursor, block));
}

namespace {

void check_elastic_constants(const Card& card, const model::Material& m) {
  if (!(m.rho > 0.0)) {
    throw card.error("RO", fmt::format("density {} must be positive", m.rho));
  }
  if (!(m.e > 0.0)) {
    throw card.error("E", fmt::format("Young's modulus {} must be positive", m.e));
  }
  if (!(m.pr > -1.0 && m.pr < 0.5)) {
    throw card.error("PR", fmt::format("Poisson's ratio {} must lie in (-1, 0.5)", m.pr));
  }
}

// The fields every material card 1 starts with: MID RO E PR, checked as elastic constants.
model::Material material_head(const Block& block, const Card& card, model::MaterialKind kind) {
  model::Material m;
  m.id = positive_id(card, 0, "MID", "material");
  m.kind = kind;
  m.keyword = block.keyword;
  m.rho = card.real(1, "RO", 0.0);
  m.e = card.real(2, "E", 0.0);
  m.pr = card.real(3, "PR", 0.0);
  m.where = card.location();
  check_elastic_constants(card, m);
  return m;
}

void add_material(ReaderContext& context, const Card& card, model::Material m) {
  check_unique(context.model.materials, m.id, card, "MID", "material");
  context.model.materials.emplace(m.id, std::move(m));
}

}  // namespace

void mat_elastic(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  read_title(block, cursor);
  const int n = block.has_option("TITLE") ? 2 : 1;
  const Card card = cursor.next(n, kEightByTen, "MID RO E PR DA DB K");
  model::Material m = material_head(block, card, model::MaterialKind::Elastic);
  // DA and DB damp beams only; they do not change a solid's response.
  if (card.real(4, "DA", 0.0) != 0.0 || card.real(5, "DB", 0.0) != 0.0) {
    context.warn(card.location(), "DA/DB (beam damping) are ignored for solid elements");
  }
  if (card.real(6, "K", 0.0) != 0.0) {
    throw card.error("K",
                     "the bulk modulus K belongs to the fluid option, which is not "
                     "supported (leave K blank)");
  }
  add_material(context, card, std::move(m));
  warn_unread_lines(block, cursor, context);
}

void mat_rigid(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  read_title(block, cursor);
  const int n = block.has_option("TITLE") ? 2 : 1;
  const Card card = cursor.next(n, kEightByTen, "MID RO E PR N COUPLE M ALIAS");
  model::Material m = material_head(block, card, model::MaterialKind::Rigid);
  if (const auto constraints = cursor.next_optional(n + 1, kEightByTen)) {
    const RigidConstraints c = read_rigid_constraints(*constraints);
    m.cmo = c.cmo;
    m.con1 = c.con1;
    m.con2 = c.con2;
    m.cmo_cid = c.cmo_cid;
    m.cmo_local_fix = c.local_fix;
  }
  // Card 3 only orients rigid body output: LCO alone, or the body-fixed vectors A and V.
  if (const auto output = cursor.next_optional(n + 2, kEightByTen)) {
    bool vectors = false;
    for (std::size_t i = 1; i < 6; ++i) vectors |= !output->blank(i);
    if (vectors) {
      static const char* const kNames[] = {"A1", "A2", "A3", "V1", "V2", "V3"};
      m.has_output_vectors = true;
      for (std::size_t k = 0; k < 3; ++k) {
        m.output_a[k] = output->real(k, kNames[k], 0.0);
        m.output_v[k] = output->real(3 + k, kNames[3 + k], 0.0);
      }
    } else {
      m.lco = output->id(0, "LCO");
      if (m.lco < 0) throw output->error("LCO", "coordinate system ID must not be negative");
    }
  }
  add_material(context, card, std::move(m));
  warn_unread_lines(block, cursor, context);
}

// *MAT_PLASTIC_KINEMATIC (003). Card 1: MID RO E PR SIGY ETAN BETA; card 2: SRC SRP FS VP.
// Range checks that need E (ETAN < E) are made here; the curve-free law needs nothing later.
void mat_plastic_kinematic(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  read_title(block, cursor);
  const int n = block.has_option("TITLE") ? 2 : 1;
  const Card card = cursor.next(n, kEightByTen, "MID RO E PR SIGY ETAN BETA");
  model::Material m = material_head(block, card, model::MaterialKind::PlasticKinematic);
  auto& p = m.plastic;
  p.sigy = card.real(4, "SIGY", 0.0);
  p.etan = card.real(5, "ETAN", 0.0);
  p.beta = card.real(6, "BETA", 0.0);
  if (!(p.sigy > 0.0))
    throw card.error("SIGY", fmt::format("yield stress {} must be positive", p.sigy));
  if (!(p.etan >= 0.0 && p.etan < m.e))
    throw card.error("ETAN",
                     fmt::format("tangent modulus {} must lie in [0, E) with E = {}", p.etan, m.e));
  if (!(p.beta >= 0.0 && p.beta <= 1.0))
    throw card.error("BETA",
                     fmt::format("hardening parameter {} must lie in [0, 1] (0 kinematic, 1 "
                                 "isotropic)",
                                 p.beta));
  p.card2 = m.where;
  if (const auto c2 = cursor.next_optional(n + 1, kEightByTen)) {
    p.card2 = c2->location();
    p.c = c2->real(0, "SRC", 0.0);
    p.p = c2->real(1, "SRP", 0.0);
    p.fail = c2->real(2, "FS", 0.0);
    const double vp = c2->real(3, "VP", 0.0);
    if (p.c < 0.0)
      throw c2->error("SRC", fmt::format("strain rate parameter C {} must not be negative", p.c));
    if (p.p < 0.0)
      throw c2->error("SRP", fmt::format("strain rate parameter P {} must not be negative", p.p));
    if ((p.c > 0.0) != (p.p > 0.0))
      throw c2->error(p.c > 0.0 ? "SRP" : "SRC",
                      "Cowper-Symonds rate effects need both SRC and SRP (or neither)");
    if (p.fail < 0.0)
      throw c2->error("FS", fmt::format("failure strain {} must not be negative", p.fail));
    p.fail_where = c2->location();
    if (vp != 0.0 && vp != 1.0)
      throw c2->error("VP",
                      fmt::format("VP {} is not 0 (scale yield stress) or 1 (viscoplastic)", vp));
    p.vp = static_cast<int>(vp);
  }
  add_material(context, card, std::move(m));
  warn_unread_lines(block, cursor, context);
}

// *MAT_PIECEWISE_LINEAR_PLASTICITY (024). Card 1: MID RO E PR SIGY ETAN FAIL TDEL; card 2:
// C P LCSS LCSR VP; cards 3-4: EPS1-8, ES1-8. Curves (LCSS, LCSR) are resolved and checked when
// the solver state is built (material/plastic_setup.cpp): they may come later in the deck.
void mat_piecewise_linear_plasticity(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  read_title(block, cursor);
  const int n = block.has_option("TITLE") ? 2 : 1;
  const Card card = cursor.next(n, kEightByTen, "MID RO E PR SIGY ETAN FAIL TDEL");
  model::Material m = material_head(block, card, model::MaterialKind::PiecewiseLinearPlasticity);
  auto& p = m.plastic;
  p.sigy = card.real(4, "SIGY", 0.0);
  p.etan = card.real(5, "ETAN", 0.0);
  p.fail = card.real(6, "FAIL", 0.0);
  if (p.fail >= 1.0e20) p.fail = 0.0;  // LS-DYNA's default 10^20: no failure
  if (p.sigy < 0.0)
    throw card.error("SIGY", fmt::format("yield stress {} must not be negative", p.sigy));
  if (!(p.etan >= 0.0 && p.etan < m.e))
    throw card.error("ETAN",
                     fmt::format("tangent modulus {} must lie in [0, E) with E = {}", p.etan, m.e));
  if (p.fail < 0.0)
    throw card.error("FAIL",
                     "a negative FAIL calls a user failure subroutine, which is not supported");
  p.tdel = card.real(7, "TDEL", 0.0);
  if (!(p.tdel >= 0.0) || !std::isfinite(p.tdel))
    throw card.error("TDEL", fmt::format("minimum time step for element deletion {} must be a "
                                         "non-negative number",
                                         p.tdel));
  p.fail_where = card.location();
  p.card2 = p.card3 = m.where;
  if (const auto c2 = cursor.next_optional(n + 1, kEightByTen)) {
    p.card2 = c2->location();
    p.c = c2->real(0, "C", 0.0);
    p.p = c2->real(1, "P", 0.0);
    p.lcss = c2->id(2, "LCSS");
    p.lcsr = c2->id(3, "LCSR");
    const double vp = c2->real(4, "VP", 0.0);
    if (p.c < 0.0)
      throw c2->error("C", fmt::format("strain rate parameter {} must not be negative", p.c));
    if (p.p < 0.0)
      throw c2->error("P", fmt::format("strain rate parameter {} must not be negative", p.p));
    if (p.lcss < 0) throw c2->error("LCSS", "curve ID must not be negative");
    if (p.lcsr < 0) throw c2->error("LCSR", "curve ID must not be negative");
    if (vp == 3.0)
      throw c2->error("VP", "VP 3 (filtered rates) exists for shells only; solids take -1, 0 or 1");
    if (vp != 0.0 && vp != 1.0 && vp != -1.0)
      throw c2->error(
          "VP", fmt::format("VP {} is not -1, 0 (scale yield stress) or 1 (viscoplastic)", vp));
    p.vp = static_cast<int>(vp);
  }
  if (const auto c3 = cursor.next_optional(n + 2, kEightByTen)) {
    p.card3 = c3->location();
    const auto c4 = cursor.next_optional(n + 3, kEightByTen);
    static const char* const kEps[] = {"EPS1", "EPS2", "EPS3", "EPS4",
                                       "EPS5", "EPS6", "EPS7", "EPS8"};
    static const char* const kEs[] = {"ES1", "ES2", "ES3", "ES4", "ES5", "ES6", "ES7", "ES8"};
    for (std::size_t i = 0; i < 8; ++i) {
      p.eps.push_back(c3->real(i, kEps[i], 0.0));
      p.es.push_back(c4 ? c4->real(i, kEs[i], 0.0) : 0.0);
    }
  }
  add_material(context, card, std::move(m));
  warn_unread_lines(block, cursor, context);
}

// *MAT_3-PARAMETER_BARLAT (036), shells only. Card 1: MID RO E PR HR P1 P2 ITER; card 2: M R00
// R45 R90 LCID E0 SPI P3; card 3: AOPT C P VLCID (blank) PB NLP HTB; card 4: XP YP ZP A1 A2 A3
// HTC HTD; card 5: V1 V2 V3 D1 D2 D3 BETA HTFLAG; card 6 (optional): USRFAIL LCBI LCSH. Values
// that would change the physics and are not implemented are errors naming the field.
void mat_three_parameter_barlat(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  read_title(block, cursor);
  const int n = block.has_option("TITLE") ? 2 : 1;
  const Card card = cursor.next(n, kEightByTen, "MID RO E PR HR P1 P2 ITER");
  model::Material m = material_head(block, card, model::MaterialKind::ThreeParameterBarlat);
  model::BarlatCard& b = m.barlat;
  const double hr = card.real(4, "HR", 1.0);
  if (hr != 1.0 && hr != 2.0 && hr != 3.0)
    throw card.error("HR", fmt::format("hardening rule HR {} is not supported (1 linear, 2 power "
                                       "law, 3 curve LCID)",
                                       hr));
  b.hr = static_cast<int>(hr);
  b.p1 = card.real(5, "P1", 0.0);
  b.p2 = card.real(6, "P2", 0.0);
  const double iter = card.real(7, "ITER", 0.0);
  if (iter != 0.0 && iter != 1.0)
    throw card.error("ITER", fmt::format("ITER {} is not 0 (fully iterative) or 1", iter));
  if (iter == 1.0)
    context.warn(card.location(),
                 "ITER 1 (three fixed iterations) is treated as 0: the return is always solved "
                 "to convergence");
  if (b.hr == 1) {
    if (!(b.p2 > 0.0))
      throw card.error("P2", fmt::format("HR 1 takes the yield stress in P2, which must be "
                                         "positive (got {})",
                                         b.p2));
    if (!(b.p1 >= 0.0 && b.p1 < m.e))
      throw card.error("P1", fmt::format("HR 1 takes the tangent modulus in P1, which must lie "
                                         "in [0, E) with E = {} (got {})",
                                         m.e, b.p1));
  } else if (b.hr == 2) {
    if (!(b.p1 > 0.0))
      throw card.error("P1", fmt::format("HR 2 takes the strength coefficient k in P1, which "
                                         "must be positive (got {})",
                                         b.p1));
    if (!(b.p2 > 0.0 && b.p2 < 1.0))
      throw card.error("P2", fmt::format("HR 2 takes the hardening exponent n in P2, which must "
                                         "lie in (0, 1) (got {})",
                                         b.p2));
  }

  const Card c2 = cursor.next(n + 1, kEightByTen, "M R00 R45 R90 LCID E0 SPI P3");
  b.card2 = c2.location();
  b.m = c2.real(0, "M", 0.0);
  b.r00 = c2.real(1, "R00", 0.0);
  b.r45 = c2.real(2, "R45", 0.0);
  b.r90 = c2.real(3, "R90", 0.0);
  b.lcid = c2.id(4, "LCID");
  b.e0 = c2.real(5, "E0", 0.0);
  b.spi = c2.real(6, "SPI", 0.0);
  if (b.m < 0.0)
    throw c2.error("M", fmt::format("M = {} < 0 asks for the Chaboche-Rousselier kinematic "
                                    "hardening card, which is not supported",
                                    b.m));
  if (!(b.m >= 1.0))
    throw c2.error("M", fmt::format("the exponent M of the yield function must be at least 1 "
                                    "(6 for BCC, 8 for FCC metals; got {})",
                                    b.m));
  if (b.hr == 3 && b.lcid <= 0)
    throw c2.error("LCID",
                   "HR 3 needs the hardening curve LCID (yield stress against effective "
                   "plastic strain)");
  if (b.hr == 2 && (b.e0 < 0.0 || b.spi < 0.0))
    throw c2.error(b.e0 < 0.0 ? "E0" : "SPI", "E0 and SPI must not be negative");

  const Card c3 = cursor.next(n + 2, kEightByTen, "AOPT C P VLCID UNUSED PB NLP HTB");
  b.card3 = c3.location();
  const double aopt = c3.real(0, "AOPT", 0.0);
  if (aopt != 0.0 && aopt != 2.0 && aopt != 3.0)
    throw c3.error("AOPT", fmt::format("material axes option AOPT {} is not supported (0 element "
                                       "side 1-2, 2 vector A, 3 V x normal)",
                                       aopt));
  b.aopt = static_cast<int>(aopt);
  if (c3.real(1, "C", 0.0) != 0.0 || c3.real(2, "P", 0.0) != 0.0)
    throw c3.error(c3.real(1, "C", 0.0) != 0.0 ? "C" : "P",
                   "Cowper-Symonds rate effects (C, P) are not supported for *MAT_036 (leave "
                   "them blank or 0)");
  if (c3.id(3, "VLCID") != 0)
    throw c3.error("VLCID", "the volume correction curve VLCID is not supported (leave it blank)");
  b.pb = c3.real(5, "PB", 0.0);
  if (b.pb < 0.0) throw c3.error("PB", fmt::format("PB {} must not be negative", b.pb));
  if (c3.id(6, "NLP") != 0)
    context.warn(c3.location(), "NLP (forming limit curve for output) is ignored");
  if (c3.real(7, "HTB", 0.0) != 0.0)
    throw c3.error("HTB", "heat treatment (HTB, HTC, HTD, HTFLAG) is not supported");

  if (b.pb > 0.0) {
    // The alternative: AB, CB, HB in the R fields and p = PB.
    if (!(b.r00 > 0.0 && b.r00 < 2.0))
      throw c2.error("R00", fmt::format("with PB > 0 this field is the coefficient a of the "
                                        "yield function, which must lie in (0, 2) (got {})",
                                        b.r00));
    if (!(b.r45 > 0.0))
      throw c2.error("R45", fmt::format("with PB > 0 this field is the coefficient c, which must "
                                        "be positive (got {})",
                                        b.r45));
    if (!(b.r90 > 0.0))
      throw c2.error("R90", fmt::format("with PB > 0 this field is the coefficient h, which must "
                                        "be positive (got {})",
                                        b.r90));
  } else {
    static const char* const kR[] = {"R00", "R45", "R90"};
    const double r[] = {b.r00, b.r45, b.r90};
    for (int i = 0; i < 3; ++i)
      if (!(r[i] > 0.0))
        throw c2.error(kR[i], fmt::format("the Lankford coefficient {} must be positive (got {}); "
                                          "to give the yield function's a, c, h directly set "
                                          "PB > 0 on card 3",
                                          kR[i], r[i]));
  }

  b.card4 = b.card5 = b.card3;
  if (const auto c4 = cursor.next_optional(n + 3, kEightByTen)) {
    b.card4 = c4->location();
    b.a = {c4->real(3, "A1", 0.0), c4->real(4, "A2", 0.0), c4->real(5, "A3", 0.0)};
    if (c4->id(6, "HTC") != 0 || c4->id(7, "HTD") != 0)
      throw c4->error(c4->id(6, "HTC") != 0 ? "HTC" : "HTD",
                      "heat treatment (HTB, HTC, HTD, HTFLAG) is not supported");
  }
  if (const auto c5 = cursor.next_optional(n + 4, kEightByTen)) {
    b.card5 = c5->location();
    b.v = {c5->real(0, "V1", 0.0), c5->real(1, "V2", 0.0), c5->real(2, "V3", 0.0)};
    b.beta = c5->real(6, "BETA", 0.0);
    if (c5->real(7, "HTFLAG", 0.0) != 0.0)
      throw c5->error("HTFLAG", "heat treatment (HTB, HTC, HTD, HTFLAG) is not supported");
  }
  const auto norm = [](const std::array<double, 3>& x) {
    return std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  };
  if (b.aopt == 2 && !(norm(b.a) > 0.0))
    throw located_error(b.card4, "A1", "AOPT 2 needs a nonzero vector A (A1 A2 A3 on card 4)");
  if (b.aopt == 3 && !(norm(b.v) > 0.0))
    throw located_error(b.card5, "V1", "AOPT 3 needs a nonzero vector V (V1 V2 V3 on card 5)");
  if (const auto c6 = cursor.next_optional(n + 5, kEightByTen)) {
    if (c6->real(0, "USRFAIL", 0.0) != 0.0)
      throw c6->error("USRFAIL", "user failure subroutines (USRFAIL) are not supported");
  }
  add_material(context, card, std::move(m));
  warn_unread_lines(block, cursor, context);
}

namespace {

// The rubber cards start MID RO PR (no E): E is set to the equivalent small-strain Young's
// modulus 2 G (1 + PR), which the wave speed (time step), the hourglass and contact stiffness
// use like any material's E.
model::Material rubber_head(const Block& block, const Card& card, model::MaterialKind kind) {
  model::Material m;
  m.id = positive_id(card, 0, "MID", "material");
  m.kind = kind;
  m.keyword = block.keyword;
  m.rho = card.real(1, "RO", 0.0);
  m.pr = card.real(2, "PR", 0.0);
  m.where = card.location();
  if (!(m.rho > 0.0)) throw card.error("RO", fmt::format("density {} must be positive", m.rho));
  return m;
}

void check_rubber_poisson(const Card& card, double pr) {
  if (!(pr >= 0.0 && pr < 0.5))
    throw card.error("PR", fmt::format("Poisson's ratio {} must lie in [0, 0.5) (values of 0.49 "
                                       "and above describe rubber)",
                                       pr));
}

void set_equivalent_young(model::Material& m) {
  m.e = 2.0 * material::rubber_shear_modulus(m.rubber, m.kind) * (1.0 + m.pr);
}

}  // namespace

// *MAT_MOONEY-RIVLIN_RUBBER (027). Card 1: MID RO PR A B REF; card 2: SGL SW ST LCID (the fit of
// A and B to test data, not supported).
void mat_mooney_rivlin_rubber(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  read_title(block, cursor);
  const int n = block.has_option("TITLE") ? 2 : 1;
  const Card card = cursor.next(n, kEightByTen, "MID RO PR A B REF");
  model::Material m = rubber_head(block, card, model::MaterialKind::MooneyRivlinRubber);
  check_rubber_poisson(card, m.pr);
  m.rubber.a = card.real(3, "A", 0.0);
  m.rubber.b = card.real(4, "B", 0.0);
  if (card.real(5, "REF", 0.0) != 0.0)
    throw card.error("REF",
                     "the reference geometry of *INITIAL_FOAM_REFERENCE_GEOMETRY is not "
                     "supported (leave REF blank or 0)");
  bool fit = m.rubber.a == 0.0 && m.rubber.b == 0.0;
  if (const auto c2 = cursor.next_optional(n + 1, kEightByTen)) {
    if (c2->id(3, "LCID") != 0)
      throw c2->error("LCID",
                      "fitting A and B to test data (SGL, SW, ST, LCID) is not supported: "
                      "give A and B on card 1 and leave LCID blank");
    fit = fit && (c2->real(0, "SGL", 0.0) != 0.0 || c2->real(1, "SW", 0.0) != 0.0 ||
                  c2->real(2, "ST", 0.0) != 0.0);
  }
  if (m.rubber.a == 0.0 && m.rubber.b == 0.0)
    throw card.error("A", fit ? "A = B = 0 asks for a fit to test data, which is not supported: "
                                "give A and B"
                              : "A and B are both zero: the material has no stiffness");
  if (!(m.rubber.a + m.rubber.b > 0.0))
    throw card.error("B", fmt::format("A + B = {} must be positive (the shear modulus is "
                                      "2 (A + B))",
                                      m.rubber.a + m.rubber.b));
  set_equivalent_young(m);
  add_material(context, card, std::move(m));
  warn_unread_lines(block, cursor, context);
}

// *MAT_OGDEN_RUBBER (077_O). Card 1: MID RO PR N NV G SIGF REF; with N = 0 cards 2 and 3: MU1-8,
// ALPHA1-8; then optional viscoelastic cards GI BETAI VFLAG. Fitting (N > 0), PR < 0 (the
// hysteresis table card), frictional damping (G, SIGF), viscoelastic terms and REF are refused.
void mat_ogden_rubber(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  read_title(block, cursor);
  const int n = block.has_option("TITLE") ? 2 : 1;
  const Card card = cursor.next(n, kEightByTen, "MID RO PR N NV G SIGF REF");
  model::Material m = rubber_head(block, card, model::MaterialKind::OgdenRubber);
  if (m.pr < 0.0)
    throw card.error("PR", fmt::format("PR {} < 0 asks for the hysteresis table card (TBHYS), "
                                       "which is not supported",
                                       m.pr));
  check_rubber_poisson(card, m.pr);
  const std::int64_t order = card.integer(3, "N", 0);
  if (order != 0)
    throw card.error("N", fmt::format("N = {} asks for a fit of the constants to test data, "
                                      "which is not supported: give MU and ALPHA with N = 0",
                                      order));
  if (card.real(5, "G", 0.0) != 0.0)
    throw card.error("G", "frictional damping (G, SIGF) is not supported (leave G blank or 0)");
  if (card.real(6, "SIGF", 0.0) != 0.0)
    throw card.error("SIGF",
                     "frictional damping (G, SIGF) is not supported (leave SIGF blank or "
                     "0)");
  if (card.real(7, "REF", 0.0) != 0.0)
    throw card.error("REF",
                     "the reference geometry of *INITIAL_FOAM_REFERENCE_GEOMETRY is not "
                     "supported (leave REF blank or 0)");
  const Card mu_card = cursor.next(n + 1, kEightByTen, "MU1 MU2 MU3 MU4 MU5 MU6 MU7 MU8");
  const Card alpha_card =
      cursor.next(n + 2, kEightByTen, "ALPHA1 ALPHA2 ALPHA3 ALPHA4 ALPHA5 ALPHA6 ALPHA7 ALPHA8");
  static const char* const kMu[] = {"MU1", "MU2", "MU3", "MU4", "MU5", "MU6", "MU7", "MU8"};
  static const char* const kAlpha[] = {"ALPHA1", "ALPHA2", "ALPHA3", "ALPHA4",
                                       "ALPHA5", "ALPHA6", "ALPHA7", "ALPHA8"};
  model::RubberCard& r = m.rubber;
  for (std::size_t i = 0; i < 8; ++i) {
    const double mu = mu_card.real(i, kMu[i], 0.0);
    const double alpha = alpha_card.real(i, kAlpha[i], 0.0);
    if (mu == 0.0) continue;  // unused pair
    if (alpha == 0.0)
      throw alpha_card.error(kAlpha[i], fmt::format("{} is nonzero but {} is zero: the term "
                                                    "mu / alpha (lambda^alpha - 1) needs alpha "
                                                    "!= 0",
                                                    kMu[i], kAlpha[i]));
    r.mu[r.terms] = mu;
    r.alpha[r.terms] = alpha;
    ++r.terms;
  }
  if (r.terms == 0) throw mu_card.error("MU1", "all MU are zero: the material has no stiffness");
  const double g = material::rubber_shear_modulus(r, m.kind);
  if (!(g > 0.0))
    throw mu_card.error("MU1", fmt::format("the shear modulus sum(MU ALPHA) / 2 = {} must be "
                                           "positive",
                                           g));
  // Viscoelastic (Prony) cards: accepted only when they add nothing.
  int k = n + 3;
  while (const auto visco = cursor.next_optional(k++, kEightByTen)) {
    if (visco->real(0, "GI", 0.0) != 0.0)
      throw visco->error("GI",
                         "viscoelastic (Prony series) terms are not supported (leave the "
                         "GI, BETAI cards out)");
  }
  set_equivalent_young(m);
  add_material(context, card, std::move(m));
  warn_unread_lines(block, cursor, context);
}

void hourglass(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  do {
    read_title(block, cursor);
    const int n = block.has_option("TITLE") ? 2 : 1;
    const Card card = cursor.next(n, kEightByTen, "HGID IHQ QM IBQ Q1 Q2 QB QW");
    model::Hourglass h;
    h.id = positive_id(card, 0, "HGID", "hourglass");
    h.ihq = card.flag(1, "IHQ", 0);
    h.qm = card.real(2, "QM", 0.1);
    // Blank Q1/Q2 keep NaN: the parts then use *CONTROL_BULK_VISCOSITY's coefficients.
    if (!card.blank(4)) h.q1 = card.real(4, "Q1", 1.5);
    if (!card.blank(5)) h.q2 = card.real(5, "Q2", 0.06);
    h.qb = card.real(6, "QB", h.qm);
    h.qw = card.real(7, "QW", h.qm);
    h.where = card.location();
    if (h.ihq < 0 || h.ihq > 10) {
      throw card.error("IHQ", fmt::format("value {} is not a hourglass type 0..10", h.ihq));
    }
    if (h.qm < 0.0) throw card.error("QM", fmt::format("value {} must not be negative", h.qm));
    if (h.q1 < 0.0) throw card.error("Q1", fmt::format("value {} must not be negative", h.q1));
    if (h.q2 < 0.0) throw card.error("Q2", fmt::format("value {} must not be negative", h.q2));
    check_unique(context.model.hourglass, h.id, card, "HGID", "hourglass");
    context.model.hourglass.emplace(h.id, std::move(h));
  } while (!only_blank_lines_left(cursor, block));
}

namespace {

// Shared by node and part lists: card 1 SID DA1..DA4 SOLVER, then eight IDs per card.
template <typename Set>
Set read_id_list(const Block& block, ReaderContext& context, const char* id_field,
                 std::vector<model::Id>& ids) {
  CardCursor cursor(block, context.parameters);
  read_title(block, cursor);
  int n = block.has_option("TITLE") ? 2 : 1;
  const Card head = cursor.next(n, kEightByTen, "SID DA1 DA2 DA3 DA4 SOLVER");
  Set set;
  set.id = positive_id(head, 0, "SID", "set");
  set.where = head.location();
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(++n, kEightByTen, id_field);
    for (std::size_t i = 0; i < card.field_count(); ++i) {
      const model::Id id = card.id(i, id_field);
      if (id < 0) throw card.error(id_field, fmt::format("ID {} must not be negative", id));
      if (id != 0) ids.push_back(id);
    }
  }
  return set;
}

}  // namespace

void set_node_list(const Block& block, ReaderContext& context) {
  std::vector<model::Id> ids;
  auto set = read_id_list<model::NodeSet>(block, context, "NID", ids);
  set.nodes = std::move(ids);
  if (const auto it = context.model.node_sets.find(set.id); it != context.model.node_sets.end()) {
    throw located_error(set.where, "SID",
                        fmt::format("node set {} is already defined at {}:{}", set.id,
                                    it->second.where.file, it->second.where.line));
  }
  context.model.node_sets.emplace(set.id, std::move(set));
}

void set_part_list(const Block& block, ReaderContext& context) {
  std::vector<model::Id> ids;
  auto set = read_id_list<model::PartSet>(block, context, "PID", ids);
  set.parts = std::move(ids);
  if (const auto it = context.model.part_sets.find(set.id); it != context.model.part_sets.end()) {
    throw located_error(set.where, "SID",
                        fmt::format("part set {} is already defined at {}:{}", set.id,
                                    it->second.where.file, it->second.where.line));
  }
  context.model.part_sets.emplace(set.id, std::move(set));
}

void set_segment(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  read_title(block, cursor);
  int n = block.has_option("TITLE") ? 2 : 1;
  const Card head = cursor.next(n, kEightByTen, "SID DA1 DA2 DA3 DA4 SOLVER");
  model::SegmentSet set;
  set.id = positive_id(head, 0, "SID", "segment set");
  set.where = head.location();
  static const char* const kFields[] = {"N1", "N2", "N3", "N4"};
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(++n, kEightByTen, "N1 N2 N3 N4");
    std::array<model::Id, 4> segment{};
    for (std::size_t k = 0; k < 4; ++k) {
      segment[k] = card.id(k, kFields[k]);
      if (segment[k] < 0 || (k < 3 && segment[k] == 0)) {
        throw card.error(kFields[k], fmt::format("node ID {} is not valid", segment[k]));
      }
    }
    if (segment[3] == 0) segment[3] = segment[2];  // triangle: N4 repeats N3
    set.segments.push_back(segment);
  }
  if (const auto it = context.model.segment_sets.find(set.id);
      it != context.model.segment_sets.end()) {
    throw head.error("SID", fmt::format("segment set {} is already defined at {}:{}", set.id,
                                        it->second.where.file, it->second.where.line));
  }
  context.model.segment_sets.emplace(set.id, std::move(set));
}

}  // namespace rf::io::handlers

namespace rf::io::handlers {

// RigidFlex extension in LS-DYNA decks: the IMPETUS *CHANGE_P-ORDER card, fields TYPE ID ORDER
// (10 wide, or comma-separated). TYPE is P/PART, PS/PSET or ALL.
void change_p_order(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 0;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(++n, kEightByTen, "TYPE ID ORDER");
    model::POrderChange change;
    const std::string type = to_upper(card.text(0));
    if (type == "P" || type == "PART") {
      change.target = model::Target::Part;
    } else if (type == "PS" || type == "PSET") {
      change.target = model::Target::PartSet;
    } else if (type == "ALL") {
      change.target = model::Target::All;
    } else {
      throw card.error(
          "TYPE", fmt::format("'{}' is not P, PART, PS, PSET or ALL", std::string(card.text(0))));
    }
    change.id = card.id(1, "ID");
    change.order = card.flag(2, "ORDER", 0);
    if (change.order < 1 || change.order > 3) {
      throw card.error("ORDER", fmt::format("order {} is not supported (1, 2 or 3)", change.order));
    }
    change.where = card.location();
    context.model.p_order_changes.push_back(change);
  }
}

// The discrete-element materials: *MAT_SPRING_ELASTIC (S01) MID K, *MAT_DAMPER_VISCOUS (S02)
// MID DC, *MAT_SPRING_NONLINEAR_ELASTIC (S04) MID LCD LCR.
void mat_discrete(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  read_title(block, cursor);
  const int n = block.has_option("TITLE") ? 2 : 1;
  const std::string& base = block.base;
  model::Material m;
  if (base == "*MAT_SPRING_ELASTIC" || base == "*MAT_S01") {
    m.kind = model::MaterialKind::SpringElastic;
  } else if (base == "*MAT_DAMPER_VISCOUS" || base == "*MAT_S02") {
    m.kind = model::MaterialKind::DamperViscous;
  } else {
    m.kind = model::MaterialKind::SpringNonlinearElastic;
  }
  const char* fields = m.kind == model::MaterialKind::SpringElastic   ? "MID K"
                       : m.kind == model::MaterialKind::DamperViscous ? "MID DC"
                                                                      : "MID LCD LCR";
  const Card card = cursor.next(n, kEightByTen, fields);
  m.id = positive_id(card, 0, "MID", "material");
  m.keyword = block.keyword;
  m.where = card.location();
  if (m.kind == model::MaterialKind::SpringElastic) {
    m.spring_k = card.real(1, "K", 0.0);
    if (!(m.spring_k > 0.0) || !std::isfinite(m.spring_k)) {
      throw card.error("K",
                       fmt::format("the spring stiffness must be positive (got {})", m.spring_k));
    }
  } else if (m.kind == model::MaterialKind::DamperViscous) {
    m.damper_dc = card.real(1, "DC", 0.0);
    if (!(m.damper_dc > 0.0) || !std::isfinite(m.damper_dc)) {
      throw card.error("DC",
                       fmt::format("the damping constant must be positive (got {})", m.damper_dc));
    }
  } else {
    m.lcd = card.id(1, "LCD");
    if (m.lcd <= 0) throw card.error("LCD", "give the force vs elongation curve (LCD > 0)");
    if (card.id(2, "LCR") != 0) {
      throw card.error("LCR", "the rate scale curve LCR is not supported (leave blank or 0)");
    }
  }
  add_material(context, card, std::move(m));
  warn_unread_lines(block, cursor, context);
}

}  // namespace rf::io::handlers
