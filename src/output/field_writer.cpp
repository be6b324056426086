// Result frames as VTK XML UnstructuredGrid (.vtu) with appended raw binary data, plus a
// .pvd collection so ParaView sees one time series (frames.pvd; modes.pvd for eigen analyses).
//
// Appended raw layout (header_type="UInt64"): after the XML, `<AppendedData encoding="raw">_`
// is followed by one block per DataArray: a little/big-endian (host order, declared in
// byte_order) UInt64 byte count and then the raw values. Each DataArray's offset attribute is
// the position of its block relative to the byte after '_'. Raw binary is exact (no decimal
// round trip) and several times smaller and faster to write than ASCII.
#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "output/writers.hpp"

namespace rf::output {

namespace {

const char* byte_order_name() {
  return std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";
}

// Minimal escaping for text placed in an XML attribute value.
std::string xml_attribute(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// One DataArray of the appended section: its XML description and where its bytes live.
struct AppendedArray {
  std::string name;
  const char* type;  // VTK type name: Float64, Int64, UInt8
  int components;
  const void* data;
  std::uint64_t bytes;
  std::uint64_t offset = 0;  // filled when the layout is computed
  // Optional component labels (ParaView shows them instead of 0..n-1).
  std::vector<std::string_view> component_names = {};
};

void append_data_array(fmt::memory_buffer& xml, const AppendedArray& a, std::string_view indent) {
  fmt::format_to(std::back_inserter(xml), "{}<DataArray type=\"{}\" Name=\"{}\"", indent, a.type,
                 a.name);
  if (a.components != 1) {
    fmt::format_to(std::back_inserter(xml), " NumberOfComponents=\"{}\"", a.components);
  }
  for (std::size_t c = 0; c < a.component_names.size(); ++c) {
    fmt::format_to(std::back_inserter(xml), " ComponentName{}=\"{}\"", c, a.component_names[c]);
  }
  fmt::format_to(std::back_inserter(xml), " format=\"appended\" offset=\"{}\"/>\n", a.offset);
}

// RAII stdio file so that every error path closes it.
struct OutputFile {
  std::FILE* file = nullptr;
  std::filesystem::path path;
  explicit OutputFile(const std::filesystem::path& p) : path(p) {
    file = std::fopen(p.c_str(), "wb");
    if (file == nullptr) {
      throw std::runtime_error(fmt::format("cannot open output file '{}' for writing", p.string()));
    }
  }
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile() {
    if (file != nullptr) std::fclose(file);
  }
  void write(const void* data, std::size_t bytes) {
    if (bytes != 0 && std::fwrite(data, 1, bytes, file) != bytes) {
      throw std::runtime_error(fmt::format("cannot write to output file '{}'", path.string()));
    }
  }
  void close() {
    const int rc = std::fclose(file);
    file = nullptr;
    if (rc != 0) {
      throw std::runtime_error(fmt::format("cannot write to output file '{}'", path.string()));
    }
  }
};

// Writes to `path` through a temporary name and renames, so a reader (or a crash) never sees
// a half-written file.
template <typename WriteBody>
void write_atomically(const std::filesystem::path& path, WriteBody&& body) {
  std::filesystem::path temporary = path;
  temporary += ".tmp";
  {
    OutputFile out(temporary);
    body(out);
    out.close();
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    throw std::runtime_error(fmt::format("cannot rename '{}' to '{}': {}", temporary.string(),
                                         path.string(), ec.message()));
  }
}

}  // namespace

// Co-rotational frame of a shell at the current configuration (rows e1, e2, e3): e3 along the
// cross product of the diagonals, e1 along side 1-2 made normal to e3 (Belytschko, Lin and Tsay
// 1984), the frame the kernel keeps the stresses in.
std::array<std::array<double, 3>, 3> shell_frame(const solver::NodalState& nodes,
                                                 const std::int32_t* c) {
  auto at = [&](int k) {
    return std::array<double, 3>{nodes.x.x[c[k]], nodes.x.y[c[k]], nodes.x.z[c[k]]};
  };
  const auto x1 = at(0), x2 = at(1), x3 = at(2), x4 = at(3);
  const std::array<double, 3> d13{x3[0] - x1[0], x3[1] - x1[1], x3[2] - x1[2]};
  const std::array<double, 3> d24{x4[0] - x2[0], x4[1] - x2[1], x4[2] - x2[2]};
  std::array<double, 3> e3{d13[1] * d24[2] - d13[2] * d24[1], d13[2] * d24[0] - d13[0] * d24[2],
                           d13[0] * d24[1] - d13[1] * d24[0]};
  if (c[2] == c[3]) {  // triangle: the normal of the face
    const std::array<double, 3> a{x2[0] - x1[0], x2[1] - x1[1], x2[2] - x1[2]};
    e3 = {a[1] * d13[2] - a[2] * d13[1], a[2] * d13[0] - a[0] * d13[2],
          a[0] * d13[1] - a[1] * d13[0]};
  }
  auto normalise = [](std::array<double, 3>& v) {
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0.0)
      for (double& x : v) x /= l;
  };
  normalise(e3);
  std::array<double, 3> e1{x2[0] - x1[0], x2[1] - x1[1], x2[2] - x1[2]};
  const double p = e1[0] * e3[0] + e1[1] * e3[1] + e1[2] * e3[2];
  for (int k = 0; k < 3; ++k) e1[k] -= p * e3[k];
  normalise(e1);
  const std::array<double, 3> e2{e3[1] * e1[2] - e3[2] * e1[1], e3[2] * e1[0] - e3[0] * e1[2],
                                 e3[0] * e1[1] - e3[1] * e1[0]};
  return {e1, e2, e3};
}

// sigma_global = sum_ab e_a (x) e_b sigma_ab for the co-rotational components xx yy xy yz zx
// (sigma_zz = 0), returned in Voigt order xx yy zz xy yz zx.
void shell_stress_to_global(const double* local, const std::array<std::array<double, 3>, 3>& e,
                            double out[6]) {
  const double s[3][3] = {
      {local[0], local[2], local[4]}, {local[2], local[1], local[3]}, {local[4], local[3], 0.0}};
  static constexpr int kI[6] = {0, 1, 2, 0, 1, 2}, kJ[6] = {0, 1, 2, 1, 2, 0};
  for (int v = 0; v < 6; ++v) {
    double sum = 0.0;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) sum += e[a][kI[v]] * s[a][b] * e[b][kJ[v]];
    out[v] = sum;
  }
}

