#include "modal/flexible_body.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rf::modal {

Eigen::Vector3d FlexibleBody::displacement(std::size_t node, const std::vector<double>& a) const {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (int d = 0; d < 3; ++d) {
    const double* row = shape_row(node, d);
    double sum = 0.0;
    for (std::size_t k = 0; k < mode_count; ++k) sum += row[k] * a[k];
    u[d] = sum;
  }
  return u;
}

Eigen::Vector3d FlexibleBody::rotation(std::size_t row, const std::vector<double>& a) const {
  Eigen::Vector3d theta = Eigen::Vector3d::Zero();
  for (int d = 0; d < 3; ++d) {
    const double* psi = rotation_row(row, d);
    double sum = 0.0;
    for (std::size_t k = 0; k < mode_count; ++k) sum += psi[k] * a[k];
    theta[d] = sum;
  }
  return theta;
}

double FlexibleBody::kinetic_energy() const {
  double e = 0.0;
  for (const double v : s) e += 0.5 * v * v;
  return e;
}

double FlexibleBody::elastic_energy() const {
  double e = 0.0;
  for (std::size_t k = 0; k < mode_count; ++k) e += 0.5 * omega[k] * omega[k] * q[k] * q[k];
  return e;
}

namespace {

// G_mkl = sum over the 2x2x2 Gauss points of the body's hexahedra of
// w det J sigma(phi_m) : (grad phi_k^T grad phi_l), gradients in the reference (body) frame.
// From the Green strain E = eps + 1/2 grad u^T grad u: U = U2 + 1/2 int sigma(u) : grad u^T
// grad u dV + O(u^4) (docs/flexible_bodies.md section 2).
//
// Cost n^3 per Gauss point: the contraction over m is done as one matrix product per batch of
// Gauss points, G_sym (n x pairs) += S (n x 9B) H (9B x pairs), S = det * sigma(phi_m) and H the
// grad_k^T grad_l of the pairs k <= l, so that it runs at dense-BLAS speed (it was a scalar
// loop with n^2-strided writes: 1.8 s for 40 modes on 2048 hexahedra).
void compute_stiffening_invariants(FlexibleBody& body, const ModeInput& input) {
  const std::size_t n = body.mode_count;
  body.inv_g.assign(n * n * n, 0.0);
  const Eigen::Index pairs = static_cast<Eigen::Index>(n * (n + 1) / 2);
  constexpr Eigen::Index kBatch = 64;  // Gauss points per product
  Eigen::MatrixXd stress_batch(static_cast<Eigen::Index>(n), 9 * kBatch);
  Eigen::MatrixXd product_batch(9 * kBatch, pairs);
  Eigen::MatrixXd g_sym = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), pairs);
  Eigen::Index filled = 0;
  const auto flush = [&] {
    if (filled == 0) return;
    g_sym.noalias() += stress_batch.leftCols(9 * filled) * product_batch.topRows(9 * filled);
    filled = 0;
  };
  static constexpr double kSign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                         {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  const double g = 1.0 / std::sqrt(3.0);
  std::vector<double> grad(9 * n), stress(9 * n);  // per mode: grad phi (row-major), sigma
  const std::size_t elements = input.hexahedra.size() / 8;
  for (std::size_t e = 0; e < elements; ++e) {
    const std::int32_t* nodes = &input.hexahedra[8 * e];
    for (int p = 0; p < 8; ++p) {
      const double xi[3] = {kSign[p][0] * g, kSign[p][1] * g, kSign[p][2] * g};
      double dn[8][3];
      for (int a = 0; a < 8; ++a) {
        for (int d = 0; d < 3; ++d) {
          double v = 0.125 * kSign[a][d];
          for (int o = 0; o < 3; ++o) {
            if (o != d) v *= 1.0 + kSign[a][o] * xi[o];
          }
          dn[a][d] = v;
        }
      }
      Eigen::Matrix3d jac = Eigen::Matrix3d::Zero();  // J_ij = dX_i / dxi_j
      for (int a = 0; a < 8; ++a) {
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) jac(i, j) += body.body_coords[3 * nodes[a] + i] * dn[a][j];
        }
      }
      const double det = jac.determinant();
      const Eigen::Matrix3d inv = jac.inverse();
      double dndx[8][3];  // dN/dX_j = sum_i dN/dxi_i dxi_i/dX_j
      for (int a = 0; a < 8; ++a) {
        for (int j = 0; j < 3; ++j) {
          dndx[a][j] = dn[a][0] * inv(0, j) + dn[a][1] * inv(1, j) + dn[a][2] * inv(2, j);
        }
      }
      for (std::size_t k = 0; k < n; ++k) {
        double* gk = &grad[9 * k];
        for (int c = 0; c < 9; ++c) gk[c] = 0.0;
        for (int a = 0; a < 8; ++a) {
          for (int i = 0; i < 3; ++i) {
            const double phi = body.shapes[(3 * static_cast<std::size_t>(nodes[a]) + i) * n + k];
            for (int j = 0; j < 3; ++j) gk[3 * i + j] += phi * dndx[a][j];
          }
        }
        const double trace = gk[0] + gk[4] + gk[8];
        double* sk = &stress[9 * k];
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) {
            sk[3 * i + j] = input.lame_mu * (gk[3 * i + j] + gk[3 * j + i]) +
                            (i == j ? input.lame_lambda * trace : 0.0);
          }
        }
      }
      const Eigen::Index column = 9 * filled;
      for (std::size_t m = 0; m < n; ++m) {
        for (int c = 0; c < 9; ++c) {
          stress_batch(static_cast<Eigen::Index>(m), column + c) = det * stress[9 * m + c];
        }
      }
      Eigen::Index pair = 0;
      for (std::size_t k = 0; k < n; ++k) {
        for (std::size_t l = k; l < n; ++l, ++pair) {
          // H = grad_k^T grad_l: H_ab = sum_c G_k,ca G_l,cb.
          const double* gk = &grad[9 * k];
          const double* gl = &grad[9 * l];
          for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < 3; ++b) {
              product_batch(column + 3 * a + b, pair) =
                  gk[a] * gl[b] + gk[3 + a] * gl[3 + b] + gk[6 + a] * gl[6 + b];
            }
          }
        }
      }
      if (++filled == kBatch) flush();
    }
  }
  flush();
  for (std::size_t m = 0; m < n; ++m) {
    Eigen::Index pair = 0;
    for (std::size_t k = 0; k < n; ++k) {
      for (std::size_t l = k; l < n; ++l, ++pair) {
        const double v = g_sym(static_cast<Eigen::Index>(m), pair);
        body.inv_g[(m * n + k) * n + l] = v;
        body.inv_g[(m * n + l) * n + k] = v;
      }
    }
  }
}

}  // namespace

