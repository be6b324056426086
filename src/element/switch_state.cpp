#include "element/switch_state.hpp"

#include <cmath>

namespace rf::element {

namespace {

// s -> Q s Q^T for a symmetric tensor in Voigt order xx yy zz xy yz zx.
void rotate_symmetric(const Eigen::Matrix3d& q, double* s) {
  Eigen::Matrix3d m;
  m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  const Eigen::Matrix3d r = q * m * q.transpose();
  s[0] = r(0, 0);
  s[1] = r(1, 1);
  s[2] = r(2, 2);
  s[3] = r(0, 1);
  s[4] = r(1, 2);
  s[5] = r(2, 0);
}

void rotate_vector(const Eigen::Matrix3d& q, double* v) {
  const Eigen::Vector3d r = q * Eigen::Vector3d(v[0], v[1], v[2]);
  v[0] = r.x();
  v[1] = r.y();
  v[2] = r.z();
}

}  // namespace

// Complementary strain energy of the frozen stresses, sum over stress points of
// V_q [(1 + nu) s:s - nu (tr s)^2] / (2 E) (linear isotropic elasticity).
double frozen_strain_energy(const HexBlock& block) {
  const double young = block.material.young, nu = block.material.poisson;
  if (!(young > 0.0)) return 0.0;
  const int points = block.points_per_element();
  double sum = 0.0;
  for (std::size_t e = 0; e < block.size(); ++e) {
    for (int q = 0; q < points; ++q) {
      const double* s = &block.stress[(e * points + q) * 6];
      const double trace = s[0] + s[1] + s[2];
      const double ss =
          s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
      double weight = block.volume[e] / points;
      if (block.order > 1) weight = block.reference_weight[e * points + q];
      sum += weight * ((1.0 + nu) * ss - nu * trace * trace) / (2.0 * young);
    }
  }
  return sum;
}

// Plane stress (xx, yy, xy) and transverse shear (yz, zx, updated with SHRF G in the kernel) at
// every through-thickness point, weight A t/2 w_p:
//   [sxx^2 + syy^2 - 2 nu sxx syy + 2 (1 + nu) sxy^2] / (2E) + (syz^2 + szx^2) / (2 SHRF G).
double frozen_strain_energy(const ShellBlock& block) {
  const double young = block.material.young, nu = block.material.poisson;
  if (!(young > 0.0)) return 0.0;
  const double shear = young / (2.0 * (1.0 + nu));
  const double transverse = block.shear_factor > 0.0 ? block.shear_factor * shear : shear;
  const int in_plane = block.in_plane_points();
  const int nip = block.nip;
  const int points = block.points_per_element();
  double sum = 0.0;
  for (std::size_t e = 0; e < block.size(); ++e) {
    const double half_t = 0.5 * block.element_thickness[e];
    for (int k = 0; k < points; ++k) {
      const double* s = &block.stress[(e * points + k) * kShellStress];
      const double membrane =
          (s[0] * s[0] + s[1] * s[1] - 2.0 * nu * s[0] * s[1] + 2.0 * (1.0 + nu) * s[2] * s[2]) /
          (2.0 * young);
      const double transverse_energy = (s[3] * s[3] + s[4] * s[4]) / (2.0 * transverse);
      const double weight = block.area[e] / in_plane * half_t * block.weight[k % nip];
      sum += weight * (membrane + transverse_energy);
    }
  }
  return sum;
}

// Per element of current length L, from the resultants (N, Qs, Qt, T, Ms, Mt) and the axial
// stresses: truss sigma^2 A L / 2E; ELFORM 2 (Timoshenko element with cubic deflection,
// beam_block.cpp eqs. (6)-(8)): N^2 L / 2EA + T^2 L / 2GJ + M^2 L / 2EI + Q^2 L^3 (1 + phi) /
// 24 EI per bending plane; ELFORM 1: sum_q w_q sigma_q^2 L / 2E + Q^2 L / 2 kGA + T^2 L / 2GJ.
double frozen_strain_energy(const BeamBlock& block) {
  const double young = block.material.young, nu = block.material.poisson;
  if (!(young > 0.0)) return 0.0;
  const double shear = young / (2.0 * (1.0 + nu));
  const double shear_area =
      block.shear_area > 0.0 ? block.shear_area : block.shear_factor * block.area;
  const double kga = shear * shear_area, gj = shear * block.torsion;
  auto quotient = [](double a, double b) { return b > 0.0 ? a / b : 0.0; };
  double sum = 0.0;
  const int points = block.points_per_element();
  for (std::size_t e = 0; e < block.size(); ++e) {
    const double length = block.length[e];
    const double* r = &block.resultant[6 * e];
    if (block.elform == 3) {
      const double s = block.stress[e];
      sum += s * s * block.area * length / (2.0 * young);
      continue;
    }
    double energy = quotient(r[3] * r[3] * length, 2.0 * gj);
    if (block.elform == 2) {
      energy += quotient(r[0] * r[0] * length, 2.0 * young * block.area);
      // Qs, Mt bend about t (I_tt); Qt, Ms about s (I_ss).
      const double pairs[2][3] = {{r[1], r[5], block.itt}, {r[2], r[4], block.iss}};
      for (const auto& p : pairs) {
        const double ei = young * p[2];
        if (!(ei > 0.0)) continue;
        const double phi = kga > 0.0 ? 12.0 * ei / (kga * length * length) : 0.0;
        energy += p[1] * p[1] * length / (2.0 * ei) +
                  p[0] * p[0] * length * length * length * (1.0 + phi) / (24.0 * ei);
      }
    } else {
      for (int q = 0; q < points; ++q) {
        const double s = block.stress[static_cast<std::size_t>(points) * e + q];
        energy += block.section_weight[q] * s * s * length / (2.0 * young);
      }
      energy += quotient((r[1] * r[1] + r[2] * r[2]) * length, 2.0 * kga);
    }
    sum += energy;
  }
  return sum;
}

void turn_frozen_state(HexBlock& block, const Eigen::Matrix3d& q) {
  const std::size_t points = block.stress.size() / 6;
  for (std::size_t k = 0; k < points; ++k) rotate_symmetric(q, &block.stress[k * 6]);
  // Material history that is a symmetric tensor (e.g. a back stress) turns like the stress.
  for (auto& h : block.history) {
    if (!h.field.symmetric_tensor) continue;
    for (std::size_t k = 0; k + 5 < h.values.size(); k += 6) rotate_symmetric(q, &h.values[k]);
  }
  // hourglass_state, IHQ 4/5: 4 modes x (x, y, z) per element in global axes. IHQ 6 keeps
  // them in the element's corotational frame, which turned with the body already.
  if (block.hourglass.ihq != 4 && block.hourglass.ihq != 5) return;
  for (std::size_t k = 0; k + 2 < block.hourglass_state.size(); k += 3) {
    rotate_vector(q, &block.hourglass_state[k]);
  }
}

// Stresses, history and hourglass forces are co-rotational (shell_block.hpp): nothing turns.
void turn_frozen_state(ShellBlock&, const Eigen::Matrix3d&) {}

// The frames (rows e1, s, t in global axes): each row -> Q row. Resultants and axial stresses are
// components in the frame and stay.
void turn_frozen_state(BeamBlock& block, const Eigen::Matrix3d& q) {
  for (std::size_t k = 0; k + 2 < block.frame.size(); k += 3) rotate_vector(q, &block.frame[k]);
}

}  // namespace rf::element
