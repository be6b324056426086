// Beam and truss kernels (element/beam_block.hpp) driven directly by a small explicit
// central-difference loop written here (lumped mass and rotational inertia from
// add_beam_lumped_mass, internal forces and moments from compute_beam_forces), against
// references that do not come from our code:
//   truss: static stretch F L / (E A), the bar wave speed c = sqrt(E / rho) and the stress
//          rho c v0 behind the front (d'Alembert), a rigidly spinning truss stays stress-free;
//   resultant beam: Euler-Bernoulli / Timoshenko cantilever tip deflection P L^3 / (3 E I)
//          (+ P L / (kappa G A)), Clapeyron's U = P delta / 2, the first bending frequency
//          1.875104^2 sqrt(E I / (rho A L^4)) / (2 pi), torsion T L / (G J), energy
//          conservation in free vibration, rigid rotations stay stress-free (objectivity),
//          element force and moment balance for arbitrary states, and the critical step
//          against the element's highest frequency from a numerical eigen-analysis.
#include <gtest/gtest.h>

#include <omp.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "element/beam_block.hpp"
#include "material/registry.hpp"
#include "model/error.hpp"

namespace rf::test {
namespace {

using element::BeamBlock;
using element::BeamCrossSection;

constexpr double kRho = 7850.0, kE = 210e9, kNu = 0.3;

// Nodes with translations and rotations (rotational index = node index), a beam block, and a
// central-difference loop: a^{n} = (f_ext - f_int) / m, v^{n+1/2} = (1 - c dt) v^{n-1/2} +
// dt a^n (mass-proportional damping c), x^{n+1} = x^n + dt v^{n+1/2}; forces at x^{n+1}.
struct BeamModel {
  std::size_t nn = 0;
  std::vector<double> x, y, z, vx, vy, vz, wx, wy, wz;
  std::vector<double> mass, inertia;
  std::vector<double> fext;          // 6 per node: fx fy fz mx my mz
  std::vector<unsigned char> fixed;  // 6 per node
  std::vector<double> vfix;          // 6 per node: velocity of a fixed DOF (default 0)
  std::vector<double> fint;          // 6 per node, assembled
  BeamBlock block;
  double damping = 0.0;

  explicit BeamModel(std::size_t nodes)
      : nn(nodes),
        x(nodes),
        y(nodes),
        z(nodes),
        vx(nodes),
        vy(nodes),
        vz(nodes),
        wx(nodes),
        wy(nodes),
        wz(nodes),
        mass(nodes),
        inertia(nodes),
        fext(6 * nodes),
        fixed(6 * nodes),
        vfix(6 * nodes),
        fint(6 * nodes) {}

  element::NodalView view() const {
    return {x.data(), y.data(), z.data(), vx.data(), vy.data(), vz.data()};
  }
  element::RotationalView rview() const { return {wx.data(), wy.data(), wz.data()}; }

  void initialize() {
    element::initialize_beam_block(block, view());
    std::fill(mass.begin(), mass.end(), 0.0);
    std::fill(inertia.begin(), inertia.end(), 0.0);
    element::add_beam_lumped_mass(block, mass, inertia);
    forces(0.0);
  }

  element::KernelResult forces(double dt) {
    const element::KernelResult r = element::compute_beam_forces(block, view(), rview(), dt);
    EXPECT_FALSE(r.failed);
    std::fill(fint.begin(), fint.end(), 0.0);
    for (std::size_t e = 0; e < block.size(); ++e)
      for (int a = 0; a < 2; ++a) {
        const std::size_t n = static_cast<std::size_t>(block.conn[2 * e + a]);
        for (int i = 0; i < 6; ++i) fint[6 * n + i] += block.force[12 * e + 6 * a + i];
      }
    return r;
  }

  void step(double dt) {
    const double keep = 1.0 - damping * dt;
    double* v[6] = {vx.data(), vy.data(), vz.data(), wx.data(), wy.data(), wz.data()};
    for (std::size_t n = 0; n < nn; ++n)
      for (int i = 0; i < 6; ++i) {
        if (fixed[6 * n + i]) {
          v[i][n] = vfix[6 * n + i];
          continue;
        }
        const double m = i < 3 ? mass[n] : inertia[n];
        if (!(m > 0.0)) continue;
        v[i][n] = keep * v[i][n] + dt * (fext[6 * n + i] - fint[6 * n + i]) / m;
      }
    for (std::size_t n = 0; n < nn; ++n) {
      x[n] += dt * vx[n];
      y[n] += dt * vy[n];
      z[n] += dt * vz[n];
    }
    forces(dt);
  }

