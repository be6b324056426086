// Volume, degenerate shapes, lumped mass, critical time step and failure reporting.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "element/hex_geometry.hpp"
#include "hex_test_support.hpp"
#include "model/error.hpp"

namespace {

using rf::test::HexMesh;

double tet_volume(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

// Independent volume: cone from the centroid over each (bilinear, possibly warped) face. The cone
// over a bilinear patch is the mean of the cones over its two diagonal triangulations (the patch
// splits the corner tetrahedron in half), so each face gives 4 tetrahedra with weight 1/2.
double tetrahedral_volume(const double c[8][3]) {
  Eigen::Vector3d p[8], centroid = Eigen::Vector3d::Zero();
  for (int k = 0; k < 8; ++k) {
    p[k] = Eigen::Vector3d(c[k][0], c[k][1], c[k][2]);
    centroid += p[k] / 8.0;
  }
  double v = 0.0;
  for (const auto& f : rf::element::hex::kFaces) {
    // Faces are listed counter-clockwise seen from outside, so (centroid, a, b, c) is positive.
    const auto& a = p[f[0]];
    const auto& b = p[f[1]];
    const auto& cc = p[f[2]];
    const auto& d = p[f[3]];
    v += 0.5 * (tet_volume(centroid, a, b, cc) + tet_volume(centroid, a, cc, d));
    v += 0.5 * (tet_volume(centroid, a, b, d) + tet_volume(centroid, b, cc, d));
  }
  return v;
}

double gauss_volume(const double c[8][3]) {
  double x[3][8];
  for (int k = 0; k < 8; ++k)
    for (int i = 0; i < 3; ++i) x[i][k] = c[k][i];
  double a[8][3];
  rf::element::hex::base_vectors(x, a);
  double dndx[3][8], v = 0.0;
  for (int g = 0; g < 8; ++g) v += rf::element::hex::gauss_gradients(a, g, dndx);
  return v;
}

TEST(HexGeometry, DistortedVolumeMatchesTetrahedralDecompositionAndGauss) {
  HexMesh m = rf::test::single_hex(rf::test::kDistorted);
  rf::test::set_material(m, 1.0, 1.0, 0.25, 1, 2, 0.1);
  m.initialize();
  const double vt = tetrahedral_volume(rf::test::kDistorted);
  EXPECT_NEAR(m.block.volume0[0], vt, 1e-13 * vt);
  EXPECT_NEAR(m.block.volume0[0], gauss_volume(rf::test::kDistorted), 1e-13 * vt);
  EXPECT_GT(std::abs(vt - 1.0), 0.05);  // really distorted
}

TEST(HexGeometry, ExpandNodalIsTheTransposeOfBaseVectors) {
  // expand_nodal(c)_I = sum_k s_k(I) c_k, checked against the monomials evaluated directly.
  double c[8][3];
  for (int k = 0; k < 8; ++k)
    for (int i = 0; i < 3; ++i) c[k][i] = std::sin(1.0 + 3.0 * k + i);
  double f[3][8];
  rf::element::hex::expand_nodal(c, f);
  using rf::element::hex::kEta;
  using rf::element::hex::kXi;
  using rf::element::hex::kZeta;
  for (int n = 0; n < 8; ++n) {
    const double s[8] = {1.0,
                         kXi[n],
                         kEta[n],
                         kZeta[n],
                         kEta[n] * kZeta[n],
                         kZeta[n] * kXi[n],
                         kXi[n] * kEta[n],
                         kXi[n] * kEta[n] * kZeta[n]};
    for (int i = 0; i < 3; ++i) {
      double expected = 0.0;
      for (int k = 0; k < 8; ++k) expected += s[k] * c[k][i];
      EXPECT_NEAR(f[i][n], expected, 1e-14);
    }
  }
}

TEST(HexGeometry, FaceAreasFromBaseVectorsMatchDiagonalForm) {
  double x[3][8];
  for (int k = 0; k < 8; ++k)
    for (int i = 0; i < 3; ++i) x[i][k] = rf::test::kDistorted[k][i];
  double a[8][3];
  rf::element::hex::base_vectors(x, a);
  const double direct = rf::element::hex::max_face_area_squared(x);
  EXPECT_NEAR(rf::element::hex::max_face_area_squared_from_base(a), direct, 1e-14 * direct);
  // Collapsed face (wedge pattern n1..n4 n5 n5 n6 n6): the triangle areas still agree.
  for (int i = 0; i < 3; ++i) {
    x[i][5] = x[i][4];
    x[i][7] = x[i][6];
  }
  rf::element::hex::base_vectors(x, a);
  const double wedge = rf::element::hex::max_face_area_squared(x);
  EXPECT_NEAR(rf::element::hex::max_face_area_squared_from_base(a), wedge, 1e-14 * wedge);
}

TEST(HexGeometry, UniformGradientReproducesLinearFields) {
  // sum_I b_jI x_kI = V delta_jk for the exact volume-averaged operator.
  double x[3][8];
  for (int k = 0; k < 8; ++k)
    for (int i = 0; i < 3; ++i) x[i][k] = rf::test::kDistorted[k][i];
  rf::element::hex::Geometry g;
  rf::element::hex::compute_geometry(x, g);
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 3; ++k) {
      double s = 0.0, t = 0.0;
      for (int n = 0; n < 8; ++n) {
        s += g.b[j][n] * x[k][n];
        t += g.b[j][n];
      }
      EXPECT_NEAR(s, j == k ? g.volume : 0.0, 1e-14);
      EXPECT_NEAR(t, 0.0, 1e-14);
    }
}

TEST(HexGeometry, UnitCubeTimeStepIsOneOverWaveSpeed) {
  HexMesh m = rf::test::single_hex(rf::test::kUnitCube);
  rf::test::set_material(m, 7800.0, 2.0e11, 0.3, 1, 1, 0.1);
  m.initialize();
  const auto r = rf::element::hex_critical_timestep(m.block, m.view());
  EXPECT_NEAR(r.min_dt, 1.0 / m.block.material.wave_speed, 1e-15);
  EXPECT_EQ(r.min_dt_element, 0);
  const auto f = rf::element::compute_hex_forces(m.block, m.view(), 1e-6);
  EXPECT_NEAR(f.min_dt, 1.0 / m.block.material.wave_speed, 1e-15);
}

// Box-corner tetrahedron with LS-DYNA's pattern n1 n2 n3 n4 n4 n4 n4 n4.
TEST(HexGeometry, DegenerateTetrahedron) {
  HexMesh m;
  m.add_node(0, 0, 0);
  m.add_node(2, 0, 0);
  m.add_node(0, 3, 0);
  m.add_node(0, 0, 4);
  m.add_element({0, 1, 2, 3, 3, 3, 3, 3});
  rf::test::set_material(m, 10.0, 1.0e3, 0.25, 1, 2, 0.1);
  m.initialize();
  EXPECT_EQ(m.block.shape[0], rf::element::HexShape::kTetrahedron);
  EXPECT_NEAR(m.block.volume0[0], 2.0 * 3.0 * 4.0 / 6.0, 1e-13);
  std::vector<double> mass(4, 0.0);
  rf::element::add_hex_lumped_mass(m.block, mass);
  for (double mm : mass) EXPECT_NEAR(mm, 10.0 * 4.0 / 4.0, 1e-12);
  // Smallest altitude: from the origin onto the slanted face.
  const double slanted = 0.5 * Eigen::Vector3d(-2, 3, 0).cross(Eigen::Vector3d(-2, 0, 4)).norm();
  const double altitude = 3.0 * 4.0 / slanted;
  const auto r = rf::element::hex_critical_timestep(m.block, m.view());
  EXPECT_NEAR(r.min_dt, altitude / m.block.material.wave_speed, 1e-14);

  // A uniform stretch gives the exact stress and equilibrated forces on the 4 distinct nodes;
  // duplicate slots carry nothing.
  const double eps = 1e-6, dt = 1e-3;
  for (std::size_t i = 0; i < 4; ++i) {
    m.vx[i] = eps * m.x[i] / dt;
    m.x[i] += eps * m.x[i];
  }
  ASSERT_FALSE(rf::element::compute_hex_forces(m.block, m.view(), dt).failed);
  const double sxx =
      (m.block.material.lambda + 2 * m.block.material.shear) * eps / (1.0 + 0.5 * eps);
  EXPECT_NEAR(m.block.stress[0], sxx, 1e-9 * sxx);
  double fsum = 0.0;
  for (int k = 0; k < 8; ++k) fsum += m.block.force[3 * k];
  EXPECT_NEAR(fsum, 0.0, 1e-12 * std::abs(m.block.force[3]));
  for (int k = 4; k < 8; ++k) EXPECT_EQ(m.block.force[3 * k], 0.0);
}

TEST(HexGeometry, DegenerateWedgeAndPyramid) {
  HexMesh m;
  for (int k = 0; k < 8; ++k)
    m.add_node(rf::test::kUnitCube[k][0], rf::test::kUnitCube[k][1], rf::test::kUnitCube[k][2]);
  m.add_node(0.5, 0.5, 1.0);  // apex, index 8
  // Wedge: unit cube cut along the plane through edges 4-5 and 2-3 -> volume 1/2.
  m.add_element({0, 1, 2, 3, 4, 4, 5, 5});
  m.add_element({0, 1, 2, 3, 8, 8, 8, 8});  // pyramid, volume 1/3
  // A 'wedge' n1 n2 n3 n4 n5 n5 n6 n6 with n5 = node 4 (0,0,1), n6 = node 7 (0,1,1).
  m.block.conn[4] = 4;
  m.block.conn[5] = 4;
  m.block.conn[6] = 7;
  m.block.conn[7] = 7;
  rf::test::set_material(m, 2.0, 1.0e3, 0.25, 1, 2, 0.1);
  m.initialize();
  EXPECT_EQ(m.block.shape[0], rf::element::HexShape::kWedge);
  EXPECT_EQ(m.block.shape[1], rf::element::HexShape::kPyramid);
  EXPECT_NEAR(m.block.volume0[0], 0.5, 1e-14);
  EXPECT_NEAR(m.block.volume0[1], 1.0 / 3.0, 1e-14);
  std::vector<double> mass(9, 0.0);
  rf::element::add_hex_lumped_mass(m.block, mass);
  EXPECT_NEAR(mass[4], 2.0 * 0.5 / 6.0, 1e-14);
  EXPECT_NEAR(mass[8], 2.0 / 3.0 / 5.0, 1e-14);
  EXPECT_NEAR(mass[0], 2.0 * 0.5 / 6.0 + 2.0 / 3.0 / 5.0, 1e-14);
  const auto r = rf::element::hex_critical_timestep(m.block, m.view());
  EXPECT_TRUE(std::isfinite(r.min_dt));
  EXPECT_GT(r.min_dt, 0.0);
  // Wedge: V = 1/2 over the slanted 1 x sqrt2 face (L = 0.354); pyramid: V = 1/3 over the unit
  // base (L = 1/3) is the smaller.
  EXPECT_NEAR(r.min_dt, (1.0 / 3.0) / m.block.material.wave_speed, 1e-14);
  EXPECT_EQ(r.min_dt_element, 1);
  HexMesh wedge = m;
  wedge.block.conn.resize(8);
  wedge.block.element_id.resize(1);
  wedge.initialize();
  const auto rw = rf::element::hex_critical_timestep(wedge.block, wedge.view());
  EXPECT_NEAR(rw.min_dt, 0.5 / std::sqrt(2.0) / m.block.material.wave_speed, 1e-14);
}

TEST(HexGeometry, InvertedElementThrowsNamingElementAndPart) {
  HexMesh m = rf::test::single_hex(rf::test::kUnitCube);
  m.block.element_id[0] = 4711;
  std::swap(m.block.conn[1], m.block.conn[3]);  // clockwise bottom face
  std::swap(m.block.conn[5], m.block.conn[7]);
  rf::test::set_material(m, 1.0, 1.0, 0.25, 1, 2, 0.1);
  try {
    m.initialize();
    FAIL() << "expected rf::SolverError";
  } catch (const rf::SolverError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("element 4711 of part 7"), std::string::npos) << msg;
    EXPECT_NE(msg.find("non-positive volume"), std::string::npos) << msg;
  }
}

TEST(HexGeometry, InversionDuringRunIsReportedNotThrown) {
  HexMesh m = rf::test::single_hex(rf::test::kUnitCube);
  m.add_node(5, 5, 5);
  m.add_element({0, 1, 2, 3, 4, 5, 6, 7});  // second element, same nodes
  rf::test::set_material(m, 1.0, 1.0, 0.25, 1, 2, 0.1);
  m.initialize();
  for (int k = 4; k < 8; ++k) m.z[k] = -0.5;  // crush through the bottom face
  const auto r = rf::element::compute_hex_forces(m.block, m.view(), 1e-3);
  EXPECT_TRUE(r.failed);
  EXPECT_EQ(r.failed_element, 0);
  EXPECT_LT(r.failed_volume, 0.0);
}

}  // namespace
