// Shell and beam meshes for verification decks (free format), next to deck_builder.hpp's solids.
#pragma once

#include <fmt/format.h>

#include <Eigen/Dense>
#include <functional>
#include <regex>
#include <string>
#include <vector>

namespace rf::test {

// nx x ny quadrilateral shells of part `pid` over [0, lx] x [0, ly] in the local (u, v) plane,
// mapped to space by `place` (default: the global x-y plane at z = 0). Node IDs first_node..,
// element IDs first_element.. .
struct ShellPlate {
  int nx = 1, ny = 1;
  double lx = 1.0, ly = 1.0;
  int first_node = 1, first_element = 1, pid = 1;
  std::function<Eigen::Vector3d(double, double)> place;

  int node_id(int i, int j) const { return first_node + i + (nx + 1) * j; }
  int node_count() const { return (nx + 1) * (ny + 1); }
  int element_count() const { return nx * ny; }
  Eigen::Vector3d position(int i, int j) const {
    const double u = lx * i / nx, v = ly * j / ny;
    return place ? place(u, v) : Eigen::Vector3d(u, v, 0.0);
  }

  std::string nodes_text() const {
    std::string s = "*NODE\n";
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        const Eigen::Vector3d p = position(i, j);
        s += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", node_id(i, j), p.x(), p.y(), p.z());
      }
    return s;
  }
  std::string elements_text() const {
    std::string s = "*ELEMENT_SHELL\n";
    int eid = first_element;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        s += fmt::format("{},{},{},{},{},{}\n", eid++, pid, node_id(i, j), node_id(i + 1, j),
                         node_id(i + 1, j + 1), node_id(i, j + 1));
      }
    return s;
  }
  std::string text() const { return nodes_text() + elements_text(); }

  std::vector<int> column(int i) const {  // nodes with u index i
    std::vector<int> ids;
    for (int j = 0; j <= ny; ++j) ids.push_back(node_id(i, j));
    return ids;
  }
};

// *PART, *SECTION_SHELL (ELFORM `elform`, SHRF 5/6, NIP) and *MAT_ELASTIC with IDs = pid, and
// an *HOURGLASS card of type `ihq` (ignored by ELFORM 16).
inline std::string shell_part(int pid, double thickness, double rho, double e, double nu,
                              int nip = 2, int ihq = 4, double qm = 0.05, int elform = 2) {
  return fmt::format(
      "*PART\nshell part {0}\n{0},{0},{0},0,{0}\n*SECTION_SHELL\n{0},{8},0.8333333333333334,{1}\n"
      "{2:.17g},{2:.17g},{2:.17g},{2:.17g}\n*MAT_ELASTIC\n{0},{3:.17g},{4:.17g},{5:.17g}\n"
      "*HOURGLASS\n{0},{6},{7:.17g}\n",
      pid, nip, thickness, rho, e, nu, ihq, qm, elform);
}

// The deck with every *SECTION_SHELL of ELFORM 2 (first card "SECID,2,...") made ELFORM 16.
inline std::string fully_integrated(const std::string& deck) {
  static const std::regex kSection(R"((\*SECTION_SHELL\n\d+),2,)");
  return std::regex_replace(deck, kSection, "$1,16,");
}

}  // namespace rf::test
