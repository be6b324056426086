#include "contact/contact.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "element/tet10_block.hpp"
#include "mesh/vec3_ops.hpp"
#include "model/error.hpp"
#include "model/error_context.hpp"

namespace rf::contact {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// LS-DYNA's default penalty scale SLSFAC (*CONTROL_CONTACT), Theory Manual eq. for k_i.
constexpr double kSlsfac = 0.1;
// A node whose projection leaves the segment by more than this fraction of its size is not on
// that segment (it is beside it: an edge or corner of the master surface).
constexpr double kEdgeTolerance = 0.05;
// Nodes deeper than this fraction of the segment size are not pushed back (they came from the
// other side, or the surface is thinner than the penetration: LS-DYNA releases them as well).
constexpr double kDepthFraction = 0.5;
// A segment faces a node when their outward normals make an angle above about 101.5 degrees
// (cosine below minus this): an edge or corner node's normal leans 45-55 degrees from each face
// it bounds, and a node on a side face of a body is not pressed by that body's bottom face.
constexpr double kFacingTolerance = 0.2;

using mesh::cross;
using mesh::dot;
using mesh::norm;
using mesh::sub;
using mesh::Vec;

Vec position(const solver::Vec3Array& x, std::int32_t i) {
  return {x.x[i], x.y[i], x.z[i]};
}

// Area of a quadrilateral (exact when planar): half the cross product of its diagonals.
Vec diagonal_normal(const Vec& a, const Vec& b, const Vec& c, const Vec& d) {
  return cross(sub(c, a), sub(d, b));
}

// Tensor positions of the corners of side s (0..5: i=0, i=p, j=0, j=p, k=0, k=p), cyclic, and
// of the node (u, v) of that side's node grid.
std::array<int, 3> side_node(int s, int p, int u, int v) {
  const int a = (s % 2 == 0) ? 0 : p;
  switch (s / 2) {
    case 0:
      return {a, u, v};
    case 1:
      return {u, a, v};
    default:
      return {u, v, a};
  }
}

std::int32_t block_node(const element::HexBlock& block, std::size_t e,
                        const std::array<int, 3>& t) {
  const std::int32_t* conn = block.conn.data() + e * block.nodes_per_element();
  if (block.order == 1) {
    static constexpr int kCorner[2][2][2] = {{{0, 4}, {3, 7}}, {{1, 5}, {2, 6}}};  // [i][j][k]
    return conn[kCorner[t[0]][t[1]][t[2]]];
  }
  const int n = block.order + 1;
  return conn[t[0] + n * (t[1] + n * t[2])];
}

using FaceKey = std::array<std::int32_t, 4>;

// Sorted distinct corner nodes (a repeated node is kept once; fewer than 3: no face).
std::optional<FaceKey> face_key(std::array<std::int32_t, 4> corners) {
  std::sort(corners.begin(), corners.end());
  const auto end = std::unique(corners.begin(), corners.end());
  const auto distinct = end - corners.begin();
  if (distinct < 3) return std::nullopt;
  if (distinct == 3) corners[3] = -1;
  return corners;
}

struct FaceRef {
  std::int32_t block = 0;
  std::int64_t element = 0;
  int side = 0;
  int count = 0;
  // The second element of a face two elements share (other_block -1: none).
  std::int32_t other_block = -1;
  std::int64_t other_element = 0;
  int other_side = 0;
};

// 10-node tetrahedra (ELFORM 16): face s has corners kTetFace[s] (local 0..3), and its 6-node
// face is split into 4 linear triangles through the mid-side nodes (corner, mid, mid) x 3 and
// (mid, mid, mid), each a contact segment with its third node repeated, as LS-DYNA's triangles.
constexpr int kTetFace[4][3] = {{0, 1, 2}, {0, 1, 3}, {1, 2, 3}, {0, 2, 3}};

// Local index (4..9) of the mid-side node of the edge between corners i and j.
int tet10_midside(int i, int j) {
  for (int m = 0; m < 6; ++m) {
    const int a = element::kTet10Edge[m][0], b = element::kTet10Edge[m][1];
    if ((a == i && b == j) || (a == j && b == i)) return 4 + m;
  }
  return -1;
}

int side_count(const element::HexBlock& block) {
  return block.quadratic_tetrahedra() ? 4 : 6;
}

std::array<std::int32_t, 4> corners_of(const element::HexBlock& block, std::size_t e, int s) {
  if (block.quadratic_tetrahedra()) {
    const std::int32_t* conn = block.conn.data() + e * element::kTet10Nodes;
    const int* f = kTetFace[s];
    return {conn[f[0]], conn[f[1]], conn[f[2]], conn[f[2]]};
  }
  const int p = block.order;
  return {block_node(block, e, side_node(s, p, 0, 0)), block_node(block, e, side_node(s, p, p, 0)),
          block_node(block, e, side_node(s, p, p, p)), block_node(block, e, side_node(s, p, 0, p))};
}

// Every face of the blocks accepted by `use_block`, with how many elements share it.
std::map<FaceKey, FaceRef> face_table(const solver::State& state,
                                      const std::vector<bool>& use_block) {
  std::map<FaceKey, FaceRef> faces;
  for (std::size_t b = 0; b < state.hex_blocks.size(); ++b) {
    if (!use_block[b]) continue;
    const auto& block = state.hex_blocks[b];
    for (std::size_t e = 0; e < block.size(); ++e) {
      for (int s = 0; s < side_count(block); ++s) {
        const auto key = face_key(corners_of(block, e, s));
        if (!key) continue;
        auto [it, inserted] = faces.try_emplace(
            *key, FaceRef{static_cast<std::int32_t>(b), static_cast<std::int64_t>(e), s, 0});
        if (++it->second.count == 2) {
          it->second.other_block = static_cast<std::int32_t>(b);
          it->second.other_element = static_cast<std::int64_t>(e);
          it->second.other_side = s;
        }
      }
    }
  }
  return faces;
}

// Adds the segments of face `s` of element e: the face itself (order 1) or the p x p linear
// sub-quads of its node grid, each ordered so that its normal points out of the element.
void add_segment(const solver::State& state, const element::HexBlock& block,
                 std::array<std::int32_t, 4> q, const Vec& outward, double depth,
                 double half_thickness, ContactSurface& surface);

// The 4 triangles of face `face.side` of a 10-node tetrahedron. Penalty stiffness as for a
// p = 2 hexahedron face: each sub-triangle takes the element's depth normal to the face over 2,
// V / (2 A_face), so that the face's total stiffness is SLSFAC K A_face^2 / V (LS-DYNA's
// k = SLSFAC K A^2 / V) when the sub-triangles are equal.
void add_tet10_face_segments(const solver::State& state, const FaceRef& face, double half_thickness,
                             ContactSurface& surface) {
  const auto& block = state.hex_blocks[face.block];
  const std::size_t e = static_cast<std::size_t>(face.element);
  const std::int32_t* conn = block.conn.data() + e * element::kTet10Nodes;
  const auto& x = state.nodes.x;
  Vec centre{0, 0, 0}, face_centre{0, 0, 0};
  for (int a = 0; a < 4; ++a) {
    const Vec c = position(x, conn[a]);
    for (int d = 0; d < 3; ++d) centre[d] += c[d] / 4.0;
  }
  const int* f = kTetFace[face.side];
  for (int a = 0; a < 3; ++a) {
    const Vec c = position(x, conn[f[a]]);
    for (int d = 0; d < 3; ++d) face_centre[d] += c[d] / 3.0;
  }
  const Vec outward = sub(face_centre, centre);
  const Vec p0 = position(x, conn[f[0]]), p1 = position(x, conn[f[1]]),
            p2 = position(x, conn[f[2]]);
  const double face_area = 0.5 * norm(cross(sub(p1, p0), sub(p2, p0)));
  double volume = (e < block.volume0.size()) ? block.volume0[e] : 0.0;
  if (!(volume > 0.0)) volume = face_area * std::sqrt(face_area);
  const double depth = volume / (face_area * 2.0);
  const std::int32_t c0 = conn[f[0]], c1 = conn[f[1]], c2 = conn[f[2]];
  const std::int32_t m01 = conn[tet10_midside(f[0], f[1])];
  const std::int32_t m12 = conn[tet10_midside(f[1], f[2])];
  const std::int32_t m20 = conn[tet10_midside(f[2], f[0])];
  const std::array<std::array<std::int32_t, 4>, 4> triangles = {
      {{c0, m01, m20, m20}, {m01, c1, m12, m12}, {m20, m12, c2, c2}, {m01, m12, m20, m20}}};
  for (const auto& t : triangles)
    add_segment(state, block, t, outward, depth, half_thickness, surface);
}

void add_face_segments(const solver::State& state, const FaceRef& face, double half_thickness,
                       ContactSurface& surface) {
  const auto& block = state.hex_blocks[face.block];
  if (block.quadratic_tetrahedra()) {
    add_tet10_face_segments(state, face, half_thickness, surface);
    return;
  }
  const std::size_t e = static_cast<std::size_t>(face.element);
  const int p = block.order;
  const auto& x = state.nodes.x;
  // Element centre from its 8 corners; face centre and area from its 4 corners.
  Vec centre{0, 0, 0};
  for (int i = 0; i <= 1; ++i)
    for (int j = 0; j <= 1; ++j)
      for (int k = 0; k <= 1; ++k) {
        const Vec c = position(x, block_node(block, e, {i * p, j * p, k * p}));
        for (int d = 0; d < 3; ++d) centre[d] += c[d] / 8.0;
      }
  const auto corners = corners_of(block, e, face.side);
  Vec face_centre{0, 0, 0};
  for (const auto n : corners) {
    const Vec c = position(x, n);
    for (int d = 0; d < 3; ++d) face_centre[d] += c[d] / 4.0;
  }
  const Vec outward = sub(face_centre, centre);
  const double face_area =
      0.5 * norm(diagonal_normal(position(x, corners[0]), position(x, corners[1]),
                                 position(x, corners[2]), position(x, corners[3])));
  double volume = (e < block.volume0.size()) ? block.volume0[e] : 0.0;
  if (!(volume > 0.0)) volume = face_area * std::sqrt(face_area);
  // Penalty stiffness of a solid segment, LS-DYNA Theory Manual (contact, penalty method):
  // k = SLSFAC K A^2 / V. A sub-quad of a higher-order face takes the element's thickness
  // normal to the face divided by p as its depth (V / (A_face p)); for p = 1 the formula.
  const double depth = volume / (face_area * p);
  for (int u = 0; u < p; ++u) {
    for (int v = 0; v < p; ++v) {
      std::array<std::int32_t, 4> q = {block_node(block, e, side_node(face.side, p, u, v)),
                                       block_node(block, e, side_node(face.side, p, u + 1, v)),
                                       block_node(block, e, side_node(face.side, p, u + 1, v + 1)),
                                       block_node(block, e, side_node(face.side, p, u, v + 1))};
      // Degenerate elements: drop repeated corners (a triangle repeats its third node).
      std::array<std::int32_t, 4> distinct{};
      int count = 0;
      for (int c = 0; c < 4; ++c) {
        bool seen = false;
        for (int d = 0; d < count; ++d) seen |= distinct[d] == q[c];
        if (!seen) distinct[count++] = q[c];
      }
      if (count < 3) continue;
      if (count == 3) distinct[3] = distinct[2];
      add_segment(state, block, distinct, outward, depth, half_thickness, surface);
    }
  }
}

// One segment q of a solid face (a triangle repeats its third node), turned so that its normal
// points along `outward`, with the penalty stiffness SLSFAC K A / depth.
void add_segment(const solver::State& state, const element::HexBlock& block,
                 std::array<std::int32_t, 4> q, const Vec& outward, double depth,
                 double half_thickness, ContactSurface& surface) {
  const auto& x = state.nodes.x;
  const double bulk = block.material.bulk;
  const Vec n =
      diagonal_normal(position(x, q[0]), position(x, q[1]), position(x, q[2]), position(x, q[3]));
  if (dot(n, outward) < 0.0) std::swap(q[1], q[3]);
  const double area = 0.5 * norm(n);
  surface.segments.push_back(q);
  surface.stiffness.push_back(bulk > 0.0 && depth > 0.0 ? kSlsfac * bulk * area / depth
                                                        : kInfinity);
  surface.two_sided.push_back(0);
  surface.half_thickness.push_back(half_thickness);
  surface.size.push_back(std::sqrt(area));
  surface.part.push_back(block.part_id);
  // A rigid part's segment moves with the whole body: as heavy as it gets.
  double m = 0.0;
  for (const auto node : q) m += state.nodes.mass[node] / 4.0;
  surface.mass.push_back(block.rigid ? kInfinity : m);
}

// The contact thickness of one side (SST or MST) and the scale of its shell thickness (SFST or
// SFMT): LS-DYNA's rule, a nonzero SST overrides the shell thickness.
struct SideThickness {
  double given = 0.0;
  double shell_scale = 1.0;
};

// Adds shell element e of block b as a two-sided segment (a triangle repeats its third node).
// Penalty stiffness of a shell segment, LS-DYNA Theory Manual (contact, penalty method):
// k = SLSFAC K A / max(shell diagonal); the contact surface lies at half the (scaled) mean nodal
// thickness on each side of the element.
void add_shell_segment(const solver::State& state, std::size_t b, std::size_t e,
                       const SideThickness& thickness, ContactSurface& surface) {
  const auto& block = state.shell_blocks[b];
  const auto& x = state.nodes.x;
  std::array<std::int32_t, 4> q{};
  for (int k = 0; k < 4; ++k) q[k] = block.conn[4 * e + k];
  const Vec a = position(x, q[0]), bb = position(x, q[1]), c = position(x, q[2]),
            d = position(x, q[3]);
  const double area = 0.5 * norm(diagonal_normal(a, bb, c, d));
  const double diagonal = std::max(norm(sub(c, a)), norm(sub(d, bb)));
  const double bulk = block.material.bulk;
  double mean_thickness = 0.0;
  const int corners = block.triangle[e] ? 3 : 4;
  for (int k = 0; k < corners; ++k) mean_thickness += block.thickness[4 * e + k] / corners;
  surface.segments.push_back(q);
  surface.stiffness.push_back(bulk > 0.0 && diagonal > 0.0 ? kSlsfac * bulk * area / diagonal
                                                           : kInfinity);
  surface.two_sided.push_back(1);
  surface.half_thickness.push_back(
      thickness.given > 0.0 ? 0.5 * thickness.given : 0.5 * thickness.shell_scale * mean_thickness);
  surface.size.push_back(std::sqrt(area));
  surface.part.push_back(block.part_id);
  double m = 0.0;
  for (const auto node : q) m += state.nodes.mass[node] / 4.0;
  surface.mass.push_back(block.rigid ? kInfinity : m);
}

std::vector<model::Id> parts_of_side(const model::Model& model, model::Id id, int type) {
  std::vector<model::Id> parts;
  if (type == 3) parts.push_back(id);
  if (type == 2) parts = model.part_sets.at(id).parts;
  if (type == 5) {
    for (const auto& [pid, part] : model.parts) parts.push_back(pid);
  }
  std::sort(parts.begin(), parts.end());
  parts.erase(std::unique(parts.begin(), parts.end()), parts.end());
  return parts;
}

// ---- Erosion (docs/contact.md, "Erosion") ----

bool can_erode(const solver::State& state, const ElementRef& element) {
  switch (element.family) {
    case ElementRef::kHex:
      return state.hex_blocks[element.block].erosion.enabled;
    case ElementRef::kShell:
      return state.shell_blocks[element.block].erosion.enabled;
    default:
      return false;
  }
}

bool is_eroded(const solver::State& state, const ElementRef& element) {
  const auto e = static_cast<std::size_t>(element.element);
  switch (element.family) {
    case ElementRef::kHex:
      return state.hex_blocks[element.block].erosion.is_eroded(e);
    case ElementRef::kShell:
      return state.shell_blocks[element.block].erosion.is_eroded(e);
    default:
      return true;  // no element: an exterior face has nothing across it
  }
}

bool any_block_erodes(const solver::State& state) {
  for (const auto& b : state.hex_blocks) {
    if (b.erosion.enabled) return true;
  }
  for (const auto& b : state.shell_blocks) {
    if (b.erosion.enabled) return true;
  }
  for (const auto& b : state.beam_blocks) {
    if (b.erosion.enabled) return true;
  }
  return false;
}

// Which segments and nodes of an erodible side take part now (the rule of ContactSurface).
// A segment's nodes belong to its live owner, so they are not removed in a consistent state;
// the test keeps a removed node from ever exerting a force all the same. Returns whether a
// segment's flag changed.
bool refresh_active(ContactSurface& surface, const solver::State& state) {
  if (!surface.erodible) return false;
  bool changed = false;
  const auto& nodes = state.nodes;
  for (std::size_t s = 0; s < surface.segments.size(); ++s) {
    const auto& q = surface.segments[s];
    bool active = !is_eroded(state, surface.owner[s]) && is_eroded(state, surface.covered_by[s]);
    for (int a = 0; a < 4 && active; ++a)
      active = !nodes.is_removed(static_cast<std::size_t>(q[a]));
    changed |= surface.segment_active[s] != static_cast<std::uint8_t>(active);
    surface.segment_active[s] = active ? 1 : 0;
  }
  const bool node_set = surface.segments.empty();
  for (std::size_t j = 0; j < surface.nodes.size(); ++j) {
    bool active = !nodes.is_removed(static_cast<std::size_t>(surface.nodes[j]));
    if (!node_set && active) {
      // On an active segment; its contact offset the largest of those (a node of a solid face
      // and of an eroded shell keeps only the face's offset).
      bool on_active = false;
      double half_thickness = 0.0;
      for (auto k = surface.node_segment_start[j]; k < surface.node_segment_start[j + 1]; ++k) {
        const auto s = static_cast<std::size_t>(surface.node_segments[k]);
        if (!surface.segment_active[s]) continue;
        half_thickness = on_active ? std::max(half_thickness, surface.half_thickness[s])
                                   : surface.half_thickness[s];
        on_active = true;
      }
      active = on_active;
      if (on_active) surface.node_half_thickness[j] = half_thickness;
    }
    surface.node_active[j] = active ? 1 : 0;
  }
  return changed;
}

// Sets up the flags of a side once its segments, owners and nodes are known: a side none of
// whose elements can erode drops the owner arrays and keeps the code path of no erosion.
void finish_erosion(ContactSurface& surface, const solver::State& state, bool node_set) {
  surface.erodible = false;
  if (node_set) {
    surface.erodible = any_block_erodes(state);
  } else {
    for (std::size_t s = 0; s < surface.owner.size() && !surface.erodible; ++s) {
      surface.erodible =
          can_erode(state, surface.owner[s]) || can_erode(state, surface.covered_by[s]);
    }
  }
  if (!surface.erodible) {
    surface.owner.clear();
    surface.covered_by.clear();
    surface.owner.shrink_to_fit();
    surface.covered_by.shrink_to_fit();
    return;
  }
  surface.segment_active.assign(surface.segments.size(), 0);
  surface.node_active.assign(surface.nodes.size(), 0);
  refresh_active(surface, state);
}

// Records the owner of the segments added since `first` (a face's p x p sub-quads share it).
void set_owner(ContactSurface& surface, std::size_t first, const ElementRef& owner,
               const ElementRef& covered_by) {
  surface.owner.resize(first, ElementRef{});
  surface.covered_by.resize(first, ElementRef{});
  surface.owner.resize(surface.segments.size(), owner);
  surface.covered_by.resize(surface.segments.size(), covered_by);
}

// `node_set_half_thickness`: the contact offset of nodes without segments (SST/2); nodes of
// shells (a node set of NODES_TO_SURFACE) take `shell_half_thickness` (by dense node; empty: none).
void finish_surface(const solver::State& state, double node_set_half_thickness,
                    ContactSurface& surface, const std::vector<double>& shell_half_thickness = {}) {
  struct NodeData {
    double stiffness;
    model::Id part;
    double half_thickness;
  };
  std::map<std::int32_t, NodeData> node_data;
  for (std::size_t s = 0; s < surface.segments.size(); ++s) {
    for (const auto n : surface.segments[s]) {
      auto [it, inserted] = node_data.try_emplace(
          n, NodeData{surface.stiffness[s], surface.part[s], surface.half_thickness[s]});
      if (!inserted) {
        it->second.stiffness = std::min(it->second.stiffness, surface.stiffness[s]);
        it->second.half_thickness = std::max(it->second.half_thickness, surface.half_thickness[s]);
      }
    }
    surface.max_size = std::max(surface.max_size, surface.size[s]);
    surface.max_half_thickness = std::max(surface.max_half_thickness, surface.half_thickness[s]);
  }
  if (surface.nodes.empty()) {  // segment-based side: its nodes are the segments' nodes
    for (const auto& [n, data] : node_data) surface.nodes.push_back(n);
  }
  // Part of a node without segments (node set): the first block that uses it.
  std::vector<model::Id> block_part;
  if (node_data.size() < surface.nodes.size()) {
    block_part.assign(state.nodes.size(), 0);
    for (auto b = state.shell_blocks.rbegin(); b != state.shell_blocks.rend(); ++b) {
      for (const auto n : b->conn) block_part[n] = b->part_id;
    }
    for (auto b = state.hex_blocks.rbegin(); b != state.hex_blocks.rend(); ++b) {
      for (const auto n : b->conn) block_part[n] = b->part_id;
    }
  }
  for (const auto n : surface.nodes) {
    if (const auto it = node_data.find(n); it != node_data.end()) {
      surface.node_stiffness.push_back(it->second.stiffness);
      surface.node_part.push_back(it->second.part);
      surface.node_half_thickness.push_back(it->second.half_thickness);
      continue;
    }
    surface.node_stiffness.push_back(kInfinity);
    surface.node_part.push_back(block_part[n]);
    const double h = !shell_half_thickness.empty() && shell_half_thickness[n] >= 0.0
                         ? shell_half_thickness[n]
                         : node_set_half_thickness;
    surface.node_half_thickness.push_back(h);
    surface.max_half_thickness = std::max(surface.max_half_thickness, h);
  }
  // Node -> segment incidence (CSR), segments in ascending order for each node.
  const std::size_t nn = surface.nodes.size();
  surface.node_segment_start.assign(nn + 1, 0);
  auto slot = [&](std::int32_t node) {
    const auto it = std::lower_bound(surface.nodes.begin(), surface.nodes.end(), node);
    return static_cast<std::size_t>(it - surface.nodes.begin());
  };
  for (const auto& segment : surface.segments) {
    for (int a = 0; a < 4; ++a) {
      if (a == 3 && segment[3] == segment[2]) continue;
      ++surface.node_segment_start[slot(segment[a]) + 1];
    }
  }
  for (std::size_t j = 0; j < nn; ++j) {
    surface.node_segment_start[j + 1] += surface.node_segment_start[j];
  }
  surface.node_segments.resize(static_cast<std::size_t>(surface.node_segment_start[nn]));
  std::vector<std::int64_t> fill(surface.node_segment_start.begin(),
                                 surface.node_segment_start.end() - 1);
  for (std::size_t s = 0; s < surface.segments.size(); ++s) {
    const auto& segment = surface.segments[s];
    for (int a = 0; a < 4; ++a) {
      if (a == 3 && segment[3] == segment[2]) continue;
      surface.node_segments[fill[slot(segment[a])]++] = static_cast<std::int32_t>(s);
    }
  }
  surface.node_normal.assign(3 * nn, 0.0);
}

// Outward node normals from the segments' area vectors at the current positions.
// kErosion: only the active segments bound the live surface (a side without erosion runs the
// loop without the test, as evaluate_pass_of does).
template <bool kErosion>
void update_node_normals_of(ContactSurface& surface, const solver::Vec3Array& x,
                            std::int64_t parallel_minimum) {
  const std::int64_t nn = static_cast<std::int64_t>(surface.nodes.size());
  const std::uint8_t* active = surface.segment_active.data();
#pragma omp parallel for schedule(static) if (nn >= parallel_minimum)
  for (std::int64_t j = 0; j < nn; ++j) {
    Vec sum{0, 0, 0};
    for (auto k = surface.node_segment_start[j]; k < surface.node_segment_start[j + 1]; ++k) {
      // A shell has no outward side: its nodes meet segments from either side.
      if (surface.two_sided[surface.node_segments[k]]) continue;
      if constexpr (kErosion) {
        if (!active[surface.node_segments[k]]) continue;
      }
      const auto& q = surface.segments[surface.node_segments[k]];
      const Vec n = diagonal_normal(position(x, q[0]), position(x, q[1]), position(x, q[2]),
                                    position(x, q[3]));
      for (int d = 0; d < 3; ++d) sum[d] += n[d];
    }
    const double length = norm(sum);
    for (int d = 0; d < 3; ++d)
      surface.node_normal[3 * j + d] = length > 0.0 ? sum[d] / length : 0.0;
  }
}

void update_node_normals(ContactSurface& surface, const solver::Vec3Array& x,
                         std::int64_t parallel_minimum) {
  if (!surface.segment_active.empty()) {
    update_node_normals_of<true>(surface, x, parallel_minimum);
  } else {
    update_node_normals_of<false>(surface, x, parallel_minimum);
  }
}

ContactSurface build_side(const model::Model& model, const solver::NodeIndex& node_index,
                          const solver::State& state, const model::Contact& contact, model::Id id,
                          int type, const char* field, const SideThickness& thickness) {
  ContactSurface surface;
  const double solid_half_thickness = 0.5 * thickness.given;
  if (type == 4) {  // node set: slave nodes only
    for (const auto nid : model.node_sets.at(id).nodes) {
      surface.nodes.push_back(node_index.at(nid, contact.where, field));
    }
    std::sort(surface.nodes.begin(), surface.nodes.end());
    surface.nodes.erase(std::unique(surface.nodes.begin(), surface.nodes.end()),
                        surface.nodes.end());
    // A node of a shell carries the shell's contact thickness as LS-DYNA's nodes-to-surface
    // does: SST/2 when given, else SFST times half the largest thickness of its shells.
    std::vector<double> shell_half;
    if (!state.shell_blocks.empty() && !(thickness.given > 0.0)) {
      shell_half.assign(state.nodes.size(), -1.0);
      for (const auto& block : state.shell_blocks) {
        for (std::size_t k = 0; k < block.conn.size(); ++k) {
          const double h = 0.5 * thickness.shell_scale * block.thickness[k];
          shell_half[block.conn[k]] = std::max(shell_half[block.conn[k]], h);
        }
      }
    }
    finish_surface(state, solid_half_thickness, surface, shell_half);
    finish_erosion(surface, state, true);
    return surface;
  }
  if (type == 0) {  // segment set: each segment must be a solid face or a shell element
    const std::vector<bool> all(state.hex_blocks.size(), true);
    const auto faces = face_table(state, all);
    std::map<FaceKey, std::pair<std::size_t, std::size_t>> shells;  // block, element
    for (std::size_t b = 0; b < state.shell_blocks.size(); ++b) {
      const auto& block = state.shell_blocks[b];
      for (std::size_t e = 0; e < block.size(); ++e) {
        const auto key = face_key({block.conn[4 * e], block.conn[4 * e + 1], block.conn[4 * e + 2],
                                   block.conn[4 * e + 3]});
        if (key) shells.try_emplace(*key, b, e);
      }
    }
    for (const auto& segment : model.segment_sets.at(id).segments) {
      std::array<std::int32_t, 4> dense{};
      for (int k = 0; k < 4; ++k) dense[k] = node_index.at(segment[k], contact.where, field);
      const auto key = face_key(dense);
      // A listed segment leaves with its element; nothing is exposed (the set names segments).
      const std::size_t first = surface.segments.size();
      if (const auto it = key ? faces.find(*key) : faces.end(); it != faces.end()) {
        add_face_segments(state, it->second, solid_half_thickness, surface);
        set_owner(surface, first, {ElementRef::kHex, it->second.block, it->second.element}, {});
        continue;
      }
      if (const auto it = key ? shells.find(*key) : shells.end(); it != shells.end()) {
        add_shell_segment(state, it->second.first, it->second.second, thickness, surface);
        set_owner(surface, first,
                  {ElementRef::kShell, static_cast<std::int32_t>(it->second.first),
                   static_cast<std::int64_t>(it->second.second)},
                  {});
        continue;
      }
      throw InputError(model::context_of(contact.where, field),
                       fmt::format("segment {} {} {} {} of segment set {} is neither a face of a "
                                   "solid element nor a shell element: contact segments need "
                                   "the element behind them (stiffness, orientation, thickness)",
                                   segment[0], segment[1], segment[2], segment[3], id));
    }
    finish_surface(state, solid_half_thickness, surface);
    finish_erosion(surface, state, false);
    return surface;
  }
  const auto parts = parts_of_side(model, id, type);
  auto on_side = [&](model::Id pid) { return std::binary_search(parts.begin(), parts.end(), pid); };
  // Beams have no contact segments (edge-to-edge and beam contact are not implemented): refuse
  // rather than let them pass through everything.
  for (const auto& block : state.beam_blocks) {
    if (!on_side(block.part_id)) continue;
    throw InputError(model::context_of(contact.where, field),
                     fmt::format("part {} (beam elements) is on this contact side: contact with "
                                 "beams is not supported (leave beam parts out of the side: "
                                 "use a part or part set instead of all parts)",
                                 block.part_id));
  }
  std::vector<bool> use(state.hex_blocks.size(), false);
  bool erodes = false;  // an element of the side can erode: owners are recorded
  for (std::size_t b = 0; b < state.hex_blocks.size(); ++b) {
    use[b] = on_side(state.hex_blocks[b].part_id);
    erodes |= use[b] && state.hex_blocks[b].erosion.enabled;
  }
  for (const auto& block : state.shell_blocks) {
    erodes |= on_side(block.part_id) && block.erosion.enabled;
  }
  // Exterior faces: those of one element only among the side's elements. With erosion, also
  // the interior faces next to an erodible element, out of each element whose neighbour can
  // erode (exposed when it has; LS-DYNA's eroding contacts likewise update the surface).
  for (const auto& [key, face] : face_table(state, use)) {
    const ElementRef first_element{ElementRef::kHex, face.block, face.element};
    const std::size_t first = surface.segments.size();
    if (face.count == 1) {
      add_face_segments(state, face, solid_half_thickness, surface);
      if (erodes) set_owner(surface, first, first_element, {});
      continue;
    }
    if (!erodes || face.count != 2 || face.other_block < 0) continue;
    const ElementRef second_element{ElementRef::kHex, face.other_block, face.other_element};
    if (face.block == face.other_block && face.element == face.other_element) continue;
    if (can_erode(state, second_element)) {
      add_face_segments(state, face, solid_half_thickness, surface);
      set_owner(surface, first, first_element, second_element);
    }
    if (can_erode(state, first_element)) {
      const std::size_t second = surface.segments.size();
      const FaceRef other{face.other_block, face.other_element, face.other_side, 2};
      add_face_segments(state, other, solid_half_thickness, surface);
      set_owner(surface, second, second_element, first_element);
    }
  }
  // Shells: every element is a (two-sided) segment.
  for (std::size_t b = 0; b < state.shell_blocks.size(); ++b) {
    if (!on_side(state.shell_blocks[b].part_id)) continue;
    for (std::size_t e = 0; e < state.shell_blocks[b].size(); ++e) {
      const std::size_t first = surface.segments.size();
      add_shell_segment(state, b, e, thickness, surface);
      if (erodes) {
        set_owner(surface, first,
                  {ElementRef::kShell, static_cast<std::int32_t>(b), static_cast<std::int64_t>(e)},
                  {});
      }
    }
  }
  if (surface.segments.empty()) {
    throw InputError(model::context_of(contact.where, field),
                     fmt::format("{} {} has no solid or shell elements, so no contact surface",
                                 type == 3 ? "part" : "part set", id));
  }
  finish_surface(state, solid_half_thickness, surface);
  finish_erosion(surface, state, false);
  return surface;
}

// ---- Broad phase ----

void segment_box(const solver::Vec3Array& x, const std::array<std::int32_t, 4>& s, double grow,
                 Vec& lo, Vec& hi) {
  lo = {kInfinity, kInfinity, kInfinity};
  hi = {-kInfinity, -kInfinity, -kInfinity};
  for (const auto n : s) {
    const Vec p = position(x, n);
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], p[d] - grow);
      hi[d] = std::max(hi[d], p[d] + grow);
    }
  }
}

