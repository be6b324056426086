// Penalty contact between surfaces of solid and shell parts (*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE,
// _NODES_TO_SURFACE, _ONE_WAY_SURFACE_TO_SURFACE, _SINGLE_SURFACE).
//
// Node-to-segment penalty method (LS-DYNA Theory Manual, "Contact-Impact Algorithm", penalty
// method; Hallquist, Goudreau & Benson, CMAME 51 (1985) 107-137): every slave node is projected
// on the nearest master segment (bilinear quadrilateral), and a node behind the segment by
// g < 0 gets the force k |g| along the segment's outward normal, the segment's nodes the
// opposite force distributed by the bilinear shape functions at the projection. Surface-to-
// surface contact runs this twice with the sides exchanged (symmetric treatment), one-way and
// nodes-to-surface once, single surface once with the surface against itself. Coulomb friction
// uses an elastic tangential spring with a return map onto the friction cone; viscous damping
// (VDC) acts along the normal. Forces are evaluated at x^{n+1} with v^{n+1/2} and added to
// f_ext, so rigid bodies gather the forces on their nodes like any other nodal force. Node
// positions are read from the state arrays every cycle: any node moved by any means (element,
// rigid body, flexible body) takes part.
//
// The broad phase is a bucket sort of the master segments on a uniform grid, rebuilt when the
// master nodes have moved farther than the grid's slack since the last build (O(n) build, O(1)
// lookup per slave node). Results are deterministic for any thread count: each slave node's
// force is computed independently, the reactions are gathered in slave-node order.
// Erosion: segments of eroded elements leave, interior faces of erodible solids they uncover
// join, as in LS-DYNA's *CONTACT_ERODING_* (update_after_erosion, docs/contact.md section 7).
// Theory, stiffness formulas, energy accounting and choices: docs/contact.md.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "model/model.hpp"
#include "solver/build_state.hpp"
#include "solver/state.hpp"

namespace rf::contact {

// An element of the state's blocks, as a contact segment refers to it (erosion).
struct ElementRef {
  enum Family : std::int8_t { kNone = 0, kHex = 1, kShell = 2 };
  Family family = kNone;
  std::int32_t block = -1;  // in state.hex_blocks or state.shell_blocks
  std::int64_t element = -1;
};

// Segments (bilinear quadrilaterals, triangles repeat their third node) of one contact side:
// exterior faces of solids, ordered so that (x2 - x1) x (x4 - x1) points out of the solid
// (one-sided), and shell elements in their element order (two-sided: a node meets them from
// either side, docs/contact.md section 1).
//
// Erosion (docs/contact.md, "Erosion"; LS-DYNA's *CONTACT_ERODING_*): a side with elements that
// can erode also holds, as candidate segments, every interior face of its erodible solids, once
// out of each element whose neighbour across the face can erode. A segment is active while the
// element it bounds (`owner`) is alive, the element across it (`covered_by`, kNone for an
// exterior face) has eroded, and none of its nodes is removed; a node while it is on an active
// segment (node set: always) and not removed. update_after_erosion() recomputes the flags. A side
// that cannot erode leaves all four arrays empty: everything is active, as before erosion.
struct ContactSurface {
  std::vector<std::array<std::int32_t, 4>> segments;  // dense node indices
  // SOFT = 0 penalty stiffness: SLSFAC K A^2 / V (solids), SLSFAC K A / max diagonal (shells).
  std::vector<double> stiffness;
  std::vector<std::uint8_t> two_sided;  // 1: a shell element (contact on both sides)
  // Distance of the contact surface from the segment: half the shell thickness times SFST/SFMT
  // (or SST/2, MST/2 when given), SST/2 or MST/2 for solid faces.
  std::vector<double> half_thickness;
  std::vector<double> size;     // sqrt of the segment area at the start
  std::vector<model::Id> part;  // part of the element the segment bounds
  std::vector<double> mass;     // mean lumped mass of the segment's nodes (SOFT = 1)
  // Distinct nodes of the side (ascending): segment nodes, or a node set (NODES_TO_SURFACE).
  std::vector<std::int32_t> nodes;
  std::vector<double> node_stiffness;  // smallest stiffness of the node's segments (inf: none)
  // The node's own contact offset: the largest half thickness of its segments (SST/2 or MST/2
  // for the nodes of a node set).
  std::vector<double> node_half_thickness;
  std::vector<model::Id> node_part;  // part of the node's first segment (or element)
  // Segments of each node (CSR over `nodes`) and the node's outward normal at the last
  // evaluation (3 per node, the normalised sum of its one-sided segments' area vectors; zero
  // for nodes without solid faces: node sets, shell nodes). A node with a normal only meets
  // segments that face it (n_node . n_segment < 0).
  std::vector<std::int64_t> node_segment_start;
  std::vector<std::int32_t> node_segments;
  std::vector<double> node_normal;
  double max_size = 0.0;
  double max_half_thickness = 0.0;  // over segments and nodes

  // Erosion (see above).
  std::vector<ElementRef> owner;             // per segment (erodible sides only)
  std::vector<ElementRef> covered_by;        // per segment (erodible sides only)
  std::vector<std::uint8_t> segment_active;  // per segment (erodible sides only)
  std::vector<std::uint8_t> node_active;     // per node (erodible sides only)
  bool erodible = false;  // an element (or, node sets: a node) of the side can leave

