// modes.h5 reader and writer; the layout is in mode_set.hpp and docs/eigen.md.
#include <fmt/format.h>

#include <cmath>

#include "io/restart/hdf5_file.hpp"
#include "modal/mode_set.hpp"
#include "model/error.hpp"

namespace rf::modal {

namespace {

constexpr const char* kFormat = "rigidflex-modes";
// Version 1: translations only (solid models, still written for them). Version 2: rotational
// components of the nodes of shells and beams (mode_set.hpp).
constexpr std::int64_t kVersion = 1;
constexpr std::int64_t kRotationsVersion = 2;

template <class T>
std::span<const T> view(const std::vector<T>& v) {
  return {v.data(), v.size()};
}

}  // namespace

void write_mode_database(const std::filesystem::path& file, const ModeSet& modes) {
  const std::size_t n = modes.node_count();
  const std::size_t m = modes.mode_count();
  if (modes.node_parts.size() != n || modes.coordinates.size() != 3 * n || modes.mass.size() != n ||
      modes.generalized_mass.size() != m || modes.residual.size() != m || modes.rigid.size() != m ||
      modes.shapes.size() != 3 * n * m ||
      modes.rotational_inertia.size() != modes.rotation_count() ||
      modes.rotation_shapes.size() != 3 * modes.rotation_count() * m) {
    throw std::invalid_argument("write_mode_database: inconsistent ModeSet sizes");
  }
  io::h5::File h5 = io::h5::File::create(file);
  {
    const io::h5::Group root = h5.root();
    root.set("format", std::string(kFormat));
    const bool rotations = modes.rotation_count() > 0;
    root.set("version", rotations ? kRotationsVersion : kVersion);
    root.set("rigid_mode_count", static_cast<std::int64_t>(modes.rigid_mode_count));
    root.set("node_count", static_cast<std::int64_t>(n));
    root.set("mode_count", static_cast<std::int64_t>(m));
    const io::h5::Group nodes = root.create_group("nodes");
    nodes.write("id", view(modes.node_ids));
    nodes.write("part", view(modes.node_parts));
    nodes.write("coordinates", view(modes.coordinates));
    nodes.write("mass", view(modes.mass));
    if (rotations) {
      nodes.write("rotation_node", view(modes.rotation_nodes));
      nodes.write("rotational_inertia", view(modes.rotational_inertia));
    }
    const io::h5::Group group = root.create_group("modes");
    std::vector<double> frequency(m);
    for (std::size_t k = 0; k < m; ++k) {
      frequency[k] = std::sqrt(std::max(modes.eigenvalues[k], 0.0)) / (2.0 * M_PI);
    }
    group.write("eigenvalue", view(modes.eigenvalues));
    group.write("frequency_hz", view(frequency));
    group.write("generalized_mass", view(modes.generalized_mass));
    group.write("residual", view(modes.residual));
    group.write("rigid", view(modes.rigid));
    group.write("shape", view(modes.shapes));
    if (rotations) group.write("rotation_shape", view(modes.rotation_shapes));
  }
  h5.close();
}

ModeSet read_mode_database(const std::filesystem::path& file) {
  const io::h5::File h5 = io::h5::File::open(file);
  const io::h5::Group root = h5.root();
  if (!root.has_attribute("format") || root.get_string("format") != kFormat) {
    root.fail("format", fmt::format("is not \"{}\": not a RigidFlex mode database", kFormat));
  }
  const std::int64_t version = root.get_int("version");
  if (version != kVersion && version != kRotationsVersion) {
    root.fail("version", fmt::format("is {}, this version reads versions {} and {}", version,
                                     kVersion, kRotationsVersion));
  }
  ModeSet modes;
  modes.rigid_mode_count = static_cast<int>(root.get_int("rigid_mode_count"));
  const io::h5::Group nodes = root.group("nodes");
  modes.node_ids = nodes.read_int64("id");
  const std::size_t n = modes.node_ids.size();
  modes.node_parts = nodes.read_int64("part");
  modes.coordinates = nodes.read_doubles("coordinates");
  modes.mass = nodes.read_doubles("mass");
  if (modes.node_parts.size() != n) nodes.fail("part", fmt::format("must have {} entries", n));
  if (modes.coordinates.size() != 3 * n) {
    nodes.fail("coordinates", fmt::format("must have {} entries (3 per node)", 3 * n));
  }
  if (modes.mass.size() != n) nodes.fail("mass", fmt::format("must have {} entries", n));
  const io::h5::Group group = root.group("modes");
  modes.eigenvalues = group.read_doubles("eigenvalue");
  const std::size_t m = modes.eigenvalues.size();
  modes.generalized_mass = group.read_doubles("generalized_mass");
  modes.residual = group.read_doubles("residual");
  modes.rigid = group.read_bytes("rigid");
  modes.shapes = group.read_doubles("shape");
  if (group.length("frequency_hz") != m) {
    group.fail("frequency_hz", fmt::format("must have {} entries (one per mode)", m));
  }
  if (modes.generalized_mass.size() != m) {
    group.fail("generalized_mass", fmt::format("must have {} entries (one per mode)", m));
  }
  if (modes.residual.size() != m) {
    group.fail("residual", fmt::format("must have {} entries (one per mode)", m));
  }
  if (modes.rigid.size() != m) group.fail("rigid", fmt::format("must have {} entries", m));
  if (modes.shapes.size() != 3 * n * m) {
    group.fail("shape", fmt::format("must have {} entries (modes x 3 x nodes)", 3 * n * m));
  }
  if (version == kRotationsVersion) {
    modes.rotation_nodes = nodes.read_int64("rotation_node");
    const std::size_t r = modes.rotation_nodes.size();
    for (const std::int64_t i : modes.rotation_nodes) {
      if (i < 0 || static_cast<std::size_t>(i) >= n) {
        nodes.fail("rotation_node", fmt::format("has the node index {}, outside [0, {})", i, n));
      }
    }
    modes.rotational_inertia = nodes.read_doubles("rotational_inertia");
    if (modes.rotational_inertia.size() != r) {
      nodes.fail("rotational_inertia", fmt::format("must have {} entries (one per rotation "
                                                   "node)",
                                                   r));
    }
    modes.rotation_shapes = group.read_doubles("rotation_shape");
    if (modes.rotation_shapes.size() != 3 * r * m) {
      group.fail("rotation_shape",
                 fmt::format("must have {} entries (modes x 3 x rotation nodes)", 3 * r * m));
    }
  }
  return modes;
}

}  // namespace rf::modal