std::int64_t cell_coordinate(const SegmentGrid& grid, double value, int d) {
  return static_cast<std::int64_t>(std::floor((value - grid.origin[d]) / grid.cell));
}

void build_grid(SegmentGrid& grid, const ContactSurface& master, const ContactSurface& moved,
                const solver::State& state) {
  const auto& x = state.nodes.x;
  const std::size_t nseg = master.segments.size();
  ++grid.rebuilds;
  grid.built = true;
  grid.built_x.resize(moved.nodes.size());
  grid.built_y.resize(moved.nodes.size());
  grid.built_z.resize(moved.nodes.size());
  for (std::size_t j = 0; j < moved.nodes.size(); ++j) {
    grid.built_x[j] = x.x[moved.nodes[j]];
    grid.built_y[j] = x.y[moved.nodes[j]];
    grid.built_z[j] = x.z[moved.nodes[j]];
  }
  Vec lo_all{kInfinity, kInfinity, kInfinity}, hi_all{-kInfinity, -kInfinity, -kInfinity};
  double extent = 0.0;
  // Only active segments are listed (erosion): update_after_erosion rebuilds the grid when
  // segments join or leave, so the lookup never visits the interior of an erodible solid.
  std::size_t listed = 0;
  for (std::size_t s = 0; s < nseg; ++s) {
    if (!master.is_active_segment(s)) continue;
    ++listed;
    Vec lo, hi;
    segment_box(x, master.segments[s], grid.expansion, lo, hi);
    for (int d = 0; d < 3; ++d) {
      lo_all[d] = std::min(lo_all[d], lo[d]);
      hi_all[d] = std::max(hi_all[d], hi[d]);
      extent = std::max(extent, hi[d] - lo[d]);
    }
  }
  if (listed == 0) {
    grid.dims = {0, 0, 0};
    grid.cell_start.assign(1, 0);
    grid.cell_segments.clear();
    grid.visit_stamp.assign(nseg, 0);
    return;
  }
  // Cells as large as the largest grown box: a segment is listed in at most 8 cells. The
  // number of cells is kept within a few times the number of segments (O(n) memory).
  grid.cell = std::max(
      extent, 1e-12 * (1.0 + std::abs(hi_all[0]) + std::abs(hi_all[1]) + std::abs(hi_all[2])));
  const double limit = 4.0 * static_cast<double>(listed) + 64.0;
  for (;;) {
    double cells = 1.0;
    for (int d = 0; d < 3; ++d) {
      grid.dims[d] = static_cast<std::int64_t>(std::floor((hi_all[d] - lo_all[d]) / grid.cell)) + 1;
      cells *= static_cast<double>(grid.dims[d]);
    }
    if (cells <= limit) break;
    grid.cell *= std::cbrt(cells / limit) * 1.01;
  }
  grid.origin = lo_all;
  const std::int64_t cells = grid.dims[0] * grid.dims[1] * grid.dims[2];
  grid.cell_start.assign(static_cast<std::size_t>(cells) + 1, 0);
  auto for_cells = [&](std::size_t s, auto&& visit) {
    Vec lo, hi;
    segment_box(x, master.segments[s], grid.expansion, lo, hi);
    std::array<std::int64_t, 3> a{}, b{};
    for (int d = 0; d < 3; ++d) {
      a[d] = std::clamp<std::int64_t>(cell_coordinate(grid, lo[d], d), 0, grid.dims[d] - 1);
      b[d] = std::clamp<std::int64_t>(cell_coordinate(grid, hi[d], d), 0, grid.dims[d] - 1);
    }
    for (auto k = a[2]; k <= b[2]; ++k)
      for (auto j = a[1]; j <= b[1]; ++j)
        for (auto i = a[0]; i <= b[0]; ++i) visit(i + grid.dims[0] * (j + grid.dims[1] * k));
  };
  for (std::size_t s = 0; s < nseg; ++s) {
    if (master.is_active_segment(s))
      for_cells(s, [&](std::int64_t c) { ++grid.cell_start[c + 1]; });
  }
  for (std::int64_t c = 0; c < cells; ++c) grid.cell_start[c + 1] += grid.cell_start[c];
  grid.cell_segments.resize(static_cast<std::size_t>(grid.cell_start[cells]));
  grid.fill.assign(grid.cell_start.begin(), grid.cell_start.end() - 1);
  for (std::size_t s = 0; s < nseg; ++s) {
    if (!master.is_active_segment(s)) continue;
    for_cells(s, [&](std::int64_t c) {
      grid.cell_segments[grid.fill[c]++] = static_cast<std::int32_t>(s);
    });
  }
  grid.visit_stamp.assign(nseg, 0);
}

