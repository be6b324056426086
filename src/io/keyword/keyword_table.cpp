// Registered keywords. Adding a keyword: write a handler, list it here, document it in
// docs/keywords.md.
#include "io/keyword/handlers.hpp"

namespace rf::io {

namespace {

const std::vector<KeywordEntry>& table() {
  using namespace handlers;
  static const std::vector<KeywordEntry> entries{
      {"*NODE", node, {}},
      {"*ELEMENT_SOLID", element_solid, {"TET4TOTET10"}},
      {"*PART", part, {"INERTIA"}},
      {"*SECTION_SOLID", section_solid, {"TITLE"}},
      {"*ELEMENT_SHELL", element_shell, {"THICKNESS", "BETA", "MCID", "OFFSET"}},
      {"*ELEMENT_BEAM", element_beam, {"ORIENTATION"}},
      {"*SECTION_SHELL", section_shell, {"TITLE"}},
      {"*SECTION_BEAM", section_beam, {"TITLE"}},
      {"*ELEMENT_DISCRETE", element_discrete, {}},
      {"*SECTION_DISCRETE", section_discrete, {"TITLE"}},
      {"*MAT_SPRING_ELASTIC", mat_discrete, {"TITLE"}},
      {"*MAT_S01", mat_discrete, {"TITLE"}},
      {"*MAT_DAMPER_VISCOUS", mat_discrete, {"TITLE"}},
      {"*MAT_S02", mat_discrete, {"TITLE"}},
      {"*MAT_SPRING_NONLINEAR_ELASTIC", mat_discrete, {"TITLE"}},
      {"*MAT_S04", mat_discrete, {"TITLE"}},
      {"*CONTROL_SHELL", control_shell, {}},
      {"*CONTROL_CONTACT", control_contact, {}},
      {"*MAT_ELASTIC", mat_elastic, {"TITLE"}},
      {"*MAT_001", mat_elastic, {"TITLE"}},
      {"*MAT_RIGID", mat_rigid, {"TITLE"}},
      {"*MAT_020", mat_rigid, {"TITLE"}},
      {"*MAT_PLASTIC_KINEMATIC", mat_plastic_kinematic, {"TITLE"}},
      {"*MAT_003", mat_plastic_kinematic, {"TITLE"}},
      {"*MAT_PIECEWISE_LINEAR_PLASTICITY", mat_piecewise_linear_plasticity, {"TITLE"}},
      {"*MAT_024", mat_piecewise_linear_plasticity, {"TITLE"}},
      {"*MAT_MOONEY-RIVLIN_RUBBER", mat_mooney_rivlin_rubber, {"TITLE"}},
      {"*MAT_027", mat_mooney_rivlin_rubber, {"TITLE"}},
      {"*MAT_OGDEN_RUBBER", mat_ogden_rubber, {"TITLE"}},
      {"*MAT_077_O", mat_ogden_rubber, {"TITLE"}},
      {"*MAT_3-PARAMETER_BARLAT", mat_three_parameter_barlat, {"TITLE"}},
      {"*MAT_036", mat_three_parameter_barlat, {"TITLE"}},
      {"*MAT_JOHNSON_COOK", mat_johnson_cook, {"TITLE"}},
      {"*MAT_015", mat_johnson_cook, {"TITLE"}},
      {"*MAT_ADD_EROSION", mat_add_erosion, {"TITLE"}},
      {"*EOS_LINEAR_POLYNOMIAL", eos_linear_polynomial, {"TITLE"}},
      {"*EOS_001", eos_linear_polynomial, {"TITLE"}},
      {"*HOURGLASS", hourglass, {"TITLE"}},
      {"*SET_NODE", set_node_list, {"TITLE"}},
      {"*SET_NODE_LIST", set_node_list, {"TITLE"}},
      {"*SET_PART", set_part_list, {"TITLE"}},
      {"*SET_PART_LIST", set_part_list, {"TITLE"}},
      {"*SET_SEGMENT", set_segment, {"TITLE"}},
      {"*SET_NODE_LIST_GENERATE", set_list_generate, {"TITLE"}},
      {"*SET_PART_LIST_GENERATE", set_list_generate, {"TITLE"}},
      {"*SET_SOLID_GENERATE", set_list_generate, {"TITLE"}},
      {"*SET_NODE_GENERAL", set_general, {"TITLE"}},
      {"*SET_PART_GENERAL", set_general, {"TITLE"}},
      {"*SET_SOLID", set_solid_list, {"TITLE"}},
      {"*SET_SOLID_LIST", set_solid_list, {"TITLE"}},
      {"*SET_SHELL", set_solid_list, {"TITLE"}},
      {"*SET_SHELL_LIST", set_solid_list, {"TITLE"}},
      {"*SET_BEAM", set_solid_list, {"TITLE"}},
      {"*CHANGE_P-ORDER", change_p_order, {}},
      {"*BOUNDARY_SPC_NODE", boundary_spc, {"ID"}},
      {"*BOUNDARY_SPC_SET", boundary_spc, {"ID"}},
      {"*BOUNDARY_PRESCRIBED_MOTION_NODE", boundary_prescribed_motion, {"ID"}},
      {"*BOUNDARY_PRESCRIBED_MOTION_SET", boundary_prescribed_motion, {"ID"}},
      {"*DEFINE_CURVE", define_curve, {"TITLE"}},
      {"*DEFINE_CURVE_FUNCTION", define_curve_function, {"TITLE"}},
      {"*DEFINE_TABLE", define_table, {"TITLE", "2D"}},
      {"*DEFINE_COORDINATE_SYSTEM", define_coordinate_system, {"TITLE"}},
      {"*DEFINE_COORDINATE_VECTOR", define_coordinate_vector, {"TITLE"}},
      {"*DEFINE_COORDINATE_NODES", define_coordinate_nodes, {"TITLE"}},
      {"*DEFINE_VECTOR", define_vector, {"TITLE"}},
      {"*CONSTRAINED_RIGID_BODIES", constrained_rigid_bodies, {}},
      {"*CONSTRAINED_EXTRA_NODES_NODE", constrained_extra_nodes, {}},
      {"*CONSTRAINED_EXTRA_NODES_SET", constrained_extra_nodes, {}},
      {"*CONSTRAINED_JOINT_SPHERICAL", constrained_joint, {"ID", "FAILURE"}},
      {"*CONSTRAINED_JOINT_REVOLUTE", constrained_joint, {"ID", "FAILURE"}},
      {"*CONSTRAINED_JOINT_CYLINDRICAL", constrained_joint, {"ID", "FAILURE"}},
      {"*CONSTRAINED_JOINT_TRANSLATIONAL", constrained_joint, {"ID", "FAILURE"}},
      {"*CONSTRAINED_JOINT_UNIVERSAL", constrained_joint, {"ID", "FAILURE"}},
      {"*CONSTRAINED_JOINT_LOCKING", constrained_joint, {"ID", "FAILURE"}},
      {"*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED", constrained_joint_stiffness, {}},
      {"*CONSTRAINED_NODAL_RIGID_BODY", constrained_nodal_rigid_body, {"SPC", "INERTIA", "TITLE"}},
      {"*CONSTRAINED_SPOTWELD", constrained_spotweld, {"ID", "FILTERED", "FORCE"}},
      {"*CONSTRAINED_GENERALIZED_WELD_SPOT", constrained_generalized_weld_spot, {"ID"}},
      {"*CONSTRAINED_NODE_SET", constrained_node_set, {"ID"}},
      {"*BOUNDARY_PRESCRIBED_MOTION_RIGID", boundary_prescribed_motion_rigid, {"ID", "LOCAL"}},
      {"*LOAD_RIGID_BODY", load_rigid_body, {}},
      {"*RIGID_BODY_UPDATE", rigid_body_update, {}},
      {"*CONTROL_RIGID", control_rigid, {}},
      {"*PART_MODES", part_modes, {}},
      {"*RIGIDWALL_PLANAR", rigidwall_planar, {"ID", "FINITE", "MOVING", "FORCES"}},
      {"*RIGIDWALL_GEOMETRIC_FLAT", rigidwall_geometric, {"ID", "MOTION", "DISPLAY"}},
      {"*RIGIDWALL_GEOMETRIC_PRISM", rigidwall_geometric, {"ID", "MOTION", "DISPLAY"}},
      {"*RIGIDWALL_GEOMETRIC_CYLINDER",
       rigidwall_geometric,
       {"ID", "MOTION", "DISPLAY", "INTERIOR"}},
      {"*RIGIDWALL_GEOMETRIC_SPHERE", rigidwall_geometric, {"ID", "MOTION", "DISPLAY"}},
      {"*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE", contact_automatic, {"ID", "TITLE"}},
      {"*CONTACT_AUTOMATIC_NODES_TO_SURFACE", contact_automatic, {"ID", "TITLE"}},
      {"*CONTACT_AUTOMATIC_ONE_WAY_SURFACE_TO_SURFACE", contact_automatic, {"ID", "TITLE"}},
      {"*CONTACT_AUTOMATIC_SINGLE_SURFACE", contact_automatic, {"ID", "TITLE"}},
      // The other *DEFINE_BOX_... keywords (adaptivity, SPH, drawbeads, local boxes) are
      // separate keywords in LS-DYNA: unsupported keywords (keyword_classes.cpp).
      {"*DEFINE_BOX", define_box, {"TITLE"}},
      {"*DEFORMABLE_TO_RIGID", deformable_to_rigid, {}},
      {"*DEFORMABLE_TO_RIGID_AUTOMATIC", deformable_to_rigid_automatic, {}},
      {"*DEFORMABLE_TO_RIGID_INERTIA", deformable_to_rigid_inertia, {}},
      {"*INITIAL_VELOCITY", initial_velocity, {}},
      {"*INITIAL_VELOCITY_NODE", initial_velocity_node, {}},
      {"*INITIAL_VELOCITY_GENERATION", initial_velocity_generation, {}},
      {"*LOAD_NODE_POINT", load_node, {}},
      {"*LOAD_NODE_SET", load_node, {}},
      {"*LOAD_SEGMENT", load_segment, {"ID"}},
      {"*LOAD_SEGMENT_SET", load_segment_set, {"ID"}},
      {"*LOAD_SHELL_ELEMENT", load_shell, {"ID"}},
      {"*LOAD_SHELL_SET", load_shell, {"ID"}},
      {"*ELEMENT_MASS", element_mass, {}},
      {"*ELEMENT_MASS_PART", element_mass_part, {}},
      {"*ELEMENT_MASS_PART_SET", element_mass_part, {}},
      {"*DAMPING_GLOBAL", damping_global, {}},
      {"*DAMPING_PART_MASS", damping_part_mass, {}},
      {"*DAMPING_PART_MASS_SET", damping_part_mass, {}},
      {"*LOAD_BODY_X", load_body, {}},
      {"*LOAD_BODY_Y", load_body, {}},
      {"*LOAD_BODY_Z", load_body, {}},
      {"*CONTROL_TERMINATION", control_termination, {}},
      {"*CONTROL_TIMESTEP", control_timestep, {}},
      {"*CONTROL_HOURGLASS", control_hourglass, {}},
      {"*CONTROL_BULK_VISCOSITY", control_bulk_viscosity, {}},
      {"*CONTROL_DYNAMIC_RELAXATION", control_dynamic_relaxation, {}},
      {"*CONTROL_IMPLICIT_GENERAL", control_implicit_general, {}},
      {"*CONTROL_IMPLICIT_EIGENVALUE", control_implicit_eigenvalue, {}},
      {"*DATABASE_GLSTAT", database_ascii, {}},
      {"*DATABASE_NODOUT", database_ascii, {}},
      {"*DATABASE_RBDOUT", database_ascii, {}},
      {"*DATABASE_RWFORC", database_ascii, {}},
      {"*DATABASE_RCFORC", database_ascii, {}},
      {"*DATABASE_MATSUM", database_ascii, {}},
      {"*DATABASE_SPCFORC", database_ascii, {}},
      {"*DATABASE_ELOUT", database_ascii, {}},
      {"*DATABASE_SECFORC", database_ascii, {}},
      {"*DATABASE_JNTFORC", database_ascii, {}},
      {"*DATABASE_SWFORC", database_ascii, {}},
      {"*DATABASE_CROSS_SECTION_PLANE", database_cross_section_plane, {"ID"}},
      {"*DATABASE_CROSS_SECTION_SET", database_cross_section_set, {"ID"}},
      {"*DATABASE_HISTORY_SOLID", database_history_elements, {}},
      {"*DATABASE_HISTORY_SOLID_SET", database_history_elements, {}},
      {"*DATABASE_HISTORY_SOLID_ID", database_history_elements, {}},
      {"*DATABASE_HISTORY_SHELL", database_history_elements, {}},
      {"*DATABASE_HISTORY_SHELL_SET", database_history_elements, {}},
      {"*DATABASE_HISTORY_SHELL_ID", database_history_elements, {}},
      {"*DATABASE_BINARY_D3PLOT", database_binary_d3plot, {}},
      {"*DATABASE_HISTORY_NODE", database_history_node, {}},
      {"*DATABASE_HISTORY_NODE_SET", database_history_node, {}},
      {"*DEFINE_FUNCTION", define_function, {"TITLE"}},
      {"*DEFINE_FUNCTION_TABULATED", skip_unsupported, {"TITLE"}},
      {"*SENSOR_DEFINE_NODE", sensor_define_node, {"TITLE"}},
      {"*SENSOR_DEFINE_ELEMENT", sensor_define_element, {"TITLE"}},
      {"*SENSOR_DEFINE_FUNCTION", sensor_define_function, {"TITLE"}},
      {"*SENSOR_SWITCH", sensor_switch, {"TITLE"}},
      {"*SENSOR_SWITCH_CALC-LOGIC", sensor_switch_calc_logic, {"TITLE"}},
      {"*SENSOR_CONTROL", sensor_control, {"TITLE"}},
      {"*PARAMETER", parameter, {"NOECHO"}},
      {"*PARAMETER_EXPRESSION", parameter_expression, {"NOECHO"}},
      {"*PARAMETER_DUPLICATION", parameter_duplication, {}},
      {"*INCLUDE_PATH", include_path, {"RELATIVE"}},
      {"*TITLE", title, {}},
      {"*INCLUDE", include, {}},
      {"*KEYWORD", ignore, {"ID"}},  // format switches are applied while splitting
      {"*COMMENT", ignore, {}},
  };
  return entries;
}

}  // namespace

const KeywordEntry* find_keyword(std::string_view keyword, std::vector<std::string>& options) {
  const KeywordEntry* best = nullptr;
  for (const auto& entry : table()) {
    if (!keyword.starts_with(entry.name)) continue;
    if (keyword.size() > entry.name.size() && keyword[entry.name.size()] != '_') continue;
    if (!best || entry.name.size() > best->name.size()) best = &entry;
  }
  options.clear();
  if (!best) return nullptr;
  std::string_view rest = keyword.substr(best->name.size());
  while (!rest.empty()) {
    rest.remove_prefix(1);  // the '_'
    const auto next = rest.find('_');
    options.emplace_back(rest.substr(0, next));
    if (next == std::string_view::npos) break;
    rest.remove_prefix(next);
  }
  return best;
}

}  // namespace rf::io
