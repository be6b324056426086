// p-elevation of 8-node hexahedra (mesh/p_order.hpp): shared edge and face nodes whatever the
// neighbours' relative orientation, node counts of structured grids, node positions at the GLL
// points of every element's own trilinear map, positive Jacobians, shared registries across
// blocks, rejection of degenerate elements, and the parent lists used to move nodes onto curved
// surfaces.
#include "mesh/p_order.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "element/lagrange_hex.hpp"
#include "material/elastic.hpp"

namespace {

using rf::mesh::HexElevator;
using Vec3 = std::array<double, 3>;
using Hex = std::array<std::int32_t, 8>;

// Corner sign vectors of the LS-DYNA hexahedron (n1..n8).
constexpr int kSign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                             {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

int corner_with_sign(int sx, int sy, int sz) {
  for (int c = 0; c < 8; ++c)
    if (kSign[c][0] == sx && kSign[c][1] == sy && kSign[c][2] == sz) return c;
  return -1;
}

// The 24 proper rotations of the cube as signed permutation matrices (det +1), and, with
// `mirrors`, the 24 improper ones too.
std::vector<Eigen::Matrix3i> cube_symmetries(bool mirrors) {
  std::vector<Eigen::Matrix3i> out;
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& perm : perms)
    for (int s = 0; s < 8; ++s) {
      Eigen::Matrix3i R = Eigen::Matrix3i::Zero();
      for (int r = 0; r < 3; ++r) R(r, perm[r]) = (s >> r) & 1 ? -1 : 1;
      const int det = R.cast<double>().determinant() > 0 ? 1 : -1;
      if (det > 0 || mirrors) out.push_back(R);
    }
  return out;
}

// The same hexahedron with its corners relabelled by the cube symmetry R: new corner c is the
// old corner at position R s_c.
Hex relabel(const Hex& h, const Eigen::Matrix3i& R) {
  Hex out{};
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3i s = R * Eigen::Vector3i(kSign[c][0], kSign[c][1], kSign[c][2]);
    out[c] = h[corner_with_sign(s[0], s[1], s[2])];
  }
  return out;
}

// Trilinear map of the 8 corners at (xi, eta, zeta).
Vec3 trilinear(const std::vector<Vec3>& x, const Hex& h, double xi, double eta, double zeta) {
  Vec3 p{};
  for (int c = 0; c < 8; ++c) {
    const double w =
        0.125 * (1 + xi * kSign[c][0]) * (1 + eta * kSign[c][1]) * (1 + zeta * kSign[c][2]);
    for (int i = 0; i < 3; ++i) p[i] += w * x[h[c]][i];
  }
  return p;
}

// Every node of every elevated element sits at the GLL point of that element's own trilinear
// map: with shared nodes this holds only if each element indexes the shared edge and face nodes
// in its own orientation correctly. Returns the largest deviation.
double max_position_error(const std::vector<Vec3>& x, const std::vector<Hex>& hexes,
                          const std::vector<std::int32_t>& conn, int p) {
  const auto& pt = rf::element::gll_rule(p).points;
  const int n = p + 1;
  double err = 0.0;
  for (std::size_t e = 0; e < hexes.size(); ++e)
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const Vec3 expected = trilinear(x, hexes[e], pt[i], pt[j], pt[k]);
          const Vec3& got = x[conn[e * n * n * n + i + n * (j + n * k)]];
          for (int c = 0; c < 3; ++c) err = std::max(err, std::abs(got[c] - expected[c]));
        }
  return err;
}

// Structured nx x ny x nz grid of distorted hexahedra; element e relabelled by symmetry
// sym[e % sym.size()] so that neighbours meet in all relative orientations.
struct Grid {
  std::vector<Vec3> x;
  std::vector<Hex> hexes;
};

Grid make_grid(int nx, int ny, int nz, const std::vector<Eigen::Matrix3i>& sym) {
  Grid g;
  auto id = [&](int i, int j, int k) {
    return static_cast<std::int32_t>(i + (nx + 1) * (j + (ny + 1) * k));
  };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        g.x.push_back({i + 0.15 * std::sin(1.3 * j + 0.7 * k), j + 0.12 * std::cos(0.9 * i + k),
                       k + 0.1 * std::sin(2.1 * i - 0.4 * j)});
  int e = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i, ++e) {
        const Hex h = {
            id(i, j, k),     id(i + 1, j, k),     id(i + 1, j + 1, k),     id(i, j + 1, k),
            id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        g.hexes.push_back(sym.empty() ? h : relabel(h, sym[(7 * e + 3) % sym.size()]));
      }
  return g;
}