// Largest displacement of the searched surface's nodes since the grid was built.
double moved_since_build(const SegmentGrid& grid, const ContactSurface& moved,
                         const solver::State& state, std::int64_t parallel_minimum) {
  const auto& x = state.nodes.x;
  const std::int64_t n = static_cast<std::int64_t>(moved.nodes.size());
  double worst2 = 0.0;
#pragma omp parallel for schedule(static) reduction(max : worst2) if (n >= parallel_minimum)
  for (std::int64_t j = 0; j < n; ++j) {
    const auto i = moved.nodes[j];
    const double dx = x.x[i] - grid.built_x[j];
    const double dy = x.y[i] - grid.built_y[j];
    const double dz = x.z[i] - grid.built_z[j];
    worst2 = std::max(worst2, dx * dx + dy * dy + dz * dz);
  }
  return std::sqrt(worst2);
}

// Cell index range of the box p +- r (empty when outside the grid).
bool cell_range(const SegmentGrid& grid, const Vec& p, double r, std::array<std::int64_t, 3>& a,
                std::array<std::int64_t, 3>& b) {
  if (grid.dims[0] == 0) return false;
  for (int d = 0; d < 3; ++d) {
    a[d] = cell_coordinate(grid, p[d] - r, d);
    b[d] = cell_coordinate(grid, p[d] + r, d);
    if (b[d] < 0 || a[d] >= grid.dims[d]) return false;
    a[d] = std::max<std::int64_t>(a[d], 0);
    b[d] = std::min<std::int64_t>(b[d], grid.dims[d] - 1);
  }
  return true;
}

