// FieldWriter: .vtu/.pvd files are well-formed XML, the appended raw binary decodes to exactly
// the state that was written, and LS-DYNA degenerate hexes become proper, positively oriented
// VTK cells.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "output/writers.hpp"

namespace rf::output {
namespace {

// ---- A small XML reader: enough to prove well-formedness of what FieldWriter emits --------

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::vector<XmlElement> children;

  const XmlElement& child(const std::string& child_name) const {
    for (const XmlElement& c : children) {
      if (c.name == child_name) return c;
    }
    throw std::runtime_error("no child " + child_name + " in " + name);
  }
  const XmlElement& data_array(const std::string& array_name) const {
    for (const XmlElement& c : children) {
      if (c.name == "DataArray" && c.attributes.at("Name") == array_name) return c;
    }
    throw std::runtime_error("no DataArray " + array_name + " in " + name);
  }
};

struct XmlDocument {
  XmlElement root;
  std::size_t appended_base = std::string::npos;  // first byte after the '_' marker
  std::size_t appended_end = std::string::npos;   // where the raw bytes must stop
};

class XmlReader {
 public:
  explicit XmlReader(const std::string& text) : s_(text) {}

  XmlDocument read() {
    skip_space();
    if (s_.compare(p_, 5, "<?xml") == 0) {
      const auto end = s_.find("?>", p_);
      if (end == std::string::npos) fail("unterminated XML declaration");
      p_ = end + 2;
    }
    skip_space();
    doc_.root = element();
    skip_space();
    if (p_ != s_.size()) fail("content after the root element");
    return doc_;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("XML error at byte " + std::to_string(p_) + ": " + what);
  }
  void skip_space() {
    while (p_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[p_]))) ++p_;
  }
  void expect(char c) {
    if (p_ >= s_.size() || s_[p_] != c) fail(std::string("expected '") + c + "'");
    ++p_;
  }
  std::string name() {
    const std::size_t start = p_;
    while (p_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[p_])) || s_[p_] == '_' ||
                              s_[p_] == ':' || s_[p_] == '-' || s_[p_] == '.')) {
      ++p_;
    }
    if (p_ == start) fail("expected a name");
    return s_.substr(start, p_ - start);
  }
  std::string attribute_value() {
    expect('"');
    std::string value;
    while (p_ < s_.size() && s_[p_] != '"') {
      if (s_[p_] == '<') fail("'<' in attribute value");
      if (s_[p_] == '&') {
        static const std::pair<const char*, char> kEntities[] = {
            {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
        bool known = false;
        for (const auto& [entity, ch] : kEntities) {
          if (s_.compare(p_, std::strlen(entity), entity) == 0) {
            value += ch;
            p_ += std::strlen(entity);
            known = true;
            break;
          }
        }
        if (!known) fail("unknown entity");
        continue;
      }
      value += s_[p_++];
    }
    expect('"');
    return value;
  }
  XmlElement element() {
    XmlElement e;
    expect('<');
    e.name = name();
    for (;;) {
      skip_space();
      if (s_.compare(p_, 2, "/>") == 0) {
        p_ += 2;
        return e;
      }
      if (p_ < s_.size() && s_[p_] == '>') {
        ++p_;
        break;
      }
      const std::string key = name();
      skip_space();
      expect('=');
      skip_space();
      if (!e.attributes.emplace(key, attribute_value()).second) fail("duplicate " + key);
    }
    if (e.name == "AppendedData") {
      // Raw bytes are not XML; they run from after '_' to the closing tag at the end.
      skip_space();
      expect('_');
      doc_.appended_base = p_;
      const std::string closing = "</AppendedData>";
      const auto close = s_.rfind(closing);
      if (close == std::string::npos || close < p_) fail("no </AppendedData>");
      doc_.appended_end = s_.find_last_not_of(" \n", close - 1) + 1;
      p_ = close + closing.size();
      return e;
    }
    for (;;) {
      skip_space();
      if (s_.compare(p_, 2, "</") == 0) {
        p_ += 2;
        if (name() != e.name) fail("mismatched closing tag for " + e.name);
        skip_space();
        expect('>');
        return e;
      }
      if (p_ >= s_.size()) fail("unterminated element " + e.name);
      if (s_[p_] != '<') fail("unexpected text in " + e.name);
      e.children.push_back(element());
    }
  }

  const std::string& s_;
  std::size_t p_ = 0;
  XmlDocument doc_;
};

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Decodes one appended raw block: UInt64 byte count, then the values.
template <typename T>
std::vector<T> decode(const std::string& file, const XmlDocument& doc, const XmlElement& array,
                      const char* expected_type) {
  EXPECT_EQ(array.attributes.at("type"), expected_type);
  EXPECT_EQ(array.attributes.at("format"), "appended");
  const std::size_t at = doc.appended_base + std::stoull(array.attributes.at("offset"));
  std::uint64_t bytes = 0;
  if (at + sizeof(bytes) > doc.appended_end) throw std::runtime_error("block header past end");
  std::memcpy(&bytes, file.data() + at, sizeof(bytes));
  if (at + sizeof(bytes) + bytes > doc.appended_end) throw std::runtime_error("block past end");
  if (bytes % sizeof(T) != 0) throw std::runtime_error("block size not a multiple");
  std::vector<T> values(bytes / sizeof(T));
  std::memcpy(values.data(), file.data() + at + sizeof(bytes), bytes);
  return values;
}

// ---- Test model: two hexes (ELFORM 2) + tet, wedge, pyramid written as degenerate hexes ----

solver::State make_state() {
  solver::State state;
  std::vector<std::array<double, 3>> coords;
  for (int iz = 0; iz < 2; ++iz)  // hex grid, nodes 0..11: index = ix + 3 iy + 6 iz
    for (int iy = 0; iy < 2; ++iy)
      for (int ix = 0; ix < 3; ++ix) coords.push_back({double(ix), double(iy), double(iz)});
  const std::array<double, 3> others[] = {
      {3, 0, 0}, {4, 0, 0}, {3, 1, 0}, {3, 0, 1},                           // tet 12..15
      {5, 0, 0}, {6, 0, 0}, {6, 1, 0}, {5, 1, 0}, {5, 0, 1},    {5, 1, 1},  // wedge 16..21
      {7, 0, 0}, {8, 0, 0}, {8, 1, 0}, {7, 1, 0}, {7.5, 0.5, 1}};           // pyramid 22..26
  coords.insert(coords.end(), std::begin(others), std::end(others));
  const std::size_t n = coords.size();
  auto& nodes = state.nodes;
  for (auto* v : {&nodes.x0, &nodes.x, &nodes.v, &nodes.a, &nodes.f_int, &nodes.f_ext}) {
    v->resize(n);
  }
  nodes.mass.assign(n, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    nodes.id.push_back(static_cast<model::Id>(1000 + 3 * i));
    nodes.x0.x[i] = coords[i][0];
    nodes.x0.y[i] = coords[i][1];
    nodes.x0.z[i] = coords[i][2];
    // Hex nodes move by awkward amounts (bit-exact decoding is tested on them); the
    // degenerate cells stay put so their exact volumes can be checked.
    const double d = i < 12 ? 1e-3 / (i + 3.0) : 0.0;
    nodes.x.x[i] = nodes.x0.x[i] + d;
    nodes.x.y[i] = nodes.x0.y[i] - d / 7.0;
    nodes.x.z[i] = nodes.x0.z[i] + d * std::sqrt(2.0);
    nodes.v.x[i] = 1.0 / (i + 1.0);
    nodes.v.y[i] = -std::sqrt(i + 0.5);
    nodes.v.z[i] = std::exp(-static_cast<double>(i));
  }

  element::HexBlock hexes;
  hexes.part_id = 10;
  hexes.elform = 2;
  hexes.element_id = {1, 2};
  hexes.conn = {0, 1, 4, 3, 6, 7, 10, 9, 1, 2, 5, 4, 7, 8, 11, 10};
  for (int e = 0; e < 2; ++e)  // integer stresses so the 8-point mean is exact
    for (int p = 0; p < 8; ++p)
      for (int c = 0; c < 6; ++c) hexes.stress.push_back(100.0 * e + 10.0 * c + p);

  element::HexBlock degenerate;
  degenerate.part_id = 20;
  degenerate.elform = 1;
  degenerate.element_id = {30000000001LL, 4, 5};       // IDs beyond 32 bits must survive
  degenerate.conn = {12, 13, 14, 15, 15, 15, 15, 15,   // tet
                     16, 17, 18, 19, 20, 20, 21, 21,   // wedge
                     22, 23, 24, 25, 26, 26, 26, 26};  // pyramid
  for (int e = 0; e < 3; ++e)
    for (int c = 0; c < 6; ++c) degenerate.stress.push_back((c + 1) / 3.0 - e);

  state.hex_blocks = {hexes, degenerate};
  state.time = 0.125;
  return state;
}

// Signed volume from VTK's own face lists (each face ordered with an outward right-hand
// normal): a positive result means VTK sees a valid, non-inverted cell.
double vtk_signed_volume(int type, const std::vector<std::array<double, 3>>& p) {
  using Faces = std::vector<std::vector<int>>;
  static const std::map<int, Faces> kFaces = {
      {10, {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {0, 2, 1}}},
      {12, {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}}},
      {13, {{0, 1, 2}, {3, 5, 4}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}}},
      {14, {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}}}};
  std::array<double, 3> center{0, 0, 0};
  for (const auto& q : p)
    for (int k = 0; k < 3; ++k) center[k] += q[k] / p.size();
  auto rel = [&](int i) {
    return std::array<double, 3>{p[i][0] - center[0], p[i][1] - center[1], p[i][2] - center[2]};
  };
  double volume = 0.0;
  for (const auto& face : kFaces.at(type)) {
    std::array<double, 3> c{0, 0, 0};
    for (int i : face)
      for (int k = 0; k < 3; ++k) c[k] += rel(i)[k] / face.size();
    for (std::size_t j = 0; j < face.size(); ++j) {
      const auto a = rel(face[j]);
      const auto b = rel(face[(j + 1) % face.size()]);
      volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                 a[2] * (b[0] * c[1] - b[1] * c[0])) /
                6.0;
    }
  }
  return volume;
}

