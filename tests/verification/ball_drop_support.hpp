// Shared by the switching tests that drop an elastic ball: its hexahedral mesh and measurements
// of the nodal state that do not come from the solver's own sums.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "deck_builder.hpp"
#include "switching/part_switching.hpp"

namespace rf::test {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// A hexahedral ball of radius r: an inner block of (2m)^3 hexahedra and, on each of its six
// faces, (2m)^2 x layers hexahedra extruded along rays to the sphere. The inner block is the cube
// [-a, a]^3 with its concentric cube surfaces blended (weight `rounding`) towards spheres, so
// that its corners are not the 90 degree corners that would flatten the shell elements there.
// Grid point g in [-m, m]^3 (integers), layer l (0: on the inner block's surface).
struct BallMesh {
  int m = 3, layers = 3;
  double radius = 0.1, inner = 0.05, rounding = 0.5;
  Vector3d centre = Vector3d::Zero();

  Vector3d inner_point(const Vector3d& c) const {  // c in [-1, 1]^3
    const double euclid = c.norm();
    if (euclid == 0.0) return Vector3d::Zero();
    return inner * ((1.0 - rounding) * c + rounding * c * (c.cwiseAbs().maxCoeff() / euclid));
  }
  Vector3d position(const Eigen::Vector3i& g, int l) const {
    const Vector3d c = g.cast<double>() / m;
    const double t = static_cast<double>(l) / layers;
    return centre + (1.0 - t) * inner_point(c) +
           (l == 0 ? Vector3d::Zero() : Vector3d(t * radius * c.normalized()));
  }

  // Elements as 8 (grid point, layer) corners in LS-DYNA order (positive volume).
  using Corner = std::pair<Eigen::Vector3i, int>;
  std::vector<std::array<Corner, 8>> elements() const {
    std::vector<std::array<Corner, 8>> out;
    for (int k = -m; k < m; ++k)
      for (int j = -m; j < m; ++j)
        for (int i = -m; i < m; ++i) {
          const auto g = [&](int a, int b, int c) { return Corner{{i + a, j + b, k + c}, 0}; };
          out.push_back({g(0, 0, 0), g(1, 0, 0), g(1, 1, 0), g(0, 1, 0), g(0, 0, 1), g(1, 0, 1),
                         g(1, 1, 1), g(0, 1, 1)});
        }
    // Face d (axis), side s: face coordinates (u, v) along axes chosen so that u, v and the
    // outward normal are right-handed; layers go outwards.
    for (int d = 0; d < 3; ++d)
      for (const int s : {-1, 1}) {
        int u_axis = (d + 1) % 3, v_axis = (d + 2) % 3;
        if (s < 0) std::swap(u_axis, v_axis);
        for (int u = -m; u < m; ++u)
          for (int v = -m; v < m; ++v)
            for (int l = 0; l < layers; ++l) {
              const auto g = [&](int a, int b, int layer) {
                Eigen::Vector3i p;
                p[d] = s * m;
                p[u_axis] = u + a;
                p[v_axis] = v + b;
                return Corner{p, layer};
              };
              out.push_back({g(0, 0, l), g(1, 0, l), g(1, 1, l), g(0, 1, l), g(0, 0, l + 1),
                             g(1, 0, l + 1), g(1, 1, l + 1), g(0, 1, l + 1)});
            }
      }
    return out;
  }

  // Node IDs 1.. in order of first use, positions, and element connectivity.
  struct Numbered {
    std::vector<Vector3d> nodes;
    std::vector<std::array<int, 8>> elements;
  };
  Numbered numbered() const {
    Numbered out;
    std::map<std::array<int, 4>, int> ids;
    for (const auto& element : elements()) {
      std::array<int, 8> connectivity{};
      for (int c = 0; c < 8; ++c) {
        const auto& [g, l] = element[c];
        const std::array<int, 4> key{g.x(), g.y(), g.z(), l};
        auto [it, fresh] = ids.try_emplace(key, static_cast<int>(out.nodes.size()) + 1);
        if (fresh) out.nodes.push_back(position(g, l));
        connectivity[c] = it->second;
      }
      out.elements.push_back(connectivity);
    }
    return out;
  }

  std::string keyword_text(int pid = 1) const {
    const Numbered mesh = numbered();
    std::string s = "*NODE\n";
    for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
      const Vector3d& p = mesh.nodes[i];
      s += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", i + 1, p.x(), p.y(), p.z());
    }
    s += "*ELEMENT_SOLID\n";
    for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
      const auto& n = mesh.elements[e];
      s += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", e + 1, pid, n[0], n[1], n[2], n[3], n[4],
                       n[5], n[6], n[7]);
    }
    return s;
  }
};