// ---- Narrow phase ----

struct Projection {
  double xi = 0.0, eta = 0.0;
  double weight[4] = {0, 0, 0, 0};
  Vec point{};
  Vec normal{};  // unit, outward
  double distance2 = kInfinity;
};

// Closest point of the bilinear segment to p: Gauss-Newton on |x(xi, eta) - p|^2 with the
// parameters kept in [-1, 1]^2.
Projection project(const solver::Vec3Array& x, const std::array<std::int32_t, 4>& s, const Vec& p) {
  const Vec x1 = position(x, s[0]), x2 = position(x, s[1]), x3 = position(x, s[2]),
            x4 = position(x, s[3]);
  Projection r;
  double xi = 0.0, eta = 0.0;
  Vec xx{}, t1{}, t2{};
  for (int it = 0; it < 8; ++it) {
    const double n1 = 0.25 * (1 - xi) * (1 - eta), n2 = 0.25 * (1 + xi) * (1 - eta),
                 n3 = 0.25 * (1 + xi) * (1 + eta), n4 = 0.25 * (1 - xi) * (1 + eta);
    for (int d = 0; d < 3; ++d) {
      xx[d] = n1 * x1[d] + n2 * x2[d] + n3 * x3[d] + n4 * x4[d];
      t1[d] = 0.25 * ((1 - eta) * (x2[d] - x1[d]) + (1 + eta) * (x3[d] - x4[d]));
      t2[d] = 0.25 * ((1 - xi) * (x4[d] - x1[d]) + (1 + xi) * (x3[d] - x2[d]));
    }
    const Vec res = sub(p, xx);
    const double a11 = dot(t1, t1), a12 = dot(t1, t2), a22 = dot(t2, t2);
    const double b1 = dot(t1, res), b2 = dot(t2, res);
    const double det = a11 * a22 - a12 * a12;
    if (!(det > 0.0)) break;
    const double dxi = (a22 * b1 - a12 * b2) / det;
    const double deta = (a11 * b2 - a12 * b1) / det;
    const double xi_new = std::clamp(xi + dxi, -1.0, 1.0);
    const double eta_new = std::clamp(eta + deta, -1.0, 1.0);
    const double change = std::abs(xi_new - xi) + std::abs(eta_new - eta);
    xi = xi_new;
    eta = eta_new;
    if (change < 1e-12) break;
  }
  r.xi = xi;
  r.eta = eta;
  r.weight[0] = 0.25 * (1 - xi) * (1 - eta);
  r.weight[1] = 0.25 * (1 + xi) * (1 - eta);
  r.weight[2] = 0.25 * (1 + xi) * (1 + eta);
  r.weight[3] = 0.25 * (1 - xi) * (1 + eta);
  for (int d = 0; d < 3; ++d) {
    r.point[d] =
        r.weight[0] * x1[d] + r.weight[1] * x2[d] + r.weight[2] * x3[d] + r.weight[3] * x4[d];
    t1[d] = 0.25 * ((1 - eta) * (x2[d] - x1[d]) + (1 + eta) * (x3[d] - x4[d]));
    t2[d] = 0.25 * ((1 - xi) * (x4[d] - x1[d]) + (1 + xi) * (x3[d] - x2[d]));
  }
  Vec n = cross(t1, t2);
  double length = norm(n);
  if (!(length > 0.0)) {  // collapsed corner of a triangle: the diagonal normal
    n = diagonal_normal(x1, x2, x3, x4);
    length = norm(n);
  }
  if (length > 0.0) {
    for (int d = 0; d < 3; ++d) r.normal[d] = n[d] / length;
  }
  const Vec diff = sub(p, r.point);
  r.distance2 = dot(diff, diff);
  return r;
}

