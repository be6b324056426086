#include "contact/wall_drawing.hpp"

#include <algorithm>
#include <cmath>

namespace rf::contact {

std::vector<output::WallPatch> wall_patches(const RigidWallSystem& walls,
                                            const solver::State& state) {
  const solver::Vec3Array& x0 = state.nodes.x0;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (std::size_t i = 0; i < x0.size(); ++i) {
    const Eigen::Vector3d p(x0.x[i], x0.y[i], x0.z[i]);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const bool empty = x0.size() == 0;
  const Eigen::Vector3d centre = empty ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0.5 * (lo + hi));
  const double diagonal = empty ? 1.0 : std::max((hi - lo).norm(), 1e-30);

  std::vector<output::WallPatch> patches;
  for (const RigidWall& wall : walls.walls) {
    if (wall.shape != WallShape::Plane) continue;  // prisms, cylinders, spheres: not drawn
    const Eigen::Vector3d n = wall.normal.normalized();
    const Eigen::Vector3d origin = wall.origin + wall.displacement * wall.motion_direction;
    Eigen::Vector3d l = wall.edge_l, m = wall.edge_m;
    if (!wall.finite) {
      // Any in-plane pair: the global axis least aligned with the normal, projected.
      Eigen::Index axis = 0;
      n.cwiseAbs().minCoeff(&axis);
      l = (Eigen::Vector3d::Unit(axis) - n[axis] * n).normalized();
      m = n.cross(l);
    }
    auto range = [&](const Eigen::Vector3d& e, double length) {
      if (wall.finite && length > 0.0) return std::pair{0.0, length};
      const double c = (centre - origin).dot(e);
      return std::pair{c - 0.6 * diagonal, c + 0.6 * diagonal};
    };
    const auto [a0, a1] = range(l, wall.length_l);
    const auto [b0, b1] = range(m, wall.length_m);
    output::WallPatch patch;
    patch.id = wall.id;
    patch.normal_force = wall.normal_force;
    const double corners[4][2] = {{a0, b0}, {a1, b0}, {a1, b1}, {a0, b1}};
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d p = origin + corners[k][0] * l + corners[k][1] * m;
      patch.corners[k] = {p.x(), p.y(), p.z()};
    }
    patches.push_back(patch);
  }
  return patches;
}

}  // namespace rf::contact
