#include "solver/flexible_bodies.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <unordered_map>

#include "model/error.hpp"
#include "model/error_context.hpp"

namespace rf::solver {

namespace {

using model::context_of;

Eigen::Vector3d body_position(const modal::FlexibleBody& f, std::size_t k,
                              const std::vector<double>& amplitudes) {
  return Eigen::Vector3d(f.body_coords[3 * k], f.body_coords[3 * k + 1], f.body_coords[3 * k + 2]) +
         f.displacement(k, amplitudes);
}

}  // namespace

SelectedModes select_part_modes(const model::PartModes& card, const std::string& owner,
                                const std::vector<std::int32_t>& body_nodes,
                                const NodalState& nodes, const ModeLoader& loader,
                                const RotationalState* rotations) {
  modal::ModeSet set;
  try {
    set = loader(card.path);
  } catch (const InputError&) {
    // Name the keyword and field: the database reader knows only the file.
    if (!std::filesystem::exists(card.path)) {
      throw InputError(context_of(card.where, "FILENAME"),
                       fmt::format("mode database '{}' does not exist: compute it with an "
                                   "eigen analysis of the part (rigidflex eigen, "
                                   "docs/eigen.md) or correct FILENAME",
                                   card.path));
    }
    throw;
  } catch (const std::exception& e) {
    throw InputError(context_of(card.where, "FILENAME"),
                     fmt::format("cannot read mode database '{}': {}", card.path, e.what()));
  }
  const std::size_t dn = set.node_count();
  if (set.shapes.size() != set.mode_count() * 3 * dn || set.coordinates.size() != 3 * dn) {
    throw InputError(context_of(card.where, "FILENAME"),
                     fmt::format("mode database '{}' is inconsistent (shape and node array "
                                 "sizes do not match)",
                                 card.path));
  }
  // A database with rotational components comes from a model with shells or beams: its shapes
  // are mass-normalised with the rotational inertia included. Bodies that cannot carry nodal
  // rotations (a deformable part switched rigid) refuse it.
  if (set.rotation_count() > 0 && rotations == nullptr) {
    throw InputError(context_of(card.where, "FILENAME"),
                     fmt::format("mode database '{}' has rotational components ({} nodes of "
                                 "shells or beams): flexible bodies made of shells or beams are "
                                 "not supported for a part that becomes a flexible body by "
                                 "switching; compute the modes of a solid part",
                                 card.path, set.rotation_count()));
  }
  // Node matching by ID.
  std::unordered_map<model::Id, std::size_t> row_of;
  for (std::size_t r = 0; r < dn; ++r) row_of.emplace(set.node_ids[r], r);
  std::vector<std::size_t> rows;
  std::vector<model::Id> missing;
  double size = 0.0;
  for (const auto i : body_nodes) {
    const auto it = row_of.find(nodes.id[i]);
    if (it == row_of.end()) {
      missing.push_back(nodes.id[i]);
    } else {
      rows.push_back(it->second);
    }
    size =
        std::max(size, std::abs(nodes.x0.x[i]) + std::abs(nodes.x0.y[i]) + std::abs(nodes.x0.z[i]));
  }
  if (!missing.empty()) {
    std::string list;
    for (std::size_t k = 0; k < std::min<std::size_t>(missing.size(), 10); ++k) {
      list += fmt::format("{}{}", k ? ", " : "", missing[k]);
    }
    throw InputError(
        context_of(card.where, "FILENAME"),
        fmt::format("mode database '{}' has no data for {} node(s) of {}: {}{}", card.path,
                    missing.size(), owner, list, missing.size() > 10 ? ", ..." : ""));
  }
  // Every node of the body is in the database; the database must hold no others either. Modes
  // of a larger structure (more parts, e.g. `run` on a deck that analyses every part) are not
  // the modes of this body: their shapes restricted to its nodes are neither mass-orthonormal
  // nor eigenvectors of its stiffness, and the answer would silently change.
  if (dn != body_nodes.size()) {
    std::vector<std::uint8_t> used(dn, 0);
    for (const auto r : rows) used[r] = 1;
    std::vector<model::Id> extra;
    for (std::size_t r = 0; r < dn; ++r) {
      if (!used[r]) extra.push_back(set.node_ids[r]);
    }
    std::sort(extra.begin(), extra.end());
    std::string list;
    for (std::size_t k = 0; k < std::min<std::size_t>(extra.size(), 10); ++k) {
      list += fmt::format("{}{}", k ? ", " : "", extra[k]);
    }
    std::set<model::Id> parts;
    for (std::size_t r = 0; r < dn && r < set.node_parts.size(); ++r) {
      if (!used[r]) parts.insert(set.node_parts[r]);
    }
    std::string part_list;
    for (const auto p : parts) part_list += fmt::format("{}{}", part_list.empty() ? "" : ", ", p);
    throw InputError(
        context_of(card.where, "FILENAME"),
        fmt::format("mode database '{}' has {} nodes, {} has {}: {} node(s) in it are not the "
                    "body's ({}{}{}), so its modes belong to a larger model. Compute the modes of "
                    "this part alone (rigidflex eigen --parts, docs/eigen.md)",
                    card.path, dn, owner, body_nodes.size(), extra.size(), list,
                    extra.size() > 10 ? ", ..." : "",
                    part_list.empty() ? "" : fmt::format("; of part(s) {}", part_list)));
  }
  for (std::size_t k = 0; k < body_nodes.size(); ++k) {
    const auto i = body_nodes[k];
    const double* c = &set.coordinates[3 * rows[k]];
    const double gap = std::abs(c[0] - nodes.x0.x[i]) + std::abs(c[1] - nodes.x0.y[i]) +
                       std::abs(c[2] - nodes.x0.z[i]);
    if (gap > 1e-6 * std::max(size, 1e-30)) {
      throw InputError(context_of(card.where, "FILENAME"),
                       fmt::format("node {} is at ({:.6g}, {:.6g}, {:.6g}) in mode database "
                                   "'{}' but at ({:.6g}, {:.6g}, {:.6g}) in the model: the "
                                   "modes belong to another geometry",
                                   nodes.id[i], c[0], c[1], c[2], card.path, nodes.x0.x[i],
                                   nodes.x0.y[i], nodes.x0.z[i]));
    }
  }
  // Mode selection: KMFLAG 0 the first NMFB elastic modes, KMFLAG 1 the listed ones.
  SelectedModes selected;
  std::vector<int>& chosen = selected.file_modes;
  if (card.kmflag == 0) {
    for (std::size_t m = 0; m < set.mode_count() && static_cast<int>(chosen.size()) < card.nmfb;
         ++m) {
      const bool rigid_mode = m < set.rigid.size() && set.rigid[m] != 0;
      if (!rigid_mode) chosen.push_back(static_cast<int>(m) + 1);
    }
    if (static_cast<int>(chosen.size()) < card.nmfb) {
      throw InputError(context_of(card.where, "NMFB"),
                       fmt::format("NMFB {}: mode database '{}' has only {} elastic modes",
                                   card.nmfb, card.path, chosen.size()));
    }
  } else {
    for (const int m : card.modes) {
      if (m > static_cast<int>(set.mode_count())) {
        throw InputError(context_of(card.where, "MODE1"),
                         fmt::format("mode {} is listed but mode database '{}' has {} modes", m,
                                     card.path, set.mode_count()));
      }
      if (static_cast<std::size_t>(m - 1) < set.rigid.size() && set.rigid[m - 1] != 0) {
        throw InputError(context_of(card.where, "MODE1"),
                         fmt::format("mode {} of '{}' is a rigid-body mode; the body's rigid "
                                     "motion is its own: list elastic modes only",
                                     m, card.path));
      }
      chosen.push_back(m);
    }
  }
  const std::size_t bn = body_nodes.size();
  selected.shapes.resize(chosen.size() * 3 * bn);
  selected.damping.assign(chosen.size(), 0.0);
  for (std::size_t c = 0; c < chosen.size(); ++c) {
    const std::size_t m = static_cast<std::size_t>(chosen[c] - 1);
    const double* shape = set.shape(m);
    for (std::size_t k = 0; k < bn; ++k) {
      for (int d = 0; d < 3; ++d) selected.shapes[c * 3 * bn + 3 * k + d] = shape[3 * rows[k] + d];
    }
    selected.eigenvalues.push_back(set.eigenvalues[m]);
  }
  // Rotational components: every body node with rotations in the model gets a row (zero where
  // the database node has none: a solid part's node shared with a shell); a database node
  // with rotations must have them in the model.
  if (rotations != nullptr) {
    std::vector<std::int64_t> db_rotation(dn, -1);
    for (std::size_t j = 0; j < set.rotation_count(); ++j) {
      const auto row = set.rotation_nodes[j];
      if (row < 0 || static_cast<std::size_t>(row) >= dn) {
        throw InputError(context_of(card.where, "FILENAME"),
                         fmt::format("mode database '{}' is inconsistent (rotation node {} out "
                                     "of range)",
                                     card.path, row));
      }
      db_rotation[static_cast<std::size_t>(row)] = static_cast<std::int64_t>(j);
    }
    for (std::size_t k = 0; k < bn; ++k) {
      const std::int32_t i = body_nodes[k];
      if (rotations->index(i) >= 0) {
        selected.rotation_position.push_back(static_cast<std::int32_t>(k));
      } else if (db_rotation[rows[k]] >= 0) {
        throw InputError(context_of(card.where, "FILENAME"),
                         fmt::format("node {} has rotations in mode database '{}' but none in "
                                     "the model (no shell or beam of the model uses it): the "
                                     "modes belong to another model",
                                     nodes.id[i], card.path));
      }
    }
    const std::size_t r = selected.rotation_position.size();
    const std::size_t dr = set.rotation_count();
    selected.rotation_shapes.assign(chosen.size() * 3 * r, 0.0);
    for (std::size_t c = 0; c < chosen.size(); ++c) {
      const std::size_t m = static_cast<std::size_t>(chosen[c] - 1);
      if (dr == 0) continue;
      const double* shape = set.rotation_shape(m);
      for (std::size_t j = 0; j < r; ++j) {
        const auto row = db_rotation[rows[static_cast<std::size_t>(selected.rotation_position[j])]];
        if (row < 0) continue;
        for (int d = 0; d < 3; ++d) {
          selected.rotation_shapes[c * 3 * r + 3 * j + d] =
              shape[3 * static_cast<std::size_t>(row) + d];
        }
      }
    }
  }
  for (const auto& d : card.damping) {
    for (int m = d.mstart; m <= d.mstop; ++m) selected.damping[m - 1] = d.dampf;
  }
  return selected;
}

void attach_flexible_bodies(const model::Model& model, const NodeIndex& node_index,
                            const State& state, const Boundary& boundary,
                            const std::vector<std::int32_t>& contact_nodes, RigidSystem& rigid,
                            const ModeLoader& loader) {
  if (model.part_modes.empty()) return;
  const NodalState& nodes = state.nodes;
  std::vector<std::uint8_t> deformable_node(nodes.size(), 0);
  // Every family's deformable elements (and springs, dampers) act on the nodes they share with
  // a body: those nodes are reconstructed every cycle.
  for (const auto& block : state.hex_blocks) {
    if (block.rigid) continue;
    for (const std::int32_t i : block.conn) deformable_node[i] = 1;
  }
  for (const auto& block : state.shell_blocks) {
    if (block.rigid) continue;
    for (const std::int32_t i : block.conn) deformable_node[i] = 1;
  }
  for (const auto& block : state.beam_blocks) {
    if (block.rigid) continue;
    for (const std::int32_t i : block.conn) deformable_node[i] = 1;
  }
  for (const auto& block : state.discrete_blocks) {
    for (const std::int32_t i : block.conn) deformable_node[i] = 1;
  }
  std::vector<std::uint8_t> needed(nodes.size(), 0);  // reconstructed every cycle
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (deformable_node[i] || boundary.fixed[i] != 0) needed[i] = 1;
  }
  for (const auto& p : boundary.prescribed) needed[p.node] = 1;
  for (const auto& f : boundary.nodal_forces) needed[f.node] = 1;
  for (const auto id : model.output.history_nodes) needed[node_index.at(id, {}, "NID")] = 1;
  for (const std::int32_t i : contact_nodes) needed[i] = 1;
  // Searches that read every node's position each cycle.
  const bool all_needed = !model.rigid_walls.empty() || !model.sensors.empty() ||
                          !model.switching.at_start.empty() || !model.switching.automatic.empty();

