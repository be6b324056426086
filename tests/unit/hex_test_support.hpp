// Small helpers for driving the hexahedron kernels directly in unit tests.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "element/hex_block.hpp"
#include "material/elastic.hpp"
#include "material/elastic_update.hpp"

namespace rf::test {

struct HexMesh {
  std::vector<double> x, y, z, vx, vy, vz;
  element::HexBlock block;

  std::size_t nodes() const { return x.size(); }
  void add_node(double px, double py, double pz) {
    x.push_back(px);
    y.push_back(py);
    z.push_back(pz);
    vx.push_back(0.0);
    vy.push_back(0.0);
    vz.push_back(0.0);
  }
  element::NodalView view() const {
    return {x.data(), y.data(), z.data(), vx.data(), vy.data(), vz.data()};
  }
  void add_element(const std::array<std::int32_t, 8>& c) {
    block.element_id.push_back(static_cast<model::Id>(block.element_id.size() + 1));
    block.conn.insert(block.conn.end(), c.begin(), c.end());
  }
  void initialize() { element::initialize_hex_block(block, view()); }
};

inline void set_material(HexMesh& m, double rho, double young, double nu, int elform, int ihq,
                         double qm) {
  m.block.part_id = 7;
  m.block.material = material::make_elastic(rho, young, nu);
  m.block.elform = elform;
  m.block.hourglass.ihq = ihq;
  m.block.hourglass.qm = qm;
}

// One element from 8 corner coordinates (LS-DYNA node order).
inline HexMesh single_hex(const double corners[8][3]) {
  HexMesh m;
  for (int k = 0; k < 8; ++k) m.add_node(corners[k][0], corners[k][1], corners[k][2]);
  m.add_element({0, 1, 2, 3, 4, 5, 6, 7});
  return m;
}

inline const double kUnitCube[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                       {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
// A generally distorted (non-parallelepiped, warped faces) but valid hexahedron.
inline const double kDistorted[8][3] = {{0.0, 0.0, 0.0},    {1.2, 0.1, -0.1},  {1.3, 1.1, 0.2},
                                        {-0.1, 0.9, 0.05},  {0.1, -0.05, 1.0}, {1.0, 0.2, 1.3},
                                        {1.15, 1.25, 0.95}, {0.05, 1.0, 1.1}};

// Elastic stress C : eps (Voigt, tensor shear).
inline std::array<double, 6> elastic_stress(const material::ElasticConstants& c,
                                            const double eps[6]) {
  const double tr = eps[0] + eps[1] + eps[2];
  return {c.lambda * tr + 2 * c.shear * eps[0],
          c.lambda * tr + 2 * c.shear * eps[1],
          c.lambda * tr + 2 * c.shear * eps[2],
          2 * c.shear * eps[3],
          2 * c.shear * eps[4],
          2 * c.shear * eps[5]};
}

}  // namespace rf::test