double von_mises(const double* s) {
  const double dxy = s[0] - s[1];
  const double dyz = s[1] - s[2];
  const double dzx = s[2] - s[0];
  const double shear = s[3] * s[3] + s[4] * s[4] + s[5] * s[5];
  return std::sqrt(0.5 * (dxy * dxy + dyz * dyz + dzx * dzx) + 3.0 * shear);
}

// Degenerate LS-DYNA solids and their VTK node order.
//
// LS-DYNA (and VTK) hexahedron: N1 N2 N3 N4 is the bottom face, counter-clockwise seen from
// the top face N5 N6 N7 N8, with N5 above N1 etc. Faces: bottom 1234, top 5678, front 1265,
// right 2376, back 3487, left 1584.
//
// Tetra, N1 N2 N3 N4 N4 N4 N4 N4: the bottom face keeps triangle N1 N2 N3 (counter-clockwise
// seen from above) and everything above collapses to apex N4. VTK tetra wants (0,1,2)
// counter-clockwise seen from 3, so the order is N1 N2 N3 N4 unchanged. The older form
// N1 N2 N3 N3 N4 N4 N4 N4 has the same base triangle and apex.
//
// Pyramid, N1 N2 N3 N4 N5 N5 N5 N5: base quad N1..N4 counter-clockwise seen from the apex,
// which is exactly VTK's pyramid (base 0..3, apex 4).
//
// Wedge, N1 N2 N3 N4 N5 N5 N6 N6: hex node 5 = 6 (= N5) and 7 = 8 (= N6), i.e. the top edges
// 5-6 and 7-8 collapse. The faces containing those edges degenerate: top 5678 -> edge N5-N6,
// front 1265 -> triangle (N1 N2 N5), back 3487 -> triangle (N3 N4 N6). Right 2376 -> quad
// N2 N3 N6 N5, left 1584 -> quad N1 N5 N6 N4, bottom stays N1 N2 N3 N4. So the prism's
// triangles are (N1 N2 N5) and (N4 N3 N6), joined by the edges N1-N4, N2-N3, N5-N6.
// Example: N1=(0,0,0) N2=(1,0,0) N5=(0.5,0,1): the front triangle N1 N2 N5 has normal
// (N2-N1)x(N5-N1) = (0,-1,0), pointing away from the back triangle at y=1.
// VTK's wedge (vtkWedge) takes (0,1,2) as a triangle whose right-hand normal points away from
// triangle (3,4,5), with edges 0-3, 1-4, 2-5 (its face list {0,1,2}, {3,5,4}, ... is outward).
// Hence VTK order = N1 N2 N5 N4 N3 N6. Tests check its outward-face volume is positive.
VtkCell vtk_cell_from_solid(const std::int32_t* n) {
  VtkCell cell;
  std::copy(n, n + 8, cell.nodes.begin());
  const bool top_collapsed = n[4] == n[5] && n[5] == n[6] && n[6] == n[7];
  auto distinct = [](std::initializer_list<std::int32_t> ids) {
    for (auto i = ids.begin(); i != ids.end(); ++i) {
      for (auto j = i + 1; j != ids.end(); ++j) {
        if (*i == *j) return false;
      }
    }
    return true;
  };
  if (distinct({n[0], n[1], n[2], n[3], n[4], n[5], n[6], n[7]})) {
    return cell;  // regular hexahedron
  }
  if (top_collapsed && (n[3] == n[4] || n[2] == n[3]) && distinct({n[0], n[1], n[2], n[4]})) {
    cell.type = VtkCellType::kTetra;
    cell.node_count = 4;
    cell.nodes = {n[0], n[1], n[2], n[4], -1, -1, -1, -1};
    return cell;
  }
  if (top_collapsed && distinct({n[0], n[1], n[2], n[3], n[4]})) {
    cell.type = VtkCellType::kPyramid;
    cell.node_count = 5;
    cell.nodes = {n[0], n[1], n[2], n[3], n[4], -1, -1, -1};
    return cell;
  }
  if (n[4] == n[5] && n[6] == n[7] && distinct({n[0], n[1], n[2], n[3], n[4], n[6]})) {
    cell.type = VtkCellType::kWedge;
    cell.node_count = 6;
    cell.nodes = {n[0], n[1], n[4], n[3], n[2], n[6], -1, -1};
    return cell;
  }
  return cell;  // other degeneracies: keep the repeated nodes, VTK still draws something
}

