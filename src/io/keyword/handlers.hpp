// Keyword handlers: each reads one block into the model. Registered in keyword_table.cpp.
#pragma once

#include "io/keyword/context.hpp"

namespace rf::io::handlers {

// handlers_mesh.cpp
void node(const Block&, ReaderContext&);
void element_solid(const Block&, ReaderContext&);
void part(const Block&, ReaderContext&);
void section_solid(const Block&, ReaderContext&);
void mat_elastic(const Block&, ReaderContext&);
void mat_rigid(const Block&, ReaderContext&);
void hourglass(const Block&, ReaderContext&);
void set_node_list(const Block&, ReaderContext&);
void set_part_list(const Block&, ReaderContext&);
void set_segment(const Block&, ReaderContext&);

// handlers_loads.cpp
void boundary_spc(const Block&, ReaderContext&);
void boundary_prescribed_motion(const Block&, ReaderContext&);
void define_curve(const Block&, ReaderContext&);
void initial_velocity(const Block&, ReaderContext&);
void initial_velocity_node(const Block&, ReaderContext&);
void initial_velocity_generation(const Block&, ReaderContext&);
void load_node(const Block&, ReaderContext&);
void load_body(const Block&, ReaderContext&);

// handlers_control.cpp
void control_termination(const Block&, ReaderContext&);
void control_timestep(const Block&, ReaderContext&);
void control_hourglass(const Block&, ReaderContext&);
void database_ascii(const Block&, ReaderContext&);
void database_binary_d3plot(const Block&, ReaderContext&);
void database_history_node(const Block&, ReaderContext&);
void parameter(const Block&, ReaderContext&);
void parameter_expression(const Block&, ReaderContext&);
void title(const Block&, ReaderContext&);
void include(const Block&, ReaderContext&);
void ignore(const Block&, ReaderContext&);

}  // namespace rf::io::handlers
