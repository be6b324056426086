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

}  // namespace rf::io::handlers