  for (const auto& [pid, card] : model.part_modes) {
    // 10-node tetrahedra (ELFORM 16) have not been verified as flexible bodies (their mode
    // shapes, stiffening and switching): refused rather than run untested.
    for (const auto& block : state.hex_blocks) {
      if (block.part_id == pid && block.quadratic_tetrahedra())
        throw InputError(context_of(card.where, "PID"),
                         fmt::format("part {} has 10-node tetrahedra (*SECTION_SOLID ELFORM 16): "
                                     "*PART_MODES flexible bodies are not supported for them",
                                     pid));
    }
    // A deformable part becomes a flexible body when it is switched to rigid
    // (switching/flexible_switching.hpp).
    if (model.materials.at(model.parts.at(pid).mid).kind != model::MaterialKind::Rigid) continue;
    int index = -1;
    for (std::size_t b = 0; b < rigid.bodies.size(); ++b) {
      if (!rigid.bodies[b].nodal && rigid.bodies[b].id == pid) index = static_cast<int>(b);
    }
    if (index < 0) {
      throw InputError(context_of(card.where, "PID"),
                       fmt::format("part {} is not the lead part of a rigid body", pid));
    }
    RigidBody& body = rigid.bodies[index];
    if (body.inertia_from_card) {
      throw InputError(context_of(card.where, "PID"),
                       fmt::format("rigid body {} takes mass from *PART_INERTIA; a flexible body "
                                   "needs the nodal masses its modes are normalised with",
                                   pid));
    }
    const SelectedModes selected = select_part_modes(card, fmt::format("flexible body {}", pid),
                                                     body.nodes, nodes, loader, &state.rotations);
    modal::ModeInput input;
    input.form = card.form == 1 ? modal::ModalForm::kFast : modal::ModalForm::kExact;
    input.initial_rotation = body.initial_rotation;
    const std::size_t bn = body.nodes.size();
    input.mass.resize(bn);
    input.body_coords.resize(3 * bn);
    for (std::size_t k = 0; k < bn; ++k) {
      input.mass[k] = nodes.mass[body.nodes[k]];
      input.body_coords[3 * k] = body.body_coordinates.x[k];
      input.body_coords[3 * k + 1] = body.body_coordinates.y[k];
      input.body_coords[3 * k + 2] = body.body_coordinates.z[k];
    }
    input.shapes_global = selected.shapes;
    input.eigenvalues = selected.eigenvalues;
    input.damping = selected.damping;
    input.rotation_position = selected.rotation_position;
    input.rotation_shapes_global = selected.rotation_shapes;
    for (const std::int32_t k : selected.rotation_position) {
      input.rotational_inertia.push_back(
          state.rotations.inertia[static_cast<std::size_t>(state.rotations.index(body.nodes[k]))]);
    }
    // Geometric stiffening (FORM 0): the body's 8-node hexahedra and its material. The cubic
    // invariants cost n^3 per step and n^3 x (Gauss points) once: above kMaxStiffeningModes
    // modes they are left out (with a notice).
    constexpr int kMaxStiffeningModes = 40;
    if (input.form == modal::ModalForm::kExact) {
      if (static_cast<int>(selected.file_modes.size()) > kMaxStiffeningModes) {
        rigid.warnings.push_back(
            {card.where, fmt::format("flexible body {}: {} modes, geometric stiffening (FORM 0) "
                                     "is computed for at most {} modes and is left out",
                                     pid, selected.file_modes.size(), kMaxStiffeningModes)});
      } else {
        // The cubic invariants come from the body's 8-node hexahedra; shells and beams of the
        // body add none (docs/flexible_bodies.md, What is left).
        bool structural = false;
        for (const auto& block : state.shell_blocks) {
          structural = structural || std::find(body.parts.begin(), body.parts.end(),
                                               block.part_id) != body.parts.end();
        }
        for (const auto& block : state.beam_blocks) {
          structural = structural || std::find(body.parts.begin(), body.parts.end(),
                                               block.part_id) != body.parts.end();
        }
        if (structural) {
          rigid.warnings.push_back(
              {card.where, fmt::format("flexible body {}: geometric stiffening (FORM 0) is "
                                       "computed from hexahedra only; its shells and beams "
                                       "add none",
                                       pid)});
        }
        std::unordered_map<std::int32_t, std::int32_t> position;
        for (std::size_t k = 0; k < bn; ++k) {
          position.emplace(body.nodes[k], static_cast<std::int32_t>(k));
        }
        for (const auto& block : state.hex_blocks) {
          if (std::find(body.parts.begin(), body.parts.end(), block.part_id) == body.parts.end() ||
              block.order != 1 || block.quadratic_tetrahedra()) {
            continue;
          }
          for (const std::int32_t i : block.conn) input.hexahedra.push_back(position.at(i));
          const auto& mat = model.materials.at(model.parts.at(block.part_id).mid);
          input.lame_mu = mat.e / (2.0 * (1.0 + mat.pr));
          input.lame_lambda = mat.e * mat.pr / ((1.0 + mat.pr) * (1.0 - 2.0 * mat.pr));
        }
      }
    }
    modal::FlexibleBody flexible;
    try {
      flexible = modal::prepare_flexible_body(input);
    } catch (const std::invalid_argument& e) {
      throw InputError(context_of(card.where, "FILENAME"),
                       fmt::format("flexible body {} ('{}'): {}", pid, card.path, e.what()));
    }
    flexible.body = index;
    flexible.part = pid;
    flexible.file_modes = selected.file_modes;
    std::vector<std::uint8_t> in_ansid(nodes.size(), 0);
    if (card.ansid != 0) {
      for (const auto i : resolve_nodes(model, node_index, state, model::Target::NodeSet,
                                        card.ansid, card.where, "ANSID")) {
        in_ansid[i] = 1;
      }
    }
    for (std::size_t k = 0; k < bn; ++k) {
      const auto i = body.nodes[k];
      if (all_needed || needed[i] || in_ansid[i]) {
        flexible.active.push_back(static_cast<std::int32_t>(k));
        flexible.active_nodes.push_back(i);
      } else {
        flexible.passive.push_back(static_cast<std::int32_t>(k));
      }
    }
    body.update = NodeUpdate::kCurvilinear;
    body.flexible = static_cast<int>(rigid.flexible.size());
    rigid.flexible.push_back(std::move(flexible));
  }
  rigid.modal_work_velocity.assign(3 * nodes.size(), 0.0);
  if (!state.rotations.empty()) {
    rigid.modal_rotation_velocity.assign(3 * state.rotations.size(), 0.0);
    rigid.modal_rotation_work_velocity.assign(3 * state.rotations.size(), 0.0);
  }
}