// Smallest corner Jacobian of the hexahedra, each scaled by its three edge lengths (1: a right
// angle corner, <= 0: degenerate or inverted), from the connectivity and positions alone.
inline double smallest_scaled_jacobian(const BallMesh::Numbered& mesh) {
  // Corner c and its neighbours along +xi, +eta, +zeta in the element's orientation.
  static constexpr int kNeighbours[8][4] = {{0, 1, 3, 4}, {1, 2, 0, 5}, {2, 3, 1, 6}, {3, 0, 2, 7},
                                            {4, 7, 5, 0}, {5, 4, 6, 1}, {6, 5, 7, 2}, {7, 6, 4, 3}};
  double worst = std::numeric_limits<double>::infinity();
  for (const auto& n : mesh.elements) {
    for (const auto& c : kNeighbours) {
      const Vector3d& x = mesh.nodes[n[c[0]] - 1];
      const Vector3d a = mesh.nodes[n[c[1]] - 1] - x, b = mesh.nodes[n[c[2]] - 1] - x,
                     d = mesh.nodes[n[c[3]] - 1] - x;
      worst = std::min(worst, a.cross(b).dot(d) / (a.norm() * b.norm() * d.norm()));
    }
  }
  return worst;
}

// Momentum of free nodes plus bodies, both at v^{n+1/2}.
inline Vector3d total_momentum(const solver::Simulation& sim) {
  Vector3d p = Vector3d::Zero();
  const auto& n = sim.state().nodes;
  const auto& rigid = sim.rigid_bodies();
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (rigid.is_rigid(static_cast<std::int32_t>(i))) continue;
    p += n.mass[i] * Vector3d(n.v.x[i], n.v.y[i], n.v.z[i]);
  }
  for (const auto& b : rigid.bodies) p += b.state.mass * b.state.velocity;
  return p;
}

// Nodal kinetic energy, mass, centre of mass and the kinetic energy of the best rigid fit
// (same linear and angular momentum) of the nodal velocity field. Nodes of a body carry its
// velocity field, so these are totals; the fit is this test's own, not the switcher's.
struct NodalField {
  double mass = 0.0, kinetic = 0.0, rigid_kinetic = 0.0;
  Vector3d centre = Vector3d::Zero(), p = Vector3d::Zero();
};

inline NodalField nodal_field(const solver::State& s) {
  NodalField f;
  const auto& n = s.nodes;
  Vector3d h = Vector3d::Zero();
  for (std::size_t i = 0; i < n.size(); ++i) {
    const Vector3d x(n.x.x[i], n.x.y[i], n.x.z[i]), v(n.v.x[i], n.v.y[i], n.v.z[i]);
    f.mass += n.mass[i];
    f.centre += n.mass[i] * x;
    f.p += n.mass[i] * v;
    h += x.cross(n.mass[i] * v);
    f.kinetic += 0.5 * n.mass[i] * v.squaredNorm();
  }
  f.centre /= f.mass;
  Matrix3d inertia = Matrix3d::Zero();
  for (std::size_t i = 0; i < n.size(); ++i) {
    const Vector3d r = Vector3d(n.x.x[i], n.x.y[i], n.x.z[i]) - f.centre;
    inertia += n.mass[i] * (r.squaredNorm() * Matrix3d::Identity() - r * r.transpose());
  }
  const Vector3d omega = inertia.inverse() * (h - f.centre.cross(f.p));
  f.rigid_kinetic = 0.5 * f.p.squaredNorm() / f.mass + 0.5 * omega.dot(inertia * omega);
  return f;
}

inline double lowest_z(const solver::State& s) {
  return *std::min_element(s.nodes.x.z.begin(), s.nodes.x.z.end());
}

// The time of v^{n+1/2} after Simulation::cycle() (the last cycle stops before the positions).
inline double half_step_time(const solver::Simulation& sim) {
  return sim.finished() ? sim.state().time + 0.5 * sim.state().dt
                        : sim.state().time - 0.5 * sim.state().dt_prev;
}

// The paired-set sequence of the drop tests (set 10 rigid, set 20 deformable): rigid at the
// start, deformable before the first push (OFFSET), rigid again only after the last push.
inline void expect_rigid_deformable_rigid(const std::vector<switching::SwitchEvent>& events,
                                          double first_push, double last_push) {
  for (const auto& e : events) {
    std::printf("switch set %lld at t = %.6f to %s, kinetic energy %.6f -> %.6f\n",
                static_cast<long long>(e.swset), e.time, e.to_rigid ? "rigid" : "deformable",
                e.kinetic_energy_before, e.kinetic_energy_after);
  }
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].swset, 10);
  EXPECT_TRUE(events[0].to_rigid);
  EXPECT_EQ(events[0].time, 0.0);
  EXPECT_EQ(events[1].swset, 20);
  EXPECT_FALSE(events[1].to_rigid);
  EXPECT_EQ(events[2].swset, 10);
  EXPECT_TRUE(events[2].to_rigid);
  EXPECT_LT(events[1].time, first_push);  // OFFSET: switched before the first push
  EXPECT_GT(events[2].time, last_push);   // and rigid only after the last
}

}  // namespace rf::test