FlexibleBody prepare_flexible_body(const ModeInput& input) {
  const std::size_t nodes = input.mass.size();
  const std::size_t n = input.eigenvalues.size();
  const std::size_t rotations = input.rotation_position.size();
  // Translational rows 3 i + d, then rotational rows 3 N + 3 j + d.
  const Eigen::Index tdofs = static_cast<Eigen::Index>(3 * nodes);
  const Eigen::Index dofs = static_cast<Eigen::Index>(3 * (nodes + rotations));
  if (input.body_coords.size() != 3 * nodes || input.shapes_global.size() != n * 3 * nodes ||
      input.rotational_inertia.size() != rotations ||
      input.rotation_shapes_global.size() != n * 3 * rotations) {
    throw std::invalid_argument("mode input sizes do not match the body's nodes");
  }
  // Phi in body axes, (3N + 3r) x n.
  Eigen::MatrixXd phi(dofs, static_cast<Eigen::Index>(n));
  const Eigen::Matrix3d rt = input.initial_rotation.transpose();
  for (std::size_t k = 0; k < n; ++k) {
    const double* g = input.shapes_global.data() + k * 3 * nodes;
    for (std::size_t i = 0; i < nodes; ++i) {
      const Eigen::Vector3d b = rt * Eigen::Vector3d(g[3 * i], g[3 * i + 1], g[3 * i + 2]);
      for (int d = 0; d < 3; ++d) phi(static_cast<Eigen::Index>(3 * i + d), k) = b[d];
    }
    const double* gr = input.rotation_shapes_global.data() + k * 3 * rotations;
    for (std::size_t j = 0; j < rotations; ++j) {
      const Eigen::Vector3d b = rt * Eigen::Vector3d(gr[3 * j], gr[3 * j + 1], gr[3 * j + 2]);
      for (int d = 0; d < 3; ++d) phi(tdofs + static_cast<Eigen::Index>(3 * j + d), k) = b[d];
    }
  }
  Eigen::VectorXd m(dofs);
  for (std::size_t i = 0; i < nodes; ++i) {
    for (int d = 0; d < 3; ++d) m[static_cast<Eigen::Index>(3 * i + d)] = input.mass[i];
  }
  for (std::size_t j = 0; j < rotations; ++j) {
    for (int d = 0; d < 3; ++d) {
      m[tdofs + static_cast<Eigen::Index>(3 * j + d)] = input.rotational_inertia[j];
    }
  }
  // The six rigid modes, mass-orthonormalised by modified Gram-Schmidt (no assumption on the
  // centre: X need not have its mass centre exactly at 0). A rigid rotation about axis a turns
  // every node with rotations by e_a as well: its rotational rows are e_a.
  Eigen::MatrixXd rigid(dofs, 6);
  rigid.setZero();
  for (std::size_t i = 0; i < nodes; ++i) {
    const Eigen::Vector3d x(input.body_coords[3 * i], input.body_coords[3 * i + 1],
                            input.body_coords[3 * i + 2]);
    for (int a = 0; a < 3; ++a) {
      rigid(static_cast<Eigen::Index>(3 * i + a), a) = 1.0;
      const Eigen::Vector3d r = Eigen::Vector3d::Unit(a).cross(x);
      for (int d = 0; d < 3; ++d) rigid(static_cast<Eigen::Index>(3 * i + d), 3 + a) = r[d];
    }
  }
  for (std::size_t j = 0; j < rotations; ++j) {
    for (int a = 0; a < 3; ++a) rigid(tdofs + static_cast<Eigen::Index>(3 * j + a), 3 + a) = 1.0;
  }
  std::vector<Eigen::Index> kept_rigid;
  for (Eigen::Index r = 0; r < 6; ++r) {
    const double initial = std::sqrt(rigid.col(r).dot(m.cwiseProduct(rigid.col(r))));
    for (const Eigen::Index p : kept_rigid) {
      rigid.col(r) -= rigid.col(p) * rigid.col(p).dot(m.cwiseProduct(rigid.col(r)));
    }
    const double norm = std::sqrt(rigid.col(r).dot(m.cwiseProduct(rigid.col(r))));
    if (norm > 1e-10 * initial && norm > 0.0) {  // a line of nodes has only 5 rigid modes
      rigid.col(r) /= norm;
      kept_rigid.push_back(r);
    }
  }
  for (const Eigen::Index r : kept_rigid) {
    const Eigen::RowVectorXd c = (m.cwiseProduct(rigid.col(r))).transpose() * phi;
    phi -= rigid.col(r) * c;
  }
  // Re-orthonormalise: K^ N = M^ N Lambda with K^ = diag(lambda), M^ = Phi^T M Phi.
  const Eigen::MatrixXd mhat = phi.transpose() * m.asDiagonal() * phi;
  Eigen::MatrixXd khat =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  for (std::size_t k = 0; k < n; ++k) khat(k, k) = input.eigenvalues[k];
  // When the masses match the database's, M^ = I to round-off and the modes are kept as they
  // are (a rotation would mix degenerate pairs, e.g. the two bending modes of a square beam,
  // and the modes would no longer be the database's).
  const bool orthonormal =
      (mhat - Eigen::MatrixXd::Identity(mhat.rows(), mhat.cols())).cwiseAbs().maxCoeff() < 1e-9;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig;
  if (!orthonormal) eig.compute(khat, mhat);
  if (!orthonormal && eig.info() != Eigen::Success) {
    throw std::invalid_argument(
        "the selected modes are (nearly) rigid or linearly dependent after removing their rigid "
        "content; select elastic modes only");
  }
  const Eigen::MatrixXd rotation =
      orthonormal ? Eigen::MatrixXd::Identity(mhat.rows(), mhat.cols()) : eig.eigenvectors();
  const Eigen::VectorXd lambdas = orthonormal ? khat.diagonal() : eig.eigenvalues();
  const Eigen::MatrixXd phi_new = phi * rotation;

  FlexibleBody body;
  body.form = input.form;
  body.node_count = nodes;
  body.mode_count = n;
  body.mass = input.mass;
  body.body_coords = input.body_coords;
  body.omega.resize(n);
  body.zeta = input.damping;
  body.zeta.resize(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const double lambda = lambdas[static_cast<Eigen::Index>(k)];
    if (!(lambda > 0.0)) {
      throw std::invalid_argument(fmt::format(
          "mode {} has eigenvalue {:.4g} after removing rigid content: it is a rigid-body "
          "mode; select elastic modes only",
          k + 1, lambda));
    }
    body.omega[k] = std::sqrt(lambda);
  }
  // Damping follows the database mode order; after the n x n rotation each new mode takes the
  // damping of the database mode it overlaps most (the rotation is the identity when the
  // masses match the database's).
  std::vector<double> zeta(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    Eigen::Index best = 0;
    rotation.col(static_cast<Eigen::Index>(k)).cwiseAbs().maxCoeff(&best);
    zeta[k] = body.zeta[static_cast<std::size_t>(best)];
  }
  body.zeta = zeta;
  body.shapes.resize(3 * nodes * n);
  for (std::size_t r = 0; r < 3 * nodes; ++r) {
    for (std::size_t k = 0; k < n; ++k) {
      body.shapes[r * n + k] = phi_new(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k));
    }
  }
  body.rotation_count = rotations;
  body.rotation_position = input.rotation_position;
  body.rotation_of.assign(nodes, -1);
  for (std::size_t j = 0; j < rotations; ++j) {
    body.rotation_of[static_cast<std::size_t>(input.rotation_position[j])] =
        static_cast<std::int32_t>(j);
  }
  body.rotational_inertia = input.rotational_inertia;
  body.rotation_shapes.resize(3 * rotations * n);
  for (std::size_t r = 0; r < 3 * rotations; ++r) {
    for (std::size_t k = 0; k < n; ++k) {
      body.rotation_shapes[r * n + k] =
          phi_new(tdofs + static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k));
    }
  }
  // Invariants.
  body.inv_a.assign(9 * n, 0.0);
  body.trace_a.assign(n, 0.0);
  body.inv_b.assign(9 * n * n, 0.0);
  body.inv_s.assign(3 * n * n, 0.0);
  if (body.form == ModalForm::kExact) {
    std::vector<double> phi_i(3 * n);
    for (std::size_t i = 0; i < nodes; ++i) {
      const double mi = body.mass[i];
      for (int d = 0; d < 3; ++d) {
        for (std::size_t k = 0; k < n; ++k) phi_i[d * n + k] = body.shapes[(3 * i + d) * n + k];
      }
      for (std::size_t k = 0; k < n; ++k) {
        for (int a = 0; a < 3; ++a) {
          for (int b = 0; b < 3; ++b) {
            body.inv_a[9 * k + 3 * a + b] += mi * phi_i[a * n + k] * body.body_coords[3 * i + b];
          }
        }
        for (std::size_t l = 0; l < n; ++l) {
          double* bkl = &body.inv_b[9 * (k * n + l)];
          for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < 3; ++b) bkl[3 * a + b] += mi * phi_i[a * n + k] * phi_i[b * n + l];
          }
        }
      }
    }
    for (std::size_t k = 0; k < n; ++k) {
      body.trace_a[k] = body.inv_a[9 * k] + body.inv_a[9 * k + 4] + body.inv_a[9 * k + 8];
    }
    // s_lk = sum m phi_l x phi_k: (s)_a = eps_abc (B_lk)_bc.
    for (std::size_t l = 0; l < n; ++l) {
      for (std::size_t k = 0; k < n; ++k) {
        const double* b = &body.inv_b[9 * (l * n + k)];
        double* s = &body.inv_s[3 * (l * n + k)];
        s[0] = b[3 * 1 + 2] - b[3 * 2 + 1];
        s[1] = b[3 * 2 + 0] - b[3 * 0 + 2];
        s[2] = b[3 * 0 + 1] - b[3 * 1 + 0];
      }
    }
  }
  if (body.form == ModalForm::kExact && !input.hexahedra.empty()) {
    compute_stiffening_invariants(body, input);
  }
  body.q.assign(n, 0.0);
  body.s.assign(n, 0.0);
  body.q_previous.assign(n, 0.0);
  body.s_mid.assign(n, 0.0);
  body.force.assign(n, 0.0);
  body.inertia.assign(n, 0.0);
  return body;
}

