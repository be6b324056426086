// Writes small LS-DYNA decks for verification tests: a structured box of hexahedra plus
// whatever keyword text a test appends. Free (comma) format keeps the generator short.
#pragma once

#include <fmt/format.h>
#include <omp.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "contact/contact.hpp"
#include "io/keyword/reader.hpp"
#include "model/error.hpp"
#include "solver/simulation.hpp"

namespace rf::test {

struct BoxMesh {
  int nx = 1, ny = 1, nz = 1;
  double lx = 1.0, ly = 1.0, lz = 1.0;
  // Optional map from reference to actual coordinates (mesh distortion).
  std::function<void(double&, double&, double&)> distort;

  int node_id(int i, int j, int k) const { return 1 + i + (nx + 1) * (j + (ny + 1) * k); }
  int node_count() const { return (nx + 1) * (ny + 1) * (nz + 1); }
  int element_count() const { return nx * ny * nz; }

  void coordinates(int i, int j, int k, double& x, double& y, double& z) const {
    x = lx * i / nx;
    y = ly * j / ny;
    z = lz * k / nz;
    if (distort) distort(x, y, z);
  }

  std::string keyword_text(int pid = 1) const {
    return keyword_text([pid](int, int, int) { return pid; });
  }
  // The same with the part of element (i, j, k) chosen by `part_of` (multi-part blocks).
  std::string keyword_text(const std::function<int(int, int, int)>& part_of) const {
    std::string s = "*NODE\n";
    for (int k = 0; k <= nz; ++k)
      for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
          double x, y, z;
          coordinates(i, j, k, x, y, z);
          s += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", node_id(i, j, k), x, y, z);
        }
    s += "*ELEMENT_SOLID\n";
    int eid = 0;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          s += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", ++eid, part_of(i, j, k),
                           node_id(i, j, k), node_id(i + 1, j, k), node_id(i + 1, j + 1, k),
                           node_id(i, j + 1, k), node_id(i, j, k + 1), node_id(i + 1, j, k + 1),
                           node_id(i + 1, j + 1, k + 1), node_id(i, j + 1, k + 1));
        }
    return s;
  }

  // Node IDs of the face i == const (or j, k) for sets.
  std::vector<int> face_x(int i) const {
    std::vector<int> ids;
    for (int k = 0; k <= nz; ++k)
      for (int j = 0; j <= ny; ++j) ids.push_back(node_id(i, j, k));
    return ids;
  }
};

// A block of nx x ny x nz hexahedra of part `pid` over [0, lx] x [0, ly] x [0, lz] + `local`,
// rotated by `tilt` (radians) about the y axis, then shifted by `shift`. Node IDs
// first_node.., element IDs first_element... Several blocks with disjoint ID ranges make
// multi-part decks (contact, walls).
struct Block {
  int nx = 1, ny = 1, nz = 1;
  double lx = 1.0, ly = 1.0, lz = 1.0;
  Eigen::Vector3d local = Eigen::Vector3d::Zero();
  double tilt = 0.0;
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
  int first_node = 1, first_element = 1, pid = 1;

  int node(int i, int j, int k) const { return first_node + i + (nx + 1) * (j + (ny + 1) * k); }
  int last_node() const { return node(nx, ny, nz); }
  Eigen::Vector3d position(int i, int j, int k) const {
    const Eigen::Vector3d p = Eigen::Vector3d(lx * i / nx, ly * j / ny, lz * k / nz) + local;
    const double c = std::cos(tilt), s = std::sin(tilt);
    return Eigen::Vector3d(c * p.x() + s * p.z(), p.y(), -s * p.x() + c * p.z()) + shift;
  }
  std::string text() const {
    std::string out = "*NODE\n";
    for (int k = 0; k <= nz; ++k)
      for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
          const Eigen::Vector3d p = position(i, j, k);
          out += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", node(i, j, k), p.x(), p.y(), p.z());
        }
    out += "*ELEMENT_SOLID\n";
    int eid = first_element;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          out += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", eid++, pid, node(i, j, k),
                             node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k),
                             node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1),
                             node(i, j + 1, k + 1));
        }
    return out;
  }
};

// Part `pid` with its own section (ELFORM 1), elastic material and hourglass control.
inline std::string elastic(int pid, double rho, double e, double nu, int ihq = 1) {
  return fmt::format(
      "*PART\npart {0}\n{0},{0},{0},0,{0}\n*SECTION_SOLID\n{0},1\n*MAT_ELASTIC\n{0},{1:.17g},"
      "{2:.17g},{3:.17g}\n*HOURGLASS\n{0},{4},0.1\n",
      pid, rho, e, nu, ihq);
}

