// Structured hexahedral meshes of simple solids (IMPETUS *COMPONENT_BOX, *COMPONENT_CYLINDER).
// The generators return coordinates and 8-node connectivity by local index; the reader turns
// them into numbered nodes and elements.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace rf::mesh {

struct GeneratedMesh {
  std::vector<std::array<double, 3>> nodes;
  // LS-DYNA node order: n1..n4 counter-clockwise seen from n5..n8, so every Jacobian is positive.
  std::vector<std::array<std::int32_t, 8>> hexes;
};

// Box between opposite corners lo and hi (axis-aligned), nx x ny x nz elements.
GeneratedMesh generate_box(const std::array<double, 3>& lo, const std::array<double, 3>& hi, int nx,
                           int ny, int nz);

// Solid cylinder from end centre p1 to end centre p2 with the given radius. The cross-section
// is an O-grid ("butterfly"): a central square of n x n elements surrounded by four blocks of
// n (around) x m (radial) elements, so 4n elements lie on the circumference and no element
// degenerates at the axis. n_axial layers along the axis.
struct CylinderDivisions {
  int axial = 1;
  int square = 2;  // n: elements along a side of the central square (4n around)
  int radial = 1;  // m: element layers between the square and the mantle
};
GeneratedMesh generate_cylinder(const std::array<double, 3>& p1, const std::array<double, 3>& p2,
                                double radius, const CylinderDivisions& divisions);

// Index of the node nearest to each point of `points` among `candidates` within `tolerance`;
// used by *MERGE_DUPLICATED_NODES. Returns -1 where none is that close. Spatial hashing keeps
// it O(n).
std::vector<std::int64_t> nearest_within(const std::vector<std::array<double, 3>>& candidates,
                                         const std::vector<std::array<double, 3>>& points,
                                         double tolerance);

}  // namespace rf::mesh