std::filesystem::path fresh_directory(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("rigidflex_" + name);
  std::filesystem::remove_all(dir);
  return dir;  // FieldWriter creates it
}

TEST(OutputField, DegenerateHexClassification) {
  const std::int32_t hex[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  EXPECT_EQ(vtk_cell_from_solid(hex).type, VtkCellType::kHexahedron);
  EXPECT_EQ(vtk_cell_from_solid(hex).node_count, 8);

  const std::int32_t tet[8] = {4, 5, 6, 7, 7, 7, 7, 7};
  const std::int32_t old_tet[8] = {4, 5, 6, 6, 7, 7, 7, 7};
  for (const auto* t : {tet, old_tet}) {
    const VtkCell cell = vtk_cell_from_solid(t);
    EXPECT_EQ(cell.type, VtkCellType::kTetra);
    ASSERT_EQ(cell.node_count, 4);
    EXPECT_EQ((std::vector<int>(cell.nodes.begin(), cell.nodes.begin() + 4)),
              (std::vector<int>{4, 5, 6, 7}));
  }

  const std::int32_t wedge[8] = {1, 2, 3, 4, 5, 5, 6, 6};
  const VtkCell w = vtk_cell_from_solid(wedge);
  EXPECT_EQ(w.type, VtkCellType::kWedge);
  ASSERT_EQ(w.node_count, 6);
  EXPECT_EQ((std::vector<int>(w.nodes.begin(), w.nodes.begin() + 6)),
            (std::vector<int>{1, 2, 5, 4, 3, 6}));

  const std::int32_t pyramid[8] = {1, 2, 3, 4, 5, 5, 5, 5};
  const VtkCell py = vtk_cell_from_solid(pyramid);
  EXPECT_EQ(py.type, VtkCellType::kPyramid);
  EXPECT_EQ(py.node_count, 5);

  // A repetition that matches no convention stays a (degenerate) hexahedron.
  const std::int32_t odd[8] = {1, 1, 2, 3, 4, 5, 6, 7};
  EXPECT_EQ(vtk_cell_from_solid(odd).type, VtkCellType::kHexahedron);
}

TEST(OutputField, VonMises) {
  const double uniaxial[6] = {250.0, 0, 0, 0, 0, 0};
  EXPECT_DOUBLE_EQ(von_mises(uniaxial), 250.0);
  const double shear[6] = {0, 0, 0, 0, 0, 10.0};
  EXPECT_DOUBLE_EQ(von_mises(shear), 10.0 * std::sqrt(3.0));
  const double hydrostatic[6] = {-5, -5, -5, 0, 0, 0};
  EXPECT_DOUBLE_EQ(von_mises(hydrostatic), 0.0);
}

// Cell arrays `pressure` and `principal_stress`: analytic eigenvalues of known tensors.
TEST(OutputField, PressureAndPrincipalStresses) {
  const double diagonal[6] = {1.0, 2.0, 3.0, 0, 0, 0};
  EXPECT_DOUBLE_EQ(pressure_of(diagonal), -2.0);
  auto p = principal_stresses(diagonal);
  EXPECT_NEAR(p[0], 3.0, 1e-14);
  EXPECT_NEAR(p[1], 2.0, 1e-14);
  EXPECT_NEAR(p[2], 1.0, 1e-14);
  // Pure shear tau in xy: principal +tau, 0, -tau; no pressure.
  const double shear[6] = {0, 0, 0, 5.0, 0, 0};
  EXPECT_DOUBLE_EQ(pressure_of(shear), 0.0);
  p = principal_stresses(shear);
  EXPECT_NEAR(p[0], 5.0, 1e-14);
  EXPECT_NEAR(p[1], 0.0, 1e-14);
  EXPECT_NEAR(p[2], -5.0, 1e-14);
  // diag(4, -1, 7) rotated by 30 degrees about z: sxx = 4 c^2 - s^2, syy = 4 s^2 - c^2,
  // sxy = 5 c s; the eigenvalues stay 7, 4, -1.
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  const double rotated[6] = {4 * c * c - s * s, 4 * s * s - c * c, 7.0, 5 * c * s, 0, 0};
  p = principal_stresses(rotated);
  EXPECT_NEAR(p[0], 7.0, 1e-13);
  EXPECT_NEAR(p[1], 4.0, 1e-13);
  EXPECT_NEAR(p[2], -1.0, 1e-13);
  EXPECT_NEAR(pressure_of(rotated), -10.0 / 3.0, 1e-14);
}

TEST(OutputField, VtuDecodesToTheStateAndCellsAreValid) {
  const auto dir = fresh_directory("field_single");
  const solver::State state = make_state();
  FieldWriter writer(dir);
  writer.write_frame(state);
  ASSERT_EQ(writer.frames(), 1);

  const std::string file = read_file(dir / "frames_0000.vtu");
  XmlDocument doc;
  ASSERT_NO_THROW(doc = XmlReader(file).read());
  const XmlElement& root = doc.root;
  EXPECT_EQ(root.name, "VTKFile");
  EXPECT_EQ(root.attributes.at("type"), "UnstructuredGrid");
  EXPECT_EQ(root.attributes.at("header_type"), "UInt64");
  EXPECT_EQ(root.attributes.at("byte_order"), "LittleEndian");
  EXPECT_EQ(root.child("AppendedData").attributes.at("encoding"), "raw");
  const XmlElement& grid = root.child("UnstructuredGrid");
  const XmlElement& piece = grid.child("Piece");
  const std::size_t n = state.nodes.size();
  EXPECT_EQ(piece.attributes.at("NumberOfPoints"), std::to_string(n));
  EXPECT_EQ(piece.attributes.at("NumberOfCells"), "5");

  const auto time =
      decode<double>(file, doc, grid.child("FieldData").data_array("TimeValue"), "Float64");
  EXPECT_EQ(time, std::vector<double>{0.125});

  // Points and point data, bit-exact.
  const auto points =
      decode<double>(file, doc, piece.child("Points").data_array("Points"), "Float64");
  const XmlElement& point_data = piece.child("PointData");
  const auto displacement =
      decode<double>(file, doc, point_data.data_array("displacement"), "Float64");
  const auto velocity = decode<double>(file, doc, point_data.data_array("velocity"), "Float64");
  const auto node_id = decode<std::int64_t>(file, doc, point_data.data_array("node_id"), "Int64");
  EXPECT_EQ(point_data.data_array("displacement").attributes.at("NumberOfComponents"), "3");
  ASSERT_EQ(points.size(), 3 * n);
  ASSERT_EQ(displacement.size(), 3 * n);
  ASSERT_EQ(velocity.size(), 3 * n);
  ASSERT_EQ(node_id.size(), n);
  const auto& s = state.nodes;
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(points[3 * i + 0], s.x.x[i]);
    EXPECT_EQ(points[3 * i + 1], s.x.y[i]);
    EXPECT_EQ(points[3 * i + 2], s.x.z[i]);
    EXPECT_EQ(displacement[3 * i + 0], s.x.x[i] - s.x0.x[i]);
    EXPECT_EQ(displacement[3 * i + 1], s.x.y[i] - s.x0.y[i]);
    EXPECT_EQ(displacement[3 * i + 2], s.x.z[i] - s.x0.z[i]);
    EXPECT_EQ(velocity[3 * i + 0], s.v.x[i]);
    EXPECT_EQ(velocity[3 * i + 1], s.v.y[i]);
    EXPECT_EQ(velocity[3 * i + 2], s.v.z[i]);
    EXPECT_EQ(node_id[i], s.id[i]);
  }

  // Cells.
  const XmlElement& cells = piece.child("Cells");
  const auto connectivity =
      decode<std::int64_t>(file, doc, cells.data_array("connectivity"), "Int64");
  const auto offsets = decode<std::int64_t>(file, doc, cells.data_array("offsets"), "Int64");
  const auto types = decode<std::uint8_t>(file, doc, cells.data_array("types"), "UInt8");
  EXPECT_EQ(types, (std::vector<std::uint8_t>{12, 12, 10, 13, 14}));
  EXPECT_EQ(offsets, (std::vector<std::int64_t>{8, 16, 20, 26, 31}));
  EXPECT_EQ(connectivity, (std::vector<std::int64_t>{0,  1,  4,  3,  6,  7,  10, 9,  1,  2,  5,
                                                     4,  7,  8,  11, 10, 12, 13, 14, 15, 16, 17,
                                                     20, 19, 18, 21, 22, 23, 24, 25, 26}));
  const double expected_volume[] = {1.0, 1.0, 1.0 / 6.0, 0.5, 1.0 / 3.0};
  for (std::size_t c = 0; c < types.size(); ++c) {
    std::vector<std::array<double, 3>> corners;
    for (auto k = c == 0 ? 0 : offsets[c - 1]; k < offsets[c]; ++k) {
      const auto i = connectivity[k];
      corners.push_back({points[3 * i], points[3 * i + 1], points[3 * i + 2]});
    }
    const double volume = vtk_signed_volume(types[c], corners);
    EXPECT_GT(volume, 0.0) << "cell " << c << " type " << int(types[c]);
    EXPECT_NEAR(volume, expected_volume[c], c < 2 ? 1e-2 : 1e-14) << "cell " << c;
  }

  // Cell data.
  const XmlElement& cell_data = piece.child("CellData");
  const auto stress = decode<double>(file, doc, cell_data.data_array("stress"), "Float64");
  const auto effective =
      decode<double>(file, doc, cell_data.data_array("effective_stress"), "Float64");
  const auto part = decode<std::int64_t>(file, doc, cell_data.data_array("part_id"), "Int64");
  const auto element = decode<std::int64_t>(file, doc, cell_data.data_array("element_id"), "Int64");
  EXPECT_EQ(cell_data.data_array("stress").attributes.at("NumberOfComponents"), "6");
  EXPECT_EQ(cell_data.data_array("stress").attributes.at("ComponentName0"), "xx");
  EXPECT_EQ(cell_data.data_array("stress").attributes.at("ComponentName5"), "zx");
  EXPECT_EQ(part, (std::vector<std::int64_t>{10, 10, 20, 20, 20}));
  EXPECT_EQ(element, (std::vector<std::int64_t>{1, 2, 30000000001LL, 4, 5}));
  ASSERT_EQ(stress.size(), 30u);
  ASSERT_EQ(effective.size(), 5u);
  for (int e = 0; e < 2; ++e)  // mean of 8 points: 100 e + 10 c + 3.5
    for (int c = 0; c < 6; ++c) EXPECT_EQ(stress[6 * e + c], 100.0 * e + 10.0 * c + 3.5);
  for (int e = 0; e < 3; ++e)  // one point: written as is
    for (int c = 0; c < 6; ++c) EXPECT_EQ(stress[6 * (2 + e) + c], (c + 1) / 3.0 - e);
  for (int e = 0; e < 5; ++e) EXPECT_EQ(effective[e], von_mises(&stress[6 * e]));

  // The last block ends exactly where the raw section ends.
  std::uint64_t end = 0;
  for (const XmlElement* section : {&point_data, &cell_data, &cells}) {
    for (const XmlElement& a : section->children) {
      std::uint64_t bytes = 0;
      const auto offset = std::stoull(a.attributes.at("offset"));
      std::memcpy(&bytes, file.data() + doc.appended_base + offset, sizeof(bytes));
      end = std::max<std::uint64_t>(end, offset + sizeof(bytes) + bytes);
    }
  }
  EXPECT_EQ(doc.appended_base + end, doc.appended_end);
}

