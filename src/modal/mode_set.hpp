// The result of an eigen analysis of a (usually free-free) part, as the flexible-body code and
// the mode database `modes.h5` hold it. Modes are mass-normalised with the lumped mass of the
// explicit solver: shapes^T M shapes = I, M = diag(mass per node, repeated for x, y, z).
//
// modes.h5 layout (version 1, documented for outside tools in docs/modes.md):
//   /            attributes: format = "rigidflex-modes", version = 1,
//                            rigid_mode_count (int: modes flagged rigid, kept or removed)
//   /nodes/id            int64[n]    user node IDs, in the order of every per-node array
//   /nodes/part          int64[n]    user part ID of each node (the first part found)
//   /nodes/coordinates   double[3n]  reference coordinates, x0 y0 z0 x1 y1 z1 ...
//   /nodes/mass          double[n]   lumped translational mass
//   /modes/eigenvalue    double[m]   lambda = omega^2 (rad^2/s^2)
//   /modes/frequency_hz  double[m]   sqrt(max(lambda, 0)) / (2 pi)
//   /modes/generalized_mass double[m] phi^T M phi before normalisation
//   /modes/residual      double[m]   ||K phi - lambda M phi|| / ||K phi|| (or / ||M phi|| when
//                                    K phi vanishes, rigid modes)
//   /modes/rigid         uint8[m]    1 for a rigid-body (near-zero) mode
//   /modes/shape         double[m*3n] mode k at offset k*3n, x y z per node (mass-normalised)
// Version 2 (written only when some nodes have rotations: shells, beams; a solid model's file
// stays version 1) adds
//   /nodes/rotation_node      int64[r]    index (0-based, into /nodes/id) of each node with
//                                         rotations
//   /nodes/rotational_inertia double[r]   lumped rotational inertia (about every axis)
//   /modes/rotation_shape     double[m*3r] mode k at offset k*3r, rx ry rz per rotation node
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "model/model.hpp"

namespace rf::modal {

struct ModeSet {
  std::vector<model::Id> node_ids;
  std::vector<model::Id> node_parts;
  std::vector<double> coordinates;  // 3 per node
  std::vector<double> mass;         // per node
  std::vector<double> eigenvalues;  // per mode, omega^2
  std::vector<double> generalized_mass;
  std::vector<double> residual;
  std::vector<std::uint8_t> rigid;
  std::vector<double> shapes;  // mode k, node i, direction d at [k * 3n + 3 i + d]
  // Nodes with rotations (shells, beams; empty for solids): the node index (into node_ids) of
  // each, its lumped rotational inertia (about every axis) and the rotational components of the
  // modes, mode k, rotation node j, axis d at [k * 3r + 3 j + d]. Mass normalisation covers
  // both: shapes^T M shapes + rotation_shapes^T J rotation_shapes = I.
  std::vector<std::int64_t> rotation_nodes;
  std::vector<double> rotational_inertia;
  std::vector<double> rotation_shapes;
  int rigid_mode_count = 0;

  std::size_t node_count() const { return node_ids.size(); }
  std::size_t mode_count() const { return eigenvalues.size(); }
  const double* shape(std::size_t k) const { return shapes.data() + k * 3 * node_count(); }
  std::size_t rotation_count() const { return rotation_nodes.size(); }
  const double* rotation_shape(std::size_t k) const {
    return rotation_shapes.data() + k * 3 * rotation_count();
  }
};

// Writes / reads modes.h5 (layout above). Reading checks format, version and sizes and throws
// rf::InputError naming the file and the dataset on any mismatch.
void write_mode_database(const std::filesystem::path& file, const ModeSet& modes);
ModeSet read_mode_database(const std::filesystem::path& file);

}  // namespace rf::modal