void gather_modal_forces(const RigidBody& body, modal::FlexibleBody& f, const NodalState& nodes,
                         const RotationalState& rotations) {
  const std::size_t n = f.mode_count;
  std::fill(f.force.begin(), f.force.end(), 0.0);
  const Eigen::Matrix3d rt = body.state.rotation.transpose();
  for (std::size_t a = 0; a < f.active.size(); ++a) {
    const std::size_t k = static_cast<std::size_t>(f.active[a]);
    const std::int32_t i = f.active_nodes[a];
    const Eigen::Vector3d global(nodes.f_ext.x[i] - nodes.f_int.x[i],
                                 nodes.f_ext.y[i] - nodes.f_int.y[i],
                                 nodes.f_ext.z[i] - nodes.f_int.z[i]);
    if (global.x() == 0.0 && global.y() == 0.0 && global.z() == 0.0) continue;
    const Eigen::Vector3d local = rt * global;
    for (int d = 0; d < 3; ++d) {
      const double* row = f.shape_row(k, d);
      const double fd = local[d];
      for (std::size_t m = 0; m < n; ++m) f.force[m] += row[m] * fd;
    }
  }
  if (f.rotation_count == 0) return;
  for (std::size_t a = 0; a < f.active.size(); ++a) {  // nodal moments through Psi
    const std::int32_t j = f.rotation_of[static_cast<std::size_t>(f.active[a])];
    if (j < 0) continue;
    const std::int32_t r = rotations.index(f.active_nodes[a]);
    const Eigen::Vector3d global(rotations.m_ext.x[r] - rotations.m_int.x[r],
                                 rotations.m_ext.y[r] - rotations.m_int.y[r],
                                 rotations.m_ext.z[r] - rotations.m_int.z[r]);
    if (global.x() == 0.0 && global.y() == 0.0 && global.z() == 0.0) continue;
    const Eigen::Vector3d local = rt * global;
    for (int d = 0; d < 3; ++d) {
      const double* row = f.rotation_row(static_cast<std::size_t>(j), d);
      const double md = local[d];
      for (std::size_t m = 0; m < n; ++m) f.force[m] += row[m] * md;
    }
  }
}

