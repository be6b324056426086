// Test-side mode sets for flexible-body verification, made without the solver's eigen analysis:
// the stiffness of a mesh is measured column by column from the element kernel (a unit velocity
// of one DOF over a tiny step gives the force K e_j eps), and Eigen's dense generalized
// eigensolver gives K phi = lambda M phi with the solver's lumped masses. The modes then belong
// to exactly the element the deformable comparison runs use.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "deck_builder.hpp"
#include "element/kernels.hpp"
#include "modal/mode_set.hpp"
#include "solver/simulation.hpp"

namespace rf::test {

// Frequency (Hz) from the upward zero crossings of a sampled signal (linear interpolation).
inline double zero_crossing_frequency(const std::vector<double>& t, const std::vector<double>& y) {
  std::vector<double> crossings;
  for (std::size_t i = 1; i < y.size(); ++i) {
    if (y[i - 1] < 0.0 && y[i] >= 0.0) {
      crossings.push_back(t[i - 1] + (t[i] - t[i - 1]) * (-y[i - 1]) / (y[i] - y[i - 1]));
    }
  }
  if (crossings.size() < 2) return 0.0;
  return static_cast<double>(crossings.size() - 1) / (crossings.back() - crossings.front());
}

// In-plane (x, y) coordinate of node `tip` across a spinning hub's axis line: the hub frame has
// its origin midway between the hub nodes `hub_a` and `hub_b` and its x axis from a to b.
inline double offset_across_hub_axis(const solver::NodalState& nodes, std::size_t hub_a,
                                     std::size_t hub_b, std::size_t tip) {
  const double cx = 0.5 * (nodes.x.x[hub_a] + nodes.x.x[hub_b]);
  const double cy = 0.5 * (nodes.x.y[hub_a] + nodes.x.y[hub_b]);
  const double angle =
      std::atan2(nodes.x.y[hub_b] - nodes.x.y[hub_a], nodes.x.x[hub_b] - nodes.x.x[hub_a]);
  return -std::sin(angle) * (nodes.x.x[tip] - cx) + std::cos(angle) * (nodes.x.y[tip] - cy);
}

// The steel test beam of the flexible-body tests: 1 x 0.1 x 0.15 m, 10 x 2 x 2 hexahedra,
// part 1 (its modes are computed densely per test).
constexpr double kSteelDensity = 7850.0, kSteelYoung = 2.0e11, kSteelPoisson = 0.3;
inline BoxMesh steel_beam_mesh() {
  BoxMesh mesh;
  mesh.nx = 10;
  mesh.ny = 2;
  mesh.nz = 2;
  mesh.lx = 1.0;
  mesh.ly = 0.1;
  mesh.lz = 0.15;
  return mesh;
}

struct DenseModel {
  Eigen::MatrixXd stiffness;  // 3N x 3N
  Eigen::VectorXd mass;       // 3N (lumped, repeated per direction)
};

// K and M of every deformable block of a (deformable) simulation at its reference state.
inline DenseModel dense_stiffness(const solver::Simulation& sim) {
  const solver::State& state = sim.state();
  const std::size_t n = state.nodes.size();
  const Eigen::Index dofs = static_cast<Eigen::Index>(3 * n);
  DenseModel out;
  out.stiffness = Eigen::MatrixXd::Zero(dofs, dofs);
  out.mass.resize(dofs);
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d)
      out.mass[static_cast<Eigen::Index>(3 * i + d)] = state.nodes.mass[i];
  }
  std::vector<double> zero(n, 0.0);
  std::vector<double> v[3] = {zero, zero, zero};
  const double eps = 1e-9;
  for (Eigen::Index j = 0; j < dofs; ++j) {
    v[j % 3][static_cast<std::size_t>(j / 3)] = 1.0;
    const element::NodalView view{state.nodes.x0.x.data(),
                                  state.nodes.x0.y.data(),
                                  state.nodes.x0.z.data(),
                                  v[0].data(),
                                  v[1].data(),
                                  v[2].data()};
    for (const auto& original : state.hex_blocks) {
      element::HexBlock block = original;  // fresh stresses
      block.bulk_viscosity = {};           // a damping, not stiffness: the unit rate would swamp K
      std::fill(block.stress.begin(), block.stress.end(), 0.0);
      std::fill(block.hourglass_state.begin(), block.hourglass_state.end(), 0.0);
      element::compute_block_forces(block, view, eps);
      const int per = block.nodes_per_element();
      for (std::size_t e = 0; e < block.size(); ++e) {
        for (int a = 0; a < per; ++a) {
          const std::int32_t node = block.conn[e * per + a];
          for (int d = 0; d < 3; ++d) {
            out.stiffness(3 * node + d, j) += block.force[(e * per + a) * 3 + d] / eps;
          }
        }
      }
    }
    v[j % 3][static_cast<std::size_t>(j / 3)] = 0.0;
  }
  out.stiffness = 0.5 * (out.stiffness + out.stiffness.transpose()).eval();
  return out;
}

// All modes of K phi = lambda M phi, ascending, mass-normalised; the `rigid_count` lowest are
// flagged rigid. Node data from the simulation (IDs, reference coordinates, masses).
inline modal::ModeSet dense_modes(const solver::Simulation& sim, const DenseModel& km,
                                  int rigid_count = 6) {
  const solver::State& state = sim.state();
  const std::size_t n = state.nodes.size();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(
      km.stiffness, km.mass.asDiagonal().toDenseMatrix());
  modal::ModeSet set;
  for (std::size_t i = 0; i < n; ++i) {
    set.node_ids.push_back(state.nodes.id[i]);
    set.node_parts.push_back(1);
    set.coordinates.push_back(state.nodes.x0.x[i]);
    set.coordinates.push_back(state.nodes.x0.y[i]);
    set.coordinates.push_back(state.nodes.x0.z[i]);
    set.mass.push_back(state.nodes.mass[i]);
  }
  const Eigen::Index m = eig.eigenvalues().size();
  for (Eigen::Index k = 0; k < m; ++k) {
    const double lambda = eig.eigenvalues()[k];
    set.eigenvalues.push_back(lambda);
    set.generalized_mass.push_back(1.0);
    set.residual.push_back(0.0);
    set.rigid.push_back(k < rigid_count ? 1 : 0);
    const Eigen::VectorXd phi = eig.eigenvectors().col(k);
    for (Eigen::Index r = 0; r < phi.size(); ++r) set.shapes.push_back(phi[r]);
  }
  set.rigid_mode_count = rigid_count;
  return set;
}

}  // namespace rf::test