bool contains(const std::array<std::int32_t, 4>& s, std::int32_t node) {
  return s[0] == node || s[1] == node || s[2] == node || s[3] == node;
}

// kErosion: a side of the pass can erode, and the flags are tested. A model without erosion runs
// the instantiation without them: the loop of the code before erosion, instruction for
// instruction (the tests alone cost it 6-9 % of the evaluation, measured with callgrind).
template <bool kErosion>
void evaluate_pass_of(ContactInterface& contact, ContactPass& pass, const solver::State& state,
                      double dt, std::int64_t parallel_minimum) {
  const ContactSurface& slave = contact.sides[pass.slave_side];
  const ContactSurface& master = contact.sides[pass.master_side];
  const auto& x = state.nodes.x;
  const auto& v = state.nodes.v;
  const auto& mass = state.nodes.mass;
  const SegmentGrid& grid = pass.grid;
  const std::int64_t n = static_cast<std::int64_t>(slave.nodes.size());
  const double soft_dt = contact.soft_dt;
  const double reach = grid.expansion - grid.slack;
  const bool self_contact = contact.kind == model::ContactKind::SingleSurface;
  // Erosion: the flags of the sides (null: everything takes part, docs/contact.md section 7).
  const std::uint8_t* slave_active =
      kErosion && !slave.node_active.empty() ? slave.node_active.data() : nullptr;
  const std::uint8_t* own_active =
      kErosion && !slave.segment_active.empty() ? slave.segment_active.data() : nullptr;
  const std::uint8_t* master_active =
      kErosion && !master.segment_active.empty() ? master.segment_active.data() : nullptr;
#pragma omp parallel for schedule(dynamic, 256) if (n >= parallel_minimum)
  for (std::int64_t j = 0; j < n; ++j) {
    const std::int32_t node = slave.nodes[j];
    NodeContact& result = pass.results[j];
    double* ft = pass.tangential_force.data() + 3 * j;
    double* remembered = pass.contact_normal.data() + 3 * j;
    result.segment = -1;
    // Not on the live surface (interior of an erodible solid, eroded, removed): its state was
    // reset when it left.
    if constexpr (kErosion) {
      if (slave_active && !slave_active[j]) continue;
    }
    const Vec p = position(x, node);
    // The node's position at the start of the step, x^n = x^{n+1} - dt v^{n+1/2}: the side of a
    // shell it approaches from when it was not in contact before.
    const Vec p_old{p[0] - dt * v.x[node], p[1] - dt * v.y[node], p[2] - dt * v.z[node]};
    const Vec side_memory{remembered[0], remembered[1], remembered[2]};
    const std::int32_t remembered_segment = pass.contact_segment[j];
    const bool has_memory = remembered_segment >= 0 && dot(side_memory, side_memory) > 0.0;
    std::array<std::int64_t, 3> a{}, b{};
    Projection best;
    std::int32_t best_segment = -1;
    const Vec node_normal{slave.node_normal[3 * j], slave.node_normal[3 * j + 1],
                          slave.node_normal[3 * j + 2]};
    const bool has_normal = dot(node_normal, node_normal) > 0.0;
    // Single surface: the node's neighbours (the nodes of its own segments) bound no segment
    // it may contact: those segments meet the node's own at an edge or corner.
    std::array<std::int32_t, 32> neighbours{};
    int neighbour_count = 0;
    if (self_contact) {
      for (auto q = slave.node_segment_start[j]; q < slave.node_segment_start[j + 1]; ++q) {
        if constexpr (kErosion) {
          if (own_active && !own_active[slave.node_segments[q]]) continue;
        }
        for (const auto other : slave.segments[slave.node_segments[q]]) {
          bool seen = false;
          for (int a = 0; a < neighbour_count; ++a) seen |= neighbours[a] == other;
          if (!seen && neighbour_count < static_cast<int>(neighbours.size())) {
            neighbours[neighbour_count++] = other;
          }
        }
      }
    }
    if (cell_range(grid, p, 0.0, a, b)) {
      const std::int64_t c = a[0] + grid.dims[0] * (a[1] + grid.dims[1] * a[2]);
      for (auto k = grid.cell_start[c]; k < grid.cell_start[c + 1]; ++k) {
        const std::int32_t s = grid.cell_segments[k];
        // The grid lists active segments only (update_after_erosion has it rebuilt); the flag
        // is checked all the same.
        if constexpr (kErosion) {
          if (master_active && !master_active[s]) continue;
        }
        const auto& q = master.segments[s];
        if (contains(q, node)) continue;
        if (self_contact) {
          bool adjacent = false;
          for (int a = 0; a < neighbour_count && !adjacent; ++a)
            adjacent = contains(q, neighbours[a]);
          if (adjacent) continue;
        }
        // Cheap rejection: a node in contact lies within `reach` of the segment's box.
        bool outside = false;
        for (int d = 0; d < 3 && !outside; ++d) {
          const double* c = d == 0 ? x.x.data() : (d == 1 ? x.y.data() : x.z.data());
          const double lo = std::min(std::min(c[q[0]], c[q[1]]), std::min(c[q[2]], c[q[3]]));
          const double hi = std::max(std::max(c[q[0]], c[q[1]]), std::max(c[q[2]], c[q[3]]));
          outside = p[d] < lo - reach || p[d] > hi + reach;
        }
        if (outside) continue;
        Projection trial = project(x, q, p);
        if (master.two_sided[s]) {
          // A shell pushes the node back to the side it came from: the side of the node's
          // contact normal of the last cycle if it was in contact, else the side its position
          // x^n was on relative to the segment's position at x^n (docs/contact.md section 3).
          // The memory holds on the segment touched and its neighbours (a node sliding over the
          // shell): a node between two shells keeps its own side of the other one.
          bool near_remembered = false;
          if (has_memory) {
            const auto& last = master.segments[remembered_segment];
            for (int a4 = 0; a4 < 4 && !near_remembered; ++a4) {
              near_remembered = contains(q, last[a4]);
            }
          }
          double side = 0.0;
          if (near_remembered) {
            side = dot(trial.normal, side_memory);
          } else {
            Vec point_old = trial.point;
            for (int a4 = 0; a4 < 4; ++a4) {
              point_old[0] -= dt * trial.weight[a4] * v.x[q[a4]];
              point_old[1] -= dt * trial.weight[a4] * v.y[q[a4]];
              point_old[2] -= dt * trial.weight[a4] * v.z[q[a4]];
            }
            side = dot(sub(p_old, point_old), trial.normal);
          }
          if (side < 0.0) {
            for (int d = 0; d < 3; ++d) trial.normal[d] = -trial.normal[d];
          }
        }
        // Only segments that face the node's own surface (not the sides of the body it is
        // pressed against: an edge node lies in the plane of the other body's side faces).
        if (has_normal && dot(trial.normal, node_normal) > -kFacingTolerance) continue;
        if (trial.distance2 < best.distance2 ||
            (trial.distance2 == best.distance2 && s < best_segment)) {
          best = trial;
          best_segment = s;
        }
      }
    }
    bool touching = false;
    double gap = 0.0;
    if (best_segment >= 0) {
      const Vec diff = sub(p, best.point);
      const double along = dot(diff, best.normal);
      const double offset = slave.node_half_thickness[j] + master.half_thickness[best_segment];
      gap = along - offset;
      const double size = master.size[best_segment];
      Vec beside{};
      for (int d = 0; d < 3; ++d) beside[d] = diff[d] - along * best.normal[d];
      // Depth release: beyond half a segment behind a solid face's contact surface; for a shell
      // (whose side is remembered) beyond half a segment past its mid-surface.
      const double deepest =
          master.two_sided[best_segment] ? offset + kDepthFraction * size : kDepthFraction * size;
      touching = gap < 0.0 && gap > -deepest && norm(beside) <= kEdgeTolerance * size;
    }
    if (!touching) {
      ft[0] = ft[1] = ft[2] = 0.0;
      remembered[0] = remembered[1] = remembered[2] = 0.0;
      pass.contact_segment[j] = -1;
      continue;
    }
    for (int d = 0; d < 3; ++d) remembered[d] = best.normal[d];
    pass.contact_segment[j] = best_segment;
    const auto& segment = master.segments[best_segment];
    // Stiffness (docs/contact.md): SOFT = 0, the smaller of the master segment's SLSFAC K A^2 / V
    // and that of the node's own segment that faces it most directly, each with its side's
    // scale (SFM / SFS) (PENOPT 1; 2 takes the segment's, 3 the node's); SOFT = 1, at least the
    // soft-constraint stiffness 0.5 SOFSCL m / dt_c^2 with m the pair's reduced mass.
    double k = pass.master_scale * master.stiffness[best_segment];
    if (contact.penopt != 2 || std::isinf(k)) {
      double most_opposed = 2.0;
      double k_slave = kInfinity;
      for (auto q = slave.node_segment_start[j]; q < slave.node_segment_start[j + 1]; ++q) {
        if constexpr (kErosion) {
          if (own_active && !own_active[slave.node_segments[q]]) continue;
        }
        const auto& own = slave.segments[slave.node_segments[q]];
        const Vec n_own = diagonal_normal(position(x, own[0]), position(x, own[1]),
                                          position(x, own[2]), position(x, own[3]));
        const double length = norm(n_own);
        if (!(length > 0.0)) continue;
        double facing = dot(n_own, best.normal) / length;
        if (slave.two_sided[slave.node_segments[q]]) facing = -std::abs(facing);
        if (facing < most_opposed) {
          most_opposed = facing;
          k_slave = slave.stiffness[slave.node_segments[q]];
        }
      }
      const double k_node = pass.slave_scale * k_slave;
      k = contact.penopt == 3 && !std::isinf(k_node) ? k_node : std::min(k, k_node);
    }
    const double m_slave = mass[node];
    const double m_master = master.mass[best_segment];
    double m_pair = m_slave;
    if (m_slave > 0.0 && m_master > 0.0 && !std::isinf(m_master)) {
      m_pair = m_slave * m_master / (m_slave + m_master);
    }
    if (m_slave <= 0.0) m_pair = std::isinf(m_master) ? 0.0 : m_master;
    if (contact.soft == 1 && soft_dt > 0.0) {
      const double k_soft = 0.5 * contact.sofscl * m_pair / (soft_dt * soft_dt);
      k = std::isinf(k) ? k_soft : std::max(k, k_soft);
    }
    // Stability: the pair's spring must not raise the frequency of the nodes beyond what the
    // element step leaves (omega_e dt <= 0.9 * 2): k dt^2 / m <= 0.5 leaves (omega dt)^2 <= 3.74
    // even with a symmetric second pass, below the limit 4 (docs/contact.md).
    if (dt > 0.0 && m_pair > 0.0) k = std::min(k, pass.stability_scale * m_pair / (dt * dt));
    if (std::isinf(k)) k = 0.0;  // neither side has a stiffness (rejected when building)
    // Relative velocity of the node and the segment point at n+1/2.
    Vec v_rel{v.x[node], v.y[node], v.z[node]};
    for (int a4 = 0; a4 < 4; ++a4) {
      const auto m = segment[a4];
      v_rel[0] -= best.weight[a4] * v.x[m];
      v_rel[1] -= best.weight[a4] * v.y[m];
      v_rel[2] -= best.weight[a4] * v.z[m];
    }
    const Vec& nrm = best.normal;
    const double vn = dot(v_rel, nrm);
    double fn = -k * gap;
    if (contact.vdc > 0.0 && m_pair > 0.0) {
      // Viscous damping VDC percent of critical for the pair's oscillator (k, m_pair).
      fn -= 0.01 * contact.vdc * 2.0 * std::sqrt(k * m_pair) * vn;
    }
    fn = std::max(fn, 0.0);  // contact pushes only
    Vec force{fn * nrm[0], fn * nrm[1], fn * nrm[2]};
    const double mu_static = contact.fs * contact.fsf;
    if (mu_static > 0.0 || contact.fd > 0.0) {
      Vec vt{};
      for (int d = 0; d < 3; ++d) vt[d] = v_rel[d] - vn * nrm[d];
      // The spring force kept from the last cycle, turned into the current tangent plane with
      // its magnitude kept, then the trial increment -k dt v_t and the return map onto the cone.
      Vec f{ft[0], ft[1], ft[2]};
      const double old_magnitude = norm(f);
      const double fn_part = dot(f, nrm);
      for (int d = 0; d < 3; ++d) f[d] -= fn_part * nrm[d];
      const double projected = norm(f);
      if (projected > 0.0) {
        for (int d = 0; d < 3; ++d) f[d] *= old_magnitude / projected;
      }
      for (int d = 0; d < 3; ++d) f[d] -= k * dt * vt[d];
      const double mu =
          contact.fsf * (contact.fd + (contact.fs - contact.fd) * std::exp(-contact.dc * norm(vt)));
      const double cap = mu * fn;
      const double magnitude = norm(f);
      if (magnitude > cap && magnitude > 0.0) {
        for (int d = 0; d < 3; ++d) f[d] *= cap / magnitude;
      }
      for (int d = 0; d < 3; ++d) {
        ft[d] = f[d];
        force[d] += f[d];
      }
    } else {
      ft[0] = ft[1] = ft[2] = 0.0;
    }
    result.segment = best_segment;
    for (int a4 = 0; a4 < 4; ++a4) result.weight[a4] = best.weight[a4];
    for (int d = 0; d < 3; ++d) result.force[d] = force[d];
    result.gap = gap;
  }
}