void oscillator_flow(double omega, double zeta, double h, double& q, double& s) {
  if (!(omega > 0.0)) {
    q += h * s;
    return;
  }
  const double q0 = q, s0 = s;
  if (zeta <= 0.0) {
    const double c = std::cos(omega * h), sn = std::sin(omega * h);
    q = q0 * c + s0 / omega * sn;
    s = s0 * c - omega * q0 * sn;
  } else if (zeta < 1.0 - 1e-8) {
    const double wd = omega * std::sqrt(1.0 - zeta * zeta);
    const double e = std::exp(-zeta * omega * h);
    const double c = std::cos(wd * h), sn = std::sin(wd * h);
    q = e * (q0 * c + (s0 + zeta * omega * q0) / wd * sn);
    s = e * (s0 * c - (zeta * omega * s0 + omega * omega * q0) / wd * sn);
  } else if (zeta <= 1.0 + 1e-8) {
    const double e = std::exp(-omega * h);
    const double b = s0 + omega * q0;
    q = e * (q0 + b * h);
    s = e * (s0 - b * omega * h);
  } else {
    const double root = omega * std::sqrt(zeta * zeta - 1.0);
    const double r1 = -zeta * omega + root, r2 = -zeta * omega - root;
    const double c1 = (s0 - r2 * q0) / (r1 - r2), c2 = q0 - c1;
    const double e1 = std::exp(r1 * h), e2 = std::exp(r2 * h);
    q = c1 * e1 + c2 * e2;
    s = r1 * c1 * e1 + r2 * c2 * e2;
  }
}