// Initializes a Lagrange block on the elevated mesh (throws if a Jacobian is not positive) and
// returns the total reference volume.
double lagrange_volume(const std::vector<Vec3>& x, const std::vector<std::int32_t>& conn,
                       std::size_t elements, int p) {
  std::vector<double> px, py, pz;
  for (const auto& q : x) {
    px.push_back(q[0]);
    py.push_back(q[1]);
    pz.push_back(q[2]);
  }
  std::vector<double> zero(x.size(), 0.0);
  rf::element::HexBlock block;
  block.order = p;
  block.conn = conn;
  block.material = rf::material::make_elastic(1000.0, 1e9, 0.25);
  for (std::size_t e = 0; e < elements; ++e) block.element_id.push_back(static_cast<long>(e + 1));
  rf::element::initialize_lagrange_hex_block(
      block, {px.data(), py.data(), pz.data(), zero.data(), zero.data(), zero.data()});
  double v = 0.0;
  for (const double a : block.volume0) v += a;
  return v;
}

double hex_grid_volume(const Grid& g) {
  // Sum of the exact trilinear volumes, by a 2x2x2 Gauss rule (exact for the trilinear map).
  const double a = 1.0 / std::sqrt(3.0);
  double v = 0.0;
  for (const auto& h : g.hexes)
    for (int q = 0; q < 8; ++q) {
      const double s[3] = {a * kSign[q][0], a * kSign[q][1], a * kSign[q][2]};
      Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
      for (int c = 0; c < 8; ++c) {
        const double d[3] = {
            0.125 * kSign[c][0] * (1 + s[1] * kSign[c][1]) * (1 + s[2] * kSign[c][2]),
            0.125 * kSign[c][1] * (1 + s[0] * kSign[c][0]) * (1 + s[2] * kSign[c][2]),
            0.125 * kSign[c][2] * (1 + s[0] * kSign[c][0]) * (1 + s[1] * kSign[c][1])};
        for (int i = 0; i < 3; ++i)
          for (int r = 0; r < 3; ++r) J(i, r) += g.x[h[c]][i] * d[r];
      }
      v += J.determinant();
    }
  return v;
}

class Elevation : public ::testing::TestWithParam<int> {};

TEST_P(Elevation, TwoHexesSharingAFaceInEveryRelativeOrientation) {
  const int p = GetParam();
  const auto rotations = cube_symmetries(false);
  ASSERT_EQ(rotations.size(), 24u);
  // The second hexahedron is relabelled by each of the 24 rotations; also the first by a fixed
  // one, so the shared face is seen in every one of its 8 dihedral orientations from one side
  // and a non-trivial one from the other.
  for (const auto& R : rotations) {
    Grid g = make_grid(2, 1, 1, {});
    g.hexes[0] = relabel(g.hexes[0], rotations[5]);
    g.hexes[1] = relabel(g.hexes[1], R);
    std::vector<Vec3> x = g.x;
    HexElevator elevator(p, x);
    const auto conn = elevator.add_block(g.hexes);
    EXPECT_EQ(x.size(), static_cast<std::size_t>((2 * p + 1) * (p + 1) * (p + 1)));
    EXPECT_LT(max_position_error(x, g.hexes, conn, p), 1e-14);
    if (p <= rf::element::kMaxLagrangeHexOrder)
      EXPECT_NEAR(lagrange_volume(x, conn, 2, p), hex_grid_volume(g), 1e-12);
  }
}

TEST_P(Elevation, MirroredNeighboursStillShareNodes) {
  // Improper relabellings (left-handed elements): elevation is purely topological and must still
  // share the nodes; only the Jacobian sign differs, which initialize_lagrange_hex_block rejects.
  const int p = GetParam();
  const auto all = cube_symmetries(true);
  ASSERT_EQ(all.size(), 48u);
  for (const auto& R : all) {
    Grid g = make_grid(1, 2, 1, {});
    g.hexes[1] = relabel(g.hexes[1], R);
    std::vector<Vec3> x = g.x;
    HexElevator elevator(p, x);
    const auto conn = elevator.add_block(g.hexes);
    EXPECT_EQ(x.size(), static_cast<std::size_t>((p + 1) * (2 * p + 1) * (p + 1)));
    EXPECT_LT(max_position_error(x, g.hexes, conn, p), 1e-14);
  }
}

