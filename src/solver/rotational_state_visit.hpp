// The arrays of solver::RotationalState that carry state from one cycle to the next, named: the
// angular velocities omega^{n-1/2} and the previous ones (energy sums), internal and external
// moments, and the lumped rotational inertias (mass scaling changes them during a run). Used by
// the restart dump (restart/dump.cpp), as element/block_state.hpp is for the element families.
// `visit(std::string name, std::vector<double>& array)`; `Rotations` is RotationalState or its
// const.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "solver/state.hpp"

namespace rf::solver {

template <class Rotations, class Visit>
void visit_rotational_state(Rotations& r, Visit&& visit) {
  for (auto [name, a] : {std::pair{"w", &r.w}, std::pair{"w_previous", &r.w_previous},
                         std::pair{"m_int", &r.m_int}, std::pair{"m_ext", &r.m_ext}}) {
    visit(std::string(name) + "_x", a->x);
    visit(std::string(name) + "_y", a->y);
    visit(std::string(name) + "_z", a->z);
  }
  visit(std::string("inertia"), r.inertia);
}

}  // namespace rf::solver