void set_flexible_node_velocities(const RigidBody& body, const modal::FlexibleBody& f, double dt,
                                  NodalState& nodes, std::vector<double>& work_velocity,
                                  const RotationalState& rotations,
                                  std::vector<double>& rotation_velocity,
                                  std::vector<double>& rotation_work_velocity) {
  const rigid::RigidBodyState& s = body.state;
  const double inv_dt = dt > 0.0 ? 1.0 / dt : 0.0;
  const Eigen::Matrix3d& r_old = s.previous_rotation;
  for (std::size_t a = 0; a < f.active.size(); ++a) {
    const std::size_t k = static_cast<std::size_t>(f.active[a]);
    const std::int32_t i = f.active_nodes[a];
    const Eigen::Vector3d target = s.centre + s.rotation * body_position(f, k, f.q);
    if (dt > 0.0) {
      nodes.v.x[i] = (target.x() - nodes.x.x[i]) * inv_dt;
      nodes.v.y[i] = (target.y() - nodes.x.y[i]) * inv_dt;
      nodes.v.z[i] = (target.z() - nodes.x.z[i]) * inv_dt;
    }
    const Eigen::Vector3d w = r_old * f.displacement(k, f.s_mid);
    work_velocity[3 * i] = w.x();
    work_velocity[3 * i + 1] = w.y();
    work_velocity[3 * i + 2] = w.z();
  }
  if (f.rotation_count == 0) return;
  // Rotations are velocities only (the kernels integrate no nodal orientation): the node turns
  // with the body (Simulation::update_rotations) plus the modal rotation increment of the step,
  // R^{n+1} Psi_j (q^{n+1} - q^n) / dt; its work velocity R^n Psi_j s_mid as for translations.
  for (std::size_t a = 0; a < f.active.size(); ++a) {
    const std::int32_t j = f.rotation_of[static_cast<std::size_t>(f.active[a])];
    if (j < 0) continue;
    const std::size_t r = static_cast<std::size_t>(rotations.index(f.active_nodes[a]));
    const std::size_t row = static_cast<std::size_t>(j);
    const Eigen::Vector3d w =
        s.rotation * ((f.rotation(row, f.q) - f.rotation(row, f.q_previous)) * inv_dt);
    const Eigen::Vector3d work = r_old * f.rotation(row, f.s_mid);
    for (int d = 0; d < 3; ++d) {
      rotation_velocity[3 * r + d] = w[d];
      rotation_work_velocity[3 * r + d] = work[d];
    }
  }
}

