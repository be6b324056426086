// Keyword handlers: each reads one block into the model. Registered in keyword_table.cpp.
#pragma once

#include <unordered_set>

#include "io/keyword/context.hpp"

namespace rf::io::handlers {

// handlers_mesh.cpp
void node(const Block&, ReaderContext&);
void element_solid(const Block&, ReaderContext&);
void element_shell(const Block&, ReaderContext&);
void element_beam(const Block&, ReaderContext&);
void section_shell(const Block&, ReaderContext&);
void section_beam(const Block&, ReaderContext&);
void element_discrete(const Block&, ReaderContext&);
void section_discrete(const Block&, ReaderContext&);
void mat_discrete(const Block&, ReaderContext&);
void part(const Block&, ReaderContext&);
void section_solid(const Block&, ReaderContext&);
void mat_elastic(const Block&, ReaderContext&);
void mat_rigid(const Block&, ReaderContext&);
void mat_plastic_kinematic(const Block&, ReaderContext&);
void mat_piecewise_linear_plasticity(const Block&, ReaderContext&);
void mat_mooney_rivlin_rubber(const Block&, ReaderContext&);
void mat_ogden_rubber(const Block&, ReaderContext&);
void mat_three_parameter_barlat(const Block&, ReaderContext&);
// handlers_johnson_cook.cpp
void mat_johnson_cook(const Block&, ReaderContext&);
void eos_linear_polynomial(const Block&, ReaderContext&);
// handlers_contact.cpp
void control_contact(const Block&, ReaderContext&);
// handlers_erosion.cpp
void mat_add_erosion(const Block&, ReaderContext&);
void hourglass(const Block&, ReaderContext&);
void set_node_list(const Block&, ReaderContext&);
void set_part_list(const Block&, ReaderContext&);
void set_segment(const Block&, ReaderContext&);
void change_p_order(const Block&, ReaderContext&);  // extension, see docs/keywords.md

// handlers_sets.cpp
void set_list_generate(const Block&, ReaderContext&);
void set_general(const Block&, ReaderContext&);
void set_solid_list(const Block&, ReaderContext&);
// After reading: ranges and rules of the sets above become node, part and solid sets.
void finish_sets(ReaderContext& context);

// handlers_loads.cpp
void boundary_spc(const Block&, ReaderContext&);
void boundary_prescribed_motion(const Block&, ReaderContext&);
void define_curve(const Block&, ReaderContext&);
void define_curve_function(const Block&, ReaderContext&);
void define_table(const Block&, ReaderContext&);
void initial_velocity(const Block&, ReaderContext&);
void initial_velocity_node(const Block&, ReaderContext&);
void initial_velocity_generation(const Block&, ReaderContext&);
void load_segment(const Block&, ReaderContext&);      // *LOAD_SEGMENT(_ID)
void load_segment_set(const Block&, ReaderContext&);  // *LOAD_SEGMENT_SET(_ID)
void load_shell(const Block&, ReaderContext&);        // *LOAD_SHELL_ELEMENT/_SET(_ID)
void load_node(const Block&, ReaderContext&);
void load_body(const Block&, ReaderContext&);

// handlers_mass.cpp
void element_mass(const Block&, ReaderContext&);
void element_mass_part(const Block&, ReaderContext&);
void damping_global(const Block&, ReaderContext&);
void damping_part_mass(const Block&, ReaderContext&);

// handlers_joints.cpp
void constrained_joint(const Block&, ReaderContext&);
void constrained_joint_stiffness(const Block&, ReaderContext&);

// handlers_welds.cpp
void constrained_spotweld(const Block&, ReaderContext&);
void constrained_generalized_weld_spot(const Block&, ReaderContext&);
// After every file is read: the generalized spot welds' node sets into model.spot_welds.
void finish_generalized_welds(ReaderContext&);
void constrained_node_set(const Block&, ReaderContext&);

// handlers_control.cpp
void control_termination(const Block&, ReaderContext&);
void control_timestep(const Block&, ReaderContext&);
void control_hourglass(const Block&, ReaderContext&);
void control_bulk_viscosity(const Block&, ReaderContext&);
void control_dynamic_relaxation(const Block&, ReaderContext&);
void control_shell(const Block&, ReaderContext&);
// handlers_implicit.cpp
void control_implicit_general(const Block&, ReaderContext&);
void control_implicit_eigenvalue(const Block&, ReaderContext&);
void database_ascii(const Block&, ReaderContext&);
void database_binary_d3plot(const Block&, ReaderContext&);
void database_history_elements(const Block&, ReaderContext&);
void database_cross_section_plane(const Block&, ReaderContext&);
void database_cross_section_set(const Block&, ReaderContext&);
void database_history_node(const Block&, ReaderContext&);
void parameter(const Block&, ReaderContext&);
void parameter_expression(const Block&, ReaderContext&);
void parameter_duplication(const Block&, ReaderContext&);
void include_path(const Block&, ReaderContext&);
void title(const Block&, ReaderContext&);
void include(const Block&, ReaderContext&);
void ignore(const Block&, ReaderContext&);

// handlers_rigid.cpp
void define_coordinate_system(const Block&, ReaderContext&);
void define_coordinate_vector(const Block&, ReaderContext&);
void define_coordinate_nodes(const Block&, ReaderContext&);
void define_vector(const Block&, ReaderContext&);
void constrained_rigid_bodies(const Block&, ReaderContext&);
void constrained_extra_nodes(const Block&, ReaderContext&);
void constrained_nodal_rigid_body(const Block&, ReaderContext&);
void boundary_prescribed_motion_rigid(const Block&, ReaderContext&);
void load_rigid_body(const Block&, ReaderContext&);
void rigid_body_update(const Block&, ReaderContext&);
void deformable_to_rigid(const Block&, ReaderContext&);
void deformable_to_rigid_automatic(const Block&, ReaderContext&);
void deformable_to_rigid_inertia(const Block&, ReaderContext&);
void control_rigid(const Block&, ReaderContext&);
void part_modes(const Block&, ReaderContext&);  // handlers_modes.cpp

// handlers_sensor.cpp
void define_function(const Block&, ReaderContext&);
void skip_unsupported(const Block&, ReaderContext&);  // as an unknown keyword: a warning
void sensor_define_node(const Block&, ReaderContext&);
void sensor_define_element(const Block&, ReaderContext&);
void sensor_define_function(const Block&, ReaderContext&);
void sensor_switch(const Block&, ReaderContext&);
void sensor_switch_calc_logic(const Block&, ReaderContext&);
void sensor_control(const Block&, ReaderContext&);
// Checks references of sensors, switches, controls and functions (finish_model).
void finish_sensors(ReaderContext& context, const std::unordered_set<model::Id>& nodes);
// handlers_walls.cpp
void rigidwall_planar(const Block&, ReaderContext&);
void rigidwall_geometric(const Block&, ReaderContext&);
void define_box(const Block&, ReaderContext&);
// After reading: the node sets and boxes the rigid walls name must exist.
void check_rigid_walls(const model::Model& model);
// handlers_contact.cpp
void contact_automatic(const Block&, ReaderContext&);
// After reading: the sets and parts the contacts name must exist.
void check_contacts(const model::Model& model);

// Cards shared by *MAT_RIGID, *PART_INERTIA and *CONSTRAINED_NODAL_RIGID_BODY.
struct RigidConstraints {
  double cmo = 0.0;
  double con1 = 0.0;
  double con2 = 0.0;
  model::Id cmo_cid = 0;            // CMO -1: CON1 as a coordinate system ID
  std::array<bool, 6> local_fix{};  // CMO -1: CON2 digits (x y z translation, x y z rotation)
};
// CMO CON1 CON2, validated for CMO 1 (codes 0..7), 0 and -1 (local system and digit code).
RigidConstraints read_rigid_constraints(const Card& card);
// XC..NODEID / IXX..IZZ / VTX..VRZ [/ XL..CID when IRCS = 1], starting at card number n.
model::RigidInertia read_rigid_inertia(CardCursor& cursor, int n, int& cards_read);

}  // namespace rf::io::handlers
