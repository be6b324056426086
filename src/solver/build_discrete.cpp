// Discrete element blocks (springs and dampers, element/discrete_block.hpp) in the solver state:
// one block per part, their forces gathered into f_int in a fixed order, and the step they
// allow from the nodal (or rigid-body) masses.
#include <fmt/format.h>

#include <map>

#include "model/error.hpp"
#include "model/error_context.hpp"
#include "solver/build_state.hpp"
#include "solver/rigid_bodies.hpp"

namespace rf::solver {

using model::context_of;

void build_discrete_blocks(const model::Model& model, const NodeIndex& node_index, State& state) {
  if (model.discretes.empty()) return;
  std::map<model::Id, std::vector<std::size_t>> elements_of_part;
  for (std::size_t e = 0; e < model.discretes.size(); ++e) {
    elements_of_part[model.discretes[e].pid].push_back(e);
  }
  const NodalState& nodes = state.nodes;
  const element::NodalView view{nodes.x.x.data(), nodes.x.y.data(), nodes.x.z.data(),
                                nodes.v.x.data(), nodes.v.y.data(), nodes.v.z.data()};
  for (const auto& [pid, indices] : elements_of_part) {
    const model::DiscreteElement& first = model.discretes[indices.front()];
    const auto part_it = model.parts.find(pid);
    if (part_it == model.parts.end()) {
      throw InputError(
          context_of(first.where, "PID"),
          fmt::format("element {} refers to part {}, which is not defined", first.id, pid));
    }
    const model::Part& part = part_it->second;
    if (!model.discrete_sections.count(part.secid)) {
      throw InputError(context_of(part.where, "SECID"),
                       fmt::format("part {} has discrete elements but section {} is not a "
                                   "*SECTION_DISCRETE",
                                   pid, part.secid));
    }
    const auto mat_it = model.materials.find(part.mid);
    if (mat_it == model.materials.end()) {
      throw InputError(
          context_of(part.where, "MID"),
          fmt::format("part {} refers to material {}, which is not defined", pid, part.mid));
    }
    const model::Material& mat = mat_it->second;
    element::DiscreteBlock block;
    block.part_id = pid;
    block.part_index = static_cast<int>(state.parts.size());
    block.material_id = mat.id;
    switch (mat.kind) {
      case model::MaterialKind::SpringElastic:
        block.law = element::DiscreteLaw::kLinearSpring;
        block.stiffness = mat.spring_k;
        break;
      case model::MaterialKind::DamperViscous:
        block.law = element::DiscreteLaw::kViscousDamper;
        block.damping = mat.damper_dc;
        break;
      case model::MaterialKind::SpringNonlinearElastic: {
        block.law = element::DiscreteLaw::kNonlinearSpring;
        const auto curve = model.curves.find(mat.lcd);
        if (curve == model.curves.end()) {
          throw InputError(
              context_of(mat.where, "LCD"),
              fmt::format("material {} refers to curve {}, which is not defined", mat.id, mat.lcd));
        }
        const model::Curve& c = curve->second;
        if (c.function || c.abscissa.empty()) {
          throw InputError(context_of(mat.where, "LCD"),
                           fmt::format("material {}: curve {} must be a *DEFINE_CURVE with "
                                       "points (force vs elongation)",
                                       mat.id, mat.lcd));
        }
        for (std::size_t k = 0; k < c.abscissa.size(); ++k) {
          // value(x) = SFO f(x / SFA - OFFA) + OFFO: the point x_k sits at SFA (x_k + OFFA).
          block.curve_elongation.push_back(c.sfa * (c.abscissa[k] + c.offa));
          block.curve_force.push_back(c.sfo * c.ordinate[k] + c.offo);
        }
        break;
      }
      default:
        throw InputError(context_of(part.where, "MID"),
                         fmt::format("part {} has discrete elements, so its material must be "
                                     "*MAT_SPRING_ELASTIC, *MAT_DAMPER_VISCOUS or "
                                     "*MAT_SPRING_NONLINEAR_ELASTIC; material {} is a {}",
                                     pid, mat.id, mat.keyword));
    }
    for (const std::size_t e : indices) {
      const model::DiscreteElement& d = model.discretes[e];
      block.element_id.push_back(d.id);
      const std::int32_t a = node_index.at(d.nodes[0], d.where, "N1");
      const std::int32_t b = node_index.at(d.nodes[1], d.where, "N2");
      // LS-DYNA needs an orientation (VID) for coincident nodes; without one the line of action
      // N1 -> N2 is undefined.
      if (nodes.x0.x[a] == nodes.x0.x[b] && nodes.x0.y[a] == nodes.x0.y[b] &&
          nodes.x0.z[a] == nodes.x0.z[b]) {
        throw InputError(context_of(d.where, "N2"),
                         fmt::format("discrete element {}: nodes N1 ({}) and N2 ({}) coincide, "
                                     "so the line of action N1 -> N2 is undefined (orientation "
                                     "vectors, VID, are not supported: move the nodes apart)",
                                     d.id, d.nodes[0], d.nodes[1]));
      }
      block.conn.push_back(a);
      block.conn.push_back(b);
      block.scale.push_back(d.scale);
      block.offset.push_back(d.offset);
    }
    element::initialize_discrete_block(block, view, part.where);
    state.parts.push_back(PartInfo{pid, part.title, 0, static_cast<std::int64_t>(block.size())});
    state.discrete_blocks.push_back(std::move(block));
  }
}

void prepare_discrete_time_steps(State& state, const RigidSystem& rigid) {
  const NodalState& nodes = state.nodes;
  auto inverse_mass = [&](std::int32_t i) {
    if (rigid.is_rigid(i)) {
      // A node of a rigid body moves with the body: its translational mass stands in (the
      // body's rotational inertia at the node's lever arm is not taken into account).
      const double m = rigid.bodies[static_cast<std::size_t>(rigid.body_of_node[i])].state.mass;
      return m > 0.0 ? 1.0 / m : 0.0;
    }
    const double m = nodes.mass[static_cast<std::size_t>(i)];
    return m > 0.0 ? 1.0 / m : 0.0;  // a node without mass is held (Simulation): immovable
  };
  for (auto& block : state.discrete_blocks) {
    for (std::size_t e = 0; e < block.size(); ++e) {
      const std::int32_t a = block.conn[2 * e], b = block.conn[2 * e + 1];
      // Both on one rigid body: the force is internal to the body and limits nothing.
      const bool same_body =
          rigid.is_rigid(a) && rigid.is_rigid(b) && rigid.body_of_node[a] == rigid.body_of_node[b];
      block.inverse_mass[e] = same_body ? 0.0 : inverse_mass(a) + inverse_mass(b);
    }
  }
}

// Serial, in (block, element, local node) order: a handful of elements in a typical model, and
// a fixed order keeps f_int the same for any thread count.
void assemble_discrete_forces(State& state) {
  NodalState& nodes = state.nodes;
  for (const auto& block : state.discrete_blocks) {
    for (std::size_t e = 0; e < block.size(); ++e) {
      const double* f = block.force.data() + element::kDiscreteSlot * e;
      for (int k = 0; k < 2; ++k) {
        const std::int32_t i = block.conn[2 * e + static_cast<std::size_t>(k)];
        nodes.f_int.x[i] += f[3 * k];
        nodes.f_int.y[i] += f[3 * k + 1];
        nodes.f_int.z[i] += f[3 * k + 2];
      }
    }
  }
}

}  // namespace rf::solver

namespace rf::solver {

void add_discrete_work(State& state, const Vec3Array& v_previous, double dt_avg) {
  const NodalState& nodes = state.nodes;
  for (auto& block : state.discrete_blocks) {
    double work = 0.0;
    for (std::size_t e = 0; e < block.size(); ++e) {
      const double* f = block.force.data() + element::kDiscreteSlot * e;
      for (int k = 0; k < 2; ++k) {
        const std::int32_t i = block.conn[2 * e + static_cast<std::size_t>(k)];
        work += 0.5 * dt_avg *
                (f[3 * k] * (v_previous.x[i] + nodes.v.x[i]) +
                 f[3 * k + 1] * (v_previous.y[i] + nodes.v.y[i]) +
                 f[3 * k + 2] * (v_previous.z[i] + nodes.v.z[i]));
      }
    }
    (block.law == element::DiscreteLaw::kViscousDamper ? block.damper_energy
                                                       : block.spring_energy) += work;
  }
}

}  // namespace rf::solver