void element_mean_stress(const element::HexBlock& block, std::size_t e, double out[6]) {
  const std::size_t points = static_cast<std::size_t>(block.points_per_element());
  for (int c = 0; c < 6; ++c) out[c] = 0.0;
  // Before the first force evaluation a block may have no stress storage: report zero.
  if (block.stress.size() < 6 * points * block.size()) return;
  const double* s = &block.stress[6 * points * e];
  for (std::size_t p = 0; p < points; ++p) {
    for (int c = 0; c < 6; ++c) out[c] += s[6 * p + c];
  }
  for (int c = 0; c < 6; ++c) out[c] /= static_cast<double>(points);
}

double pressure_of(const double* s) {
  return -(s[0] + s[1] + s[2]) / 3.0;
}

std::array<double, 3> principal_stresses(const double* s) {
  // Eigenvalues of the symmetric Cauchy tensor (Voigt xx,yy,zz,xy,yz,zx); Eigen returns them
  // in increasing order, we list the largest (most tensile) first.
  Eigen::Matrix3d t;
  t << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(t, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d e = solver.eigenvalues();
  return {e[2], e[1], e[0]};
}

int vtk_lagrange_hex_index(int i, int j, int k, int p) {
  const bool ib = i == 0 || i == p;
  const bool jb = j == 0 || j == p;
  const bool kb = k == 0 || k == p;
  const int boundaries = (ib ? 1 : 0) + (jb ? 1 : 0) + (kb ? 1 : 0);
  const int m = p - 1;  // interior nodes per edge
  if (boundaries == 3) return (i ? (j ? 2 : 1) : (j ? 3 : 0)) + (k ? 4 : 0);
  int offset = 8;
  if (boundaries == 2) {
    if (!ib) return offset + (i - 1) + (j ? 2 * m : 0) + (k ? 4 * m : 0);
    if (!jb) return offset + (j - 1) + (i ? m : 3 * m) + (k ? 4 * m : 0);
    offset += 8 * m;
    return offset + (k - 1) + m * (i ? (j ? 3 : 1) : (j ? 2 : 0));
  }
  offset += 12 * m;
  if (boundaries == 1) {
    if (ib) return offset + (j - 1) + m * (k - 1) + (i ? m * m : 0);
    offset += 2 * m * m;
    if (jb) return offset + (i - 1) + m * (k - 1) + (j ? m * m : 0);
    offset += 2 * m * m;
    return offset + (i - 1) + m * (j - 1) + (k ? m * m : 0);
  }
  offset += 6 * m * m;
  return offset + (i - 1) + m * ((j - 1) + m * (k - 1));
}

FieldWriter::FieldWriter(const std::filesystem::path& directory, std::string stem)
    : directory_(directory), stem_(std::move(stem)) {
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  if (ec) {
    throw std::runtime_error(
        fmt::format("cannot create output directory '{}': {}", directory_.string(), ec.message()));
  }
}

void FieldWriter::write_frame(const solver::State& state) {
  write_frame(state, FrameOptions{});
}

void FieldWriter::write_frame(const solver::State& state, const FrameOptions& options) {
  const solver::NodalState& nodes = state.nodes;
  const std::size_t node_count = nodes.size();
  const double scale = options.point_displacement_scale;

  // Point data, interleaved xyz as VTK stores it.
  std::vector<double> points(3 * node_count), displacement(3 * node_count),
      velocity(3 * node_count);
  std::vector<std::int64_t> node_id(node_count);
  for (std::size_t i = 0; i < node_count; ++i) {
    displacement[3 * i + 0] = nodes.x.x[i] - nodes.x0.x[i];
    displacement[3 * i + 1] = nodes.x.y[i] - nodes.x0.y[i];
    displacement[3 * i + 2] = nodes.x.z[i] - nodes.x0.z[i];
    if (scale == 1.0) {
      // Frames: exactly the current coordinates (no round-off from x0 + (x - x0)).
      points[3 * i + 0] = nodes.x.x[i];
      points[3 * i + 1] = nodes.x.y[i];
      points[3 * i + 2] = nodes.x.z[i];
    } else {
      points[3 * i + 0] = nodes.x0.x[i] + scale * displacement[3 * i + 0];
      points[3 * i + 1] = nodes.x0.y[i] + scale * displacement[3 * i + 1];
      points[3 * i + 2] = nodes.x0.z[i] + scale * displacement[3 * i + 2];
    }
    velocity[3 * i + 0] = nodes.v.x[i];
    velocity[3 * i + 1] = nodes.v.y[i];
    velocity[3 * i + 2] = nodes.v.z[i];
    node_id[i] = nodes.id[i];
  }

  std::size_t cell_count = 0;
  for (const element::HexBlock& block : state.hex_blocks) cell_count += block.size();
  for (const element::ShellBlock& block : state.shell_blocks) cell_count += block.size();
  for (const element::BeamBlock& block : state.beam_blocks) cell_count += block.size();
  // Shell and beam cell arrays (zero on other cells): thickness, stresses at the bottom and top
  // points in global axes, beam resultants N Qs Qt T Ms Mt in the beam's local axes.
  std::vector<double> thickness(cell_count, 0.0), stress_bottom(6 * cell_count, 0.0),
      stress_top(6 * cell_count, 0.0), beam_resultant(6 * cell_count, 0.0);

  std::vector<std::int64_t> connectivity, offsets, part_id, element_id;
  std::vector<std::uint8_t> types;
  std::vector<double> stress, effective_stress, pressure, principal;
  connectivity.reserve(8 * cell_count);
  offsets.reserve(cell_count);
  types.reserve(cell_count);
  part_id.reserve(cell_count);
  element_id.reserve(cell_count);
  stress.reserve(6 * cell_count);
  effective_stress.reserve(cell_count);
  pressure.reserve(cell_count);
  principal.reserve(3 * cell_count);

  for (const element::HexBlock& block : state.hex_blocks) {
    const int p = block.order;
    const std::size_t npe = static_cast<std::size_t>(block.nodes_per_element());
    std::vector<std::int32_t> lagrange(npe);
    for (std::size_t e = 0; e < block.size(); ++e) {
      VtkCell cell;
      const std::int32_t* nodes_of_cell = cell.nodes.data();
      int cell_nodes = 0;
      if (block.quadratic_tetrahedra()) {
        // N1..N4, then the mid-side nodes of edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4: VTK's order.
        cell.type = VtkCellType::kQuadraticTetra;
        nodes_of_cell = &block.conn[npe * e];
        cell_nodes = static_cast<int>(npe);
      } else if (p > 1) {
        // Curved cells: ParaView draws them with their true (polynomial) geometry. VTK places
        // Lagrange points equispaced in the cell; ours sit on GLL points, so the drawn surface
        // passes through every node but is parametrised slightly differently inside a cell.
        cell.type = VtkCellType::kLagrangeHexahedron;
        for (int kk = 0; kk <= p; ++kk)
          for (int jj = 0; jj <= p; ++jj)
            for (int ii = 0; ii <= p; ++ii)
              lagrange[static_cast<std::size_t>(vtk_lagrange_hex_index(ii, jj, kk, p))] =
                  block
                      .conn[npe * e + static_cast<std::size_t>(ii + (p + 1) * (jj + (p + 1) * kk))];
        nodes_of_cell = lagrange.data();
        cell_nodes = static_cast<int>(npe);
      } else {
        cell = vtk_cell_from_solid(&block.conn[8 * e]);
        nodes_of_cell = cell.nodes.data();
        cell_nodes = cell.node_count;
      }
      for (int k = 0; k < cell_nodes; ++k) {
        const std::int32_t node = nodes_of_cell[k];
        if (node < 0 || static_cast<std::size_t>(node) >= node_count) {
          throw std::runtime_error(
              fmt::format("d3plot: element {} of part {} refers to node index {} outside 0..{}",
                          block.element_id[e], block.part_id, node, node_count));
        }
        connectivity.push_back(node);
      }
      offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
      types.push_back(static_cast<std::uint8_t>(cell.type));
      part_id.push_back(block.part_id);
      element_id.push_back(block.element_id[e]);

      double mean[6];
      element_mean_stress(block, e, mean);
      stress.insert(stress.end(), mean, mean + 6);
      effective_stress.push_back(von_mises(mean));
      pressure.push_back(pressure_of(mean));
      const std::array<double, 3> sp = principal_stresses(mean);
      principal.insert(principal.end(), sp.begin(), sp.end());
    }
  }

  // Shells: quads or triangles. "stress" is the mean over the points through the thickness (the
  // membrane stress), effective_stress the largest von Mises value among the points; both in
  // global axes, turned from the element's co-rotational frame at the current configuration.
  for (const element::ShellBlock& block : state.shell_blocks) {
    const std::size_t nip = static_cast<std::size_t>(block.nip);
    const std::size_t points = static_cast<std::size_t>(block.points_per_element());
    for (std::size_t e = 0; e < block.size(); ++e) {
      const std::int32_t* c = &block.conn[4 * e];
      const bool triangle = block.triangle[e] != 0;
      const int corners = triangle ? 3 : 4;
      for (int k = 0; k < corners; ++k) connectivity.push_back(c[k]);
      offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
      types.push_back(triangle ? 5 : 9);  // VTK_TRIANGLE, VTK_QUAD
      part_id.push_back(block.part_id);
      element_id.push_back(block.element_id[e]);
      const std::size_t cell = part_id.size() - 1;
      // The current thickness (*CONTROL_SHELL ISTUPD 1/4 change it; without, the mean of the
      // corners' T1..T4).
      thickness[cell] = block.element_thickness[e];
      const std::array<std::array<double, 3>, 3> frame = shell_frame(nodes, c);
      double mean[6] = {0, 0, 0, 0, 0, 0};
      double worst = 0.0;
      for (std::size_t q = 0; q < points && !block.stress.empty(); ++q) {
        double g[6];
        shell_stress_to_global(&block.stress[(e * points + q) * element::kShellStress], frame, g);
        for (int k = 0; k < 6; ++k) mean[k] += g[k] / static_cast<double>(points);
        worst = std::max(worst, von_mises(g));
        // Points run bottom to top through the thickness (per in-plane point for ELFORM 16).
        if (q % nip == 0)
          for (int k = 0; k < 6; ++k)
            stress_bottom[6 * cell + k] += g[k] * static_cast<double>(nip) / points;
        if (q % nip == nip - 1)
          for (int k = 0; k < 6; ++k)
            stress_top[6 * cell + k] += g[k] * static_cast<double>(nip) / points;
      }
      stress.insert(stress.end(), mean, mean + 6);
      effective_stress.push_back(worst);
      pressure.push_back(pressure_of(mean));
      const std::array<double, 3> sp = principal_stresses(mean);
      principal.insert(principal.end(), sp.begin(), sp.end());
    }
  }
  // Beams: lines; "stress" holds the axial stress N / A along the beam axis.
  for (const element::BeamBlock& block : state.beam_blocks) {
    for (std::size_t e = 0; e < block.size(); ++e) {
      const std::int32_t a = block.conn[2 * e], b = block.conn[2 * e + 1];
      connectivity.push_back(a);
      connectivity.push_back(b);
      offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
      types.push_back(3);  // VTK_LINE
      part_id.push_back(block.part_id);
      element_id.push_back(block.element_id[e]);
      const std::size_t cell = part_id.size() - 1;
      double r[6] = {0, 0, 0, 0, 0, 0};
      if (block.resultant.size() >= 6 * (e + 1)) std::copy_n(&block.resultant[6 * e], 6, r);
      for (int k = 0; k < 6; ++k) beam_resultant[6 * cell + k] = r[k];
      const double area = block.area > 0.0 ? block.area : 0.0;
      const double axial = area > 0.0 ? r[0] / area : 0.0;
      double d[3] = {nodes.x.x[b] - nodes.x.x[a], nodes.x.y[b] - nodes.x.y[a],
                     nodes.x.z[b] - nodes.x.z[a]};
      const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (double& v : d) v = len > 0.0 ? v / len : 0.0;
      const double g[6] = {axial * d[0] * d[0], axial * d[1] * d[1], axial * d[2] * d[2],
                           axial * d[0] * d[1], axial * d[1] * d[2], axial * d[2] * d[0]};
      stress.insert(stress.end(), g, g + 6);
      effective_stress.push_back(std::abs(axial));
      pressure.push_back(pressure_of(g));
      const std::array<double, 3> sp = principal_stresses(g);
      principal.insert(principal.end(), sp.begin(), sp.end());
    }
  }

  // Material history (plastic strain, back stress, ...): one cell array per field name found
  // in any block, the mean over the element's stress points; zero in blocks without it.
  struct HistoryCells {
    std::string name;
    int components;
    std::vector<double> values;
  };
  std::vector<HistoryCells> history;
  for (const element::HexBlock& block : state.hex_blocks)
    for (const auto& h : block.history)
      if (std::none_of(history.begin(), history.end(),
                       [&](const HistoryCells& c) { return c.name == h.field.name; }))
        history.push_back({std::string(h.field.name), h.field.components,
                           std::vector<double>(cell_count * h.field.components, 0.0)});
  for (const element::ShellBlock& block : state.shell_blocks)
    for (const auto& h : block.history)
      if (std::none_of(history.begin(), history.end(),
                       [&](const HistoryCells& c) { return c.name == h.field.name; }))
        history.push_back({std::string(h.field.name), h.field.components,
                           std::vector<double>(cell_count * h.field.components, 0.0)});
  for (HistoryCells& cells : history) {  // shells after the solids, in cell order
    std::size_t first_cell = 0;
    for (const element::HexBlock& block : state.hex_blocks) first_cell += block.size();
    for (const element::ShellBlock& block : state.shell_blocks) {
      const std::size_t points = static_cast<std::size_t>(block.points_per_element());
      const std::size_t nc = static_cast<std::size_t>(cells.components);
      for (const auto& h : block.history) {
        if (h.field.name != cells.name || h.values.size() != nc * points * block.size()) continue;
        for (std::size_t e = 0; e < block.size(); ++e)
          for (std::size_t p = 0; p < points; ++p)
            for (std::size_t c = 0; c < nc; ++c)
              cells.values[(first_cell + e) * nc + c] +=
                  h.values[(e * points + p) * nc + c] / static_cast<double>(points);
      }
      first_cell += block.size();
    }
  }
  for (HistoryCells& cells : history) {
    std::size_t first_cell = 0;
    for (const element::HexBlock& block : state.hex_blocks) {
      const std::size_t points = static_cast<std::size_t>(block.points_per_element());
      const std::size_t nc = static_cast<std::size_t>(cells.components);
      const material::HistoryArray* h = element::find_history(block, cells.name);
      if (h && h->values.size() == nc * points * block.size()) {
        for (std::size_t e = 0; e < block.size(); ++e)
          for (std::size_t p = 0; p < points; ++p)
            for (std::size_t c = 0; c < nc; ++c)
              cells.values[(first_cell + e) * nc + c] +=
                  h->values[(e * points + p) * nc + c] / static_cast<double>(points);
      }
      first_cell += block.size();
    }
  }

  const double time_value = state.time;
  auto bytes_of = [](const auto& v) { return static_cast<std::uint64_t>(v.size() * sizeof(v[0])); };
  // Order here is the order of the blocks in the appended section.
  std::vector<AppendedArray> arrays = {
      {"TimeValue", "Float64", 1, &time_value, sizeof(double)},
      {"Points", "Float64", 3, points.data(), bytes_of(points)},
      {"displacement", "Float64", 3, displacement.data(), bytes_of(displacement)},
      {"velocity", "Float64", 3, velocity.data(), bytes_of(velocity)},
      {"node_id", "Int64", 1, node_id.data(), bytes_of(node_id)},
      {"stress",
       "Float64",
       6,
       stress.data(),
       bytes_of(stress),
       0,
       {"xx", "yy", "zz", "xy", "yz", "zx"}},
      {"effective_stress", "Float64", 1, effective_stress.data(), bytes_of(effective_stress)},
      {"part_id", "Int64", 1, part_id.data(), bytes_of(part_id)},
      {"element_id", "Int64", 1, element_id.data(), bytes_of(element_id)},
      {"pressure", "Float64", 1, pressure.data(), bytes_of(pressure)},
      {"principal_stress",
       "Float64",
       3,
       principal.data(),
       bytes_of(principal),
       0,
       {"max", "mid", "min"}},
      {"connectivity", "Int64", 1, connectivity.data(), bytes_of(connectivity)},
      {"offsets", "Int64", 1, offsets.data(), bytes_of(offsets)},
      {"types", "UInt8", 1, types.data(), bytes_of(types)},
      {options.scale_name, "Float64", 1, &scale, sizeof(double)},
  };
  // The scale is field data of mode shapes only.
  if (options.scale_name.empty()) arrays.pop_back();
  // Material history (effective plastic strain, back stress, ...) follows as cell arrays.
  const std::size_t first_history = arrays.size();
  for (const HistoryCells& cells : history) {
    AppendedArray a{cells.name, "Float64", cells.components, cells.values.data(),
                    bytes_of(cells.values)};
    if (cells.components == 6) a.component_names = {"xx", "yy", "zz", "xy", "yz", "zx"};
    arrays.push_back(std::move(a));
  }
  // Shell and beam cell arrays, only in models that have them.
  const bool has_shells = !state.shell_blocks.empty(), has_beams = !state.beam_blocks.empty();
  if (has_shells) {
    arrays.push_back({"thickness", "Float64", 1, thickness.data(), bytes_of(thickness)});
    arrays.push_back({"stress_bottom",
                      "Float64",
                      6,
                      stress_bottom.data(),
                      bytes_of(stress_bottom),
                      0,
                      {"xx", "yy", "zz", "xy", "yz", "zx"}});
    arrays.push_back({"stress_top",
                      "Float64",
                      6,
                      stress_top.data(),
                      bytes_of(stress_top),
                      0,
                      {"xx", "yy", "zz", "xy", "yz", "zx"}});
  }
  if (has_beams) {
    arrays.push_back({"beam_resultant",
                      "Float64",
                      6,
                      beam_resultant.data(),
                      bytes_of(beam_resultant),
                      0,
                      {"N", "Qs", "Qt", "T", "Ms", "Mt"}});
  }
  // Eroded elements (solver/erosion.hpp), in models that can erode: VTK's ghost-cell array with
  // HIDDENCELL (32), which ParaView does not draw, so deleted elements vanish as in LS-PrePost;
  // the cells stay in the file (the same cells in every frame) with their last values.
  std::vector<std::uint8_t> ghost;
  bool can_erode = false;
  for (const auto& b : state.hex_blocks) can_erode |= b.erosion.enabled;
  for (const auto& b : state.shell_blocks) can_erode |= b.erosion.enabled;
  for (const auto& b : state.beam_blocks) can_erode |= b.erosion.enabled;
  if (can_erode) {
    ghost.reserve(cell_count);
    auto mark = [&](const auto& block) {
      for (std::size_t e = 0; e < block.size(); ++e)
        ghost.push_back(block.erosion.is_eroded(e) ? std::uint8_t{32} : std::uint8_t{0});
    };
    for (const auto& b : state.hex_blocks) mark(b);
    for (const auto& b : state.shell_blocks) mark(b);
    for (const auto& b : state.beam_blocks) mark(b);
    arrays.push_back({"vtkGhostType", "UInt8", 1, ghost.data(), bytes_of(ghost)});
  }
  std::uint64_t offset = 0;
  for (AppendedArray& a : arrays) {
    a.offset = offset;
    offset += sizeof(std::uint64_t) + a.bytes;
  }
  enum {
    kTime,
    kPoints,
    kDisp,
    kVel,
    kNodeId,
    kStress,
    kEff,
    kPart,
    kElem,
    kPressure,
    kPrincipal,
    kConn,
    kOff,
    kType,
    kScale
  };

  fmt::memory_buffer xml;
  auto out = std::back_inserter(xml);
  fmt::format_to(out,
                 "<?xml version=\"1.0\"?>\n"
                 "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"{}\" "
                 "header_type=\"UInt64\">\n"
                 "  <UnstructuredGrid>\n",
                 byte_order_name());
  // TimeValue lets ParaView place a single .vtu in time even without the .pvd.
  fmt::format_to(out, "    <FieldData>\n");
  fmt::format_to(out,
                 "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" "
                 "format=\"appended\" offset=\"{}\"/>\n",
                 arrays[kTime].offset);
  if (!options.scale_name.empty()) {
    fmt::format_to(out,
                   "      <DataArray type=\"Float64\" Name=\"{}\" NumberOfTuples=\"1\" "
                   "format=\"appended\" offset=\"{}\"/>\n",
                   options.scale_name, arrays[kScale].offset);
  }
  fmt::format_to(out, "    </FieldData>\n");
  fmt::format_to(out, "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", node_count,
                 cell_count);
  fmt::format_to(out, "      <PointData Vectors=\"displacement\">\n");
  for (int i : {kDisp, kVel, kNodeId}) append_data_array(xml, arrays[i], "        ");
  fmt::format_to(out, "      </PointData>\n");
  fmt::format_to(out, "      <CellData Scalars=\"effective_stress\">\n");
  for (int i : {kStress, kEff, kPart, kElem, kPressure, kPrincipal})
    append_data_array(xml, arrays[i], "        ");
  for (std::size_t i = first_history; i < arrays.size(); ++i)
    append_data_array(xml, arrays[i], "        ");
  fmt::format_to(out, "      </CellData>\n");
  fmt::format_to(out, "      <Points>\n");
  append_data_array(xml, arrays[kPoints], "        ");
  fmt::format_to(out, "      </Points>\n");
  fmt::format_to(out, "      <Cells>\n");
  for (int i : {kConn, kOff, kType}) append_data_array(xml, arrays[i], "        ");
  fmt::format_to(out, "      </Cells>\n");
  fmt::format_to(out,
                 "    </Piece>\n"
                 "  </UnstructuredGrid>\n"
                 "  <AppendedData encoding=\"raw\">\n"
                 "   _");

  const std::string file_name = fmt::format("{}_{:04d}.vtu", stem_, frames());
  write_atomically(directory_ / file_name, [&](OutputFile& file) {
    file.write(xml.data(), xml.size());
    for (const AppendedArray& a : arrays) {
      file.write(&a.bytes, sizeof(a.bytes));
      file.write(a.data, a.bytes);
    }
    static constexpr std::string_view kTail = "\n  </AppendedData>\n</VTKFile>\n";
    file.write(kTail.data(), kTail.size());
  });

  if (options.walls != nullptr) {
    walls_ = true;
    write_walls(*options.walls, state.time, walls_file_of(file_name));
  }
  times_.push_back(state.time);
  files_.push_back(file_name);
  write_collection();
  if (walls_) write_walls_collection();
}

std::string FieldWriter::walls_file_of(const std::string& frame_file) {
  const auto underscore = frame_file.rfind('_');
  return "walls" +
         (underscore == std::string::npos ? "_" + frame_file : frame_file.substr(underscore));
}

// Walls are a handful of quadrilaterals: ASCII VTU, readable by eye.
void FieldWriter::write_walls(const std::vector<WallPatch>& walls, double time,
                              const std::string& file) {
  fmt::memory_buffer xml;
  auto out = std::back_inserter(xml);
  fmt::format_to(out,
                 "<?xml version=\"1.0\"?>\n"
                 "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"{}\" "
                 "header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <FieldData>\n"
                 "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" "
                 "format=\"ascii\">{:.17g}</DataArray>\n    </FieldData>\n"
                 "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
                 byte_order_name(), time, 4 * walls.size(), walls.size());
  fmt::format_to(out,
                 "      <CellData Scalars=\"normal_force\">\n"
                 "        <DataArray type=\"Int64\" Name=\"wall_id\" format=\"ascii\">");
  for (const WallPatch& w : walls) fmt::format_to(out, " {}", w.id);
  fmt::format_to(out,
                 "</DataArray>\n        <DataArray type=\"Float64\" Name=\"normal_force\" "
                 "format=\"ascii\">");
  for (const WallPatch& w : walls) fmt::format_to(out, " {:.17g}", w.normal_force);
  fmt::format_to(out,
                 "</DataArray>\n      </CellData>\n      <Points>\n"
                 "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" "
                 "format=\"ascii\">");
  for (const WallPatch& w : walls) {
    for (const auto& c : w.corners)
      fmt::format_to(out, " {:.17g} {:.17g} {:.17g}", c[0], c[1], c[2]);
  }
  fmt::format_to(out,
                 "</DataArray>\n      </Points>\n      <Cells>\n"
                 "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">");
  for (std::size_t k = 0; k < 4 * walls.size(); ++k) fmt::format_to(out, " {}", k);
  fmt::format_to(out,
                 "</DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" "
                 "format=\"ascii\">");
  for (std::size_t k = 1; k <= walls.size(); ++k) fmt::format_to(out, " {}", 4 * k);
  fmt::format_to(out,
                 "</DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" "
                 "format=\"ascii\">");
  for (std::size_t k = 0; k < walls.size(); ++k) fmt::format_to(out, " 9");  // VTK_QUAD
  fmt::format_to(out,
                 "</DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
                 "</VTKFile>\n");
  write_atomically(directory_ / file, [&](OutputFile& f) { f.write(xml.data(), xml.size()); });
}

void FieldWriter::write_walls_collection() const {
  fmt::memory_buffer xml;
  auto out = std::back_inserter(xml);
  fmt::format_to(out,
                 "<?xml version=\"1.0\"?>\n"
                 "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"{}\" "
                 "header_type=\"UInt64\">\n"
                 "  <Collection>\n",
                 byte_order_name());
  for (std::size_t i = 0; i < times_.size(); ++i) {
    fmt::format_to(out, "    <DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n",
                   times_[i], xml_attribute(walls_file_of(files_[i])));
  }
  fmt::format_to(out, "  </Collection>\n</VTKFile>\n");
  write_atomically(directory_ / "walls.pvd",
                   [&](OutputFile& file) { file.write(xml.data(), xml.size()); });
}

void FieldWriter::resume(std::vector<double> times, std::vector<std::string> files) {
  times_ = std::move(times);
  files_ = std::move(files);
}

void FieldWriter::write_collection() const {
  fmt::memory_buffer xml;
  auto out = std::back_inserter(xml);
  fmt::format_to(out,
                 "<?xml version=\"1.0\"?>\n"
                 "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"{}\" "
                 "header_type=\"UInt64\">\n"
                 "  <Collection>\n",
                 byte_order_name());
  for (std::size_t i = 0; i < times_.size(); ++i) {
    fmt::format_to(out, "    <DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n",
                   times_[i], xml_attribute(files_[i]));
  }
  fmt::format_to(out, "  </Collection>\n</VTKFile>\n");
  write_atomically(directory_ / (stem_ + ".pvd"),
                   [&](OutputFile& file) { file.write(xml.data(), xml.size()); });
}

}  // namespace rf::output