void place_flexible_nodes(const RigidBody& body, const modal::FlexibleBody& f, NodalState& nodes) {
  const rigid::RigidBodyState& s = body.state;
  for (std::size_t a = 0; a < f.active.size(); ++a) {
    const std::size_t k = static_cast<std::size_t>(f.active[a]);
    const std::int32_t i = f.active_nodes[a];
    const Eigen::Vector3d x = s.centre + s.rotation * body_position(f, k, f.q);
    nodes.x.x[i] = x.x();
    nodes.x.y[i] = x.y();
    nodes.x.z[i] = x.z();
  }
}

void reconstruct_passive_nodes(const RigidSystem& rigid, State& state) {
  NodalState& nodes = state.nodes;
  const double dt = state.dt;
  for (const auto& f : rigid.flexible) {
    const RigidBody& body = rigid.bodies[f.body];
    const rigid::RigidBodyState& s = body.state;
    for (const std::int32_t k : f.passive) {
      const std::int32_t i = body.nodes[k];
      const Eigen::Vector3d now =
          s.previous_centre + s.previous_rotation * body_position(f, k, f.q_previous);
      const Eigen::Vector3d next = s.centre + s.rotation * body_position(f, k, f.q);
      nodes.x.x[i] = now.x();
      nodes.x.y[i] = now.y();
      nodes.x.z[i] = now.z();
      if (dt > 0.0) {
        nodes.v.x[i] = (next.x() - now.x()) / dt;
        nodes.v.y[i] = (next.y() - now.y()) / dt;
        nodes.v.z[i] = (next.z() - now.z()) / dt;
      }
    }
  }
}