void evaluate_pass(ContactInterface& contact, ContactPass& pass, const solver::State& state,
                   double dt, std::int64_t parallel_minimum) {
  if (contact.sides[pass.slave_side].erodible || contact.sides[pass.master_side].erodible) {
    evaluate_pass_of<true>(contact, pass, state, dt, parallel_minimum);
  } else {
    evaluate_pass_of<false>(contact, pass, state, dt, parallel_minimum);
  }
}

void update_grid(ContactInterface& contact, ContactPass& pass, const solver::State& state,
                 std::int64_t parallel_minimum) {
  const ContactSurface& master = contact.sides[pass.master_side];
  SegmentGrid& grid = pass.grid;
  if (!grid.built || moved_since_build(grid, master, state, parallel_minimum) > grid.slack) {
    build_grid(grid, master, master, state);
  }
}

}  // namespace

ContactSystem build_contacts(const model::Model& model, const solver::NodeIndex& node_index,
                             const solver::State& state) {
  ContactSystem system;
  std::set<std::int32_t> all_nodes;
  for (const auto& c : model.contacts) {
    ContactInterface contact;
    contact.number = c.number;
    contact.id = c.id;
    contact.heading = c.heading;
    contact.kind = c.kind;
    contact.fs = c.fs;
    contact.fd = c.fd;
    contact.dc = c.dc;
    contact.vdc = c.vdc;
    contact.fsf = c.fsf;
    contact.birth = c.birth;
    contact.death = c.death;
    contact.soft = c.soft;
    contact.sofscl = c.sofscl;
    contact.where = c.where;
    const bool single = c.kind == model::ContactKind::SingleSurface;
    contact.sides[0] = build_side(model, node_index, state, c, c.ssid, c.sstyp, "SSID",
                                  SideThickness{c.sst, c.sfst});
    contact.sides[1] = single ? contact.sides[0]
                              : build_side(model, node_index, state, c, c.msid, c.mstyp, "MSID",
                                           SideThickness{c.mst, c.sfmt});
    if (contact.sides[1].segments.empty()) {
      throw InputError(model::context_of(c.where, "MSID"), "the master side has no segments");
    }
    // *CONTROL_CONTACT SLSFAC: the segment stiffnesses above use LS-DYNA's default 0.1.
    if (const double scale = model.contact_control.slsfac / kSlsfac; scale != 1.0) {
      for (ContactSurface& side : contact.sides) {
        for (double& k : side.stiffness) k *= scale;
        for (double& k : side.node_stiffness) k *= scale;
      }
    }
    contact.penopt = model.contact_control.penopt;
    auto add_pass = [&](int slave_side, int master_side) {
      ContactPass pass;
      pass.slave_side = slave_side;
      pass.master_side = master_side;
      pass.slave_scale = slave_side == 0 ? c.sfs : c.sfm;
      pass.master_scale = master_side == 0 ? c.sfs : c.sfm;
      const ContactSurface& master = contact.sides[master_side];
      const ContactSurface& slave = contact.sides[slave_side];
      bool stiff = false;
      for (const double k : master.stiffness) stiff |= !std::isinf(k);
      for (const double k : slave.node_stiffness) stiff |= !std::isinf(k);
      if (!stiff && c.soft != 1) {
        throw InputError(model::context_of(c.where, "SOFT"),
                         "neither side of the contact has a bulk modulus to take the penalty "
                         "stiffness from (give E and PR on the materials, or SOFT = 1)");
      }
      // Grid: nodes within reach (thickness offsets plus the deepest penetration considered)
      // of a segment find it; the grid is rebuilt after the segments moved half a segment.
      const double reach =
          slave.max_half_thickness + master.max_half_thickness + kDepthFraction * master.max_size;
      pass.grid.slack = 0.5 * master.max_size;
      pass.grid.expansion = reach + pass.grid.slack + 1e-9 * master.max_size;
      pass.results.resize(slave.nodes.size());
      pass.tangential_force.assign(3 * slave.nodes.size(), 0.0);
      pass.contact_normal.assign(3 * slave.nodes.size(), 0.0);
      pass.contact_segment.assign(slave.nodes.size(), -1);
      contact.passes.push_back(std::move(pass));
    };
    add_pass(0, 1);
    if (c.kind == model::ContactKind::SurfaceToSurface) add_pass(1, 0);
    // Two springs can act on one pair of nodes when both sides search each other: in the two
    // passes of a surface-to-surface contact, and within the one pass of a single surface.
    if (c.kind == model::ContactKind::SurfaceToSurface ||
        c.kind == model::ContactKind::SingleSurface) {
      for (auto& pass : contact.passes) pass.stability_scale = 0.25;
    }
    for (const auto& side : contact.sides) all_nodes.insert(side.nodes.begin(), side.nodes.end());
    system.interfaces.push_back(std::move(contact));
  }
  system.nodes.assign(all_nodes.begin(), all_nodes.end());
  if (!system.interfaces.empty()) system.force.resize(state.nodes.size());
  return system;
}

