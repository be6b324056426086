#include "modal/stiffness_assembly.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "element/kernels.hpp"
#include "model/error.hpp"
#include "model/error_context.hpp"
#include "solver/boundary.hpp"
#include "solver/build_state.hpp"

namespace rf::modal {

namespace {

// Relative probe displacement (times the element's size). The kernels are smooth in u, so the
// central difference error is O(h^2) ~ 1e-10 relative; the total-Lagrangian p-element kernel
// forms x - X, which loses about 1e-16 |X| / (h L_e) to rounding, ~1e-9 relative for elements
// 100 times smaller than their distance from the origin.
constexpr double kProbe = 1e-5;

// Keeps the element matrices of one chunk within about this many doubles (64 MiB).
constexpr std::size_t kChunkDoubles = std::size_t{8} << 20;

// The probe mesh of `count` elements of `npe` nodes (connectivity `conn`, dense node indices):
// element e's local node a is probe node e npe + a (a repeated node maps to its first
// occurrence, as in the shared mesh), at the reference coordinates; `size` is each element's
// largest bounding-box side.
struct ProbeMesh {
  std::array<std::vector<double>, 3> x0;
  std::vector<std::int32_t> conn;
  std::vector<double> size;
};

ProbeMesh probe_mesh(const std::int32_t* conn, int npe, std::size_t count,
                     const solver::NodalState& nodes) {
  const std::size_t copies = count * static_cast<std::size_t>(npe);
  ProbeMesh mesh;
  for (auto& coordinate : mesh.x0) coordinate.assign(copies, 0.0);
  mesh.conn.resize(copies);
  mesh.size.assign(count, 0.0);
  const std::array<const std::vector<double>*, 3> ref{&nodes.x0.x, &nodes.x0.y, &nodes.x0.z};
  for (std::size_t e = 0; e < count; ++e) {
    const std::int32_t* c = conn + e * static_cast<std::size_t>(npe);
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    const std::size_t copy = e * static_cast<std::size_t>(npe);
    for (int a = 0; a < npe; ++a) {
      int b = 0;
      while (c[b] != c[a]) ++b;
      mesh.conn[copy + static_cast<std::size_t>(a)] = static_cast<std::int32_t>(copy + b);
      for (int d = 0; d < 3; ++d) {
        const double value = (*ref[d])[static_cast<std::size_t>(c[a])];
        mesh.x0[d][copy + static_cast<std::size_t>(a)] = value;
        lo[d] = std::min(lo[d], value);
        hi[d] = std::max(hi[d], value);
      }
    }
    mesh.size[e] = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  }
  return mesh;
}

}  // namespace

model::Model extract_parts(const model::Model& model, const std::vector<model::Id>& parts,
                           std::vector<std::string>* warnings) {
  std::set<model::Id> keep;
  for (const model::Id pid : parts) {
    if (model.parts.find(pid) == model.parts.end()) {
      throw InputError(InputErrorContext{}, fmt::format("part {} is not defined in the deck "
                                                        "(eigen analysis --parts)",
                                                        pid));
    }
    keep.insert(pid);
  }
  const bool all = keep.empty();

  model::Model sub;
  sub.title = model.title;
  sub.dialect = model.dialect;
  sub.files = model.files;
  sub.solid_sections = model.solid_sections;
  sub.hourglass = model.hourglass;
  sub.hourglass_control = model.hourglass_control;
  sub.p_order_changes = model.p_order_changes;
  sub.cylinder_surfaces = model.cylinder_surfaces;
  sub.part_sets = model.part_sets;
  sub.coordinate_systems = model.coordinate_systems;
  sub.parameters = model.parameters;
  sub.implicit = model.implicit;

  sub.shell_sections = model.shell_sections;
  sub.beam_sections = model.beam_sections;
  sub.shell_control = model.shell_control;

  // Solids, shells and beams of the kept parts (shells and beams carry rotations: 6 DOFs per
  // node, docs/eigen.md). Discrete elements and point masses are not part of the analysis.
  std::unordered_set<model::Id> used_nodes;
  for (const auto& solid : model.solids) {
    if (!all && keep.count(solid.pid) == 0) continue;
    sub.solids.push_back(solid);
    for (const model::Id n : solid.nodes) used_nodes.insert(n);
    for (const model::Id n : solid.midside)  // 10-node tetrahedra (0: none, or created later)
      if (n != 0) used_nodes.insert(n);
  }
  for (const auto& shell : model.shells) {
    if (!all && keep.count(shell.pid) == 0) continue;
    sub.shells.push_back(shell);
    for (const model::Id n : shell.nodes) used_nodes.insert(n);
  }
  if (!model.beams.empty()) {
    std::unordered_map<model::Id, std::array<double, 3>> position;
    for (const auto& node : model.nodes) position.emplace(node.id, node.x);
    for (const auto& beam : model.beams) {
      if (!all && keep.count(beam.pid) == 0) continue;
      model::BeamElement b = beam;
      // The orientation node N3 is geometry only: a node outside the elements would be a
      // massless DOF of the analysis, so it becomes the equivalent orientation vector.
      if (!b.orientation && b.nodes[2] != 0) {
        const auto p1 = position.find(b.nodes[0]);
        const auto p3 = position.find(b.nodes[2]);
        if (p1 != position.end() && p3 != position.end()) {
          b.orientation =
              std::array<double, 3>{p3->second[0] - p1->second[0], p3->second[1] - p1->second[1],
                                    p3->second[2] - p1->second[2]};
          b.nodes[2] = 0;
        }
      }
      for (int k = 0; k < 2; ++k) used_nodes.insert(b.nodes[k]);
      if (b.nodes[2] != 0) used_nodes.insert(b.nodes[2]);  // unknown N3: build_state reports it
      sub.beams.push_back(std::move(b));
    }
  }
  if (sub.solids.empty() && sub.shells.empty() && sub.beams.empty()) {
    throw InputError(InputErrorContext{},
                     all ? std::string("the deck has no solid, shell or beam elements to analyse")
                         : fmt::format("the selected parts have no solid, shell or beam elements"));
  }
  if (warnings && !model.discretes.empty()) {
    warnings->push_back("*ELEMENT_DISCRETE springs and dampers are ignored by the eigen analysis");
  }
  for (const auto& node : model.nodes) {
    if (used_nodes.count(node.id)) sub.nodes.push_back(node);
  }
  for (const auto& [pid, part] : model.parts) {
    if (!all && keep.count(pid) == 0) continue;
    sub.parts.emplace(pid, part);
    const auto mat = model.materials.find(part.mid);
    if (mat == model.materials.end()) continue;  // build_state reports it with the part's card
    model::Material m = mat->second;
    if (m.kind == model::MaterialKind::Rigid) {
      // The *PART_MODES workflow: the transient deck has the part rigid, its modes come from
      // the same part made elastic with the *MAT_RIGID card's RO, E and PR.
      if (!(m.e > 0.0) || !(m.rho > 0.0)) {
        throw InputError(context_of(m.where, "E"),
                         fmt::format("part {} is *MAT_RIGID (material {}) without positive RO and "
                                     "E: the eigen analysis needs them to treat it as elastic",
                                     pid, m.id));
      }
      m.kind = model::MaterialKind::Elastic;
      if (warnings) {
        warnings->push_back(
            fmt::format("part {} is *MAT_RIGID: analysed as elastic with its "
                        "RO={:g}, E={:g}, PR={:g}",
                        pid, m.rho, m.e, m.pr));
      }
    }
    sub.materials[m.id] = m;
  }
  // Node sets restricted to the kept nodes; SPCs on nodes outside the sub-model dropped.
  for (const auto& [sid, set] : model.node_sets) {
    model::NodeSet s = set;
    s.nodes.clear();
    for (const model::Id n : set.nodes) {
      if (used_nodes.count(n)) s.nodes.push_back(n);
    }
    sub.node_sets.emplace(sid, std::move(s));
  }
  for (const auto& spc : model.spcs) {
    if (spc.target == model::Target::Node && used_nodes.count(spc.id) == 0) continue;
    if (spc.cid != 0) {
      throw InputError(context_of(spc.where, "CID"),
                       "the eigen analysis supports *BOUNDARY_SPC in global axes only (CID 0)");
    }
    sub.spcs.push_back(spc);
  }
  if (warnings && !model.prescribed_motions.empty()) {
    warnings->push_back(
        "*BOUNDARY_PRESCRIBED_MOTION is ignored by the eigen analysis (use *BOUNDARY_SPC to fix "
        "DOFs)");
  }
  return sub;
}

std::vector<double> element_stiffness_matrices(const element::HexBlock& source,
                                               const solver::NodalState& nodes, std::size_t first,
                                               std::size_t count) {
  const int npe = source.nodes_per_element();
  const std::size_t nd = 3 * static_cast<std::size_t>(npe);
  const std::size_t copies = count * static_cast<std::size_t>(npe);

  element::HexBlock probe;
  probe.part_id = source.part_id;
  probe.part_index = source.part_index;
  probe.elform = source.elform;
  probe.hourglass = source.hourglass;
  probe.material = source.material;
  probe.order = source.order;
  if (probe.order == 1 && probe.hourglass.ihq <= 3) probe.hourglass.ihq = 6;
  probe.element_id.assign(source.element_id.begin() + static_cast<std::ptrdiff_t>(first),
                          source.element_id.begin() + static_cast<std::ptrdiff_t>(first + count));

  // Every element gets its own copies of its nodes.
  ProbeMesh mesh =
      probe_mesh(&source.conn[first * static_cast<std::size_t>(npe)], npe, count, nodes);
  const std::array<std::vector<double>, 3>& x0 = mesh.x0;
  const std::vector<double>& size = mesh.size;
  probe.conn = std::move(mesh.conn);
  std::array<std::vector<double>, 3> x = x0, v;
  for (auto& velocity : v) velocity.assign(copies, 0.0);
  const element::NodalView view{x[0].data(), x[1].data(), x[2].data(),
                                v[0].data(), v[1].data(), v[2].data()};
  element::initialize_block(probe, view);
  const std::vector<double> stress0 = probe.stress;
  const std::vector<double> hourglass0 = probe.hourglass_state;

  std::vector<double> matrices(count * nd * nd, 0.0);
  for (int a = 0; a < npe; ++a) {
    for (int d = 0; d < 3; ++d) {
      const std::size_t column = 3 * static_cast<std::size_t>(a) + static_cast<std::size_t>(d);
      for (const double sign : {1.0, -1.0}) {
        for (int k = 0; k < 3; ++k) {
          std::copy(x0[k].begin(), x0[k].end(), x[k].begin());
          std::fill(v[k].begin(), v[k].end(), 0.0);
        }
        for (std::size_t e = 0; e < count; ++e) {
          const std::size_t copy = e * static_cast<std::size_t>(npe) + static_cast<std::size_t>(a);
          if (probe.conn[copy] != static_cast<std::int32_t>(copy)) continue;  // repeated node
          v[d][copy] = sign * size[e];
          x[d][copy] += sign * kProbe * size[e];
        }
        probe.stress = stress0;
        probe.hourglass_state = hourglass0;
        const element::KernelResult result = element::compute_block_forces(probe, view, kProbe);
        if (result.failed) {
          throw SolverError(fmt::format(
              "stiffness of part {}: element {} has a non-positive volume in the reference "
              "configuration",
              source.part_id, probe.element_id[static_cast<std::size_t>(result.failed_element)]));
        }
#pragma omp parallel for schedule(static)
        for (std::int64_t ie = 0; ie < static_cast<std::int64_t>(count); ++ie) {
          const std::size_t e = static_cast<std::size_t>(ie);
          const std::size_t copy = e * static_cast<std::size_t>(npe) + static_cast<std::size_t>(a);
          if (probe.conn[copy] != static_cast<std::int32_t>(copy)) continue;
          const double scale = sign / (2.0 * kProbe * size[e]);
          const double* f = &probe.force[e * nd];
          double* k = &matrices[e * nd * nd];
          for (std::size_t r = 0; r < nd; ++r) k[r * nd + column] += scale * f[r];
        }
      }
    }
  }
  return matrices;
}

namespace {

// Shell and beam blocks restricted to elements [first, first + count) on the probe nodes:
// element e's local node a is probe node e * npe + a (a repeated node maps to its first
// occurrence), its rotational index the same number (-1 for a truss). Initialised on the
// probe nodes, which start at the reference coordinates.
element::ShellBlock probe_block(const element::ShellBlock& source, std::size_t first,
                                std::size_t count, const element::NodalView& view,
                                const std::vector<std::int32_t>& conn) {
  element::ShellBlock probe = source;
  probe.owned = {};
  probe.step_scale.clear();
  probe.rigid = false;
  probe.has_force_slots = true;
  // Viscous hourglass control (IHQ 1-3) has no stiffness: the stiffness form IHQ 4, same QM.
  if (probe.hourglass.ihq <= 3) probe.hourglass.ihq = 4;
  // The tangent at the present thickness: probing must not thin the element.
  probe.thickness_update = 0;
  const auto from = static_cast<std::ptrdiff_t>(first),
             to = static_cast<std::ptrdiff_t>(first + count);
  probe.element_id.assign(source.element_id.begin() + from, source.element_id.begin() + to);
  probe.thickness.assign(source.thickness.begin() + 4 * from, source.thickness.begin() + 4 * to);
  probe.conn = conn;
  probe.rotation_conn = conn;
  element::initialize_shell_block(probe, view);
  return probe;
}

element::BeamBlock probe_block(const element::BeamBlock& source, std::size_t first,
                               std::size_t count, const element::NodalView& view,
                               const std::vector<std::int32_t>& conn) {
  element::BeamBlock probe = source;
  probe.owned = {};
  probe.step_scale.clear();
  probe.rigid = false;
  probe.has_force_slots = true;
  const auto from = static_cast<std::ptrdiff_t>(first),
             to = static_cast<std::ptrdiff_t>(first + count);
  probe.element_id.assign(source.element_id.begin() + from, source.element_id.begin() + to);
  probe.orientation.assign(source.orientation.begin() + 3 * from,
                           source.orientation.begin() + 3 * to);
  probe.conn = conn;
  probe.rotation_conn = conn;
  if (probe.elform == 3) std::fill(probe.rotation_conn.begin(), probe.rotation_conn.end(), -1);
  element::initialize_beam_block(probe, view);
  return probe;
}

element::KernelResult probe_forces(element::ShellBlock& block, const element::NodalView& nodes,
                                   const element::RotationalView& rotations, double dt) {
  return element::compute_shell_forces(block, nodes, rotations, dt);
}
element::KernelResult probe_forces(element::BeamBlock& block, const element::NodalView& nodes,
                                   const element::RotationalView& rotations, double dt) {
  return element::compute_beam_forces(block, nodes, rotations, dt);
}
constexpr int nodes_per_element(const element::ShellBlock&) {
  return 4;
}
constexpr int nodes_per_element(const element::BeamBlock&) {
  return 2;
}
bool has_rotations(const element::ShellBlock&) {
  return true;
}
bool has_rotations(const element::BeamBlock& block) {
  return block.elform != 3;
}

// Drilling stiffness of one shell element (the BLT kernel has none: the rotation of a node
// about the shell normal would be a zero-energy DOF of every node, docs/eigen.md). A penalty
// ties the drilling rotation n . theta_a of each distinct node a to the element's in-plane
// rotation omega = (dv/dx - du/dy) / 2 at the centroid (Hughes and Brezzi, Comput. Methods
// Appl. Mech. Engrg. 72 (1989) 105, with a small penalty instead of gamma = G): energy
// 1/2 k sum_a (n . theta_a - omega)^2, k = kDrillingFactor G t A / distinct nodes. Rigid
// motions have n . theta = omega, so they stay free; the element matrix gains k h_a h_a^T.
void add_drilling_stiffness(const element::ShellBlock& block, std::size_t e,
                            const solver::NodalState& nodes, double factor, double* k) {
  if (factor == 0.0) return;
  const std::int32_t* c = &block.conn[4 * e];
  const bool triangle = c[2] == c[3];
  const int distinct = triangle ? 3 : 4;
  Eigen::Vector3d p[4];
  for (int a = 0; a < 4; ++a) {
    const auto i = static_cast<std::size_t>(c[a]);
    p[a] = {nodes.x0.x[i], nodes.x0.y[i], nodes.x0.z[i]};
  }
  const Eigen::Vector3d d1 = triangle ? Eigen::Vector3d(p[1] - p[0]) : Eigen::Vector3d(p[2] - p[0]);
  const Eigen::Vector3d d2 = triangle ? Eigen::Vector3d(p[2] - p[0]) : Eigen::Vector3d(p[3] - p[1]);
  const Eigen::Vector3d n = d1.cross(d2).normalized();
  const Eigen::Vector3d e1 = (p[1] - p[0] - n.dot(p[1] - p[0]) * n).normalized();
  const Eigen::Vector3d e2 = n.cross(e1);
  double x[4], y[4];
  for (int a = 0; a < 4; ++a) {
    x[a] = e1.dot(p[a] - p[0]);
    y[a] = e2.dot(p[a] - p[0]);
  }
  // Centroid derivatives of the shape functions, b1 = dN/dx, b2 = dN/dy (Belytschko, Lin and
  // Tsay 1984, eq. 19, for the quadrilateral; the linear triangle's for a triangle).
  double b1[4] = {}, b2[4] = {}, area = 0.0;
  if (triangle) {
    const double twice = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    area = 0.5 * twice;
    b1[0] = (y[1] - y[2]) / twice, b1[1] = (y[2] - y[0]) / twice, b1[2] = (y[0] - y[1]) / twice;
    b2[0] = (x[2] - x[1]) / twice, b2[1] = (x[0] - x[2]) / twice, b2[2] = (x[1] - x[0]) / twice;
  } else {
    const double twice = (x[2] - x[0]) * (y[3] - y[1]) - (x[3] - x[1]) * (y[2] - y[0]);
    area = 0.5 * twice;
    b1[0] = (y[1] - y[3]) / twice, b1[1] = (y[2] - y[0]) / twice;
    b1[2] = (y[3] - y[1]) / twice, b1[3] = (y[0] - y[2]) / twice;
    b2[0] = (x[3] - x[1]) / twice, b2[1] = (x[0] - x[2]) / twice;
    b2[2] = (x[1] - x[3]) / twice, b2[3] = (x[2] - x[0]) / twice;
  }
  const double stiffness =
      factor * block.material.shear * block.element_thickness[e] * std::abs(area) / distinct;
  constexpr std::size_t nd = 24;
  for (int a = 0; a < distinct; ++a) {
    double h[nd] = {};
    for (int d = 0; d < 3; ++d) h[6 * a + 3 + d] = n[d];
    for (int b = 0; b < distinct; ++b) {
      const Eigen::Vector3d g = -0.5 * (b1[b] * e2 - b2[b] * e1);
      for (int d = 0; d < 3; ++d) h[6 * b + d] = g[d];
    }
    for (std::size_t r = 0; r < nd; ++r) {
      if (h[r] == 0.0) continue;
      for (std::size_t col = 0; col < nd; ++col) k[r * nd + col] += stiffness * h[r] * h[col];
    }
  }
}

// Central differences of the block's kernel forces and moments, as for hexahedra: column
// (a, d) from one kernel pass with every element's local node a moved along d (translation
// kProbe times the element size, or rotation kProbe rad), the others at rest.
template <class Block>
std::vector<double> structural_element_matrices(const Block& source,
                                                const solver::NodalState& nodes, std::size_t first,
                                                std::size_t count) {
  const int npe = nodes_per_element(source);
  const std::size_t nd = 6 * static_cast<std::size_t>(npe);
  const std::size_t copies = count * static_cast<std::size_t>(npe);
  const ProbeMesh mesh =
      probe_mesh(&source.conn[first * static_cast<std::size_t>(npe)], npe, count, nodes);
  const std::array<std::vector<double>, 3>& x0 = mesh.x0;
  const std::vector<double>& size = mesh.size;
  const std::vector<std::int32_t>& conn = mesh.conn;
  std::array<std::vector<double>, 3> x = x0, v, w;
  for (int d = 0; d < 3; ++d) {
    v[d].assign(copies, 0.0);
    w[d].assign(copies, 0.0);
  }
  const element::NodalView view{x[0].data(), x[1].data(), x[2].data(),
                                v[0].data(), v[1].data(), v[2].data()};
  const element::RotationalView spin{w[0].data(), w[1].data(), w[2].data()};
  Block probe = probe_block(source, first, count, view, conn);
  const Block pristine = probe;
  const int dofs = has_rotations(source) ? 6 : 3;

  std::vector<double> matrices(count * nd * nd, 0.0);
  for (int a = 0; a < npe; ++a) {
    for (int d = 0; d < dofs; ++d) {
      const std::size_t column = 6 * static_cast<std::size_t>(a) + static_cast<std::size_t>(d);
      for (const double sign : {1.0, -1.0}) {
        for (int k = 0; k < 3; ++k) {
          std::copy(x0[k].begin(), x0[k].end(), x[k].begin());
          std::fill(v[k].begin(), v[k].end(), 0.0);
          std::fill(w[k].begin(), w[k].end(), 0.0);
        }
        for (std::size_t e = 0; e < count; ++e) {
          const std::size_t copy = e * static_cast<std::size_t>(npe) + static_cast<std::size_t>(a);
          if (conn[copy] != static_cast<std::int32_t>(copy)) continue;  // repeated node
          if (d < 3) {
            v[d][copy] = sign * size[e];
            x[d][copy] += sign * kProbe * size[e];
          } else {
            w[d - 3][copy] = sign;
          }
        }
        probe = pristine;
        const element::KernelResult result = probe_forces(probe, view, spin, kProbe);
        if (result.failed) {
          throw SolverError(fmt::format(
              "stiffness of part {}: element {} failed in the reference configuration",
              source.part_id, probe.element_id[static_cast<std::size_t>(result.failed_element)]));
        }
#pragma omp parallel for schedule(static)
        for (std::int64_t ie = 0; ie < static_cast<std::int64_t>(count); ++ie) {
          const std::size_t e = static_cast<std::size_t>(ie);
          const std::size_t copy = e * static_cast<std::size_t>(npe) + static_cast<std::size_t>(a);
          if (conn[copy] != static_cast<std::int32_t>(copy)) continue;
          const double scale = sign / (2.0 * kProbe * (d < 3 ? size[e] : 1.0));
          const double* f = &probe.force[e * nd];
          double* k = &matrices[e * nd * nd];
          for (std::size_t r = 0; r < nd; ++r) k[r * nd + column] += scale * f[r];
        }
      }
    }
  }
  // A repeated node (a triangle's N4 = N3) has zero columns (it moves with its first
  // occurrence); the forces the kernel puts in its slot act on the same node, so its rows are
  // folded into the first occurrence's. A truss's moment rows are zero already.
#pragma omp parallel for schedule(static)
  for (std::int64_t ie = 0; ie < static_cast<std::int64_t>(count); ++ie) {
    const std::size_t e = static_cast<std::size_t>(ie);
    double* k = &matrices[e * nd * nd];
    for (int a = 0; a < npe; ++a) {
      const std::size_t copy = e * static_cast<std::size_t>(npe) + static_cast<std::size_t>(a);
      const std::size_t b =
          static_cast<std::size_t>(conn[copy]) - e * static_cast<std::size_t>(npe);
      if (b == static_cast<std::size_t>(a)) continue;
      for (std::size_t d = 0; d < 6; ++d) {
        for (std::size_t c = 0; c < nd; ++c) {
          k[(6 * b + d) * nd + c] += k[(6 * static_cast<std::size_t>(a) + d) * nd + c];
          k[(6 * static_cast<std::size_t>(a) + d) * nd + c] = 0.0;
        }
      }
    }
  }
  return matrices;
}

}  // namespace

std::vector<double> element_stiffness_matrices(const element::ShellBlock& block,
                                               const solver::NodalState& nodes, std::size_t first,
                                               std::size_t count, double drilling_factor) {
  std::vector<double> matrices = structural_element_matrices(block, nodes, first, count);
  for (std::size_t e = 0; e < count; ++e) {
    add_drilling_stiffness(block, first + e, nodes, drilling_factor, &matrices[e * 24 * 24]);
  }
  return matrices;
}

std::vector<double> element_stiffness_matrices(const element::BeamBlock& block,
                                               const solver::NodalState& nodes, std::size_t first,
                                               std::size_t count) {
  return structural_element_matrices(block, nodes, first, count);
}

namespace {

// K (the hexahedra's 3n x 3n translational block) becomes the whole (3n + 3r)^2 matrix with the
// shell and beam element matrices added: triplets in (block, element) order, summed by
// setFromTriplets in that fixed order (deterministic for any thread count).
// The shells' element matrices carry the drilling stiffness with `drilling_factor`; beams have
// a rotational stiffness about every axis and need none.
std::vector<double> structural_element_stiffness(const element::ShellBlock& block,
                                                 const solver::NodalState& nodes, std::size_t first,
                                                 std::size_t count, double drilling_factor) {
  return element_stiffness_matrices(block, nodes, first, count, drilling_factor);
}
std::vector<double> structural_element_stiffness(const element::BeamBlock& block,
                                                 const solver::NodalState& nodes, std::size_t first,
                                                 std::size_t count, double) {
  return element_stiffness_matrices(block, nodes, first, count);
}

template <class Block>
void add_block_triplets(const Block& block, const solver::State& state, std::size_t n,
                        double drilling_factor, std::vector<Eigen::Triplet<double>>& triplets,
                        double& asymmetry) {
  const int npe = static_cast<int>(block.conn.size() / std::max<std::size_t>(1, block.size()));
  const std::size_t nd = 6 * static_cast<std::size_t>(npe);
  const std::size_t chunk = std::max<std::size_t>(1, kChunkDoubles / (nd * nd));
  std::vector<std::int64_t> dof(nd);
  for (std::size_t first = 0; first < block.size(); first += chunk) {
    const std::size_t count = std::min(chunk, block.size() - first);
    const std::vector<double> ke =
        structural_element_stiffness(block, state.nodes, first, count, drilling_factor);
    for (std::size_t e = 0; e < count; ++e) {
      const std::size_t element = first + e;
      const double* k = &ke[e * nd * nd];
      for (int a = 0; a < npe; ++a) {
        const std::size_t slot =
            element * static_cast<std::size_t>(npe) + static_cast<std::size_t>(a);
        const std::int32_t node = block.conn[slot];
        const std::int32_t rotation = block.rotation_conn[slot];
        for (int d = 0; d < 6; ++d) {
          dof[6 * static_cast<std::size_t>(a) + static_cast<std::size_t>(d)] =
              d < 3 ? 3 * static_cast<std::int64_t>(node) + d
                    : (rotation < 0 ? -1
                                    : 3 * static_cast<std::int64_t>(n) +
                                          3 * static_cast<std::int64_t>(rotation) + (d - 3));
        }
      }
      double largest = 0.0, skew = 0.0;
      for (std::size_t r = 0; r < nd; ++r) {
        for (std::size_t c = 0; c < nd; ++c) {
          largest = std::max(largest, std::abs(k[r * nd + c]));
          if (c > r) skew = std::max(skew, std::abs(k[r * nd + c] - k[c * nd + r]));
        }
      }
      if (largest > 0.0) asymmetry = std::max(asymmetry, skew / largest);
      for (std::size_t r = 0; r < nd; ++r) {
        if (dof[r] < 0) continue;
        for (std::size_t c = 0; c < nd; ++c) {
          const double value = 0.5 * (k[r * nd + c] + k[c * nd + r]);
          if (dof[c] < 0 || value == 0.0) continue;
          triplets.emplace_back(static_cast<int>(dof[r]), static_cast<int>(dof[c]), value);
        }
      }
    }
  }
}

void add_structural_stiffness(const solver::State& state, double drilling_factor,
                              Eigen::SparseMatrix<double>& K, double& asymmetry) {
  const std::size_t n = state.nodes.size();
  const std::size_t ndof = 3 * n + 3 * state.rotations.size();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(K.nonZeros()));
  for (Eigen::Index c = 0; c < K.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, c); it; ++it) {
      if (it.value() != 0.0)
        triplets.emplace_back(static_cast<int>(it.row()), static_cast<int>(c), it.value());
    }
  }
  for (const auto& block : state.shell_blocks) {
    if (!block.rigid) add_block_triplets(block, state, n, drilling_factor, triplets, asymmetry);
  }
  for (const auto& block : state.beam_blocks) {
    if (!block.rigid) add_block_triplets(block, state, n, drilling_factor, triplets, asymmetry);
  }
  Eigen::SparseMatrix<double> whole(static_cast<Eigen::Index>(ndof),
                                    static_cast<Eigen::Index>(ndof));
  whole.setFromTriplets(triplets.begin(), triplets.end());
  K = std::move(whole);
}

}  // namespace