inline std::string node_set(int sid, const std::vector<int>& ids) {
  std::string s = fmt::format("*SET_NODE_LIST\n{}\n", sid);
  for (std::size_t c = 0; c < ids.size(); c += 8) {
    for (std::size_t k = c; k < std::min(ids.size(), c + 8); ++k) {
      s += fmt::format("{}{}", k == c ? "" : ",", ids[k]);
    }
    s += "\n";
  }
  return s;
}

// Part 1 with section, elastic material and hourglass type.
inline std::string elastic_part(double rho, double e, double nu, int elform, int ihq,
                                double qm = 0.1) {
  return fmt::format(
      "*PART\npart 1\n1,1,1,0,1\n*SECTION_SOLID\n1,{}\n*MAT_ELASTIC\n1,{:.17g},{:.17g},{:.17g}\n"
      "*HOURGLASS\n1,{},{}\n",
      elform, rho, e, nu, ihq, qm);
}

inline model::Model read(const std::string& text) {
  return io::read_deck_text(text, "verification.k");
}

// The InputError message of reading `deck` and building its simulation; empty if it builds.
inline std::string simulation_error_of(const std::string& deck) {
  try {
    solver::Simulation sim(read(deck), {});
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// One unit cube (part 1, ELFORM 1, IHQ 4, material card `material`) on the symmetry planes
// x = 0, y = 0, z = 0, its face x = 1 moved along x by curve 1 times `scale`: with the lateral
// faces free, uniaxial stress. The deck still needs curve 1, the termination and *END.
inline std::string cube_on_symmetry_planes(const std::string& material, double scale) {
  BoxMesh mesh;
  std::string deck = "*KEYWORD\n" + mesh.keyword_text();
  deck += "*PART\nbar\n1,1,1,0,1\n*SECTION_SOLID\n1,1\n*HOURGLASS\n1,4,0.1\n" + material;
  std::vector<int> y0, z0;
  for (int k = 0; k <= 1; ++k)
    for (int i = 0; i <= 1; ++i) y0.push_back(mesh.node_id(i, 0, k));
  for (int j = 0; j <= 1; ++j)
    for (int i = 0; i <= 1; ++i) z0.push_back(mesh.node_id(i, j, 0));
  deck +=
      node_set(1, mesh.face_x(0)) + node_set(2, mesh.face_x(1)) + node_set(3, y0) + node_set(4, z0);
  deck += "*BOUNDARY_SPC_SET\n1,0,1,0,0\n3,0,0,1,0\n4,0,0,0,1\n";
  return deck + fmt::format("*BOUNDARY_PRESCRIBED_MOTION_SET\n2,1,0,1,{}\n", scale);
}

// Strain energy of linear elastic elements from their stresses: sum V/2 sigma : C^-1 : sigma.
// Independent of the force computation, so comparing it with the work balance checks that
// the element forces are consistent with the element stresses.
inline double elastic_strain_energy(const solver::State& state) {
  double energy = 0.0;
  for (const auto& block : state.hex_blocks) {
    const double e = block.material.young, nu = block.material.poisson;
    const double g = block.material.shear;
    const int points = block.points_per_element();
    for (std::size_t el = 0; el < block.size(); ++el) {
      double density = 0.0;
      for (int p = 0; p < points; ++p) {
        const double* s = &block.stress[(el * points + p) * 6];
        const double normal = s[0] * s[0] + s[1] * s[1] + s[2] * s[2] -
                              2.0 * nu * (s[0] * s[1] + s[1] * s[2] + s[2] * s[0]);
        const double shear = s[3] * s[3] + s[4] * s[4] + s[5] * s[5];
        density += 0.5 * (normal / e + shear / g);
      }
      energy += density / points * block.volume[el];
    }
  }
  return energy;
}

// Contact determinism: runs `make()` on 1 and then 2 threads with the contacts' parallel loops
// forced on (ContactSystem::parallel_minimum = 0) and returns, per run, the final z positions,
// z and x velocities and the contact energy: equal vectors mean bit-identical runs.
inline std::vector<std::vector<double>> contact_runs_on_1_and_2_threads(
    const std::function<model::Model()>& make) {
  std::vector<std::vector<double>> finals;
  const int saved = omp_get_max_threads();
  for (const int threads : {1, 2}) {
    omp_set_num_threads(threads);
    solver::Simulation sim(make(), {});
    sim.mutable_contacts().parallel_minimum = 0;
    while (!sim.finished()) sim.cycle();
    const auto& n = sim.state().nodes;
    std::vector<double> values(n.x.z);
    values.insert(values.end(), n.v.z.begin(), n.v.z.end());
    values.insert(values.end(), n.v.x.begin(), n.v.x.end());
    values.push_back(sim.energy().contact_energy);
    finals.push_back(values);
  }
  omp_set_num_threads(saved);
  return finals;
}

}  // namespace rf::test