void initialize_modal_velocities(const RigidBody& body, modal::FlexibleBody& f,
                                 const std::vector<double>& initial_velocities, NodalState& nodes,
                                 const RotationalState* rotations) {
  const rigid::RigidBodyState& s = body.state;
  const Eigen::Matrix3d rt = s.rotation.transpose();
  std::fill(f.s.begin(), f.s.end(), 0.0);
  for (std::size_t k = 0; k < body.nodes.size(); ++k) {
    const std::int32_t i = body.nodes[k];
    const Eigen::Vector3d x(nodes.x.x[i], nodes.x.y[i], nodes.x.z[i]);
    const Eigen::Vector3d v(initial_velocities[3 * k], initial_velocities[3 * k + 1],
                            initial_velocities[3 * k + 2]);
    const Eigen::Vector3d relative =
        rt * (v - s.velocity - s.angular_velocity.cross(x - s.centre)) * f.mass[k];
    for (int d = 0; d < 3; ++d) {
      const double* row = f.shape_row(k, d);
      for (std::size_t m = 0; m < f.mode_count; ++m) f.s[m] += row[m] * relative[d];
    }
  }
  // Nodes with rotations: s_k += sum_j J_j psi_jk . R^T (omega_j - w), from their initial
  // angular velocities (the nodes turn with the body from the first update on).
  if (rotations != nullptr) {
    for (std::size_t j = 0; j < f.rotation_count; ++j) {
      const std::int32_t i = body.nodes[static_cast<std::size_t>(f.rotation_position[j])];
      const std::int32_t r = rotations->index(i);
      const Eigen::Vector3d w(rotations->w.x[r], rotations->w.y[r], rotations->w.z[r]);
      const Eigen::Vector3d relative = rt * (w - s.angular_velocity) * f.rotational_inertia[j];
      for (int d = 0; d < 3; ++d) {
        const double* row = f.rotation_row(j, d);
        for (std::size_t m = 0; m < f.mode_count; ++m) f.s[m] += row[m] * relative[d];
      }
    }
  }
  for (std::size_t k = 0; k < body.nodes.size(); ++k) {
    const std::int32_t i = body.nodes[k];
    const Eigen::Vector3d u = s.rotation * f.displacement(k, f.s);
    nodes.v.x[i] += u.x();
    nodes.v.y[i] += u.y();
    nodes.v.z[i] += u.z();
  }
}

}  // namespace rf::solver