TEST_P(Elevation, StructuredGridNodeCountPositionsAndJacobians) {
  const int p = GetParam();
  const int nx = 3, ny = 2, nz = 2;
  const Grid g = make_grid(nx, ny, nz, cube_symmetries(false));
  std::vector<Vec3> x = g.x;
  HexElevator elevator(p, x);
  const auto conn = elevator.add_block(g.hexes);
  EXPECT_EQ(x.size(), static_cast<std::size_t>((p * nx + 1) * (p * ny + 1) * (p * nz + 1)));
  EXPECT_EQ(conn.size(), g.hexes.size() * (p + 1) * (p + 1) * (p + 1));
  EXPECT_LT(max_position_error(x, g.hexes, conn, p), 1e-14);
  // No two nodes at the same place (a duplicated shared node would be).
  std::map<std::array<long long, 3>, int> seen;
  for (const auto& q : x)
    ++seen[{std::llround(q[0] * 1e8), std::llround(q[1] * 1e8), std::llround(q[2] * 1e8)}];
  EXPECT_EQ(seen.size(), x.size());
  if (p <= rf::element::kMaxLagrangeHexOrder)
    EXPECT_NEAR(lagrange_volume(x, conn, g.hexes.size(), p), hex_grid_volume(g), 1e-11);
}

TEST_P(Elevation, BlocksSharingTheRegistryStayConforming) {
  const int p = GetParam();
  const Grid g = make_grid(2, 2, 2, cube_symmetries(false));
  std::vector<Vec3> x = g.x;
  HexElevator elevator(p, x);
  std::vector<Hex> first(g.hexes.begin(), g.hexes.begin() + 3);
  std::vector<Hex> second(g.hexes.begin() + 3, g.hexes.end());
  auto conn = elevator.add_block(first);
  const auto conn2 = elevator.add_block(second);
  conn.insert(conn.end(), conn2.begin(), conn2.end());
  EXPECT_EQ(x.size(), static_cast<std::size_t>((2 * p + 1) * (2 * p + 1) * (2 * p + 1)));
  EXPECT_LT(max_position_error(x, g.hexes, conn, p), 1e-14);
}

TEST_P(Elevation, ParentsOfNewNodes) {
  const int p = GetParam();
  Grid g = make_grid(1, 1, 1, {});
  std::vector<Vec3> x = g.x;
  HexElevator elevator(p, x);
  const auto conn = elevator.elevate(g.hexes[0]);
  EXPECT_EQ(elevator.first_new_node(), 8);
  ASSERT_EQ(elevator.parents().size(), x.size() - 8);
  std::map<std::size_t, int> by_size;
  for (const auto& par : elevator.parents()) ++by_size[par.size()];
  EXPECT_EQ(by_size[2], 12 * (p - 1));
  EXPECT_EQ(by_size[4], 6 * (p - 1) * (p - 1));
  EXPECT_EQ(by_size[8], (p - 1) * (p - 1) * (p - 1));
  // The tensor node (i, 0, 0) lies on edge n1-n2; (i, j, 0) on face n1 n2 n3 n4.
  const int n = p + 1;
  const auto& e = elevator.parents()[conn[1] - 8];
  EXPECT_EQ(e, (std::vector<std::int32_t>{g.hexes[0][0], g.hexes[0][1]}));
  auto f = elevator.parents()[conn[1 + n] - 8];
  std::sort(f.begin(), f.end());
  std::vector<std::int32_t> bottom = {g.hexes[0][0], g.hexes[0][1], g.hexes[0][2], g.hexes[0][3]};
  std::sort(bottom.begin(), bottom.end());
  EXPECT_EQ(f, bottom);
  // Corner nodes are the input nodes.
  EXPECT_EQ(conn[0], g.hexes[0][0]);
  EXPECT_EQ(conn[p], g.hexes[0][1]);
  EXPECT_EQ(conn[p + n * p], g.hexes[0][2]);
  EXPECT_EQ(conn[n * p], g.hexes[0][3]);
  EXPECT_EQ(conn[n * n * p], g.hexes[0][4]);
  EXPECT_EQ(conn[n * n * n - 1], g.hexes[0][6]);
}

INSTANTIATE_TEST_SUITE_P(Orders, Elevation, ::testing::Values(2, 3, 4),
                         [](const auto& info) { return "p" + std::to_string(info.param); });