void advance_modes(FlexibleBody& body, const Eigen::Vector3d& omega_body,
                   const Eigen::Vector3d& alpha_body, double dt_avg, double dt) {
  const std::size_t n = body.mode_count;
  std::fill(body.inertia.begin(), body.inertia.end(), 0.0);
  if (body.form == ModalForm::kExact) {
    const Eigen::Vector3d& w = omega_body;
    const double w2 = w.squaredNorm();
    for (std::size_t k = 0; k < n; ++k) {
      const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> a(&body.inv_a[9 * k]);
      double h = -(w.dot(a * w) - w2 * body.trace_a[k]);
      for (std::size_t l = 0; l < n; ++l) {
        const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> b(
            &body.inv_b[9 * (k * n + l)]);
        const Eigen::Map<const Eigen::Vector3d> slk(&body.inv_s[3 * (l * n + k)]);
        // tr B_kl = delta_kl when the modes are mass-orthonormal with the translational masses
        // alone; with nodal rotational inertia, tr B_kl = delta_kl - sum_j J_j psi_jk . psi_jl.
        const double trace_b =
            body.rotation_count == 0 ? (k == l ? 1.0 : 0.0) : b(0, 0) + b(1, 1) + b(2, 2);
        h -= body.q[l] * (w.dot(b * w) - w2 * trace_b);
        h -= body.q[l] * alpha_body.dot(slk);
      }
      body.inertia[k] = h;
    }
  }
  // Geometric stiffening: f_j = -dU3/dq_j = -1/2 (G_jkl q_k q_l + 2 G_mjl q_m q_l).
  std::vector<double>& stiffening = body.stiffening;
  stiffening.assign(n, 0.0);
  if (!body.inv_g.empty()) {
    const std::vector<double>& q = body.q;
    for (std::size_t m = 0; m < n; ++m) {
      for (std::size_t k = 0; k < n; ++k) {
        const double* row = &body.inv_g[(m * n + k) * n];
        double gq = 0.0;  // sum_l G_mkl q_l
        for (std::size_t l = 0; l < n; ++l) gq += row[l] * q[l];
        stiffening[m] -= 0.5 * q[k] * gq;  // d/dq_m of the first index
        stiffening[k] -= q[m] * gq;        // the two symmetric indices
      }
    }
  }
  body.damping_loss = 0.0;
  body.inertia_work = 0.0;
  body.stiffening_work = 0.0;
  body.q_previous = body.q;
  // The Coriolis force -2 sum_l s_l Omega . s_lk is gyroscopic (C_kl = 2 Omega . s_lk is
  // antisymmetric: it does no work). Taken with the velocities before the kick (explicit) it
  // is an explicit-Euler rotation of (s_k, s_l) that gains energy by (C dt)^2 per step: with an
  // in-plane mode and the axial stretch modes of a body spinning near or above the mode's
  // frequency this made the chordwise motion grow without bound (tests/verification/
  // flexible_spin_test.cpp, spin-up). It is therefore taken at the kick's midpoint, s_mid =
  // s + dt_avg / 2 (f - C s_mid) (implicit midpoint, the Cayley map: |s| is kept by the
  // Coriolis part exactly, and its work dt_avg h . s_mid is zero), solved by Gauss-Seidel
  // sweeps in place: they contract by about dt |Omega| per sweep.
  if (body.form == ModalForm::kExact) {
    const Eigen::Vector3d& w = omega_body;
    for (std::size_t k = 0; k < n; ++k) {
      body.s_mid[k] = body.s[k] + 0.5 * dt_avg * (body.force[k] + body.inertia[k] + stiffening[k]);
    }
    const auto coriolis = [&](std::size_t k) {
      double c = 0.0;
      for (std::size_t l = 0; l < n; ++l) {
        c -= 2.0 * body.s_mid[l] *
             w.dot(Eigen::Map<const Eigen::Vector3d>(&body.inv_s[3 * (l * n + k)]));
      }
      return c;
    };
    if (w.squaredNorm() > 0.0) {
      for (int sweep = 0; sweep < 100; ++sweep) {
        double change = 0.0, size = 0.0;
        for (std::size_t k = 0; k < n; ++k) {
          const double next =
              body.s[k] +
              0.5 * dt_avg * (body.force[k] + body.inertia[k] + stiffening[k] + coriolis(k));
          change = std::max(change, std::abs(next - body.s_mid[k]));
          size = std::max(size, std::abs(next));
          body.s_mid[k] = next;
        }
        if (change <= 1e-15 * size) break;
      }
      for (std::size_t k = 0; k < n; ++k) body.inertia[k] += coriolis(k);
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    const double before = body.s[k];
    body.s[k] += dt_avg * (body.force[k] + body.inertia[k] + stiffening[k]);
    body.s_mid[k] = 0.5 * (before + body.s[k]);
    body.inertia_work += dt_avg * body.inertia[k] * body.s_mid[k];
    body.stiffening_work += dt_avg * stiffening[k] * body.s_mid[k];
    const double w = body.omega[k];
    const double e0 = 0.5 * (body.s[k] * body.s[k] + w * w * body.q[k] * body.q[k]);
    oscillator_flow(w, body.zeta[k], dt, body.q[k], body.s[k]);
    const double e1 = 0.5 * (body.s[k] * body.s[k] + w * w * body.q[k] * body.q[k]);
    if (body.zeta[k] > 0.0) body.damping_loss += e0 - e1;
  }
}

}  // namespace rf::modal