void compute_contact_forces(ContactSystem& system, const solver::State& state, double dt) {
  if (system.empty()) return;
  auto& f = system.force;
  for (const auto i : system.nodes) f.x[i] = f.y[i] = f.z[i] = 0.0;
  const double t = state.time;
  for (auto& contact : system.interfaces) {
    contact.slave_force = {0.0, 0.0, 0.0};
    contact.active_nodes = 0;
    for (auto& pass : contact.passes) update_grid(contact, pass, state, system.parallel_minimum);
    const bool alive = t >= contact.birth && t <= contact.death;
    if (!alive) {
      for (auto& pass : contact.passes) {
        std::fill(pass.tangential_force.begin(), pass.tangential_force.end(), 0.0);
        std::fill(pass.contact_normal.begin(), pass.contact_normal.end(), 0.0);
        std::fill(pass.contact_segment.begin(), pass.contact_segment.end(), -1);
        for (auto& r : pass.results) r.segment = -1;
      }
      continue;
    }
    if (contact.soft == 1 && contact.soft_dt == 0.0 && dt > 0.0) contact.soft_dt = dt;
    for (int side = 0; side < 2; ++side) {
      bool searched = false;
      for (const auto& pass : contact.passes) searched |= pass.slave_side == side;
      if (side == 1 && contact.kind == model::ContactKind::SingleSurface) searched = false;
      if (searched && !contact.sides[side].segments.empty()) {
        update_node_normals(contact.sides[side], state.nodes.x, system.parallel_minimum);
      }
    }
    for (auto& pass : contact.passes) {
      evaluate_pass(contact, pass, state, dt, system.parallel_minimum);
      // Gather in slave-node order: the same sums for any number of threads.
      const ContactSurface& slave = contact.sides[pass.slave_side];
      const ContactSurface& master = contact.sides[pass.master_side];
      const double sign = pass.slave_side == 0 ? 1.0 : -1.0;
      for (std::size_t j = 0; j < slave.nodes.size(); ++j) {
        const NodeContact& r = pass.results[j];
        if (r.segment < 0) continue;
        ++contact.active_nodes;
        const auto node = slave.nodes[j];
        f.x[node] += r.force[0];
        f.y[node] += r.force[1];
        f.z[node] += r.force[2];
        const auto& segment = master.segments[r.segment];
        for (int a = 0; a < 4; ++a) {
          f.x[segment[a]] -= r.weight[a] * r.force[0];
          f.y[segment[a]] -= r.weight[a] * r.force[1];
          f.z[segment[a]] -= r.weight[a] * r.force[2];
        }
        for (int d = 0; d < 3; ++d) contact.slave_force[d] += sign * r.force[d];
      }
    }
  }
}