model::Id StructuralMatrices::node_of_dof(std::size_t dof) const {
  const std::size_t n = state.nodes.size();
  const std::size_t node =
      dof < 3 * n ? dof / 3 : static_cast<std::size_t>(state.rotations.node[(dof - 3 * n) / 3]);
  return state.nodes.id[node];
}

StructuralMatrices assemble_structural_matrices(const model::Model& model,
                                                const std::vector<model::Id>& parts,
                                                RotaryInertia inertia, double drilling_factor) {
  StructuralMatrices out;
  const model::Model sub = extract_parts(model, parts, &out.warnings);
  const solver::NodeIndex node_index(sub);
  out.state = solver::build_state(sub, node_index);
  solver::State& state = out.state;
  const std::size_t n = state.nodes.size();
  const std::size_t rotations = state.rotations.size();
  const std::size_t ndof = 3 * n + 3 * rotations;

  for (const auto& block : state.shell_blocks) {
    if (block.hourglass.ihq <= 3 && block.elform != 16) {  // ELFORM 16 has no hourglass control
      out.warnings.push_back(fmt::format(
          "part {}: viscous shell hourglass control IHQ={} has no stiffness; the eigen analysis "
          "uses the stiffness form IHQ 4 (QM={:g}) so that hourglass modes are not zero-energy "
          "modes",
          block.part_id, block.hourglass.ihq, block.hourglass.qm));
    }
  }
  for (const auto& block : state.hex_blocks) {
    if (block.order == 1 && block.elform != 2 && block.elform != 13 &&
        !block.quadratic_tetrahedra() && block.hourglass.ihq <= 3) {
      out.warnings.push_back(fmt::format(
          "part {}: viscous hourglass control IHQ={} has no stiffness; the eigen analysis uses "
          "the Belytschko-Bindeman stiffness (IHQ 6, QM={:g}) so that hourglass modes are not "
          "zero-energy modes",
          block.part_id, block.hourglass.ihq, block.hourglass.qm));
    }
  }

  // Mass: the explicit solver's lumped mass, repeated for x, y, z, then its lumped rotational
  // inertia (docs/eigen.md: the scaled rotary inertia of shells and beams).
  out.mass.resize(static_cast<Eigen::Index>(ndof));
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d)
      out.mass[static_cast<Eigen::Index>(3 * i + d)] = state.nodes.mass[i];
  }
  std::vector<double> rotational_inertia = state.rotations.inertia;
  if (inertia == RotaryInertia::kPhysical && rotations > 0) {
    std::fill(rotational_inertia.begin(), rotational_inertia.end(), 0.0);
    for (const auto& block : state.shell_blocks) {
      for (std::size_t e = 0; e < block.size(); ++e) {
        const std::int32_t* c = &block.conn[4 * e];
        const int distinct = c[2] == c[3] ? 3 : 4;
        const double t = block.element_thickness0[e];  // the lumped mass's (initial) t
        const double m = block.material.rho * t * block.area0[e] / distinct;
        for (int a = 0; a < distinct; ++a) {
          rotational_inertia[static_cast<std::size_t>(block.rotation_conn[4 * e + a])] +=
              m * t * t / 12.0;
        }
      }
    }
    for (const auto& block : state.beam_blocks) {
      if (block.elform == 3) continue;
      for (std::size_t e = 0; e < block.size(); ++e) {
        const double j = 0.5 * block.material.rho * (block.iss + block.itt) * block.length0[e];
        for (int a = 0; a < 2; ++a) {
          rotational_inertia[static_cast<std::size_t>(block.rotation_conn[2 * e + a])] += j;
        }
      }
    }
  }
  for (std::size_t r = 0; r < rotations; ++r) {
    for (int d = 0; d < 3; ++d)
      out.mass[static_cast<Eigen::Index>(3 * n + 3 * r + d)] = rotational_inertia[r];
  }
  out.node_parts.assign(n, 0);
  const auto mark_parts = [&](const std::vector<std::int32_t>& conn, model::Id part) {
    for (const std::int32_t node : conn) {
      auto& p = out.node_parts[static_cast<std::size_t>(node)];
      if (p == 0) p = part;
    }
  };
  for (const auto& block : state.hex_blocks) mark_parts(block.conn, block.part_id);
  for (const auto& block : state.shell_blocks) mark_parts(block.conn, block.part_id);
  for (const auto& block : state.beam_blocks) mark_parts(block.conn, block.part_id);

  // SPCs and *NODE TC through the explicit solver's own resolution.
  std::vector<model::Warning> boundary_warnings;
  const solver::Boundary boundary =
      solver::resolve_boundary(sub, node_index, state, {}, boundary_warnings);
  out.fixed.assign(ndof, 0);
  for (std::size_t i = 0; i < n && i < boundary.fixed.size(); ++i) {
    for (int d = 0; d < 3; ++d) out.fixed[3 * i + d] = (boundary.fixed[i] >> d) & 1u;
  }
  for (std::size_t r = 0; r < rotations && r < boundary.rotation_fixed.size(); ++r) {
    for (int d = 0; d < 3; ++d)
      out.fixed[3 * n + 3 * r + d] = (boundary.rotation_fixed[r] >> d) & 1u;
  }

  // Sparsity: node adjacency through elements (sorted neighbour lists, CSR), 3x3 blocks.
  std::vector<std::vector<std::int32_t>> neighbours(n);
  for (const auto& block : state.hex_blocks) {
    const int npe = block.nodes_per_element();
    for (std::size_t e = 0; e < block.size(); ++e) {
      const std::int32_t* c = &block.conn[e * static_cast<std::size_t>(npe)];
      for (int a = 0; a < npe; ++a) {
        auto& list = neighbours[static_cast<std::size_t>(c[a])];
        list.insert(list.end(), c, c + npe);
      }
    }
  }
  std::vector<std::int64_t> offset(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    auto& list = neighbours[i];
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    offset[i + 1] = offset[i] + static_cast<std::int64_t>(list.size());
  }
  const std::int64_t nnz = 9 * offset[n];
  // The hexahedra's translational block first (3n x 3n, assembled in place), then the shells and
  // beams with it into the whole matrix.
  const std::size_t tdof = 3 * n;
  Eigen::SparseMatrix<double>& K = out.stiffness;
  K.resize(static_cast<Eigen::Index>(tdof), static_cast<Eigen::Index>(tdof));
  K.resizeNonZeros(static_cast<Eigen::Index>(nnz));
  {
    int* outer = K.outerIndexPtr();
    int* inner = K.innerIndexPtr();
    for (std::size_t j = 0; j < n; ++j) {
      const auto& list = neighbours[j];
      const std::int64_t deg = static_cast<std::int64_t>(list.size());
      for (int dc = 0; dc < 3; ++dc) {
        const std::int64_t start = 9 * offset[j] + dc * 3 * deg;
        outer[3 * j + static_cast<std::size_t>(dc)] = static_cast<int>(start);
        for (std::int64_t p = 0; p < deg; ++p) {
          for (int dr = 0; dr < 3; ++dr) {
            inner[start + 3 * p + dr] = 3 * list[static_cast<std::size_t>(p)] + dr;
          }
        }
      }
    }
    outer[tdof] = static_cast<int>(nnz);
    std::fill(K.valuePtr(), K.valuePtr() + nnz, 0.0);
  }

  double asymmetry = 0.0;
  double* values = K.valuePtr();
  for (const auto& block : state.hex_blocks) {
    const int npe = block.nodes_per_element();
    const std::size_t nd = 3 * static_cast<std::size_t>(npe);
    const std::size_t chunk = std::max<std::size_t>(1, kChunkDoubles / (nd * nd));
    for (std::size_t first = 0; first < block.size(); first += chunk) {
      const std::size_t count = std::min(chunk, block.size() - first);
      std::vector<double> ke = element_stiffness_matrices(block, state.nodes, first, count);
#pragma omp parallel reduction(max : asymmetry)
      {
        std::vector<std::int64_t> start(static_cast<std::size_t>(npe * npe));
#pragma omp for schedule(static)
        for (std::int64_t ie = 0; ie < static_cast<std::int64_t>(count); ++ie) {
          const std::size_t e = static_cast<std::size_t>(ie);
          double* k = &ke[e * nd * nd];
          double largest = 0.0, skew = 0.0;
          for (std::size_t r = 0; r < nd; ++r) {
            for (std::size_t c = r + 1; c < nd; ++c) {
              largest = std::max({largest, std::abs(k[r * nd + c]), std::abs(k[c * nd + r])});
              skew = std::max(skew, std::abs(k[r * nd + c] - k[c * nd + r]));
              const double mean = 0.5 * (k[r * nd + c] + k[c * nd + r]);
              k[r * nd + c] = mean;
              k[c * nd + r] = mean;
            }
            largest = std::max(largest, std::abs(k[r * nd + r]));
          }
          if (largest > 0.0) asymmetry = std::max(asymmetry, skew / largest);
          const std::int32_t* conn = &block.conn[(first + e) * static_cast<std::size_t>(npe)];
          // Column block of node conn[b], row block of node conn[a]: position in column.
          for (int b = 0; b < npe; ++b) {
            const std::size_t j = static_cast<std::size_t>(conn[b]);
            const auto& list = neighbours[j];
            for (int a = 0; a < npe; ++a) {
              const auto it = std::lower_bound(list.begin(), list.end(), conn[a]);
              start[static_cast<std::size_t>(b * npe + a)] =
                  9 * offset[j] + 3 * static_cast<std::int64_t>(it - list.begin());
            }
          }
          for (int b = 0; b < npe; ++b) {
            const std::int64_t deg = offset[conn[b] + 1] - offset[conn[b]];
            for (int dc = 0; dc < 3; ++dc) {
              const std::size_t col =
                  3 * static_cast<std::size_t>(b) + static_cast<std::size_t>(dc);
              for (int a = 0; a < npe; ++a) {
                const std::int64_t pos =
                    start[static_cast<std::size_t>(b * npe + a)] + dc * 3 * deg;
                for (int dr = 0; dr < 3; ++dr) {
                  const double value = k[(3 * static_cast<std::size_t>(a) + dr) * nd + col];
                  if (value == 0.0) continue;
#pragma omp atomic
                  values[pos + dr] += value;
                }
              }
            }
          }
        }
      }
    }
  }
  if (!state.shell_blocks.empty() || !state.beam_blocks.empty()) {
    add_structural_stiffness(state, drilling_factor, K, asymmetry);
  }
  out.element_asymmetry = asymmetry;
  return out;
}

}  // namespace rf::modal
