#include "modal/stiffness_assembly.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>
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

  std::unordered_set<model::Id> used_nodes;
  for (const auto& solid : model.solids) {
    if (!all && keep.count(solid.pid) == 0) continue;
    sub.solids.push_back(solid);
    for (const model::Id n : solid.nodes) used_nodes.insert(n);
  }
  if (sub.solids.empty()) {
    throw InputError(InputErrorContext{},
                     all ? std::string("the deck has no solid elements to analyse")
                         : fmt::format("the selected parts have no solid elements"));
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

  // Every element gets its own copies of its nodes; a node repeated in a degenerate
  // connectivity maps to the copy of its first occurrence, as in the shared mesh.
  std::array<std::vector<double>, 3> x0, x, v;
  for (int d = 0; d < 3; ++d) {
    x0[d].assign(copies, 0.0);
    v[d].assign(copies, 0.0);
  }
  probe.conn.resize(copies);
  std::vector<double> size(count, 0.0);
  const std::array<const std::vector<double>*, 3> ref{&nodes.x0.x, &nodes.x0.y, &nodes.x0.z};
  for (std::size_t e = 0; e < count; ++e) {
    const std::int32_t* c = &source.conn[(first + e) * static_cast<std::size_t>(npe)];
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (int a = 0; a < npe; ++a) {
      int b = 0;
      while (c[b] != c[a]) ++b;
      const std::size_t copy = e * static_cast<std::size_t>(npe);
      probe.conn[copy + static_cast<std::size_t>(a)] = static_cast<std::int32_t>(copy + b);
      for (int d = 0; d < 3; ++d) {
        const double value = (*ref[d])[static_cast<std::size_t>(c[a])];
        x0[d][copy + static_cast<std::size_t>(a)] = value;
        lo[d] = std::min(lo[d], value);
        hi[d] = std::max(hi[d], value);
      }
    }
    size[e] = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  }
  x = x0;
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

StructuralMatrices assemble_structural_matrices(const model::Model& model,
                                                const std::vector<model::Id>& parts) {
  StructuralMatrices out;
  const model::Model sub = extract_parts(model, parts, &out.warnings);
  const solver::NodeIndex node_index(sub);
  out.state = solver::build_state(sub, node_index);
  solver::State& state = out.state;
  const std::size_t n = state.nodes.size();
  const std::size_t ndof = 3 * n;

  for (const auto& block : state.hex_blocks) {
    if (block.order == 1 && block.elform != 2 && block.hourglass.ihq <= 3) {
      out.warnings.push_back(fmt::format(
          "part {}: viscous hourglass control IHQ={} has no stiffness; the eigen analysis uses "
          "the Belytschko-Bindeman stiffness (IHQ 6, QM={:g}) so that hourglass modes are not "
          "zero-energy modes",
          block.part_id, block.hourglass.ihq, block.hourglass.qm));
    }
  }

  // Mass: the explicit solver's lumped mass, repeated for x, y, z.
  out.mass.resize(static_cast<Eigen::Index>(ndof));
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d)
      out.mass[static_cast<Eigen::Index>(3 * i + d)] = state.nodes.mass[i];
  }
  out.node_parts.assign(n, 0);
  for (const auto& block : state.hex_blocks) {
    for (const std::int32_t node : block.conn) {
      auto& p = out.node_parts[static_cast<std::size_t>(node)];
      if (p == 0) p = block.part_id;
    }
  }

  // SPCs and *NODE TC through the explicit solver's own resolution.
  std::vector<model::Warning> boundary_warnings;
  const solver::Boundary boundary =
      solver::resolve_boundary(sub, node_index, state, {}, boundary_warnings);
  out.fixed.assign(ndof, 0);
  for (std::size_t i = 0; i < n && i < boundary.fixed.size(); ++i) {
    for (int d = 0; d < 3; ++d) out.fixed[3 * i + d] = (boundary.fixed[i] >> d) & 1u;
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
  Eigen::SparseMatrix<double>& K = out.stiffness;
  K.resize(static_cast<Eigen::Index>(ndof), static_cast<Eigen::Index>(ndof));
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
    outer[ndof] = static_cast<int>(nnz);
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
  out.element_asymmetry = asymmetry;
  return out;
}

}  // namespace rf::modal
