// Test helpers shared by the shell kernel tests (shell_kernel_test.cpp for ELFORM 2,
// shell16_kernel_test.cpp for ELFORM 16): a mesh of nodes with velocities and rotations around
// one ShellBlock, the co-rotational axes computed independently of the kernel, and the distorted
// 4-element patch of the patch tests.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "element/shell_block.hpp"

namespace rf::test {

using rf::element::ShellBlock;

struct ShellMesh {
  std::vector<double> x, y, z, vx, vy, vz, wx, wy, wz;
  ShellBlock block;

  int add_node(double px, double py, double pz) {
    for (auto* v : {&x, &y, &z, &vx, &vy, &vz, &wx, &wy, &wz}) v->push_back(0.0);
    x.back() = px;
    y.back() = py;
    z.back() = pz;
    return static_cast<int>(x.size()) - 1;
  }
  void add_element(std::array<int, 4> c, double t) {
    block.element_id.push_back(static_cast<rf::model::Id>(block.element_id.size() + 1));
    for (int k : c) {
      block.conn.push_back(k);
      block.rotation_conn.push_back(k);
      block.thickness.push_back(t);
    }
  }
  rf::element::NodalView view() const {
    return {x.data(), y.data(), z.data(), vx.data(), vy.data(), vz.data()};
  }
  rf::element::RotationalView rotations() const { return {wx.data(), wy.data(), wz.data()}; }
  void initialize() { rf::element::initialize_shell_block(block, view()); }
  rf::element::KernelResult step(double dt) {
    return rf::element::compute_shell_forces(block, view(), rotations(), dt);
  }
  // Moves the nodes by dt v (after a step was computed at the new positions: the caller sets
  // positions; see place_for_step).
  // Sets x^{n+1} = X + dt/2 v so that the mid-step configuration is exactly X.
  void place_for_step(const std::vector<std::array<double, 3>>& X, double dt) {
    for (std::size_t i = 0; i < X.size(); ++i) {
      x[i] = X[i][0] + 0.5 * dt * vx[i];
      y[i] = X[i][1] + 0.5 * dt * vy[i];
      z[i] = X[i][2] + 0.5 * dt * vz[i];
    }
  }
  std::vector<std::array<double, 3>> positions() const {
    std::vector<std::array<double, 3>> p(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) p[i] = {x[i], y[i], z[i]};
    return p;
  }
  // Velocity (d = 0..2) or angular velocity (d = 3..5) of a node.
  double* dof(std::size_t node, int d) {
    std::vector<double>* a[6] = {&vx, &vy, &vz, &wx, &wy, &wz};
    return &(*a[d])[node];
  }
};

// Co-rotational axes as the BLT paper defines them, computed here independently.
struct Axes {
  double e[3][3];
};
inline Axes element_axes(const std::array<double, 3> p[4]) {
  auto sub = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::array<double, 3>{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  };
  auto cross = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::array<double, 3>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                                 a[0] * b[1] - a[1] * b[0]};
  };
  auto unit = [](std::array<double, 3> a) {
    const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return std::array<double, 3>{a[0] / n, a[1] / n, a[2] / n};
  };
  const auto e3 = unit(cross(sub(p[2], p[0]), sub(p[3], p[1])));
  auto s = sub(p[1], p[0]);
  const double sn = s[0] * e3[0] + s[1] * e3[1] + s[2] * e3[2];
  for (int i = 0; i < 3; ++i) s[i] -= sn * e3[i];
  const auto e1 = unit(s);
  const auto e2 = cross(e3, e1);
  Axes a;
  for (int i = 0; i < 3; ++i) {
    a.e[0][i] = e1[i];
    a.e[1][i] = e2[i];
    a.e[2][i] = e3[i];
  }
  return a;
}

// Rotates a symmetric in-plane tensor given in global axes (2x2 block in e1/e2 of the plane's
// own basis u, w) to the element axes: s_ab = (e_a . T e_b).
inline std::array<double, 3> to_element_axes(const Axes& a, const double T[3][3]) {
  auto contract = [&](int i, int j) {
    double s = 0.0;
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) s += a.e[i][k] * T[k][l] * a.e[j][l];
    return s;
  };
  return {contract(0, 0), contract(1, 1), contract(0, 1)};
}

