// *CONSTRAINED_JOINT_SPHERICAL, _REVOLUTE, _CYLINDRICAL, _TRANSLATIONAL, _UNIVERSAL, _LOCKING
// (with _ID): penalty joints between node pairs (LS-DYNA manual, volume I,
// *CONSTRAINED_JOINT_OPTION).
#include <fmt/format.h>

#include <cmath>

#include "io/keyword/handlers.hpp"

namespace rf::io::handlers {

namespace {

const Layout kEightByTen = uniform_layout(8, 10);

struct JointKind {
  const char* name;
  model::Joint::Type type;
  int nodes;  // N1..Nn used
};

JointKind kind_of(const Block& block) {
  static const JointKind kinds[] = {
      {"*CONSTRAINED_JOINT_SPHERICAL", model::Joint::Type::Spherical, 2},
      {"*CONSTRAINED_JOINT_REVOLUTE", model::Joint::Type::Revolute, 4},
      {"*CONSTRAINED_JOINT_CYLINDRICAL", model::Joint::Type::Cylindrical, 4},
      {"*CONSTRAINED_JOINT_TRANSLATIONAL", model::Joint::Type::Translational, 6},
      {"*CONSTRAINED_JOINT_UNIVERSAL", model::Joint::Type::Universal, 4},
      {"*CONSTRAINED_JOINT_LOCKING", model::Joint::Type::Locking, 6},
  };
  for (const auto& k : kinds)
    if (block.base == k.name) return k;
  return kinds[0];  // not reached: only these bases are registered
}

}  // namespace

void constrained_joint(const Block& block, ReaderContext& context) {
  if (block.has_option("FAILURE")) {
    throw block_error(block, 1, "N1", "the _FAILURE option (joint failure) is not supported");
  }
  const JointKind kind = kind_of(block);
  CardCursor cursor(block, context.parameters);
  bool any = false;
  int n = 1;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    model::Joint joint;
    joint.type = kind.type;
    if (block.has_option("ID")) {
      const Card id_card = cursor.next(n++, Layout{10, 70}, "JID HEADING");
      joint.id = id_card.id(0, "JID");
      if (joint.id <= 0) throw id_card.error("JID", "a positive joint ID is required");
      joint.title = std::string(id_card.text(1));
      for (const auto& other : context.model.joints) {
        if (other.id == joint.id) {
          throw id_card.error("JID", fmt::format("joint ID {} is used twice", joint.id));
        }
      }
    } else {
      joint.id = static_cast<model::Id>(context.model.joints.size()) + 1;
    }
    const Card card = cursor.next(n++, kEightByTen, "N1 N2 N3 N4 N5 N6 RPS DAMP");
    static const char* names[6] = {"N1", "N2", "N3", "N4", "N5", "N6"};
    for (int k = 0; k < 6; ++k) {
      joint.nodes[k] = card.id(k, names[k]);
      if (k < kind.nodes && joint.nodes[k] <= 0) {
        throw card.error(names[k], fmt::format("{} needs nodes N1..N{} (positive node IDs)",
                                               kind.name, kind.nodes));
      }
      if (k >= kind.nodes && joint.nodes[k] != 0) {
        throw card.error(names[k], fmt::format("{} uses only N1..N{}; leave {} blank", kind.name,
                                               kind.nodes, names[k]));
      }
    }
    joint.rps = card.real(6, "RPS", 1.0);
    if (joint.rps == 0.0) joint.rps = 1.0;
    if (!std::isfinite(joint.rps) || joint.rps < 0.0) {
      throw card.error("RPS", fmt::format("value {} must be a finite number > 0", joint.rps));
    }
    joint.damp = card.real(7, "DAMP", 1.0);
    if (joint.damp == 0.0) joint.damp = 1.0;
    if (!std::isfinite(joint.damp) || joint.damp < 0.0) {
      throw card.error("DAMP", fmt::format("value {} must be a finite number >= 0", joint.damp));
    }
    joint.where = card.location();
    context.model.joints.push_back(joint);
    any = true;
  }
  if (!any) throw block_error(block, 1, "N1", "no joint card follows the keyword");
}

