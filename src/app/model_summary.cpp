#include "app/model_summary.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "element/kernels.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "solver/simulation.hpp"

namespace rf::app {

namespace {

// The failure criteria of an erodible block (solver/erosion.hpp), one line for the summary.
std::string erosion_line(const element::ErosionState& erosion) {
  if (!erosion.enabled) return "";
  const element::ErosionCriteria& c = erosion.criteria;
  std::vector<std::string> items;
  if (c.plastic_strain > 0.0) items.push_back(fmt::format("plastic strain {:g}", c.plastic_strain));
  if (c.damage) items.push_back("Johnson-Cook damage 1");
  if (c.tdel > 0.0) items.push_back(fmt::format("step below TDEL {:g}", c.tdel));
  if (c.below_minimum_step) items.push_back("step below TSMIN (*CONTROL_TIMESTEP ERODE)");
  if (c.add_erosion()) {
    std::vector<std::string> a;
    if (c.has_max_pressure) a.push_back(fmt::format("MXPRES {:g}", c.max_pressure));
    if (c.has_min_pressure) a.push_back(fmt::format("MNPRES {:g}", c.min_pressure));
    if (c.has_principal_stress) a.push_back(fmt::format("SIGP1 {:g}", c.principal_stress));
    if (c.has_von_mises) a.push_back(fmt::format("SIGVM {:g}", c.von_mises));
    if (c.has_volumetric_strain) a.push_back(fmt::format("VOLEPS {:g}", c.volumetric_strain));
    if (c.has_failure_time) a.push_back(fmt::format("FAILTM {:g}", c.failure_time));
    if (c.has_max_principal_strain) a.push_back(fmt::format("MXEPS {:g}", c.max_principal_strain));
    if (c.has_min_principal_strain) a.push_back(fmt::format("MNEPS {:g}", c.min_principal_strain));
    if (c.has_effective_strain) a.push_back(fmt::format("EFFEPS {:g}", c.effective_strain));
    if (c.has_shear_strain) a.push_back(fmt::format("EPSSH {:g}", c.shear_strain));
    if (c.has_tuler_butcher)
      a.push_back(fmt::format("Tuler-Butcher SIGTH {:g} IMPULSE {:g}", c.threshold_stress,
                              c.stress_impulse));
    items.push_back(fmt::format("*MAT_ADD_EROSION {} (NCS {}, NUMFIP {:g})", fmt::join(a, ", "),
                                c.criteria_at_once, c.failed_points));
  }
  return fmt::format("    erodes at: {}\n", fmt::join(items, "; "));
}

// The ELFORM as the deck wrote it (ELFORM 10 tetrahedra run the ELFORM 1 kernel).
int section_elform(const model::Model& model, model::Id secid, int kernel_elform) {
  const auto it = model.solid_sections.find(secid);
  return it != model.solid_sections.end() ? it->second.elform : kernel_elform;
}

const char* shape_of(const model::SolidElement& e) {
  if (e.ten_node) return "10-node tetrahedron";
  std::set<model::Id> distinct(e.nodes.begin(), e.nodes.end());
  switch (distinct.size()) {
    case 4:
      return "tetrahedron";
    case 5:
      return "pyramid";
    case 6:
      return "wedge";
    case 8:
      return "hexahedron";
    default:
      return "degenerate";
  }
}

}  // namespace

void print_model_summary(const model::Model& model, std::FILE* out) {
  // Building the simulation validates every cross reference exactly as `run` would.
  solver::SimulationOptions options;
  options.relax = false;  // reported below, run by `run`
  const solver::Simulation sim(model, options);
  print_model_summary(model, sim, out);
}

void print_model_summary(const model::Model& model, const solver::Simulation& sim, std::FILE* out) {
  const solver::State& state = sim.state();

  std::map<std::string, std::int64_t> shapes;
  for (const auto& e : model.solids) ++shapes[shape_of(e)];

  fmt::print(out, "title: {}\n", model.title.empty() ? "(none)" : model.title);
  fmt::print(out, "dialect: {} ({})\n", model.dialect == "impetus" ? "IMPETUS" : "LS-DYNA",
             model.dialect_reason);
  if (!model.unit_system.empty()) fmt::print(out, "unit system: {}\n", model.unit_system);
  fmt::print(out, "files: {}\n", model.files.size());
  for (const auto& f : model.files) fmt::print(out, "  {}\n", f);
  fmt::print(out, "nodes: {}", model.nodes.size());
  if (model.merged_node_count > 0) {
    fmt::print(out, " (after merging {} duplicated nodes)", model.merged_node_count);
  }
  if (state.generated_node_count > 0) {
    fmt::print(out,
               ", plus {} created by *CHANGE_P-ORDER or *ELEMENT_SOLID_TET4TOTET10 ({} in all)",
               state.generated_node_count, state.nodes.size());
  }
  fmt::print(out, "\n");
  fmt::print(out, "solid elements: {}\n", model.solids.size());
  for (const auto& [shape, count] : shapes) fmt::print(out, "  {}: {}\n", shape, count);
  fmt::print(out, "parts: {}\n", model.parts.size());
  double total_mass = 0.0;
  for (double m : state.nodes.mass) total_mass += m;
  for (const auto& block : state.hex_blocks) {
    const auto& part = model.parts.at(block.part_id);
    const auto& mat = model.materials.at(part.mid);
    if (block.rigid) {
      fmt::print(out, "  part {} '{}': {} elements (order {}), material {} {} (rho {:g}), rigid\n",
                 part.id, part.title, block.size(), block.order, mat.id, mat.keyword, mat.rho);
      continue;
    }
    double dt = 0.0;
    const element::NodalView view{state.nodes.x.x.data(), state.nodes.x.y.data(),
                                  state.nodes.x.z.data(), state.nodes.v.x.data(),
                                  state.nodes.v.y.data(), state.nodes.v.z.data()};
    dt = element::block_critical_timestep(block, view).min_dt;
    const int deck_elform = section_elform(model, part.secid, block.elform);
    const bool tetrahedra = deck_elform == 10 || deck_elform == 13 || deck_elform == 16;
    fmt::print(
        out,
        "  part {} '{}': {} elements, {}, material {} {} "
        "(rho {:g}, E {:g}, nu {:g}){}, element step {:.4g}\n",
        part.id, part.title, block.size(),
        block.order > 1 ? fmt::format("order {} ({} nodes, GLL, total-Lagrangian neo-Hookean)",
                                      block.order, block.nodes_per_element())
                        : fmt::format("section {} (ELFORM {})", part.secid, deck_elform),
        mat.id, mat.keyword, mat.rho, mat.e, mat.pr,
        block.order > 1
            ? std::string()
            : fmt::format(", {}, {}",
                          // Tetrahedra (ELFORM 10, 13) have no hourglass modes: no control runs.
                          tetrahedra ? std::string("no hourglass modes (tetrahedra)")
                                     : fmt::format("hourglass IHQ {} QM {:g}", block.hourglass.ihq,
                                                   block.hourglass.qm),
                          block.bulk_viscosity.on()
                              ? fmt::format("bulk viscosity Q1 {:g} Q2 {:g}",
                                            block.bulk_viscosity.q1, block.bulk_viscosity.q2)
                              : std::string("no bulk viscosity")),
        dt);
    fmt::print(out, "{}", erosion_line(block.erosion));
  }
  // Shell and beam parts with their sections (and the step of the deformable ones).
  if (!model.shells.empty() || !model.beams.empty()) {
    fmt::print(out, "shell elements: {}, beam elements: {}\n", model.shells.size(),
               model.beams.size());
  }
  const element::NodalView view{state.nodes.x.x.data(), state.nodes.x.y.data(),
                                state.nodes.x.z.data(), state.nodes.v.x.data(),
                                state.nodes.v.y.data(), state.nodes.v.z.data()};
  for (const auto& block : state.shell_blocks) {
    const auto& part = model.parts.at(block.part_id);
    const auto& mat = model.materials.at(part.mid);
    std::int64_t triangles = 0;
    for (const auto t : block.triangle) triangles += t;
    fmt::print(out,
               "  part {} '{}': {} shells ({} triangles), *SECTION_SHELL {} (ELFORM {}, NIP {} {}, "
               "SHRF {:g}, T1 {:g}), material {} {} (rho {:g}, E {:g}, nu {:g}){}\n",
               part.id, part.title, block.size(), triangles, part.secid, block.elform, block.nip,
               block.rule == element::ThroughThicknessRule::kLobatto ? "Lobatto" : "Gauss",
               block.shear_factor, block.thickness.empty() ? 0.0 : block.thickness.front(), mat.id,
               mat.keyword, mat.rho, mat.e, mat.pr,
               block.rigid
                   ? std::string(", rigid")
                   : fmt::format(", {}{}, element step {:.4g}",
                                 block.elform == 16
                                     ? std::string("no hourglass control (fully integrated)")
                                     : fmt::format("hourglass IHQ {} QM {:g}", block.hourglass.ihq,
                                                   block.hourglass.qm),
                                 block.bulk_viscosity.on()
                                     ? fmt::format(", membrane bulk viscosity Q1 {:g} "
                                                   "Q2 {:g}",
                                                   block.bulk_viscosity.q1, block.bulk_viscosity.q2)
                                     : std::string(),
                                 element::shell_critical_timestep(block, view).min_dt));
    fmt::print(out, "{}", erosion_line(block.erosion));
  }
  for (const auto& block : state.beam_blocks) {
    const auto& part = model.parts.at(block.part_id);
    const auto& mat = model.materials.at(part.mid);
    static constexpr const char* kName[] = {"", "Hughes-Liu", "Belytschko-Schwer", "truss"};
    fmt::print(out,
               "  part {} '{}': {} beams, *SECTION_BEAM {} (ELFORM {} {}), material {} {} (rho "
               "{:g}, E {:g}, nu {:g}){}\n",
               part.id, part.title, block.size(), part.secid, block.elform,
               kName[std::clamp(block.elform, 0, 3)], mat.id, mat.keyword, mat.rho, mat.e, mat.pr,
               block.rigid ? std::string(", rigid")
                           : fmt::format(", element step {:.4g}",
                                         element::beam_critical_timestep(block, view).min_dt));
    fmt::print(out, "{}", erosion_line(block.erosion));
  }
  if (!state.rotations.empty()) {
    fmt::print(out, "nodes with rotations: {}\n", state.rotations.size());
  }
  fmt::print(out, "total mass: {:.6g}\n", total_mass);
  const auto& rigid = sim.rigid_bodies();
  fmt::print(out, "rigid bodies: {} (*RIGID_BODY_UPDATE {})\n", rigid.bodies.size(),
             model.rigid_body_update);
  for (const auto& body : rigid.bodies) {
    const auto& s = body.state;
    std::string parts;
    for (const auto p : body.parts) parts += fmt::format("{}{}", parts.empty() ? "" : ", ", p);
    fmt::print(out,
               "  {} {}{}: {} nodes, mass {:.6g}{}, centre ({:.6g}, {:.6g}, {:.6g}), principal "
               "inertias {:.6g}, {:.6g}, {:.6g}, {} update{}{}\n",
               body.weld ? "spot weld" : (body.nodal ? "nodal rigid body" : "rigid body"), body.id,
               parts.empty() ? "" : fmt::format(" (parts {})", parts), body.nodes.size(), s.mass,
               body.inertia_from_card ? " (inertia card)" : "", s.centre.x(), s.centre.y(),
               s.centre.z(), s.principal_inertia[0], s.principal_inertia[1], s.principal_inertia[2],
               body.update == solver::NodeUpdate::kLinear ? "linear" : "curvilinear",
               body.shares_nodes ? ", shares nodes with deformable elements" : "",
               s.constraints.empty()
                   ? ""
                   : fmt::format(", {} translation and {} rotation constraint(s)",
                                 s.constraints.translation_count, s.constraints.rotation_count));
  }
  if (!sim.joint_stiffnesses().empty()) {  // *CONSTRAINED_JOINT_STIFFNESS_GENERALIZED
    fmt::print(out, "joint stiffnesses: {}\n", sim.joint_stiffnesses().joints.size());
    for (const auto& j : sim.joint_stiffnesses().joints) {
      fmt::print(out, "  joint stiffness {}: parts {} (A) and {} (B){}, stability limit {:.4g}\n",
                 j.id, j.pida, j.pidb,
                 j.jid != 0 ? fmt::format(", reported with joint {}", j.jid) : "", j.critical_step);
    }
  }
  const auto& walls = sim.rigid_walls().walls;
  auto wall_shape_name = [](const contact::RigidWall& wall) -> std::string {
    switch (wall.shape) {
      case contact::WallShape::Prism:
        return fmt::format("prism (depth {:g})", wall.depth);
      case contact::WallShape::Cylinder:
        return wall.kept_inside.empty() || !wall.kept_inside.front() ? "cylinder"
                                                                     : "cylinder (interior)";
      case contact::WallShape::Sphere:
        return "sphere";
      case contact::WallShape::Plane:
        break;
    }
    return wall.geometric ? "flat" : "planar";
  };
  auto extent = [](double length) {
    return length > 0.0 ? fmt::format("{:g}", length) : std::string("unbounded");
  };
  fmt::print(out, "rigid walls: {}\n", walls.size());
  for (const auto& wall : walls) {
    const auto& n = wall.normal;
    const auto& p = wall.origin;
    fmt::print(
        out,
        "  rigid wall {}{}: {}, {}, {}, point ({:.6g}, {:.6g}, {:.6g}), normal ({:.6g}, "
        "{:.6g}, {:.6g}), {} tracked nodes, {}{}\n",
        wall.number, wall.id != wall.number ? fmt::format(" (ID {})", wall.id) : "",
        wall_shape_name(wall),
        wall.shape == contact::WallShape::Cylinder || wall.shape == contact::WallShape::Sphere
            ? fmt::format("radius {:g}", wall.radius)
        : wall.finite ? fmt::format("finite {} x {}", extent(wall.length_l), extent(wall.length_m))
                      : "infinite",
        wall.moving       ? fmt::format("moving (mass {:g}, V0 {:g})", wall.mass, wall.velocity)
        : wall.prescribed ? std::string("prescribed motion (_MOTION)")
                          : std::string("fixed"),
        p.x(), p.y(), p.z(), n.x(), n.y(), n.z(), wall.nodes.size(),
        wall.no_sliding       ? "no sliding"
        : wall.friction > 0.0 ? fmt::format("Coulomb friction {:g}", wall.friction)
                              : "frictionless",
        wall.birth > 0.0 || wall.death < 1e20
            ? fmt::format(", birth {:g}, death {:g}", wall.birth, wall.death)
            : "");
  }
  const auto& contacts = sim.contacts().interfaces;
  if (!contacts.empty()) fmt::print(out, "contacts: {}\n", contacts.size());
  for (const auto& c : contacts) {
    static const char* const kKind[] = {"surface to surface", "nodes to surface",
                                        "one way surface to surface", "single surface"};
    std::array<std::size_t, 2> shells{};  // two-sided segments per side
    for (int side = 0; side < 2; ++side) {
      for (const auto flag : c.sides[side].two_sided) shells[side] += flag;
    }
    const std::string shell_note =
        shells[0] + shells[1] > 0
            ? fmt::format(", shell segments {} / {} (two-sided, at half the thickness)", shells[0],
                          shells[1])
            : "";
    fmt::print(
        out, "  contact {}{}: {}, {} slave nodes / {} segments, {} master segments, {}, {}{}{}{}\n",
        c.id, c.heading.empty() ? "" : fmt::format(" ({})", c.heading),
        kKind[static_cast<int>(c.kind)], c.sides[0].nodes.size(), c.sides[0].segments.size(),
        c.sides[1].segments.size(), c.soft == 1 ? "SOFT 1" : "SOFT 0",
        c.fs > 0.0 || c.fd > 0.0 ? fmt::format("friction FS {:g} FD {:g}", c.fs, c.fd)
                                 : "frictionless",
        c.vdc > 0.0 ? fmt::format(", VDC {:g}", c.vdc) : "",
        c.birth > 0.0 || c.death < 1e20 ? fmt::format(", birth {:g}, death {:g}", c.birth, c.death)
                                        : "",
        shell_note);
  }
  if (model.switching.flagged) {
    const auto& sw = model.switching;
    fmt::print(out,
               "part switching: {} switched at the start, {} automatic set(s), {} inertia "
               "card(s)\n",
               sw.at_start.size(), sw.automatic.size(), sw.inertia.size());
    for (const auto& set : sw.automatic) {
      fmt::print(
          out,
          "  set {}: CODE {}, TIME1 {:g}, TIME2 {:g}, TIME3 {:g}{}, {} to rigid, {} to "
          "deformable{}{}{}\n",
          set.swset, set.code, set.time1, set.time2, set.time3,
          set.paired != 0
              ? fmt::format(", paired with {} ({})", set.relsw, set.paired > 0 ? "first" : "second")
              : "",
          set.to_rigid.size(), set.to_deformable.size(),
          set.dtmax > 0.0 ? fmt::format(", DTMAX {:g}", set.dtmax) : "",
          set.entno > 0
              ? fmt::format(", {} {}", set.code == 2 || set.code == 4 ? "contact" : "rigid wall",
                            set.entno)
              : "",
          set.offset > 0.0 ? fmt::format(", OFFSET {:g}", set.offset) : "");
    }
  }
  fmt::print(out, "node sets: {}, part sets: {}, segment sets: {}\n", model.node_sets.size(),
             model.part_sets.size(), model.segment_sets.size());
  fmt::print(out, "curves: {}\n", model.curves.size());
  for (const auto& [id, c] : model.curves) {
    if (c.function) {
      fmt::print(out, "  curve {}: f(time) = {}\n", id, c.function_text);
    } else {
      fmt::print(out, "  curve {}: {} points\n", id, c.abscissa.size());
    }
  }
  fmt::print(out,
             "SPCs: {}, prescribed motions: {}, nodal loads: {}, body loads: {}, "
             "initial velocities: {}\n",
             model.spcs.size(), model.prescribed_motions.size(), model.nodal_loads.size(),
             model.body_loads.size(), model.initial_velocities.size());
  if (!model.pressure_loads.empty()) {
    fmt::print(out, "pressure loads: {}\n", model.pressure_loads.size());
  }
  if (!model.sensors.empty() || !model.sensor_controls.empty()) {
    int kinds[3] = {0, 0, 0};  // node, element, function
    for (const auto& [id, s] : model.sensors) ++kinds[static_cast<int>(s.kind)];
    fmt::print(out, "sensors: {} ({} node, {} element, {} function), switches: {}, controls: {}\n",
               model.sensors.size(), kinds[0], kinds[1], kinds[2], model.sensor_switches.size(),
               model.sensor_controls.size());
    for (const auto& [id, c] : model.sensor_controls) {
      std::string switches;
      for (const auto w : c.switches) switches += fmt::format(" {}", w);
      fmt::print(out, "  control {}: {} switch set {}, initially {}, switches{}{}\n", id, c.type,
                 c.type_id, c.initially_on ? "ON" : "OFF", switches.empty() ? " none" : switches,
                 c.nrep == -1 ? ", repeated without end"
                 : c.nrep > 1 ? fmt::format(", {} passes", c.nrep)
                              : "");
    }
  }
  fmt::print(
      out, "termination: ENDTIM {:g}{}\n", model.termination.endtim,
      model.termination.endcyc > 0 ? fmt::format(", ENDCYC {}", model.termination.endcyc) : "");
  if (solver::dynamic_relaxation_requested(model)) {
    const auto& dr = model.dynamic_relaxation;
    fmt::print(out,
               "dynamic relaxation before the transient: DRTOL {:g}, DRFCTR {:g}, NRCYCK {}{} "
               "(curves with SIDR 1 act only then)\n",
               dr.drtol, dr.drfctr, dr.nrcyck,
               dr.drterm > 0.0 ? fmt::format(", DRTERM {:g}", dr.drterm) : "");
  }
  fmt::print(out, "time step: TSSFAC {:g}, first step {:.4g} (controlled by element {})\n",
             model.timestep.tssfac, state.dt, sim.controlling_element());
  fmt::print(out, "warnings: {}\n", model.warnings.size() + sim.warnings().size());
  for (const auto& w : model.warnings) fmt::print(out, "  {}\n", format_warning(w));
  for (const auto& w : sim.warnings()) fmt::print(out, "  {}\n", format_warning(w));
  if (!model.unknown_keywords.empty()) {
    fmt::print(out, "unknown keywords (ignored):\n");
    for (const auto& [kw, count] : model.unknown_keywords) fmt::print(out, "  {} x{}\n", kw, count);
  }
}

std::string format_warning(const model::Warning& warning) {
  std::string text;
  if (!warning.where.file.empty()) {
    text += warning.where.file;
    if (warning.where.line > 0) text += fmt::format(":{}", warning.where.line);
    text += ": ";
  }
  if (!warning.where.keyword.empty()) text += warning.where.keyword + ": ";
  return text + warning.message;
}

}  // namespace rf::app
