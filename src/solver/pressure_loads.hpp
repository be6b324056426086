// Follower pressure on segments (*LOAD_SEGMENT, *LOAD_SEGMENT_SET, *LOAD_SHELL_ELEMENT,
// *LOAD_SHELL_SET) and nodal moments (*LOAD_NODE DOF 5-7), resolved to dense indices.
//
// Pressure. A segment is a node quadruple N1..N4 (N3 = N4: a triangle), a face of a solid or a
// shell; p(t) = SF curve(t - AT) for t >= AT and 0 before. Positive pressure pushes against the
// normal n = x_xi x x_eta of the right-hand rule N1 -> N2 -> N3 (LS-DYNA's convention: on a solid
// face numbered counterclockwise seen from outside, positive pressure pushes inward). The force
// is a follower load: the current geometry x^n every cycle. Consistent nodal forces of the
// bilinear segment, exact (no quadrature):
//   f_a = -p int N_a (x_xi x x_eta) dxi deta = -p sum_b M_ab A_b,
// because x_xi x x_eta is itself bilinear in (xi, eta) with corner values A_b (the cross products
// of the two edges meeting at corner b, over 4), and M_ab = int N_a N_b = [4 2 1 2; 2 4 2 1;
// 1 2 4 2; 2 1 2 4] / 9. A flat segment gets the resultant -p A n; a triangle (N3 = N4) the
// linear triangle's -p A n / 3 per node.
//
// Assembly: each segment writes its 4 nodal forces into its own slot (parallel over segments),
// then every loaded node sums its slots in ascending segment order (parallel over nodes), so the
// result is race-free and the same for any thread count. Nodes of rigid bodies pass the force on
// to their body as every nodal f_ext does (solver/rigid_bodies.cpp). Allocation-free per cycle.
//
// MPI: external forces are computed on every rank from the replicated state after the ranks'
// sum of internal forces (docs/parallel.md): every rank applies the whole pressure once, no rank
// sum involves it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "model/curve.hpp"
#include "model/model.hpp"
#include "solver/build_state.hpp"
#include "solver/state.hpp"

namespace rf::solver {

struct PressureLoads {
  struct History {
    const model::Curve* curve = nullptr;
    double sf = 1.0;
    double at = 0.0;
    double operator()(double t) const;  // p(t), 0 before AT
  };
  std::vector<History> histories;                  // one per load card
  std::vector<std::array<std::int32_t, 4>> nodes;  // per segment, dense node indices
  std::vector<std::int32_t> history_of_segment;
  // Gather plan: loaded nodes and, per loaded node, its slots (4 * segment + local node) in
  // ascending order (CSR).
  std::vector<std::int32_t> loaded_nodes;
  std::vector<std::int64_t> slot_start;  // loaded_nodes.size() + 1
  std::vector<std::int32_t> slots;
  // Scratch, sized once: p(t) per history, and 12 force components per segment.
  mutable std::vector<double> pressure;
  mutable std::vector<double> slot_force;
  std::size_t size() const { return nodes.size(); }
  bool empty() const { return nodes.empty(); }
};

// Resolves the model's pressure loads. Errors (file, line, keyword, field): an undefined curve,
// segment set, shell or shell set, a node that does not exist, a segment with repeated nodes
// other than N3 = N4.
PressureLoads resolve_pressure_loads(const model::Model& model, const NodeIndex& node_index);

// Adds the pressure forces at time t to state.nodes.f_ext.
void add_pressure_forces(const PressureLoads& loads, double t, State& state);

// The consistent nodal forces of pressure p on segment x[0..3] (N3 = N4 allowed): f[a][k].
void segment_pressure_forces(const double x[4][3], double p, double f[4][3]);

}  // namespace rf::solver