TEST(OutputField, CollectionListsEveryFrame) {
  const auto dir = fresh_directory("field_series");
  solver::State state = make_state();
  FieldWriter writer(dir);
  const double times[] = {0.0, 1.0 / 3.0, 2.0 / 3.0};
  for (double t : times) {
    state.time = t;
    state.nodes.x.x[0] = 0.5 + t;  // each frame differs
    writer.write_frame(state);

    // The collection is already complete after every frame (a crashed run stays readable).
    const std::string pvd = read_file(dir / "frames.pvd");
    XmlDocument doc;
    ASSERT_NO_THROW(doc = XmlReader(pvd).read());
    EXPECT_EQ(doc.root.attributes.at("type"), "Collection");
    const XmlElement& collection = doc.root.child("Collection");
    ASSERT_EQ(collection.children.size(), static_cast<std::size_t>(writer.frames()));
    for (int f = 0; f < writer.frames(); ++f) {
      const XmlElement& data_set = collection.children[f];
      EXPECT_EQ(data_set.name, "DataSet");
      EXPECT_EQ(std::strtod(data_set.attributes.at("timestep").c_str(), nullptr), times[f]);
      char expected_name[32];
      std::snprintf(expected_name, sizeof expected_name, "frames_%04d.vtu", f);
      EXPECT_EQ(data_set.attributes.at("file"), expected_name);
      EXPECT_TRUE(std::filesystem::exists(dir / expected_name));
    }
  }
  EXPECT_EQ(writer.frames(), 3);

  // Frame 2 holds frame 2's coordinates.
  const std::string file = read_file(dir / "frames_0002.vtu");
  const XmlDocument doc = XmlReader(file).read();
  const auto points = decode<double>(
      file, doc,
      doc.root.child("UnstructuredGrid").child("Piece").child("Points").data_array("Points"),
      "Float64");
  EXPECT_EQ(points[0], 0.5 + 2.0 / 3.0);

  // No temporaries left behind.
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();
  }
}

}  // namespace
}  // namespace rf::output