// Irregular 4-element patch on the unit square, interior node at (0.45, 0.58), in a plane
// spanned by unit vectors u and w through the point o.
// A linear in-plane velocity field on a patch in the plane spanned by the unit vectors u, w:
// v = (Lab (a, b)) in plane coordinates a, b along u, w about the point (0.3, -0.2, 0.5), at the
// node positions X (a spin part in Lab turns the patch rigidly).
inline void set_in_plane_linear_velocity(ShellMesh& m, const std::vector<std::array<double, 3>>& X,
                                         const double u[3], const double w[3],
                                         const double Lab[2][2]) {
  for (std::size_t i = 0; i < X.size(); ++i) {
    const double r[3] = {X[i][0] - 0.3, X[i][1] + 0.2, X[i][2] - 0.5};
    const double a = r[0] * u[0] + r[1] * u[1] + r[2] * u[2];
    const double b = r[0] * w[0] + r[1] * w[1] + r[2] * w[2];
    const double va = Lab[0][0] * a + Lab[0][1] * b, vb = Lab[1][0] * a + Lab[1][1] * b;
    m.vx[i] = va * u[0] + vb * w[0];
    m.vy[i] = va * u[1] + vb * w[1];
    m.vz[i] = va * u[2] + vb * w[2];
  }
}

// The plane stress C eps (isotropic, E, nu) of that field's strain over dt, as a global tensor
// T; returns |s_a| + |s_b|, the scale of the tests' tolerances.
inline double plane_stress_of_in_plane_rate(const double Lab[2][2], double dt, const double u[3],
                                            const double w[3], double young, double nu,
                                            double T[3][3]) {
  const double exx = Lab[0][0] * dt, eyy = Lab[1][1] * dt, gxy = (Lab[0][1] + Lab[1][0]) * dt;
  const double ep = young / (1 - nu * nu), G = young / (2 * (1 + nu));
  const double sa = ep * (exx + nu * eyy), sb = ep * (eyy + nu * exx), sab = G * gxy;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      T[i][j] = sa * u[i] * u[j] + sb * w[i] * w[j] + sab * (u[i] * w[j] + w[i] * u[j]);
  return std::abs(sa) + std::abs(sb);
}

struct Patch {
  ShellMesh mesh;
  int interior = 4;
};
inline Patch make_patch(const double u[3], const double w[3], double t) {
  Patch p;
  const double o[3] = {0.3, -0.2, 0.5};
  const double pts[9][2] = {{0, 0},    {0.5, 0}, {1, 0},    {0, 0.5}, {0.45, 0.58},
                            {1, 0.42}, {0, 1},   {0.55, 1}, {1, 1}};
  for (const auto& q : pts)
    p.mesh.add_node(o[0] + q[0] * u[0] + q[1] * w[0], o[1] + q[0] * u[1] + q[1] * w[1],
                    o[2] + q[0] * u[2] + q[1] * w[2]);
  p.mesh.add_element({0, 1, 4, 3}, t);
  p.mesh.add_element({1, 2, 5, 4}, t);
  p.mesh.add_element({3, 4, 7, 6}, t);
  p.mesh.add_element({4, 5, 8, 7}, t);
  return p;
}

inline std::array<double, 3> node_force(const ShellBlock& b, int node, int offset) {
  std::array<double, 3> f{0, 0, 0};
  for (std::size_t e = 0; e < b.size(); ++e)
    for (int I = 0; I < 4; ++I)
      if (b.conn[4 * e + I] == node)
        for (int i = 0; i < 3; ++i) f[i] += b.force[24 * e + 6 * I + offset + i];
  return f;
}

// Pulls the unit square element (nodes 0..3, node 0 at the origin) along x at a true strain rate
// of 1/s for `steps` steps of dt; each step the lateral stretch is found by secant iteration so
// that sigma_yy of the first stress point vanishes (uniaxial plane stress). Returns the
// stretches (lx, ly); m holds the state of the last step.
inline std::array<double, 2> pull_uniaxially(ShellMesh& m, int steps, double dt) {
  double lx = 1.0, ly = 1.0;
  for (int s = 0; s < steps; ++s) {
    const double nx = lx * std::exp(1.0 * dt);
    auto trial = [&](double ny, ShellMesh& out) {
      out = m;
      const double vx = (nx - lx) / dt, vy = (ny - ly) / dt;
      out.vx[1] = out.vx[2] = vx;
      out.vy[2] = out.vy[3] = vy;
      out.x[1] = out.x[2] = nx;
      out.y[2] = out.y[3] = ny;
      EXPECT_FALSE(out.step(dt).failed);
      return out.block.stress[1];
    };
    ShellMesh t0, t1;
    double y0 = ly * std::exp(-0.3 * dt), y1 = ly * std::exp(-0.5 * dt);
    double f0 = trial(y0, t0), f1 = trial(y1, t1);
    for (int it = 0; it < 20 && std::abs(f1) > 1e-3 && f1 != f0; ++it) {
      const double y2 = y1 - f1 * (y1 - y0) / (f1 - f0);
      y0 = y1;
      f0 = f1;
      y1 = y2;
      f1 = trial(y1, t1);
    }
    m = t1;
    lx = nx;
    ly = y1;
  }
  return {lx, ly};
}

}  // namespace rf::test
