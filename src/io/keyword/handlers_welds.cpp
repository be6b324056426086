// *CONSTRAINED_SPOTWELD (_ID, _FILTERED_FORCE) and *CONSTRAINED_NODE_SET (_ID): nodal
// constraints between deformable nodes (LS-DYNA manual, volume I). Node and set references are
// checked when the solver resolves them (solver/nodal_constraints.cpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "io/keyword/handlers.hpp"

namespace rf::io::handlers {

namespace {

const Layout kEightByTen = uniform_layout(8, 10);

double non_negative_real(const Card& card, std::size_t i, const char* field, double fallback) {
  const double v = card.real(i, field, fallback);
  if (!std::isfinite(v) || v < 0.0) {
    throw card.error(field, fmt::format("value {:g} must be a finite number >= 0", v));
  }
  return v;
}

// SN SS N M in fields 3-6 of a spot weld's failure card (*CONSTRAINED_SPOTWELD card 1,
// *CONSTRAINED_GENERALIZED_WELD_SPOT card 2): forces >= 0 (0: the term is off; `negative_force`
// says why a negative one is refused), exponents 0 meaning 1.
void read_failure_forces(const Card& card, model::SpotWeld& weld, const char* negative_force) {
  for (const auto& [i, name] : {std::pair{2u, "SN"}, std::pair{3u, "SS"}}) {
    if (card.real(i, name, 0.0) < 0.0) throw card.error(name, negative_force);
  }
  weld.sn = non_negative_real(card, 2, "SN", 0.0);
  weld.ss = non_negative_real(card, 3, "SS", 0.0);
  weld.n = non_negative_real(card, 4, "N", 1.0);
  if (weld.n == 0.0) weld.n = 1.0;
  weld.m = non_negative_real(card, 5, "M", 1.0);
  if (weld.m == 0.0) weld.m = 1.0;
}

}  // namespace

void constrained_spotweld(const Block& block, ReaderContext& context) {
  const bool with_id = block.has_option("ID");
  const bool filtered = block.has_option("FILTERED");
  if (filtered != block.has_option("FORCE")) {
    throw block_error(block, 1, "N1", "the option is _FILTERED_FORCE (both words)");
  }
  CardCursor cursor(block, context.parameters);
  auto& welds = context.model.spot_welds;
  bool any = false;
  int n = 1;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    model::SpotWeld weld;
    if (with_id) {
      const Card id_card = cursor.next(n++, Layout{10}, "WID");
      weld.id = id_card.id(0, "WID");
      if (weld.id <= 0) throw id_card.error("WID", "a positive spot weld ID is required");
      for (const auto& other : welds) {
        if (other.id == weld.id) {
          throw id_card.error("WID", fmt::format("spot weld ID {} is already used at {}:{}",
                                                 weld.id, other.where.file, other.where.line));
        }
      }
    } else {
      weld.id = static_cast<model::Id>(welds.size()) + 1;
    }
    const Card card = cursor.next(n++, kEightByTen, "N1 N2 SN SS N M TF EP");
    weld.n1 = card.id(0, "N1");
    weld.n2 = card.id(1, "N2");
    if (weld.n1 <= 0) throw card.error("N1", "a positive node ID is required");
    if (weld.n2 <= 0) throw card.error("N2", "a positive node ID is required");
    if (weld.n1 == weld.n2) {
      throw card.error("N2",
                       fmt::format("N2 = N1 = {}: a spot weld joins two different nodes", weld.n1));
    }
    read_failure_forces(card, weld,
                        "a negative value (a curve of failure force against temperature) is not "
                        "supported: RigidFlex has no nodal temperatures; give a force >= 0 (0 "
                        "turns the term off)");
    weld.tf = card.real(6, "TF", 1e20);
    if (!std::isfinite(weld.tf)) throw card.error("TF", "the failure time must be finite");
    if (weld.tf == 0.0) weld.tf = 1e20;
    const double ep = card.real(7, "EP", 1e20);
    if (ep != 0.0 && ep < 1e20) {
      throw card.error("EP",
                       "failure by the plastic strain of the attached shells is not supported "
                       "(leave EP blank or 0, or use SN/SS/TF)");
    }
    if (filtered) {
      const Card f = cursor.next(n++, kEightByTen, "NF TW");
      const auto nf = f.integer(0, "NF", 0);
      const double tw = f.real(1, "TW", 0.0);
      if (nf > 1 || tw != 0.0) {
        throw f.error(nf > 1 ? "NF" : "TW",
                      "filtering of the spot weld force is not supported (leave NF blank, 0 "
                      "or 1 and TW blank or 0: the failure test uses the force of each cycle)");
      }
    }
    weld.where = card.location();
    welds.push_back(weld);
    any = true;
  }
  if (!any) throw block_error(block, 1, "N1", "no spot weld card follows the keyword");
}