namespace rf::output {
namespace {

TEST(OutputFieldLagrange, PointOrderIsAPermutationMatchingVtk) {
  for (int p = 2; p <= 3; ++p) {
    const int n = p + 1;
    std::vector<int> seen(static_cast<std::size_t>(n * n * n), 0);
    for (int k = 0; k <= p; ++k)
      for (int j = 0; j <= p; ++j)
        for (int i = 0; i <= p; ++i)
          ++seen[static_cast<std::size_t>(vtk_lagrange_hex_index(i, j, k, p))];
    for (int s : seen) EXPECT_EQ(s, 1) << "order " << p;
    // VTK's layout: corners 0..7, then the i-edge at j = k = 0, the j-edge at i = p, ...
    EXPECT_EQ(vtk_lagrange_hex_index(p, p, 0, p), 2);
    EXPECT_EQ(vtk_lagrange_hex_index(0, p, p, p), 7);
    EXPECT_EQ(vtk_lagrange_hex_index(1, 0, 0, p), 8);
    EXPECT_EQ(vtk_lagrange_hex_index(p, 1, 0, p), 8 + (p - 1));
    EXPECT_EQ(vtk_lagrange_hex_index(0, 0, 1, p), 8 + 8 * (p - 1));   // first vertical edge
    EXPECT_EQ(vtk_lagrange_hex_index(0, 1, 1, p), 8 + 12 * (p - 1));  // first i-normal face
    EXPECT_EQ(vtk_lagrange_hex_index(1, 1, 1, p), 8 + 12 * (p - 1) + 6 * (p - 1) * (p - 1));
  }
}

TEST(OutputFieldLagrange, HigherOrderBlockIsWrittenAsLagrangeCells) {
  solver::State state;
  const int p = 2, n = 3;
  auto& nodes = state.nodes;
  for (auto* v : {&nodes.x0, &nodes.x, &nodes.v, &nodes.a, &nodes.f_int, &nodes.f_ext}) {
    v->resize(27);
  }
  nodes.mass.assign(27, 1.0);
  element::HexBlock block;
  block.part_id = 3;
  block.order = p;
  block.element_id = {9};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = i + n * (j + n * k);
        nodes.id.push_back(100 + a);
        nodes.x0.x[a] = nodes.x.x[a] = 0.5 * i;
        nodes.x0.y[a] = nodes.x.y[a] = 0.5 * j;
        nodes.x0.z[a] = nodes.x.z[a] = 0.5 * k;
        block.conn.push_back(26 - a);  // any numbering: tensor slot a holds node 26 - a
      }
  // conn maps slot -> node; place node coordinates to match their slot.
  for (int a = 0; a < 27; ++a) {
    const int node = 26 - a;
    nodes.x0.x[node] = nodes.x.x[node] = 0.5 * (a % 3);
    nodes.x0.y[node] = nodes.x.y[node] = 0.5 * ((a / 3) % 3);
    nodes.x0.z[node] = nodes.x.z[node] = 0.5 * (a / 9);
  }
  state.hex_blocks = {block};
  const auto dir = fresh_directory("field_lagrange");
  FieldWriter writer(dir);
  writer.write_frame(state);
  const std::string file = read_file(dir / "frames_0000.vtu");
  XmlDocument doc = XmlReader(file).read();
  const XmlElement& piece = doc.root.child("UnstructuredGrid").child("Piece");
  const XmlElement& cells = piece.child("Cells");
  const auto types = decode<std::uint8_t>(file, doc, cells.data_array("types"), "UInt8");
  const auto conn = decode<std::int64_t>(file, doc, cells.data_array("connectivity"), "Int64");
  ASSERT_EQ(types, std::vector<std::uint8_t>{72});
  ASSERT_EQ(conn.size(), 27u);
  // VTK point k of the cell must be where VTK expects it: corners at the cube's corners, point
  // 8 (first i-edge node) at (0.5, 0, 0), the last (body) point at the centre.
  auto at = [&](std::size_t k) {
    const auto node = static_cast<std::size_t>(conn[k]);
    return std::array<double, 3>{nodes.x.x[node], nodes.x.y[node], nodes.x.z[node]};
  };
  EXPECT_EQ(at(0), (std::array<double, 3>{0, 0, 0}));
  EXPECT_EQ(at(2), (std::array<double, 3>{1, 1, 0}));
  EXPECT_EQ(at(6), (std::array<double, 3>{1, 1, 1}));
  EXPECT_EQ(at(8), (std::array<double, 3>{0.5, 0, 0}));
  EXPECT_EQ(at(26), (std::array<double, 3>{0.5, 0.5, 0.5}));
}

TEST(OutputFieldTet10, QuadraticTetrahedraAreWrittenAsVtkQuadraticTetra) {
  // An ELFORM 16 block: VTK_QUADRATIC_TETRA (24) with the 10 nodes in LS-DYNA's order, which is
  // VTK's (corners, then edges 0-1, 1-2, 2-0, 0-3, 1-3, 2-3); the cell stress the mean of the 4
  // points.
  solver::State state;
  auto& nodes = state.nodes;
  for (auto* v : {&nodes.x0, &nodes.x, &nodes.v, &nodes.a, &nodes.f_int, &nodes.f_ext}) {
    v->resize(10);
  }
  nodes.mass.assign(10, 1.0);
  const double corner[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  element::HexBlock block;
  block.part_id = 4;
  block.elform = 16;
  block.element_id = {11};
  for (int a = 0; a < 10; ++a) {
    const int node = 9 - a;  // any numbering: slot a holds node 9 - a
    nodes.id.push_back(200 + a);
    double x[3];
    for (int d = 0; d < 3; ++d)
      x[d] = a < 4 ? corner[a][d] : 0.5 * (corner[edge[a - 4][0]][d] + corner[edge[a - 4][1]][d]);
    nodes.x0.x[node] = nodes.x.x[node] = x[0];
    nodes.x0.y[node] = nodes.x.y[node] = x[1];
    nodes.x0.z[node] = nodes.x.z[node] = x[2];
    block.conn.push_back(node);
  }
  block.stress.assign(24, 0.0);
  for (int q = 0; q < 4; ++q) block.stress[6 * q] = 1.0 + q;  // sigma_xx 1, 2, 3, 4: mean 2.5
  state.hex_blocks = {block};
  const auto dir = fresh_directory("field_tet10");
  FieldWriter writer(dir);
  writer.write_frame(state);
  const std::string file = read_file(dir / "frames_0000.vtu");
  XmlDocument doc = XmlReader(file).read();
  const XmlElement& piece = doc.root.child("UnstructuredGrid").child("Piece");
  const XmlElement& cells = piece.child("Cells");
  const auto types = decode<std::uint8_t>(file, doc, cells.data_array("types"), "UInt8");
  const auto conn = decode<std::int64_t>(file, doc, cells.data_array("connectivity"), "Int64");
  ASSERT_EQ(types, std::vector<std::uint8_t>{24});
  ASSERT_EQ(conn.size(), 10u);
  for (int a = 0; a < 10; ++a) EXPECT_EQ(conn[static_cast<std::size_t>(a)], 9 - a) << "point " << a;
  const auto stress =
      decode<double>(file, doc, piece.child("CellData").data_array("stress"), "Float64");
  ASSERT_GE(stress.size(), 6u);
  EXPECT_DOUBLE_EQ(stress[0], 2.5);
}

}  // namespace
}  // namespace rf::output