TEST(Elevation, DegenerateAndInvalidElementsAreRejectedByName) {
  Grid g = make_grid(2, 1, 1, {});
  std::vector<Vec3> x = g.x;
  HexElevator elevator(2, x);
  Hex wedge = g.hexes[1];
  wedge[5] = wedge[4];
  wedge[7] = wedge[6];
  try {
    elevator.add_block({g.hexes[0], wedge}, {41, 42});
    ADD_FAILURE() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("element 42"), std::string::npos) << what;
    EXPECT_NE(what.find("degenerate"), std::string::npos) << what;
  }
  // The good element before it was elevated; the bad one created nothing.
  EXPECT_EQ(x.size(), 12u + 27u - 8u);
  Hex out_of_range = g.hexes[1];
  out_of_range[2] = 1000;
  EXPECT_THROW(elevator.elevate(out_of_range), std::invalid_argument);
  // A face with the same four corners but a different cycle (crossed diagonals).
  Hex crossed = g.hexes[1];
  std::swap(crossed[0], crossed[3]);
  const std::size_t before = x.size();
  EXPECT_THROW(elevator.elevate(crossed), std::invalid_argument);
  EXPECT_EQ(x.size(), before);
  EXPECT_THROW(HexElevator(9, x), std::invalid_argument);
}

TEST(Elevation, OrderOneIsTheIdentity) {
  Grid g = make_grid(1, 1, 1, {});
  std::vector<Vec3> x = g.x;
  HexElevator elevator(1, x);
  const auto conn = elevator.elevate(g.hexes[0]);
  EXPECT_EQ(x.size(), 8u);
  // Tensor order of the 8 corners: n1 n2 n4 n3 n5 n6 n8 n7.
  const Hex& h = g.hexes[0];
  EXPECT_EQ(conn, (std::vector<std::int32_t>{h[0], h[1], h[3], h[2], h[4], h[5], h[7], h[6]}));
}

// The caller's projection hook: nodes whose parent corners all lie on a cylinder are moved onto
// it. A quarter of a thick tube (r in [1, 2], 90 degrees, height 1) from 1 x 6 x 1 hexahedra then
// has the volume of the exact tube to the accuracy of the curved interpolation.
TEST(Elevation, ProjectionOntoCylinderRecoversCurvedVolume) {
  const int sectors = 6;
  double previous = 1.0;
  for (int p = 2; p <= 3; ++p) {
    std::vector<Vec3> x;
    std::vector<Hex> hexes;
    for (int k = 0; k <= 1; ++k)
      for (int s = 0; s <= sectors; ++s)
        for (int r = 0; r <= 1; ++r) {
          const double th = 0.5 * std::numbers::pi * s / sectors, rad = 1.0 + r;
          x.push_back({rad * std::cos(th), rad * std::sin(th), static_cast<double>(k)});
        }
    auto id = [](int r, int s, int k) { return static_cast<std::int32_t>(r + 2 * (s + 7 * k)); };
    for (int s = 0; s < sectors; ++s)
      hexes.push_back({id(0, s, 0), id(1, s, 0), id(1, s + 1, 0), id(0, s + 1, 0), id(0, s, 1),
                       id(1, s, 1), id(1, s + 1, 1), id(0, s + 1, 1)});
    HexElevator elevator(p, x);
    const auto conn = elevator.add_block(hexes);
    auto radius = [&](std::int32_t node) { return std::hypot(x[node][0], x[node][1]); };
    int moved = 0;
    for (std::size_t i = 0; i < elevator.parents().size(); ++i) {
      const auto& par = elevator.parents()[i];
      if (par.size() == 8) continue;
      for (const double R : {1.0, 2.0}) {
        bool on = true;
        for (const std::int32_t c : par) on = on && std::abs(radius(c) - R) < 1e-12;
        if (!on) continue;
        auto& q = x[elevator.first_new_node() + i];
        const double scale = R / std::hypot(q[0], q[1]);
        q[0] *= scale;
        q[1] *= scale;
        ++moved;
      }
    }
    EXPECT_GT(moved, 0);
    const double exact = 0.75 * std::numbers::pi;
    const double err = std::abs(lagrange_volume(x, conn, hexes.size(), p) - exact) / exact;
    std::printf("[ cylinder ] p=%d: %d nodes projected, relative volume error %.2e\n", p, moved,
                err);
    EXPECT_LT(err, 1e-4);
    EXPECT_LT(err, previous);
    previous = err;
  }
}

}  // namespace