  double kinetic_energy() const {
    double k = 0.0;
    for (std::size_t n = 0; n < nn; ++n)
      k += 0.5 * mass[n] * (vx[n] * vx[n] + vy[n] * vy[n] + vz[n] * vz[n]) +
           0.5 * inertia[n] * (wx[n] * wx[n] + wy[n] * wy[n] + wz[n] * wz[n]);
    return k;
  }
};

// A straight chain of n elements from p0 along the unit direction d, total length len.
BeamModel chain(int elements, std::array<double, 3> d, double len, int elform) {
  BeamModel m(static_cast<std::size_t>(elements) + 1);
  for (int i = 0; i <= elements; ++i) {
    const double s = len * i / elements;
    m.x[i] = s * d[0];
    m.y[i] = s * d[1];
    m.z[i] = s * d[2];
  }
  BeamBlock& b = m.block;
  b.elform = elform;
  b.material = material::make_elastic(kRho, kE, kNu);
  b.material_index = material::material_index(model::MaterialKind::Elastic);
  for (int e = 0; e < elements; ++e) {
    b.element_id.push_back(e + 1);
    b.conn.push_back(e);
    b.conn.push_back(e + 1);
    b.rotation_conn.push_back(elform == 3 ? -1 : e);
    b.rotation_conn.push_back(elform == 3 ? -1 : e + 1);
  }
  return m;
}

// Rectangular section b (along s) x h (along t): Iss = b h^3 / 12 (bending about s), Itt =
// h b^3 / 12; J from the thin-strip series (Timoshenko & Goodier) for b < h.
void rectangle(BeamBlock& blk, double b, double h) {
  blk.area = b * h;
  blk.iss = b * h * h * h / 12.0;
  blk.itt = h * b * b * b / 12.0;
  blk.torsion = h * b * b * b * (1.0 / 3.0 - 0.21 * b / h * (1.0 - std::pow(b / h, 4) / 12.0));
  blk.shear_factor = 5.0 / 6.0;
}

double stable_dt(const BeamModel& m) {
  return element::beam_critical_timestep(m.block, m.view()).min_dt;
}

// ---------------------------------------------------------------------------------- truss ---

TEST(BeamKernelTruss, StaticStretchMatchesEAOverL) {
  // Oblique bar (the frame must not matter), node 0 fixed, axial end force F, damped to rest.
  const double len = 2.0, area = 1e-4, force = 2.1e4;  // strain F / EA = 1e-3
  const std::array<double, 3> d = {2.0 / 3.0, 1.0 / 3.0, 2.0 / 3.0};
  BeamModel m = chain(10, d, len, 3);
  m.block.area = area;
  m.initialize();
  for (int i = 0; i < 3; ++i) m.fixed[i] = 1;
  for (int i = 0; i < 3; ++i) m.fext[6 * 10 + i] = force * d[i];
  const double c = std::sqrt(kE / kRho);
  const double omega1 = std::numbers::pi * c / (2.0 * len);
  m.damping = 2.0 * omega1;
  const double dt = 0.9 * stable_dt(m);
  EXPECT_NEAR(stable_dt(m), 0.2 / c, 1e-12 * 0.2 / c);  // L / c of one element
  const int steps = static_cast<int>(40.0 / omega1 / dt);
  for (int s = 0; s < steps; ++s) m.step(dt);
  const double stretch = m.x[10] * d[0] + m.y[10] * d[1] + m.z[10] * d[2] - len;
  const double reference = force * len / (kE * area);
  std::printf("[measured] truss stretch %.9g vs F L / EA %.9g (rel %.2e), %d steps\n", stretch,
              reference, stretch / reference - 1.0, steps);
  EXPECT_NEAR(stretch, reference, 1e-3 * reference);  // small-strain reference, strain 1e-3
  for (std::size_t e = 0; e < m.block.size(); ++e)
    EXPECT_NEAR(m.block.resultant[6 * e], force, 1e-6 * force);
}

TEST(BeamKernelTruss, WaveSpeedAndStressBehindFrontMatchDAlembert) {
  // 200 trusses along x, node 0 driven at v0 into the bar: a compression front at c with
  // sigma = -rho c v0 behind it.
  const int ne = 200;
  const double len = 1.0, v0 = 1.0;
  BeamModel m = chain(ne, {1.0, 0.0, 0.0}, len, 3);
  m.block.area = 1e-4;
  m.initialize();
  m.fixed[0] = 1;  // node 0 driven at v0
  m.vfix[0] = v0;
  const double c = std::sqrt(kE / kRho);
  const double dt = 0.5 * stable_dt(m);
  const std::size_t probe = ne / 2;  // element at x = 0.5
  double t = 0.0, crossing = -1.0, previous = 0.0;
  const double sigma_ref = -kRho * c * v0;
  while (t < 0.8 * len / c) {
    m.step(dt);
    t += dt;
    const double sigma = m.block.stress[probe];
    if (crossing < 0.0 && sigma <= 0.5 * sigma_ref) {
      // Linear interpolation of the half-amplitude crossing time.
      crossing = t - dt * (0.5 * sigma_ref - sigma) / (previous - sigma);
    }
    previous = sigma;
  }
  const double arrival = (probe + 0.5) * len / ne / c;
  ASSERT_GT(crossing, 0.0);
  std::printf("[measured] front arrival %.6g vs %.6g (rel %.2e)\n", crossing, arrival,
              crossing / arrival - 1.0);
  EXPECT_NEAR(crossing, arrival, 0.02 * arrival);
  // Plateau behind the front: mean stress of the elements between x = 0.1 and 0.4.
  double mean = 0.0;
  for (int e = 20; e < 80; ++e) mean += m.block.stress[e] / 60.0;
  std::printf("[measured] plateau stress %.6g vs -rho c v0 %.6g (rel %.2e)\n", mean, sigma_ref,
              mean / sigma_ref - 1.0);
  EXPECT_NEAR(mean, sigma_ref, 0.01 * std::fabs(sigma_ref));
  // Ahead of the front (x > 0.9) the bar is still at rest.
  for (int e = 180; e < ne; ++e)
    EXPECT_LT(std::fabs(m.block.stress[e]), 1e-3 * std::fabs(sigma_ref));
}

// Rigid rotation of the whole model about `axis` through `center` at rate `rate` for `steps`
// steps of size dt: positions and velocities prescribed exactly, nodal angular velocities set.
void spin(BeamModel& m, std::array<double, 3> axis, std::array<double, 3> center, double rate,
          double dt, int steps) {
  const double an = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  for (double& a : axis) a /= an;
  const std::vector<double> x0 = m.x, y0 = m.y, z0 = m.z;
  for (int s = 1; s <= steps; ++s) {
    const double angle = rate * dt * s;
    const double cs = std::cos(angle), sn = std::sin(angle);
    for (std::size_t n = 0; n < m.nn; ++n) {
      const double p[3] = {x0[n] - center[0], y0[n] - center[1], z0[n] - center[2]};
      const double kp = axis[0] * p[0] + axis[1] * p[1] + axis[2] * p[2];
      const double kxp[3] = {axis[1] * p[2] - axis[2] * p[1], axis[2] * p[0] - axis[0] * p[2],
                             axis[0] * p[1] - axis[1] * p[0]};
      double q[3];
      for (int i = 0; i < 3; ++i)
        q[i] = center[i] + p[i] * cs + kxp[i] * sn + axis[i] * kp * (1.0 - cs);
      m.vx[n] = (q[0] - m.x[n]) / dt;
      m.vy[n] = (q[1] - m.y[n]) / dt;
      m.vz[n] = (q[2] - m.z[n]) / dt;
      m.x[n] = q[0];
      m.y[n] = q[1];
      m.z[n] = q[2];
      m.wx[n] = rate * axis[0];
      m.wy[n] = rate * axis[1];
      m.wz[n] = rate * axis[2];
    }
    m.forces(dt);
  }
}

TEST(BeamKernelTruss, RigidlySpinningTrussStaysStressFree) {
  BeamModel m = chain(1, {0.0, 0.6, 0.8}, 1.0, 3);
  m.block.area = 1e-4;
  m.initialize();
  // Two full turns about an oblique axis at 200 rad/s, 2000 steps per turn.
  const double rate = 200.0, dt = 2.0 * std::numbers::pi / rate / 2000.0;
  spin(m, {1.0, -2.0, 0.5}, {0.3, 0.1, -0.2}, rate, dt, 4000);
  EXPECT_LT(std::fabs(m.block.resultant[0]), 1e-9 * kE * m.block.area);
  EXPECT_NEAR(m.block.length[0], 1.0, 1e-12);
}

// ------------------------------------------------------------------------ resultant beam ---

// Cantilever along x with s = global y (so t = global z), clamped at node 0.
BeamModel cantilever(int elements, double len, double b, double h, int elform = 2) {
  BeamModel m = chain(elements, {1.0, 0.0, 0.0}, len, elform);
  rectangle(m.block, b, h);
  m.block.ts1 = b;  // ELFORM 1 section: b along s, h along t
  m.block.tt1 = h;
  for (int e = 0; e < elements; ++e)
    m.block.orientation.insert(m.block.orientation.end(), {0.0, 1.0, 0.0});
  return m;
}

void clamp(BeamModel& m, std::size_t node) {
  for (int i = 0; i < 6; ++i) m.fixed[6 * node + i] = 1;
}

// First-mode circular frequency of an Euler-Bernoulli cantilever.
double cantilever_omega1(double ei, double rho_a, double len) {
  return 1.875104 * 1.875104 * std::sqrt(ei / (rho_a * std::pow(len, 4)));
}

// Damped run of a cantilever with a tip load P along `dof` (1 = y, 2 = z) to rest.
double damped_tip_deflection(BeamModel& m, int dof, double load, double ei) {
  const std::size_t tip = m.nn - 1;
  m.fext[6 * tip + dof] = load;
  const double len = m.x[tip];
  const double omega1 = cantilever_omega1(ei, kRho * m.block.area, len);
  m.damping = 2.0 * omega1;
  const double dt = 0.9 * stable_dt(m);
  // Every mode decays at least like exp(-omega1 t) (mass-proportional damping, critical for
  // the Euler-Bernoulli first mode; a shear-flexible beam's softer first mode is overdamped and
  // decays like exp(-omega^2 t / 2 omega1)): 60 / omega1 leaves < 1e-7 of the transient.
  const int steps = static_cast<int>(60.0 / omega1 / dt);
  for (int s = 0; s < steps; ++s) m.step(dt);
  return dof == 1 ? m.y[tip] : m.z[tip];
}

TEST(BeamKernelResultant, CantileverTipDeflectionMatchesEulerBernoulliInBothPlanes) {
  const double len = 1.0, b = 0.02, h = 0.03, load = 10.0;
  for (int dof : {1, 2}) {
    BeamModel m = cantilever(10, len, b, h);
    m.block.shear_area = 1e6 * m.block.area;  // shear-rigid: Euler-Bernoulli
    m.initialize();
    clamp(m, 0);
    // A load along s (y) bends about t (Itt); along t (z) about s (Iss).
    const double ei = kE * (dof == 1 ? m.block.itt : m.block.iss);
    const double delta = damped_tip_deflection(m, dof, load, ei);
    const double reference = load * len * len * len / (3.0 * ei);
    std::printf("[measured] EB tip deflection (load along %s) %.9g vs %.9g (rel %.2e)\n",
                dof == 1 ? "y" : "z", delta, reference, delta / reference - 1.0);
    EXPECT_NEAR(delta, reference, 1e-5 * reference) << "load along " << (dof == 1 ? "y" : "z");
    // The off-plane deflection stays zero.
    EXPECT_NEAR(dof == 1 ? m.z.back() : m.y.back(), 0.0, 1e-9 * reference);
    // Clapeyron: strain energy = P delta / 2, from the stored resultants (beam theory energy
    // of each element: M^2 L / 2EI + Q^2 L^3 / 24EI for the linear moment, plus N and shear).
    double energy = 0.0;
    const double kga = m.block.material.shear * m.block.shear_area;
    for (std::size_t e = 0; e < m.block.size(); ++e) {
      const double* r = &m.block.resultant[6 * e];
      const double l = m.block.length[e];
      energy += r[0] * r[0] * l / (2.0 * kE * m.block.area);
      energy += r[5] * r[5] * l / (2.0 * kE * m.block.itt) +
                r[1] * r[1] * l * l * l / (24.0 * kE * m.block.itt) + r[1] * r[1] * l / (2 * kga);
      energy += r[4] * r[4] * l / (2.0 * kE * m.block.iss) +
                r[2] * r[2] * l * l * l / (24.0 * kE * m.block.iss) + r[2] * r[2] * l / (2 * kga);
    }
    std::printf("[measured] strain energy %.9g vs P delta / 2 %.9g (rel %.2e)\n", energy,
                0.5 * load * delta, energy / (0.5 * load * delta) - 1.0);
    EXPECT_NEAR(energy, 0.5 * load * delta, 1e-5 * 0.5 * load * delta);
  }
}

TEST(BeamKernelResultant, ShearFlexibleCantileverMatchesTimoshenko) {
  // A small shear area makes shear a large part of the deflection:
  // delta = P L^3 / (3 E I) + P L / (G SA).
  const double len = 1.0, b = 0.02, h = 0.03, load = 10.0;
  BeamModel m = cantilever(10, len, b, h);
  m.block.shear_area = 1e-3 * m.block.area;
  m.initialize();
  clamp(m, 0);
  const double ei = kE * m.block.iss;
  const double bending = load * len * len * len / (3.0 * ei);
  const double shear = load * len / (m.block.material.shear * m.block.shear_area);
  ASSERT_GT(shear, 0.3 * bending);
  const double delta = damped_tip_deflection(m, 2, load, ei);
  std::printf("[measured] Timoshenko tip deflection %.9g vs %.9g (shear part %.3g, rel %.2e)\n",
              delta, bending + shear, shear / (bending + shear), delta / (bending + shear) - 1.0);
  EXPECT_NEAR(delta, bending + shear, 1e-4 * (bending + shear));
}

TEST(BeamKernelResultant, TorsionMatchesTLOverGJ) {
  const double len = 1.0, torque = 5.0;
  BeamModel m = cantilever(10, len, 0.02, 0.03);
  m.initialize();
  clamp(m, 0);
  const std::size_t tip = m.nn - 1;
  m.fext[6 * tip + 3] = torque;  // about x, the beam axis
  const double gj = m.block.material.shear * m.block.torsion;
  const double rho_r = 2.0 * m.inertia[tip - 1] / (len / 10.0) / 2.0;  // inertia per length
  const double omega1 = std::numbers::pi / (2.0 * len) * std::sqrt(gj / rho_r);
  m.damping = 2.0 * omega1;
  const double dt = 0.9 * stable_dt(m);
  double twist = 0.0;
  const int steps = static_cast<int>(25.0 / omega1 / dt);
  for (int s = 0; s < steps; ++s) {
    m.step(dt);
    twist += m.wx[tip] * dt;  // rotation about the fixed x axis
  }
  const double reference = torque * len / gj;
  std::printf("[measured] tip twist %.9g vs T L / GJ %.9g (rel %.2e), %d steps\n", twist, reference,
              twist / reference - 1.0, steps);
  EXPECT_NEAR(twist, reference, 1e-5 * reference);
  for (std::size_t e = 0; e < m.block.size(); ++e)
    EXPECT_NEAR(m.block.resultant[6 * e + 3], torque, 1e-5 * torque);
}

// Free vibration of a cantilever released from the analytic first mode shape of an
// Euler-Bernoulli cantilever (w(x) = cosh bx - cos bx - sigma (sinh bx - sin bx), bL =
// 1.875104, sigma = (cosh bL + cos bL) / (sinh bL + sin bL); nodal rotations -w'(x) about y):
// the first frequency from the tip's zero crossings against 1.875104^2 sqrt(E I / (rho A L^4))
// / (2 pi), and the energy balance: kinetic energy + the work of the internal nodal forces and
// moments (trapezoid rule over each step) stays at the strain energy put in.
struct Vibration {
  double frequency_error = 0.0;  // relative
  double energy_drift = 0.0;     // max |E - U0| / U0
};

Vibration free_vibration(int elform, int elements) {
  const double len = 1.0, b = 0.01, h = 0.015, amplitude = 1e-3;
  BeamModel m = cantilever(elements, len, b, h, elform);
  if (elform == 2) m.block.shear_area = 1e6 * m.block.area;  // Euler-Bernoulli
  m.initialize();
  clamp(m, 0);
  const double ei = kE * m.block.iss;
  const double bl = 1.875104;
  const double sigma = (std::cosh(bl) + std::cos(bl)) / (std::sinh(bl) + std::sin(bl));
  // Impose the mode shape by one kinematic step of size 1 (the kernel integrates increments).
  for (std::size_t n = 0; n < m.nn; ++n) {
    const double bx = bl * m.x[n] / len;
    const double w = std::cosh(bx) - std::cos(bx) - sigma * (std::sinh(bx) - std::sin(bx));
    const double dw =
        bl / len * (std::sinh(bx) + std::sin(bx) - sigma * (std::cosh(bx) - std::cos(bx)));
    m.vz[n] = amplitude * w / 2.0;  // tip value of w is 2
    m.wy[n] = -amplitude * dw / 2.0;
    m.z[n] += m.vz[n];
  }
  m.forces(1.0);
  double work = 0.0;  // internal work of the imposing step: linear, (0 + f) / 2 . d
  for (std::size_t n = 0; n < m.nn; ++n)
    work += 0.5 * (m.fint[6 * n + 2] * m.vz[n] + m.fint[6 * n + 4] * m.wy[n]);
  const double u0 = work;
  for (auto* v : {&m.vx, &m.vy, &m.vz, &m.wx, &m.wy, &m.wz}) std::fill(v->begin(), v->end(), 0.0);
  const std::size_t tip = m.nn - 1;
  const double dt = 0.9 * stable_dt(m);
  const double omega1 = cantilever_omega1(ei, kRho * m.block.area, len);
  const int steps = static_cast<int>(6.0 * 2.0 * std::numbers::pi / omega1 / dt);
  std::vector<double> crossings;
  double previous = m.z[tip], max_drift = 0.0;
  std::vector<double> f_old = m.fint, xs, ys, zs, v_old(6 * m.nn);
  for (int s = 0; s < steps; ++s) {
    xs = m.x;
    ys = m.y;
    zs = m.z;
    for (std::size_t n = 0; n < m.nn; ++n) {
      const double v[6] = {m.vx[n], m.vy[n], m.vz[n], m.wx[n], m.wy[n], m.wz[n]};
      for (int i = 0; i < 6; ++i) v_old[6 * n + i] = v[i];
    }
    const double strain_before = work;  // U^n
    m.step(dt);
    // Rotation increments of this step: omega^{n+1/2} dt.
    double kinetic = 0.0;
    for (std::size_t n = 0; n < m.nn; ++n) {
      const double dx[6] = {m.x[n] - xs[n], m.y[n] - ys[n], m.z[n] - zs[n],
                            m.wx[n] * dt,   m.wy[n] * dt,   m.wz[n] * dt};
      const double v[6] = {m.vx[n], m.vy[n], m.vz[n], m.wx[n], m.wy[n], m.wz[n]};
      for (int i = 0; i < 6; ++i) {
        work += 0.5 * (f_old[6 * n + i] + m.fint[6 * n + i]) * dx[i];
        kinetic += 0.5 * (i < 3 ? m.mass[n] : m.inertia[n]) * v_old[6 * n + i] * v[i];
      }
    }
    f_old = m.fint;
    // The energy central differences conserve for a linear system (e.g. Belytschko, Liu &
    // Moran, Nonlinear Finite Elements, sec. 6.2): 1/2 v^{n-1/2} M v^{n+1/2} + U^n, with U the
    // work of the internal forces since the straight state (u0 included).
    const double total = kinetic + strain_before;
    max_drift = std::max(max_drift, std::fabs(total - u0));
    const double zt = m.z[tip];
    if (previous > 0.0 && zt <= 0.0) crossings.push_back((s + previous / (previous - zt)) * dt);
    previous = zt;
  }
  EXPECT_GE(crossings.size(), 5u);
  Vibration r;
  if (crossings.size() < 2) return r;
  const double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  const double f_reference = omega1 / (2.0 * std::numbers::pi);
  r.frequency_error = 1.0 / period / f_reference - 1.0;
  r.energy_drift = max_drift / u0;
  std::printf(
      "[measured] ELFORM %d, %d elements: first frequency rel error %.2e, energy drift "
      "%.2e of U0 (%zu crossings, %d steps)\n",
      elform, elements, r.frequency_error, r.energy_drift, crossings.size(), steps);
  return r;
}

TEST(BeamKernelResultant, FreeVibrationFrequencyAndEnergyConservation) {
  const Vibration coarse = free_vibration(2, 10), fine = free_vibration(2, 20);
  EXPECT_LT(std::fabs(coarse.frequency_error), 0.01);
  // Second-order convergence of the lumped-mass frequency: halving the element size divides
  // the error by about 4.
  EXPECT_LT(std::fabs(fine.frequency_error), 0.3 * std::fabs(coarse.frequency_error));
  EXPECT_LT(coarse.energy_drift, 1e-6);
  EXPECT_LT(fine.energy_drift, 1e-6);
}

TEST(BeamKernelIntegrated, FreeVibrationFrequencyAndEnergyConservation) {
  // The scaled rotary inertia (9') must not spoil the first bending mode.
  const Vibration coarse = free_vibration(1, 10), fine = free_vibration(1, 20);
  EXPECT_LT(std::fabs(coarse.frequency_error), 0.01);
  EXPECT_LT(std::fabs(fine.frequency_error), 0.3 * std::fabs(coarse.frequency_error));
  EXPECT_LT(coarse.energy_drift, 1e-6);
  EXPECT_LT(fine.energy_drift, 1e-6);
}

// Large rotations: a cantilever under a tip moment M about the fixed y axis bends into a
// circular arc of radius R = E I / M (the elastica under an end moment, exact for any
// rotation). M = pi E I / L rolls it into a half circle: the tip ends at (0, 0, -2 L / pi),
// turned by pi. The moment is ramped up and held with mass-proportional damping. The discrete
// arc (chords of length L / n turning by M L / (n E I)) differs from the continuous one by
// O(1 / n^2): about 1e-3 of L for n = 20.
TEST(BeamKernelResultant, TipMomentRollsTheCantileverIntoAHalfCircle) {
  for (int elform : {2, 1}) {
    const int n = 20;
    const double len = 1.0;
    // Bending about the WEAK axis (s, the 0.03 side along s): about the strong axis this moment
    // is far above the lateral-torsional buckling moment, and the beam does buckle sideways
    // (ELFORM 1, whose section sums break the symmetry at round-off level).
    BeamModel m = cantilever(n, len, 0.03, 0.02, elform);
    m.initialize();
    clamp(m, 0);
    const double ei = kE * m.block.iss;
    const double moment = std::numbers::pi * ei / len;
    const double omega1 = cantilever_omega1(ei, kRho * m.block.area, len);
    m.damping = 2.0 * omega1;
    const double dt = 0.9 * stable_dt(m);
    const double ramp = 10.0 / omega1;
    const int steps = static_cast<int>((ramp + 60.0 / omega1) / dt);
    double rotation = 0.0;  // tip rotation about y (the axis stays y)
    for (int s = 0; s < steps; ++s) {
      m.fext[6 * n + 4] = moment * std::min(1.0, s * dt / ramp);
      m.step(dt);
      rotation += m.wy[n] * dt;
    }
    const double tip[3] = {m.x[n], m.y[n], m.z[n]};
    std::printf(
        "[measured] ELFORM %d half circle: tip (%.5f, %.2g, %.5f) vs (0, 0, %.5f); "
        "rotation %.6f vs pi\n",
        elform, tip[0], tip[1], tip[2], -2.0 * len / std::numbers::pi, rotation);
    EXPECT_NEAR(tip[0], 0.0, 3e-3 * len);
    EXPECT_NEAR(tip[1], 0.0, 1e-9 * len);
    EXPECT_NEAR(tip[2], -2.0 * len / std::numbers::pi, 3e-3 * len);
    // The discrete arc exactly: n chords of length L / n, each turned by pi / n from the
    // previous (by pi / 2n at the clamp), span the diameter 2 R_n with L / n = 2 R_n sin(pi/2n).
    EXPECT_NEAR(tip[2], -len / n / std::sin(std::numbers::pi / (2.0 * n)), 1e-5 * len);
    EXPECT_NEAR(rotation, std::numbers::pi, 1e-3);
    // Pure bending: every element carries M about s (s stays y), no axial or shear force.
    for (int e = 0; e < n; ++e) {
      EXPECT_NEAR(m.block.resultant[6 * e + 4], moment, 1e-3 * moment) << "element " << e;
      EXPECT_NEAR(m.block.frame[9 * e + 4], 1.0, 1e-9);
    }
  }
}

TEST(BeamKernelResultant, RigidRotationsStayStressFree) {
  const std::array<std::array<double, 3>, 3> axes = {
      {{1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {0.3, -0.8, 0.5}}};
  for (const auto& axis : axes) {
    BeamModel m = cantilever(3, 1.0, 0.02, 0.03);
    m.initialize();
    const double rate = 100.0, dt = 2.0 * std::numbers::pi / rate / 4000.0;
    spin(m, axis, {0.0, 0.0, 0.0}, rate, dt, 4000 + 1000);  // 1.25 turns
    // Stress-free: every resultant below 1e-9 of its scale (force E A, moment E I / L).
    for (std::size_t e = 0; e < m.block.size(); ++e) {
      const double* r = &m.block.resultant[6 * e];
      const double l = m.block.length0[e];
      EXPECT_LT(std::fabs(r[0]), 1e-9 * kE * m.block.area);
      EXPECT_LT(std::fabs(r[1]) * l, 1e-9 * kE * m.block.itt / l);
      EXPECT_LT(std::fabs(r[2]) * l, 1e-9 * kE * m.block.iss / l);
      EXPECT_LT(std::fabs(r[3]), 1e-9 * m.block.material.shear * m.block.torsion / l);
      EXPECT_LT(std::fabs(r[4]), 1e-9 * kE * m.block.iss / l);
      EXPECT_LT(std::fabs(r[5]), 1e-9 * kE * m.block.itt / l);
      // The cross-section axis s turned with the body: compare with the rotated global y.
      const double angle = rate * dt * 5000;
      double k[3] = {axis[0], axis[1], axis[2]};
      const double kn = std::sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]);
      for (double& a : k) a /= kn;
      const double y0[3] = {0.0, 1.0, 0.0};
      const double kxy[3] = {k[1] * y0[2] - k[2] * y0[1], k[2] * y0[0] - k[0] * y0[2],
                             k[0] * y0[1] - k[1] * y0[0]};
      const double ky = k[1];
      for (int i = 0; i < 3; ++i) {
        const double expected = y0[i] * std::cos(angle) + kxy[i] * std::sin(angle) +
                                k[i] * ky * (1.0 - std::cos(angle));
        EXPECT_NEAR(m.block.frame[9 * e + 3 + i], expected, 1e-9);
      }
    }
  }
}

// Objectivity of a stressed beam: impose stretch, bending in both planes, shear and twist in
// one kinematic step, then turn the whole model rigidly by 1.25 turns about an oblique axis.
// The resultants (stored in the co-rotational frame) must not change, and the nodal forces
// must turn with the body: f' = R f.
TEST(BeamKernelResultant, StressedBeamRotatedRigidlyKeepsItsResultants) {
  for (int elform : {2, 1}) {
    BeamModel m = cantilever(2, 1.0, 0.02, 0.03, elform);
    m.initialize();
    const double d[3][6] = {{0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
                            {1e-4, 2e-3, -1e-3, 4e-3, 1e-3, -2e-3},
                            {3e-4, 1e-3, 2e-3, -3e-3, 2e-3, 5e-3}};
    for (std::size_t n = 0; n < 3; ++n) {
      m.vx[n] = d[n][0];
      m.vy[n] = d[n][1];
      m.vz[n] = d[n][2];
      m.wx[n] = d[n][3];
      m.wy[n] = d[n][4];
      m.wz[n] = d[n][5];
      m.x[n] += d[n][0];
      m.y[n] += d[n][1];
      m.z[n] += d[n][2];
    }
    m.forces(1.0);
    const std::vector<double> r0 = m.block.resultant, f0 = m.block.force;
    double scale = 0.0;
    for (double v : r0) scale = std::max(scale, std::fabs(v));
    for (int i = 0; i < 6; ++i) ASSERT_GT(std::fabs(r0[i]), 1e-6 * scale) << "component " << i;
    const std::array<double, 3> axis = {0.3, -0.8, 0.5};
    const double rate = 100.0, dt = 2.0 * std::numbers::pi / rate / 4000.0;
    spin(m, axis, {0.1, 0.2, 0.3}, rate, dt, 5000);  // 1.25 turns
    for (std::size_t i = 0; i < r0.size(); ++i)
      EXPECT_NEAR(m.block.resultant[i], r0[i], 1e-9 * scale) << "ELFORM " << elform << " " << i;
    // Forces turned by R (Rodrigues about the unit axis, angle rate dt 5000 = 2.5 pi).
    const double an = std::sqrt(0.09 + 0.64 + 0.25);
    const double k[3] = {axis[0] / an, axis[1] / an, axis[2] / an};
    const double angle = rate * dt * 5000, c = std::cos(angle), sn = std::sin(angle);
    double fscale = 0.0;
    for (double v : f0) fscale = std::max(fscale, std::fabs(v));
    for (std::size_t v = 0; v < f0.size() / 3; ++v) {
      const double* p = &f0[3 * v];
      const double kp = k[0] * p[0] + k[1] * p[1] + k[2] * p[2];
      const double kxp[3] = {k[1] * p[2] - k[2] * p[1], k[2] * p[0] - k[0] * p[2],
                             k[0] * p[1] - k[1] * p[0]};
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(m.block.force[3 * v + i], p[i] * c + kxp[i] * sn + k[i] * kp * (1.0 - c),
                    1e-9 * fscale);
    }
  }
}

TEST(BeamKernelResultant, ElementForcesAndMomentsBalanceForArbitraryStates) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  BeamModel m = chain(1, {0.48, 0.6, 0.64}, 0.5, 2);
  rectangle(m.block, 0.02, 0.05);
  m.block.orientation = {0.0, 0.0, 1.0};
  m.initialize();
  const double dt = 1e-5;
  for (int s = 0; s < 200; ++s) {
    for (std::size_t n = 0; n < 2; ++n) {
      m.vx[n] = 10.0 * u(rng);
      m.vy[n] = 10.0 * u(rng);
      m.vz[n] = 10.0 * u(rng);
      m.wx[n] = 100.0 * u(rng);
      m.wy[n] = 100.0 * u(rng);
      m.wz[n] = 100.0 * u(rng);
      m.x[n] += dt * m.vx[n];
      m.y[n] += dt * m.vy[n];
      m.z[n] += dt * m.vz[n];
    }
    m.forces(dt);
    const double* f = m.block.force.data();
    double scale = 0.0;
    for (int i = 0; i < 12; ++i) scale = std::max(scale, std::fabs(f[i]));
    ASSERT_GT(scale, 0.0);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(f[i] + f[6 + i], 0.0, 1e-12 * scale);
    // Moments about the origin: r1 x f1 + r2 x f2 + m1 + m2 = 0.
    const double r1[3] = {m.x[0], m.y[0], m.z[0]}, r2[3] = {m.x[1], m.y[1], m.z[1]};
    const double mom[3] = {
        r1[1] * f[2] - r1[2] * f[1] + r2[1] * f[8] - r2[2] * f[7] + f[3] + f[9],
        r1[2] * f[0] - r1[0] * f[2] + r2[2] * f[6] - r2[0] * f[8] + f[4] + f[10],
        r1[0] * f[1] - r1[1] * f[0] + r2[0] * f[7] - r2[1] * f[6] + f[5] + f[11]};
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(mom[i], 0.0, 1e-11 * scale);
  }
}

// The element's highest frequency from a numerical eigen-analysis (stiffness by central
// differences of the kernel's forces about the reference state, lumped masses from
// add_beam_lumped_mass) bounds the reported critical step: dt_crit <= 2 / omega_max, and equals
// it to within a few percent (the step formula is the exact free-element frequency).
struct StepCase {
  int elform;
  double slenderness;  // L / h
  bool shear_rigid;    // ELFORM 2: SA = 1e6 A (Euler-Bernoulli), where bending-shear governs
};

TEST(BeamKernelResultant, CriticalStepMatchesElementEigenfrequency) {
  const StepCase cases[] = {{2, 50.0, false}, {2, 4.0, false}, {2, 1.5, false}, {2, 1.5, true},
                            {1, 50.0, false}, {1, 4.0, false}, {1, 1.0, false}};
  for (const StepCase& sc : cases) {
    const double h = 0.02, len = sc.slenderness * h;
    const double slenderness = sc.slenderness;
    BeamModel m = chain(1, {0.6, 0.0, 0.8}, len, sc.elform);
    rectangle(m.block, 0.6 * h, h);
    m.block.ts1 = 0.6 * h;
    m.block.tt1 = h;
    if (sc.shear_rigid) m.block.shear_area = 1e6 * m.block.area;
    m.block.orientation = {0.0, 1.0, 0.0};
    m.initialize();
    Eigen::MatrixXd k(12, 12);
    const double eps = 1e-7;  // velocity perturbation times dt = displacement perturbation
    for (int j = 0; j < 12; ++j) {
      std::array<Eigen::VectorXd, 2> f;
      for (int sgn = 0; sgn < 2; ++sgn) {
        BeamModel p = m;
        const double d = sgn == 0 ? eps : -eps;
        const std::size_t n = static_cast<std::size_t>(j / 6);
        const int i = j % 6;
        // One step of size 1 with velocity d: displacement d (translation) or rotation d.
        std::fill(p.vx.begin(), p.vx.end(), 0.0);
        std::fill(p.vy.begin(), p.vy.end(), 0.0);
        std::fill(p.vz.begin(), p.vz.end(), 0.0);
        std::vector<double>* vv[6] = {&p.vx, &p.vy, &p.vz, &p.wx, &p.wy, &p.wz};
        (*vv[i])[n] = d;
        if (i == 0) p.x[n] += d;
        if (i == 1) p.y[n] += d;
        if (i == 2) p.z[n] += d;
        p.forces(1.0);
        f[sgn] = Eigen::Map<const Eigen::VectorXd>(p.block.force.data(), 12);
      }
      k.col(j) = (f[0] - f[1]) / (2.0 * eps);
    }
    k = 0.5 * (k + k.transpose()).eval();
    Eigen::VectorXd minv(12);
    for (int n = 0; n < 2; ++n)
      for (int i = 0; i < 6; ++i)
        minv(6 * n + i) = 1.0 / std::sqrt(i < 3 ? m.mass[n] : m.inertia[n]);
    const Eigen::MatrixXd a = minv.asDiagonal() * k * minv.asDiagonal();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(a);
    const double omega_max = std::sqrt(es.eigenvalues().maxCoeff());
    const double dt = stable_dt(m);
    std::printf(
        "[measured] ELFORM %d%s L/h %.1f: dt %.6g vs 2/omega_max %.6g (ratio %.6f), L/c %.6g\n",
        sc.elform, sc.shear_rigid ? " (shear-rigid)" : "", slenderness, dt, 2.0 / omega_max,
        dt * omega_max / 2.0, len / std::sqrt(kE / kRho));
    EXPECT_LE(dt, 2.0 / omega_max * (1.0 + 1e-4)) << "L/h " << slenderness;
    EXPECT_GE(dt, 2.0 / omega_max * 0.97) << "L/h " << slenderness;
    if (slenderness > 10.0)  // slender: the axial step L / c governs
      EXPECT_NEAR(dt, len / std::sqrt(kE / kRho), 1e-9 * dt);
  }
}

// ---------------------------------------------------------- ELFORM 1, integrated section ---

// One-point (constant moment, constant shear) Timoshenko elements under a tip load P: the
// element moment is the exact mid-element moment, so the rotation jump across each element,
// M_mid L_e / EI, is the exact integral of M / EI (M is linear) and the nodal rotations are
// exact; the deflection increment L_e (theta_a + theta_b) / 2 + L_e Q / kappa G A is the
// trapezoid rule applied to the exact quadratic rotation theta(x) = P (L x - x^2 / 2) / EI,
// short by L_e^3 P / 12 EI per element. Hence the n-element tip deflection
//   delta_n = P L^3 / 3EI (1 - 1 / (4 n^2)) + P L / kappa G A,
// converging at rate 2 to Euler-Bernoulli plus Timoshenko shear. The section stiffness comes
// from the section points, so this also checks the 2 x 2 Gauss rule (rectangle) and the ring
// rule (tube) against the closed forms I = b h^3 / 12 and pi (D^4 - d^4) / 64.
double integrated_cantilever(int elements, BeamCrossSection shape, int dof, double* reference) {
  const double len = 1.0, load = 10.0;
  BeamModel m = chain(elements, {1.0, 0.0, 0.0}, len, 1);
  for (int e = 0; e < elements; ++e)
    m.block.orientation.insert(m.block.orientation.end(), {0.0, 1.0, 0.0});
  m.block.cross_section = shape;
  double area = 0.0, inertia = 0.0;
  if (shape == BeamCrossSection::kRectangular) {
    m.block.ts1 = m.block.ts2 = 0.02;  // along s (y)
    m.block.tt1 = m.block.tt2 = 0.03;  // along t (z)
    area = 0.02 * 0.03;
    inertia = dof == 2 ? 0.02 * std::pow(0.03, 3) / 12.0 : 0.03 * std::pow(0.02, 3) / 12.0;
    m.block.shear_factor = 5.0 / 6.0;
  } else {
    m.block.ts1 = 0.05;  // outer diameter
    m.block.tt1 = 0.04;  // inner diameter
    area = std::numbers::pi * (0.05 * 0.05 - 0.04 * 0.04) / 4.0;
    inertia = std::numbers::pi * (std::pow(0.05, 4) - std::pow(0.04, 4)) / 64.0;
    m.block.shear_factor = 0.5;
  }
  m.initialize();
  clamp(m, 0);
  const double ei = kE * inertia;
  const double kga = m.block.material.shear * m.block.shear_factor * area;
  *reference = load * len * len * len / (3.0 * ei) * (1.0 - 1.0 / (4.0 * elements * elements)) +
               load * len / kga;
  return damped_tip_deflection(m, dof, load, ei);
}

TEST(BeamKernelIntegrated, RectangleCantileverMatchesOnePointTimoshenkoSolution) {
  for (int dof : {1, 2})
    for (int elements : {5, 10}) {
      double reference = 0.0;
      const double delta =
          integrated_cantilever(elements, BeamCrossSection::kRectangular, dof, &reference);
      std::printf(
          "[measured] ELFORM 1 rectangle, %d elements, load along %s: %.9g vs %.9g "
          "(rel %.2e)\n",
          elements, dof == 1 ? "y" : "z", delta, reference, delta / reference - 1.0);
      EXPECT_NEAR(delta, reference, 1e-5 * reference);
    }
}

TEST(BeamKernelIntegrated, TubeCantileverMatchesOnePointTimoshenkoSolution) {
  for (int dof : {1, 2}) {
    double reference = 0.0;
    const double delta = integrated_cantilever(10, BeamCrossSection::kTubular, dof, &reference);
    std::printf("[measured] ELFORM 1 tube, 10 elements, load along %s: %.9g vs %.9g (rel %.2e)\n",
                dof == 1 ? "y" : "z", delta, reference, delta / reference - 1.0);
    EXPECT_NEAR(delta, reference, 1e-5 * reference);
  }
}

TEST(BeamKernelIntegrated, RigidRotationsStayStressFree) {
  BeamModel m = chain(3, {1.0, 0.0, 0.0}, 1.0, 1);
  m.block.orientation = {0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0};
  m.block.ts1 = 0.02;
  m.block.tt1 = 0.03;
  m.initialize();
  const double rate = 100.0, dt = 2.0 * std::numbers::pi / rate / 4000.0;
  spin(m, {0.3, -0.8, 0.5}, {0.0, 0.0, 0.0}, rate, dt, 5000);
  for (double sigma : m.block.stress) EXPECT_LT(std::fabs(sigma), 1e-9 * kE);
  for (std::size_t e = 0; e < m.block.size(); ++e)
    for (int i = 0; i < 6; ++i)
      EXPECT_LT(std::fabs(m.block.resultant[6 * e + i]), 1e-9 * kE * m.block.area * 0.03);
}

// ------------------------------------------------------------------------- plasticity ---

// Uniaxial J2 plasticity with mixed hardening (Prager kinematic + linear isotropic), closed
// form: elastic to sigma_y; then sigma = sigma_y + (H_i + H_k) eps_p with eps = sigma / E +
// eps_p; on reversal the bar is elastic until sigma = alpha - (sigma_y + H_i eps_p), alpha =
// H_k eps_p (the yield surface keeps its size 2 (sigma_y + H_i eps_p) and is centred on alpha).
// Strain: logarithmic, eps = ln(L / L0), the strain a stretch of a truss integrates.
TEST(BeamKernelTruss, PlasticKinematicBarFollowsUniaxialMixedHardening) {
  BeamModel m = chain(1, {0.0, 0.8, 0.6}, 1.0, 3);
  BeamBlock& b = m.block;
  b.area = 1e-4;
  b.material_index = material::material_index(model::MaterialKind::PlasticKinematic);
  const double sigy = 250e6, hi = 2e9, hk = 1e9;
  b.plastic.linear = true;
  b.plastic.sigy = sigy;
  b.plastic.isotropic_modulus = hi;
  b.plastic.kinematic_modulus = hk;
  b.plastic.strain = {0.0, 1.0};
  b.plastic.stress = {sigy, sigy + hi};
  m.initialize();
  ASSERT_EQ(b.history.size(), 2u);
  // Drive node 1 along the axis: to a log strain of 1 %, then back to -0.5 %, 4000 steps each.
  const double d[3] = {0.0, 0.8, 0.6};
  const double dt = 1e-6;
  auto drive = [&](double eps_target, int steps) {
    const double l_start = std::log(b.length[0]);
    for (int s = 1; s <= steps; ++s) {
      const double l = std::exp(l_start + (eps_target - l_start) * s / steps);
      const double q[3] = {l * d[0], l * d[1], l * d[2]};
      m.vx[1] = (q[0] - m.x[1]) / dt;
      m.vy[1] = (q[1] - m.y[1]) / dt;
      m.vz[1] = (q[2] - m.z[1]) / dt;
      m.x[1] = q[0];
      m.y[1] = q[1];
      m.z[1] = q[2];
      m.forces(dt);
    }
  };
  drive(0.01, 4000);
  // Loading branch: eps = sigma / E + (sigma - sigma_y) / (H_i + H_k).
  const double eps1 = 0.01;
  const double sigma1 = (eps1 + sigy / (hi + hk)) / (1.0 / kE + 1.0 / (hi + hk));
  const double ep1 = (sigma1 - sigy) / (hi + hk);
  std::printf("[measured] plastic bar at 1 %%: sigma %.6g vs %.6g, eps_p %.6g vs %.6g\n",
              b.stress[0], sigma1, b.history[0].values[0], ep1);
  EXPECT_NEAR(b.stress[0], sigma1, 1e-6 * sigma1);
  EXPECT_NEAR(b.history[0].values[0], ep1, 1e-6 * ep1);
  EXPECT_NEAR(b.resultant[0], sigma1 * b.area, 1e-6 * sigma1 * b.area);
  // Reversal: elastic until the reverse yield stress, then plastic again along slope.
  const double reverse_yield = hk * ep1 - (sigy + hi * ep1);
  const double eps_reverse = eps1 - (sigma1 - reverse_yield) / kE;
  drive(eps_reverse + 1e-5, 400);  // just before reverse yield: still elastic
  EXPECT_NEAR(b.history[0].values[0], ep1, 1e-9);
  drive(-0.005, 4000);
  // Reverse plastic branch: sigma = reverse_yield + Et (eps - eps_reverse) with the tangent
  // modulus Et = E (H_i + H_k) / (E + H_i + H_k).
  const double et = kE * (hi + hk) / (kE + hi + hk);
  const double sigma2 = reverse_yield + et * (-0.005 - eps_reverse);
  std::printf("[measured] plastic bar reversed to -0.5 %%: sigma %.6g vs %.6g\n", b.stress[0],
              sigma2);
  EXPECT_NEAR(b.stress[0], sigma2, 1e-5 * std::fabs(sigma2));
}

// Cowper-Symonds rate factor (VP 0) on a truss stretched at a constant logarithmic strain rate:
// perfectly plastic, so the flow stress is SIGY (1 + (rate / C)^(1 / P)).
TEST(BeamKernelTruss, CowperSymondsFlowStressAtConstantRate) {
  BeamModel m = chain(1, {1.0, 0.0, 0.0}, 1.0, 3);
  BeamBlock& b = m.block;
  b.area = 1e-4;
  b.material_index = material::material_index(model::MaterialKind::PlasticKinematic);
  const double sigy = 250e6, rate = 20.0, c = 40.4, pp = 5.0;
  b.plastic.linear = true;
  b.plastic.sigy = sigy;
  b.plastic.strain = {0.0, 1.0};
  b.plastic.stress = {sigy, sigy};
  b.plastic.rate_model = material::RateModel::kCowperSymonds;
  b.plastic.rate_c = c;
  b.plastic.rate_p = pp;
  m.initialize();
  const double dt = 1e-6;
  for (int s = 1; s <= 1000; ++s) {  // log strain 0.02 at 20 / s
    const double l = std::exp(rate * dt * s);
    m.vx[1] = (l - m.x[1]) / dt;
    m.x[1] = l;
    m.forces(dt);
  }
  const double reference = sigy * (1.0 + std::pow(rate / c, 1.0 / pp));
  std::printf("[measured] Cowper-Symonds truss: sigma %.8g vs %.8g\n", b.stress[0], reference);
  EXPECT_NEAR(b.stress[0], reference, 1e-6 * reference);
}

// Piecewise-linear hardening (*MAT_024 table, no kinematic part): on monotonic loading the
// stress is the curve at the plastic strain, eps_p = eps - sigma / E (log strain); solved by
// hand for a point on the second segment.
TEST(BeamKernelTruss, PiecewiseLinearBarFollowsItsCurve) {
  BeamModel m = chain(1, {1.0, 0.0, 0.0}, 1.0, 3);
  BeamBlock& b = m.block;
  b.area = 1e-4;
  b.material_index = material::material_index(model::MaterialKind::PiecewiseLinearPlasticity);
  b.plastic.linear = false;
  b.plastic.strain = {0.0, 0.01, 0.05, 0.2};
  b.plastic.stress = {200e6, 260e6, 300e6, 330e6};
  m.initialize();
  const double dt = 1e-6, eps_target = 0.04;
  const int steps = 5000;
  for (int s = 1; s <= steps; ++s) {
    const double l = std::exp(eps_target * s / steps);
    m.vx[1] = (l - m.x[1]) / dt;
    m.x[1] = l;
    m.forces(dt);
  }
  // Second segment: sigma = 260e6 + 1e9 (eps_p - 0.01), eps_p = eps - sigma / E.
  const double slope = 40e6 / 0.04;
  const double sigma = (260e6 + slope * (eps_target - 0.01)) / (1.0 + slope / kE);
  std::printf("[measured] *MAT_024 bar: sigma %.8g vs %.8g\n", b.stress[0], sigma);
  EXPECT_NEAR(b.stress[0], sigma, 1e-7 * sigma);
  EXPECT_NEAR(b.history[0].values[0], eps_target - sigma / kE, 1e-9);
}

// Fully plastic bending of the integrated section: one element, node 1 clamped, node 2 turned
// about s with the chord held. With elastic-perfectly-plastic fibres every section point ends
// at +-sigma_y, so the moment saturates at sigma_y sum_q w_q |t_q|: for the 2 x 2 Gauss rule
// sigma_y A h / (2 sqrt 3) (the rule's own limit, 15 % above the continuum's sigma_y A h / 4);
// for the 8-point ring sigma_y A r_p (2 + 2 sqrt 2) / 8. The axial force stays zero.
TEST(BeamKernelIntegrated, PlasticMomentSaturatesAtTheSectionRuleLimit) {
  for (BeamCrossSection shape : {BeamCrossSection::kRectangular, BeamCrossSection::kTubular}) {
    BeamModel m = chain(1, {1.0, 0.0, 0.0}, 0.1, 1);
    BeamBlock& b = m.block;
    b.orientation = {0.0, 1.0, 0.0};
    b.cross_section = shape;
    const double sigy = 250e6;
    double limit = 0.0;
    if (shape == BeamCrossSection::kRectangular) {
      b.ts1 = 0.02;
      b.tt1 = 0.03;
      limit = sigy * 0.02 * 0.03 * 0.03 / (2.0 * std::sqrt(3.0));
    } else {
      b.ts1 = 0.05;
      b.tt1 = 0.04;
      const double area = std::numbers::pi * (0.05 * 0.05 - 0.04 * 0.04) / 4.0;
      const double rp = std::sqrt(0.5 * (0.025 * 0.025 + 0.02 * 0.02));
      limit = sigy * area * rp * (2.0 + 2.0 * std::sqrt(2.0)) / 8.0;
    }
    b.material_index = material::material_index(model::MaterialKind::PlasticKinematic);
    b.plastic.linear = true;
    b.plastic.sigy = sigy;
    b.plastic.strain = {0.0, 1.0};
    b.plastic.stress = {sigy, sigy};
    m.initialize();
    // Curvature up to 20 times the first-yield curvature, 2000 steps.
    const double kappa_max = 20.0 * sigy / kE / 0.015;
    const double dt = 1e-6;
    for (int s = 0; s < 2000; ++s) {
      m.wy[1] = kappa_max * 0.1 / 2000.0 / dt;
      m.forces(dt);
    }
    const double ms = b.resultant[4];
    std::printf("[measured] plastic moment (%s) %.8g vs rule limit %.8g; N %.3g\n",
                shape == BeamCrossSection::kRectangular ? "rectangle" : "tube", ms, limit,
                b.resultant[0]);
    EXPECT_NEAR(std::fabs(ms), limit, 1e-9 * limit);
    EXPECT_LT(std::fabs(b.resultant[0]), 1e-9 * sigy * b.area);
  }
}

// ------------------------------------------------------------------------------ input ---

TEST(BeamKernelInput, ZeroLengthAndAxialOrientationAreErrorsNamingTheElement) {
  BeamModel m = chain(2, {1.0, 0.0, 0.0}, 1.0, 2);
  rectangle(m.block, 0.02, 0.03);
  m.block.element_id = {17, 18};
  m.x[1] = m.x[0];  // element 17 collapses
  try {
    m.initialize();
    FAIL() << "zero length accepted";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("element 17"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("zero length"), std::string::npos) << e.what();
  }
  BeamModel p = chain(2, {1.0, 0.0, 0.0}, 1.0, 2);
  rectangle(p.block, 0.02, 0.03);
  p.block.element_id = {17, 18};
  p.block.orientation = {0.0, 1.0, 0.0, 2.0, 0.0, 0.0};  // element 18: along its axis
  try {
    p.initialize();
    FAIL() << "axial orientation accepted";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("element 18"), std::string::npos) << e.what();
  }
  BeamModel q = chain(2, {1.0, 0.0, 0.0}, 1.0, 2);
  rectangle(q.block, 0.02, 0.03);
  q.block.material_index = material::material_index(model::MaterialKind::PlasticKinematic);
  EXPECT_THROW(q.initialize(), SolverError);  // resultant beam: elastic only
  // ELFORM 1 sections: a rectangle needs both sides, a tube an inner diameter below the outer.
  BeamModel r = chain(1, {1.0, 0.0, 0.0}, 1.0, 1);
  r.block.ts1 = 0.02;
  EXPECT_THROW(r.initialize(), SolverError);
  BeamModel t = chain(1, {1.0, 0.0, 0.0}, 1.0, 1);
  t.block.cross_section = BeamCrossSection::kTubular;
  t.block.ts1 = 0.02;
  t.block.tt1 = 0.02;
  EXPECT_THROW(t.initialize(), SolverError);
  BeamModel u = chain(1, {1.0, 0.0, 0.0}, 1.0, 4);
  rectangle(u.block, 0.02, 0.03);
  EXPECT_THROW(u.initialize(), SolverError);  // ELFORM 4 and up: not implemented
}

TEST(BeamKernelResultant, ResultsDoNotDependOnTheThreadCount) {
  auto run = [](int threads) {
    omp_set_num_threads(threads);
    BeamModel m = cantilever(37, 1.0, 0.02, 0.03);
    m.initialize();
    clamp(m, 0);
    m.fext[6 * 37 + 2] = 10.0;
    m.fext[6 * 37 + 1] = 5.0;
    m.fext[6 * 37 + 3] = 1.0;
    const double dt = 0.9 * stable_dt(m);
    for (int s = 0; s < 300; ++s) m.step(dt);
    omp_set_num_threads(1);
    return m.block.force;
  };
  const std::vector<double> one = run(1), three = run(3);
  ASSERT_EQ(one.size(), three.size());
  for (std::size_t i = 0; i < one.size(); ++i) ASSERT_EQ(one[i], three[i]) << i;
}

}  // namespace
}  // namespace rf::test