// *CONSTRAINED_JOINT_STIFFNESS_GENERALIZED (LS-DYNA manual, volume I,
// *CONSTRAINED_JOINT_STIFFNESS): four cards per joint stiffness, repeated; trailing cards of the
// last one may be left out (their fields take the defaults, 0). Resolved and checked against
// parts, coordinate systems, curves and joints by solver/joint_stiffness.cpp.
void constrained_joint_stiffness(const Block& block, ReaderContext& context) {
  const Layout six = uniform_layout(6, 10);
  CardCursor cursor(block, context.parameters);
  bool any = false;
  int n = 1;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    model::JointStiffness js;
    js.type = model::JointStiffness::Type::Generalized;
    const Card first = cursor.next(n++, six, "JSID PIDA PIDB CIDA CIDB JID");
    js.id = first.id(0, "JSID");
    if (js.id <= 0) throw first.error("JSID", "a positive joint stiffness ID is required");
    js.pida = first.id(1, "PIDA");
    js.pidb = first.id(2, "PIDB");
    js.cida = first.id(3, "CIDA");
    js.cidb = first.id(4, "CIDB");
    js.jid = first.id(5, "JID");
    if (js.pida <= 0) throw first.error("PIDA", "the part of rigid body A is required");
    if (js.pidb <= 0) throw first.error("PIDB", "the part of rigid body B is required");
    if (js.cida <= 0) {
      throw first.error("CIDA", "the coordinate system of body A is required (a positive ID)");
    }
    if (js.cidb < 0) throw first.error("CIDB", "a coordinate system ID >= 0 is required");
    if (js.jid < 0) throw first.error("JID", "a joint ID >= 0 is required");
    js.card[0] = first.location();
    js.where = js.card[0];
    for (int c = 1; c < 4; ++c) {
      js.card[c] = js.card[c - 1];
      if (cursor.at_end()) continue;  // left out: defaults
      static const char* const names[4] = {"", "LCIDPH LCIDT LCIDPS DLCIDPH DLCIDT DLCIDPS",
                                           "ESPH FMPH EST FMT ESPS FMPS",
                                           "NSAPH PSAPH NSAT PSAT NSAPS PSAPS"};
      const Card card = cursor.next(n++, six, names[c]);
      js.card[c] = card.location();
      if (c == 1) {
        static const char* const curves[3] = {"LCIDPH", "LCIDT", "LCIDPS"};
        static const char* const damping[3] = {"DLCIDPH", "DLCIDT", "DLCIDPS"};
        for (int k = 0; k < 3; ++k) {
          js.lcid[k] = card.id(k, curves[k]);
          js.dlcid[k] = card.id(3 + k, damping[k]);
        }
      } else if (c == 2) {
        static const char* const stiffness[3] = {"ESPH", "EST", "ESPS"};
        static const char* const friction[3] = {"FMPH", "FMT", "FMPS"};
        for (int k = 0; k < 3; ++k) {
          js.stiffness[k] = card.real(2 * k, stiffness[k], 0.0);
          js.friction[k] = card.real(2 * k + 1, friction[k], 0.0);
        }
      } else {
        static const char* const negative[3] = {"NSAPH", "NSAT", "NSAPS"};
        static const char* const positive[3] = {"PSAPH", "PSAT", "PSAPS"};
        for (int k = 0; k < 3; ++k) {
          js.negative_stop[k] = card.real(2 * k, negative[k], 0.0);
          js.positive_stop[k] = card.real(2 * k + 1, positive[k], 0.0);
        }
      }
    }
    context.model.joint_stiffnesses.push_back(js);
    any = true;
  }
  if (!any) throw block_error(block, 1, "JSID", "no joint stiffness card follows the keyword");
}

}  // namespace rf::io::handlers