  bool is_active_segment(std::size_t s) const {
    return segment_active.empty() || segment_active[s] != 0;
  }
  bool is_active_node(std::size_t j) const { return node_active.empty() || node_active[j] != 0; }
};

// Uniform-grid bucket sort of a surface's active segments. Each is listed in every cell that
// its bounding box, grown by `expansion`, overlaps (the box at the build positions).
struct SegmentGrid {
  double cell = 0.0;
  std::array<double, 3> origin{};
  std::array<std::int64_t, 3> dims{};
  std::vector<std::int64_t> cell_start;  // CSR over cells
  std::vector<std::int32_t> cell_segments;
  std::vector<std::int32_t> fill;  // scratch
  double expansion = 0.0;
  double slack = 0.0;  // rebuild when a segment node moved farther than this since the build
  std::vector<double> built_x, built_y, built_z;  // positions of the surface nodes at the build
  bool built = false;
  std::int64_t rebuilds = 0;
  mutable std::vector<std::int64_t> visit_stamp;  // per segment: within_offset de-duplication
  mutable std::int64_t stamp = 0;
};

// What one slave node found in the last evaluation.
struct NodeContact {
  std::int32_t segment = -1;  // master segment in contact, -1: none
  double weight[4] = {0, 0, 0, 0};
  double force[3] = {0, 0, 0};  // on the slave node
  double gap = 0.0;
};

// One search direction: the nodes of one side against the segments of the other.
struct ContactPass {
  int slave_side = 0;         // 0: the interface's slave surface, 1: its master surface
  int master_side = 1;        // whose segments are searched
  double slave_scale = 1.0;   // SFS or SFM of the node's side
  double master_scale = 1.0;  // SFM or SFS of the segment's side
  // Largest k dt^2 / m of a pair (stability): 0.5, or 0.25 for each of two symmetric passes.
  double stability_scale = 0.5;
  SegmentGrid grid;
  std::vector<NodeContact> results;      // parallel to the slave side's nodes
  std::vector<double> tangential_force;  // 3 per slave node: the friction spring (state)
  // The side memory of two-sided (shell) segments (docs/contact.md section 1.1): per slave node
  // the unit contact normal (3 per node, zero: not in contact) and the master segment (-1) of
  // the last evaluation. A node in contact keeps its side on that segment and the segments that
  // share a node with it. State: written to restart dumps.
  std::vector<double> contact_normal;
  std::vector<std::int32_t> contact_segment;
};

struct ContactInterface {
  int number = 0;
  model::Id id = 0;
  std::string heading;
  model::ContactKind kind = model::ContactKind::SurfaceToSurface;
  double fs = 0.0, fd = 0.0, dc = 0.0, vdc = 0.0, fsf = 1.0;
  double birth = 0.0, death = 1e20;
  int soft = 0;
  double sofscl = 0.1;
  double soft_dt = 0.0;  // SOFT = 1: the time step of the first evaluation with a step
  // SOFT = 0 stiffness of a pair (*CONTROL_CONTACT PENOPT): 1 the smaller of the segment's and
  // the node's, 2 the segment's, 3 the node's (each falling back on the other where it has none).
  int penopt = 1;
  std::array<ContactSurface, 2> sides;  // slave, master (single surface: both the same)
  std::vector<ContactPass> passes;
  // Last evaluation: resultant force on the slave side's nodes (the master side's is its
  // negative), and how many nodes were in contact.
  std::array<double, 3> slave_force{};
  std::int64_t active_nodes = 0;
  model::SourceLocation where;
};

struct ContactSystem {
  std::vector<ContactInterface> interfaces;
  solver::Vec3Array force;          // nodal contact forces of the last evaluation
  std::vector<std::int32_t> nodes;  // every node any interface touches (ascending)
  // Loops over fewer items run on one thread (a parallel region costs more than they do);
  // tests set 0 to exercise the parallel path on small models.
  std::int64_t parallel_minimum = 2048;
  bool empty() const { return interfaces.empty(); }
};

// The contacts of the model with their surfaces (exterior faces of solid parts, higher-order
// faces split into the linear sub-quads of their node grid; shell elements). Throws
// rf::InputError for a segment that is neither a solid face nor a shell, and for beam parts.
ContactSystem build_contacts(const model::Model& model, const solver::NodeIndex& node_index,
                             const solver::State& state);

// The contact forces at the current positions x^{n+1}, velocities v^{n+1/2} and time t^{n+1}
// (`dt` the step just taken, for the friction slip; 0 at the start). Fills system.force; does
// not touch f_ext (add_contact_forces does). Call once per cycle: friction state advances.
void compute_contact_forces(ContactSystem& system, const solver::State& state, double dt);
// After a cycle in which elements eroded (and once after a restart was read: the flags are
// derived from the blocks' erosion state and NodalState::removed, not dumped): recomputes which
// segments and nodes take part, resets the per-pass state (result, friction spring, side memory)
// of slave nodes that left or whose segment left, and the interface's resultant and count if a
// result was reset; marks the search grids of changed sides for a rebuild (the next evaluation
// rebuilds them: an event, like a grid rebuild, not per-cycle work). docs/contact.md, "Erosion".
void update_after_erosion(ContactSystem& system, const solver::State& state);
// f_ext += the contact forces of the last evaluation (after the external forces were formed).
void add_contact_forces(const ContactSystem& system, solver::State& state);

// Query for part switching (CODE 2/4): |resultant contact force on the slave side| of the
// interface with ID `contact_id` at the last evaluation; -1 if there is no such interface.
double resultant_force(const ContactSystem& system, model::Id contact_id);
// OFFSET of part switching (CODE 4): whether a node of one of `parts` on either side of the
// interface is closer than `offset` to a segment of the other side (or a node of the other side
// closer than `offset` to a segment of one of `parts`), at the current positions.
bool within_offset(const ContactSystem& system, model::Id contact_id, double offset,
                   const std::vector<model::Id>& parts, const solver::State& state);

}  // namespace rf::contact