void update_after_erosion(ContactSystem& system, const solver::State& state) {
  for (auto& contact : system.interfaces) {
    std::array<bool, 2> changed{false, false};
    for (int side = 0; side < 2; ++side) {
      changed[side] = refresh_active(contact.sides[side], state);
    }
    bool result_reset = false;
    for (auto& pass : contact.passes) {
      const ContactSurface& slave = contact.sides[pass.slave_side];
      const ContactSurface& master = contact.sides[pass.master_side];
      if (changed[pass.master_side]) pass.grid.built = false;
      if (!slave.erodible && !master.erodible) continue;
      // Slave nodes off the live surface, and nodes whose segment (found, or remembered for the
      // side of a shell) has left: no result, no friction spring, no side memory. Resetting
      // what is already reset changes nothing, so a second call (a restart) is harmless.
      for (std::size_t j = 0; j < slave.nodes.size(); ++j) {
        const std::int32_t found = pass.results[j].segment;
        const std::int32_t remembered = pass.contact_segment[j];
        const bool left =
            !slave.is_active_node(j) ||
            (found >= 0 && !master.is_active_segment(static_cast<std::size_t>(found))) ||
            (remembered >= 0 && !master.is_active_segment(static_cast<std::size_t>(remembered)));
        if (!left) continue;
        result_reset |= found >= 0;
        pass.results[j] = NodeContact{};
        for (int d = 0; d < 3; ++d) {
          pass.tangential_force[3 * j + d] = 0.0;
          pass.contact_normal[3 * j + d] = 0.0;
        }
        pass.contact_segment[j] = -1;
      }
    }
    if (!result_reset) continue;
    // The resultant and count that resultant_force() and the output report: the remaining
    // results, summed in the order of compute_contact_forces.
    contact.slave_force = {0.0, 0.0, 0.0};
    contact.active_nodes = 0;
    for (const auto& pass : contact.passes) {
      const double sign = pass.slave_side == 0 ? 1.0 : -1.0;
      for (const auto& r : pass.results) {
        if (r.segment < 0) continue;
        ++contact.active_nodes;
        for (int d = 0; d < 3; ++d) contact.slave_force[d] += sign * r.force[d];
      }
    }
  }
}

void add_contact_forces(const ContactSystem& system, solver::State& state) {
  if (system.empty()) return;
  auto& f = state.nodes.f_ext;
  for (const auto i : system.nodes) {
    f.x[i] += system.force.x[i];
    f.y[i] += system.force.y[i];
    f.z[i] += system.force.z[i];
  }
}

double resultant_force(const ContactSystem& system, model::Id contact_id) {
  for (const auto& contact : system.interfaces) {
    if (contact.id != contact_id) continue;
    const auto& f = contact.slave_force;
    return std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  }
  return -1.0;
}

bool within_offset(const ContactSystem& system, model::Id contact_id, double offset,
                   const std::vector<model::Id>& parts, const solver::State& state) {
  const ContactInterface* contact = nullptr;
  for (const auto& c : system.interfaces) {
    if (c.id == contact_id) contact = &c;
  }
  if (!contact || contact->passes.empty()) return false;
  const ContactPass& pass = contact->passes.front();
  const ContactSurface& slave = contact->sides[pass.slave_side];
  const ContactSurface& master = contact->sides[pass.master_side];
  auto named = [&](model::Id pid) {
    return std::find(parts.begin(), parts.end(), pid) != parts.end();
  };
  bool master_named = false;
  for (const auto pid : master.part) master_named |= named(pid);
  const auto& x = state.nodes.x;
  const SegmentGrid& grid = pass.grid;
  const double offset2 = offset * offset;
  for (std::size_t j = 0; j < slave.nodes.size(); ++j) {
    if (!slave.is_active_node(j)) continue;
    const bool node_named = named(slave.node_part[j]);
    if (!node_named && !master_named) continue;
    const auto node = slave.nodes[j];
    const Vec p = position(x, node);
    auto close = [&](std::int32_t s) {
      if (!master.is_active_segment(static_cast<std::size_t>(s))) return false;
      if (!node_named && !named(master.part[s])) return false;
      if (contains(master.segments[s], node)) return false;
      const Projection r = project(x, master.segments[s], p);
      if (r.distance2 < offset2) return true;
      // A node that has already penetrated is within any offset (a shell: a node closer to
      // its mid-surface than the two contact thicknesses, on either side).
      const Vec diff = sub(p, r.point);
      const double along = dot(diff, r.normal);
      Vec beside{};
      for (int d = 0; d < 3; ++d) beside[d] = diff[d] - along * r.normal[d];
      const double size = master.size[s];
      if (norm(beside) > kEdgeTolerance * size) return false;
      if (master.two_sided[s]) {
        return std::abs(along) < slave.node_half_thickness[j] + master.half_thickness[s];
      }
      return along < 0.0 && along > -kDepthFraction * size;
    };
    if (!grid.built) {  // before the first evaluation: every segment
      for (std::size_t s = 0; s < master.segments.size(); ++s) {
        if (close(static_cast<std::int32_t>(s))) return true;
      }
      continue;
    }
    std::array<std::int64_t, 3> a{}, b{};
    if (!cell_range(grid, p, offset, a, b)) continue;
    const std::int64_t stamp = ++grid.stamp;
    for (auto k = a[2]; k <= b[2]; ++k)
      for (auto jj = a[1]; jj <= b[1]; ++jj)
        for (auto i = a[0]; i <= b[0]; ++i) {
          const std::int64_t c = i + grid.dims[0] * (jj + grid.dims[1] * k);
          for (auto q = grid.cell_start[c]; q < grid.cell_start[c + 1]; ++q) {
            const std::int32_t s = grid.cell_segments[q];
            if (grid.visit_stamp[s] == stamp) continue;
            grid.visit_stamp[s] = stamp;
            if (close(s)) return true;
          }
        }
  }
  return false;
}

}  // namespace rf::contact