// *CONSTRAINED_GENERALIZED_WELD_SPOT (_ID): [WID]; NSID CID FILTER WINDOW NPR NPRT; TFAIL EPSF
// SN SS N M. A node set of exactly two nodes is the spot weld of *CONSTRAINED_SPOTWELD between
// them, with the same failure criterion (the set is resolved in finish_model). Sets of more nodes
// (one rigid weld of many nodes) and the filter, fillet-pair and plastic-strain options are
// refused; CID (output axes for coincident nodes) and NPRT (rbdout printing) change no physics.
void constrained_generalized_weld_spot(const Block& block, ReaderContext& context) {
  const bool with_id = block.has_option("ID");
  CardCursor cursor(block, context.parameters);
  bool any = false;
  int n = 1;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    ReaderContext::GeneralizedWeld g;
    g.with_id = with_id;
    if (with_id) {
      const Card id_card = cursor.next(n++, Layout{10}, "WID");
      g.weld.id = id_card.id(0, "WID");
      if (g.weld.id <= 0) throw id_card.error("WID", "a positive spot weld ID is required");
    }
    const Card card = cursor.next(n++, kEightByTen, "NSID CID FILTER WINDOW NPR NPRT");
    g.nsid = card.id(0, "NSID");
    if (g.nsid <= 0) throw card.error("NSID", "a positive node set ID is required");
    if (card.integer(2, "FILTER", 0) > 1 || card.real(3, "WINDOW", 0.0) != 0.0) {
      throw card.error(card.integer(2, "FILTER", 0) > 1 ? "FILTER" : "WINDOW",
                       "filtering of the weld force is not supported (leave FILTER blank, 0 or 1 "
                       "and WINDOW blank or 0: the failure test uses the force of each cycle)");
    }
    if (card.integer(4, "NPR", 0) != 0) {
      throw card.error("NPR",
                       "individual node pairs (cross fillet and combined welds) are not "
                       "supported: leave NPR blank");
    }
    const int nprt = card.flag(5, "NPRT", 0);
    if (nprt < 0 || nprt > 2)
      throw card.error("NPRT", fmt::format("value {} is not 0, 1 or 2", nprt));
    const Card failure = cursor.next(n++, kEightByTen, "TFAIL EPSF SN SS N M");
    g.weld.tf = failure.real(0, "TFAIL", 1e20);
    if (!std::isfinite(g.weld.tf)) throw failure.error("TFAIL", "the failure time must be finite");
    if (g.weld.tf == 0.0) g.weld.tf = 1e20;
    const double epsf = failure.real(1, "EPSF", 0.0);
    if (epsf != 0.0) {
      throw failure.error("EPSF",
                          "failure by the plastic strain of the welded shells is not supported "
                          "(leave EPSF blank or 0, or use SN/SS/TFAIL)");
    }
    read_failure_forces(failure, g.weld,
                        "a negative failure force is not supported: give a force >= 0 (0 turns "
                        "the term off)");
    g.weld.where = card.location();
    context.generalized_welds.push_back(g);
    any = true;
  }
  if (!any) throw block_error(block, 1, "NSID", "no weld card follows the keyword");
}

void finish_generalized_welds(ReaderContext& context) {
  auto& welds = context.model.spot_welds;
  for (auto& g : context.generalized_welds) {
    const auto it = context.model.node_sets.find(g.nsid);
    if (it == context.model.node_sets.end()) {
      throw located_error(g.weld.where, "NSID", fmt::format("node set {} is not defined", g.nsid));
    }
    std::vector<model::Id> nodes = it->second.nodes;
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    if (nodes.size() != 2) {
      throw located_error(
          g.weld.where, "NSID",
          fmt::format("node set {} has {} distinct nodes; a generalized spot weld is supported "
                      "between exactly two nodes (a weld of more nodes, one rigid patch, is not)",
                      g.nsid, nodes.size()));
    }
    // In the set's order, as LS-DYNA takes the first node as the weld's first.
    g.weld.n1 = it->second.nodes.front();
    g.weld.n2 = g.weld.n1 == nodes[0] ? nodes[1] : nodes[0];
    if (!g.with_id) g.weld.id = static_cast<model::Id>(welds.size()) + 1;
    for (const auto& other : welds) {
      if (other.id == g.weld.id) {
        throw located_error(g.weld.where, g.with_id ? "WID" : "NSID",
                            fmt::format("spot weld ID {} is already used at {}:{}", g.weld.id,
                                        other.where.file, other.where.line));
      }
    }
    welds.push_back(g.weld);
  }
}

void constrained_node_set(const Block& block, ReaderContext& context) {
  const bool with_id = block.has_option("ID");
  CardCursor cursor(block, context.parameters);
  auto& sets = context.model.node_set_constraints;
  bool any = false;
  int n = 1;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    model::NodeSetConstraint c;
    if (with_id) {
      const Card id_card = cursor.next(n++, Layout{10}, "CNSID");
      c.id = id_card.id(0, "CNSID");
      if (c.id <= 0) throw id_card.error("CNSID", "a positive constraint ID is required");
      for (const auto& other : sets) {
        if (other.id == c.id) {
          throw id_card.error(
              "CNSID", fmt::format("constrained node set ID {} is already used at {}:{}", c.id,
                                   other.where.file, other.where.line));
        }
      }
    } else {
      c.id = static_cast<model::Id>(sets.size()) + 1;
    }
    const Card card = cursor.next(n++, kEightByTen, "NSID DOF TF");
    c.nsid = card.id(0, "NSID");
    if (c.nsid <= 0) throw card.error("NSID", "a positive node set ID is required");
    c.dof = card.flag(1, "DOF", 1);
    if (c.dof == 0) c.dof = 1;
    if (c.dof < 1 || c.dof > 7) {
      throw card.error("DOF", fmt::format("value {} is not supported (1 x, 2 y, 3 z, 4 xy, 5 yz, "
                                          "6 zx, 7 xyz; 8, piezoelectric, is not)",
                                          c.dof));
    }
    c.tf = card.real(2, "TF", 1e20);
    if (!std::isfinite(c.tf)) throw card.error("TF", "the failure time must be finite");
    if (c.tf == 0.0) c.tf = 1e20;
    c.where = card.location();
    sets.push_back(c);
    any = true;
  }
  if (!any) throw block_error(block, 1, "NSID", "no constrained node set card follows the keyword");
}

}  // namespace rf::io::handlers
