// modes.h5 reader and writer; the layout is in mode_set.hpp and docs/eigen.md.
#include <fmt/format.h>

#include <cmath>

#include "io/restart/hdf5_file.hpp"
#include "modal/mode_set.hpp"
#include "model/error.hpp"

namespace rf::modal {

namespace {

constexpr const char* kFormat = "rigidflex-modes";
constexpr std::int64_t kVersion = 1;

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
      modes.shapes.size() != 3 * n * m) {
    throw std::invalid_argument("write_mode_database: inconsistent ModeSet sizes");
  }
  io::h5::File h5 = io::h5::File::create(file);
  {
    const io::h5::Group root = h5.root();
    root.set("format", std::string(kFormat));
    root.set("version", kVersion);
    root.set("rigid_mode_count", static_cast<std::int64_t>(modes.rigid_mode_count));
    root.set("node_count", static_cast<std::int64_t>(n));
    root.set("mode_count", static_cast<std::int64_t>(m));
    const io::h5::Group nodes = root.create_group("nodes");
    nodes.write("id", view(modes.node_ids));
    nodes.write("part", view(modes.node_parts));
    nodes.write("coordinates", view(modes.coordinates));
    nodes.write("mass", view(modes.mass));
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
  }
  h5.close();
}

ModeSet read_mode_database(const std::filesystem::path& file) {
  const io::h5::File h5 = io::h5::File::open(file);
  const io::h5::Group root = h5.root();
  if (!root.has_attribute("format") || root.get_string("format") != kFormat) {
    root.fail("format", fmt::format("is not \"{}\": not a RigidFlex mode database", kFormat));
  }
  if (root.get_int("version") != kVersion) {
    root.fail("version", fmt::format("is {}, this version reads version {}",
                                     root.get_int("version"), kVersion));
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
  return modes;
}

}  // namespace rf::modal
