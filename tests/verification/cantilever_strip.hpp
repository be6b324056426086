// The clamped shell strip of the cantilever tests of both shell formulations
// (shell_deck_test.cpp: ELFORM 2, shell16_deck_test.cpp: ELFORM 16): L x b x t = 1 x 0.1 x 0.01 m
// along x, nu = 0, all six DOFs clamped at x = 0, 10 shells along the length. References:
// Euler-Bernoulli (P L^3 / (3 E I), the first clamped-free frequency and mode shape).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "deck_builder.hpp"
#include "shell_builder.hpp"
#include "solver/simulation.hpp"

namespace rf::test {

struct CantileverStrip {
  double length = 1.0, width = 0.1, thickness = 0.01;
  double rho = 7800.0, young = 2.0e11;
  int ny = 1;  // elements across the width

  ShellPlate plate() const {
    ShellPlate p;
    p.nx = 10;
    p.ny = ny;
    p.lx = length;
    p.ly = width;
    return p;
  }
  double ei() const { return young * width * thickness * thickness * thickness / 12.0; }
  // The strip (part 1, *SECTION_SHELL ELFORM `elform`, NIP 2, IHQ 4, QM 0.05) and its clamp.
  std::string deck(int elform) const {
    const ShellPlate p = plate();
    return "*KEYWORD\n" + p.text() + shell_part(1, thickness, rho, young, 0.0, 2, 4, 0.05, elform) +
           node_set(1, p.column(0)) + "*BOUNDARY_SPC_SET\n1,0,1,1,1,1,1,1\n";
  }
  // A total tip load along `dof` (1-3) shared by the free end's nodes, ramped over 0.2 s and
  // held; mass-proportional damping near critical for mode 1 (omega_1 = 51 rad/s) lets the strip
  // settle to the static answer by the end, 0.6 s.
  std::string static_tip_load(double load, int dof) const {
    const ShellPlate p = plate();
    std::string cards;
    for (const int id : p.column(p.nx))
      cards += fmt::format("*LOAD_NODE_POINT\n{},{},1,{}\n", id, dof, load / (ny + 1));
    return cards + "*DEFINE_CURVE\n1\n0,0\n0.2,1\n10,1\n*DAMPING_GLOBAL\n0,50.0\n" +
           "*CONTROL_TERMINATION\n0.6\n*END\n";
  }
  // The free end's mean displacement along `axis` (0-2).
  double tip_displacement(const solver::Simulation& sim, int axis) const {
    const ShellPlate p = plate();
    const auto& nodes = sim.state().nodes;
    const std::vector<double>* x[3] = {&nodes.x.x, &nodes.x.y, &nodes.x.z};
    const std::vector<double>* x0[3] = {&nodes.x0.x, &nodes.x0.y, &nodes.x0.z};
    double tip = 0.0;
    for (const int id : p.column(p.nx)) {
      const auto i = static_cast<std::size_t>(id - 1);
      tip += ((*x[axis])[i] - (*x0[axis])[i]) / (ny + 1);
    }
    return tip;
  }

  // Euler-Bernoulli's first clamped-free frequency (Hz).
  double first_frequency() const {
    return 1.8751 * 1.8751 / (2.0 * std::numbers::pi) *
           std::sqrt(ei() / (rho * width * thickness * std::pow(length, 4)));
  }
  // An initial velocity in the shape of the first mode (tip 0.01 m/s; each section turns with
  // -d v_z / dx about y) and an end time of 3.2 periods.
  std::string first_mode_velocity() const {
    const double beta = 1.8751 / length;
    const double sigma = (std::sinh(beta * length) - std::sin(beta * length)) /
                         (std::cosh(beta * length) + std::cos(beta * length));
    auto mode = [&](double x) {
      return std::cosh(beta * x) - std::cos(beta * x) -
             sigma * (std::sinh(beta * x) - std::sin(beta * x));
    };
    auto slope = [&](double x) {
      return beta * (std::sinh(beta * x) + std::sin(beta * x) -
                     sigma * (std::cosh(beta * x) - std::cos(beta * x)));
    };
    const double tip_mode = mode(length);
    const ShellPlate p = plate();
    std::string cards = "*INITIAL_VELOCITY_NODE\n";
    for (int j = 0; j <= p.ny; ++j)
      for (int i = 1; i <= p.nx; ++i) {
        const double x = length * i / p.nx;
        cards += fmt::format("{},0,0,{:.17g},0,{:.17g},0\n", p.node_id(i, j),
                             0.01 * mode(x) / tip_mode, -0.01 * slope(x) / tip_mode);
      }
    return cards + fmt::format("*CONTROL_TERMINATION\n{:.17g},\n*END\n", 3.2 / first_frequency());
  }
  // Runs `sim` (started with first_mode_velocity) to its end and returns the frequency of the
  // tip's vibration from the downward zero crossings of its z velocity (NaN, with a test
  // failure, if fewer than three).
  double run_and_measure_frequency(solver::Simulation& sim) const {
    const ShellPlate p = plate();
    const auto tip = static_cast<std::size_t>(p.node_id(p.nx, 0) - 1);
    std::vector<double> crossings;
    double previous = 0.01, previous_time = 0.0;
    sim.run([&](const solver::Simulation& s) {
      const double v = s.state().nodes.v.z[tip];
      const double t = s.state().time;
      if (previous > 0.0 && v <= 0.0 && t > 0.0)
        crossings.push_back(previous_time + (t - previous_time) * previous / (previous - v));
      previous = v;
      previous_time = t;
    });
    EXPECT_GE(crossings.size(), 3u);
    if (crossings.size() < 3) return std::nan("");
    const double period =
        (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    return 1.0 / period;
  }
};

}  // namespace rf::test
