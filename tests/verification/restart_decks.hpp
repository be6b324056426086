// Decks for the restart tests: small models that exercise every kind of state a dump must carry
// (stresses at 1 and 8 points, stiffness hourglass forces, Lagrange hexahedra, rigid bodies with
// both node updates, nodal rigid bodies, prescribed motion with accumulated travel, loads from
// curves). Free (comma) format LS-DYNA.
#pragma once

#include <fmt/format.h>

#include <string>

#include "deck_builder.hpp"
#include "shell_builder.hpp"
#include "tet_mesh.hpp"

namespace rf::test::restart_decks {

// Output at fixed intervals, so that an extended run writes rows at the same times as a longer
// uninterrupted one (default intervals scale with ENDTIM).
inline std::string output_cards(double glstat_dt, double d3plot_dt) {
  return fmt::format(
      "*DATABASE_GLSTAT\n{0},0\n*DATABASE_NODOUT\n{0},0\n*DATABASE_RBDOUT\n{0},0\n"
      "*DATABASE_BINARY_D3PLOT\n{1},0\n",
      glstat_dt, d3plot_dt);
}

// A 4 x 2 x 2 steel block (mm, t, s): part 1 (x < 2) ELFORM 1 with Belytschko-Bindeman
// stiffness hourglass control (IHQ 6, accumulated hourglass forces), part 2 ELFORM 2
// (8 stress points). Spinning and translating, a corner load and a body load from curves, a
// node with prescribed displacement.
inline std::string deformable(double end_time) {
  BoxMesh mesh;
  mesh.nx = 4;
  mesh.ny = 2;
  mesh.nz = 2;
  mesh.lx = 4.0;
  mesh.ly = 2.0;
  mesh.lz = 2.0;
  std::string s = "*KEYWORD\n*TITLE\nrestart: deformable\n";
  s += fmt::format("*CONTROL_TERMINATION\n{},0\n*CONTROL_TIMESTEP\n0,0.5\n", end_time);
  s += output_cards(2e-7, 2e-6);
  s += mesh.keyword_text([](int i, int, int) { return i < 2 ? 1 : 2; });
  s += "*PART\nstiffness hourglass\n1,1,1,0,1\n*PART\nselective reduced\n2,2,1,0,2\n";
  s += "*SECTION_SOLID\n1,1\n*SECTION_SOLID\n2,2\n";
  s += "*MAT_ELASTIC\n1,7.85e-9,210000.0,0.3\n";
  s += "*HOURGLASS\n1,6,0.1\n2,1,0.1\n";
  s += "*INITIAL_VELOCITY_GENERATION\n0,2,2.0e5,1000.0,-500.0,0.0\n1.0,1.0,1.0,0.0,0.0,1.0\n";
  s += fmt::format("*LOAD_NODE_POINT\n{},3,1,50.0\n{},2,1,-30.0\n", mesh.node_id(4, 2, 2),
                   mesh.node_id(4, 0, 2));
  s += "*LOAD_BODY_Y\n2,1.0e6\n";
  s += fmt::format("*BOUNDARY_PRESCRIBED_MOTION_NODE\n{},1,2,3,0.01\n", mesh.node_id(0, 0, 0));
  s += "*DEFINE_CURVE\n1\n0.0,0.0\n1.0e-5,1.0\n1.0,1.0\n";
  s += "*DEFINE_CURVE\n2\n0.0,1.0\n1.0e-5,0.0\n1.0,-1.0\n";
  s += "*DEFINE_CURVE\n3\n0.0,0.0\n1.0e-5,1.0\n1.0,1.0\n";
  s += fmt::format("*DATABASE_HISTORY_NODE\n{},{},{}\n", mesh.node_id(4, 2, 2),
                   mesh.node_id(2, 1, 1), mesh.node_id(0, 0, 0));
  s += "*END\n";
  return s;
}

// The deformable deck with plastic materials: part 1 *MAT_PLASTIC_KINEMATIC with a BETA mix (a
// back stress in the history) and Cowper-Symonds VP 1, part 2 *MAT_PIECEWISE_LINEAR_PLASTICITY
// with an 8-point table and C/P. The yield stresses are low enough for the spin to drive
// plastic flow (effective plastic strain up to 0.6).
inline std::string plastic(double end_time) {
  std::string s = deformable(end_time);
  auto replace = [&s](const std::string& from, const std::string& to) {
    s.replace(s.find(from), from.size(), to);
  };
  replace("*PART\nselective reduced\n2,2,1,0,2\n", "*PART\nselective reduced\n2,2,2,0,2\n");
  replace("*MAT_ELASTIC\n1,7.85e-9,210000.0,0.3\n",
          "*MAT_PLASTIC_KINEMATIC\n1,7.85e-9,210000.0,0.3,100.0,2000.0,0.5\n40.4,5.0,0,1\n"
          "*MAT_PIECEWISE_LINEAR_PLASTICITY\n2,7.85e-9,210000.0,0.3,0,0\n40.4,5.0,0,0,0\n"
          "0,0.01,0.02,0.05,0.1,0.2,0.5,1.0\n100,110,120,135,150,165,185,200\n");
  return s;
}

// The plastic deck with failure: part 1 FS 0.1, part 2 FAIL 0.12 (elements erode before and
// after the dump the test restarts from; erosion times, element work, ledger, removed nodes).
inline std::string eroding(double end_time) {
  std::string s = plastic(end_time);
  auto replace = [&s](const std::string& from, const std::string& to) {
    s.replace(s.find(from), from.size(), to);
  };
  replace("40.4,5.0,0,1\n", "40.4,5.0,0.1,1\n");
  replace("2,7.85e-9,210000.0,0.3,0,0\n", "2,7.85e-9,210000.0,0.3,0,0,0.12\n");
  return s;
}

// The deformable deck with rubber: part 1 (ELFORM 1, IHQ 6) *MAT_MOONEY-RIVLIN_RUBBER, part 2
// (ELFORM 2) a three-term *MAT_OGDEN_RUBBER, both about as stiff as steel in shear so that the
// deck's loads keep the motion moderate; the history is b - I at every stress point.
inline std::string rubber(double end_time) {
  std::string s = deformable(end_time);
  auto replace = [&s](const std::string& from, const std::string& to) {
    s.replace(s.find(from), from.size(), to);
  };
  replace("*PART\nselective reduced\n2,2,1,0,2\n", "*PART\nselective reduced\n2,2,2,0,2\n");
  replace("*MAT_ELASTIC\n1,7.85e-9,210000.0,0.3\n",
          "*MAT_MOONEY-RIVLIN_RUBBER\n1,7.85e-9,0.45,30000.0,5000.0\n0,0,0,0\n"
          "*MAT_OGDEN_RUBBER\n2,7.85e-9,0.45,0\n60000.0,2000.0,-1000.0\n2.0,4.0,-2.0\n");
  return s;
}

// Nodal-pressure tetrahedra (ELFORM 13) of *MAT_PIECEWISE_LINEAR_PLASTICITY: the deformable
// deck's block, spin, loads and prescribed node on an irregular 4 x 2 x 2 tetrahedral mesh
// (same node numbering). Stresses and plastic strain cross the dump; the nodal averages are
// recomputed every cycle and carried by nothing.
inline std::string tetrahedra(double end_time) {
  const TetGrid grid = tet_box(4, 2, 2, 4.0, 2.0, 2.0, 0.15);
  std::string s = "*KEYWORD\n*TITLE\nrestart: nodal-pressure tetrahedra\n";
  s += fmt::format("*CONTROL_TERMINATION\n{},0\n*CONTROL_TIMESTEP\n0,0.5\n", end_time);
  s += output_cards(2e-7, 2e-6);
  s += grid.text();
  s += "*PART\ntetrahedra\n1,1,1\n*SECTION_SOLID\n1,13\n";
  s += "*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,7.85e-9,210000.0,0.3,0,0\n40.4,5.0,0,0,0\n"
       "0,0.01,0.02,0.05,0.1,0.2,0.5,1.0\n100,110,120,135,150,165,185,200\n";
  s += "*INITIAL_VELOCITY_GENERATION\n0,2,2.0e5,1000.0,-500.0,0.0\n1.0,1.0,1.0,0.0,0.0,1.0\n";
  s += fmt::format("*LOAD_NODE_POINT\n{},3,1,50.0\n{},2,1,-30.0\n", grid.node(4, 2, 2),
                   grid.node(4, 0, 2));
  s += "*LOAD_BODY_Y\n2,1.0e6\n";
  s += fmt::format("*BOUNDARY_PRESCRIBED_MOTION_NODE\n{},1,2,3,0.01\n", grid.node(0, 0, 0));
  s += "*DEFINE_CURVE\n1\n0.0,0.0\n1.0e-5,1.0\n1.0,1.0\n";
  s += "*DEFINE_CURVE\n2\n0.0,1.0\n1.0e-5,0.0\n1.0,-1.0\n";
  s += "*DEFINE_CURVE\n3\n0.0,0.0\n1.0e-5,1.0\n1.0,1.0\n";
  s += fmt::format("*DATABASE_HISTORY_NODE\n{},{},{}\n", grid.node(4, 2, 2), grid.node(2, 1, 1),
                   grid.node(0, 0, 0));
  s += "*END\n";
  return s;
}

// The same with 10-node tetrahedra (ELFORM 16): stresses and plastic history at 4 points.
inline std::string tetrahedra16(double end_time) {
  std::string s = tetrahedra(end_time);
  const TetGrid grid = tet_box(4, 2, 2, 4.0, 2.0, 2.0, 0.15);
  s.replace(s.find(grid.text()), grid.text().size(), grid.text10());
  s.replace(s.find("*SECTION_SOLID\n1,13\n"), 20, "*SECTION_SOLID\n1,16\n");
  s.replace(s.find("nodal-pressure tetrahedra"), 25, "10-node tetrahedra");
  return s;
}

// The deformable deck with *MAT_JOHNSON_COOK and *EOS_LINEAR_POLYNOMIAL in both parts (part 2
// VP 1): plastic strain, temperature, EOS energy, relative volume and the spall flag are
// history that the dump must carry.
inline std::string johnson_cook(double end_time) {
  std::string s = deformable(end_time);
  auto replace = [&s](const std::string& from, const std::string& to) {
    s.replace(s.find(from), from.size(), to);
  };
  replace("*PART\nstiffness hourglass\n1,1,1,0,1\n", "*PART\nstiffness hourglass\n1,1,1,1,1\n");
  replace("*PART\nselective reduced\n2,2,1,0,2\n", "*PART\nselective reduced\n2,2,2,1,2\n");
  replace("*MAT_ELASTIC\n1,7.85e-9,210000.0,0.3\n",
          "*MAT_JOHNSON_COOK\n1,7.85e-9,80769.0\n100,200,0.3,0.02,1,1800,293,1\n4.5e8,-1e20,1\n"
          "*MAT_JOHNSON_COOK\n2,7.85e-9,80769.0,0,0,0,1\n100,200,0.3,0.02,1,1800,293,1\n"
          "4.5e8,-1e20,1\n*EOS_LINEAR_POLYNOMIAL\n1,0,175000.0,350000.0\n");
  return s;
}

// A spinning 3 x 2 x 2 block: x < 1 is a rigid part, the rest is deformable (ELFORM 1, viscous
// hourglass) and shares the interface nodes with it; the far face is a nodal rigid body. The
// rigid part gets a moment from a curve; *RIGID_BODY_UPDATE selects the node update (&type).
inline std::string spinning_rigid(double end_time, int update_type) {
  BoxMesh mesh;
  mesh.nx = 3;
  mesh.ny = 2;
  mesh.nz = 2;
  mesh.lx = 3.0;
  mesh.ly = 2.0;
  mesh.lz = 2.0;
  std::string s = "*KEYWORD\n*TITLE\nrestart: spinning rigid and deformable\n";
  s += fmt::format("*PARAMETER\nI type,{}\n*RIGID_BODY_UPDATE\n&type\n", update_type);
  s += fmt::format("*CONTROL_TERMINATION\n{},0\n*CONTROL_TIMESTEP\n0,0.5\n", end_time);
  s += output_cards(2e-7, 2e-6);
  s += mesh.keyword_text([](int i, int, int) { return i < 1 ? 1 : 2; });
  s += "*PART\nrigid hub\n1,1,1\n*PART\nelastic shaft\n2,1,2,0,1\n";
  s += "*SECTION_SOLID\n1,1\n";
  s += "*MAT_RIGID\n1,7.85e-9,210000.0,0.3\n*MAT_ELASTIC\n2,7.85e-9,210000.0,0.3\n";
  s += "*HOURGLASS\n1,1,0.1\n";
  s += node_set(5, mesh.face_x(3));
  s += "*CONSTRAINED_NODAL_RIGID_BODY\n7,0,5\n";
  // Spin about the block's long axis plus a sideways drift.
  s += "*INITIAL_VELOCITY_GENERATION\n0,2,3.0e5,0.0,200.0,0.0\n0.0,1.0,1.0,1.0,0.0,0.0\n";
  s += "*LOAD_RIGID_BODY\n1,6,1,2.0e4\n1,5,1,-1.0e4\n";
  s += "*DEFINE_CURVE\n1\n0.0,0.0\n1.0e-5,1.0\n1.0,1.0\n";
  s += fmt::format("*DATABASE_HISTORY_NODE\n{},{}\n", mesh.node_id(3, 2, 2), mesh.node_id(1, 1, 1));
  s += "*END\n";
  return s;
}

// A 2 x 1 x 1 block of 27-node Lagrange hexahedra (*CHANGE_P-ORDER 2), spinning and loaded.
inline std::string quadratic(double end_time) {
  BoxMesh mesh;
  mesh.nx = 2;
  mesh.lx = 2.0;
  std::string s = "*KEYWORD\n*TITLE\nrestart: p = 2\n";
  s += fmt::format("*CONTROL_TERMINATION\n{},0\n*CONTROL_TIMESTEP\n0,0.5\n", end_time);
  s += output_cards(2e-7, 2e-6);
  s += mesh.keyword_text(1);
  s += elastic_part(7.85e-9, 210000.0, 0.3, 1, 1);
  s += "*CHANGE_P-ORDER\nPART,1,2\n";
  s += "*INITIAL_VELOCITY_GENERATION\n0,2,1.0e5,500.0,0.0,0.0\n1.0,0.5,0.5,0.0,1.0,0.0\n";
  s += fmt::format("*LOAD_NODE_POINT\n{},3,1,20.0\n", mesh.node_id(2, 1, 1));
  s += "*DEFINE_CURVE\n1\n0.0,0.0\n1.0e-5,1.0\n1.0,1.0\n";
  s += fmt::format("*DATABASE_HISTORY_NODE\n{},{}\n", mesh.node_id(2, 1, 1), mesh.node_id(0, 0, 0));
  s += "*END\n";
  return s;
}

// A 4 x 4 mm steel plate of shells (0.2 mm) with beams along two edges (mm, t, s), spinning about
// its normal and drifting, bent by a corner force and a corner moment from curves: part 1
// (x < 2) ELFORM 2, *MAT_PIECEWISE_LINEAR_PLASTICITY (*MAT_024), stiffness hourglass IHQ 4
// (accumulated hourglass forces); part 2 ELFORM 2 with 5 Gauss points, IHQ 5,
// *MAT_PLASTIC_KINEMATIC with a back stress; part 3 integrated beams (ELFORM 1)
// *MAT_PLASTIC_KINEMATIC along y = 0; part 4 resultant beams (ELFORM 2) along y = 4. The spin (1e5
// rad/s) yields the plate in membrane, the loads bend it and turn the nodes: stresses, plastic
// strains and back stresses, hourglass forces, beam frames and resultants and the nodal angular
// velocities all cross the dump.
inline std::string shells_and_beams(double end_time, double dt2ms = 0.0) {
  ShellPlate plate;
  plate.nx = 4;
  plate.ny = 4;
  plate.lx = 4.0;
  plate.ly = 4.0;
  std::string s = "*KEYWORD\n*TITLE\nrestart: shells and beams\n";
  s += fmt::format("*CONTROL_TERMINATION\n{},0\n*CONTROL_TIMESTEP\n0,0.5,0,0.0,{}\n", end_time,
                   dt2ms);
  s += output_cards(2e-7, 2e-6);
  s += plate.nodes_text();
  s += "*ELEMENT_SHELL\n";
  int eid = 1;
  for (int j = 0; j < plate.ny; ++j)
    for (int i = 0; i < plate.nx; ++i) {
      s += fmt::format("{},{},{},{},{},{}\n", eid++, i < 2 ? 1 : 2, plate.node_id(i, j),
                       plate.node_id(i + 1, j), plate.node_id(i + 1, j + 1),
                       plate.node_id(i, j + 1));
    }
  s += "*ELEMENT_BEAM\n";
  for (int i = 0; i < plate.nx; ++i) {
    s += fmt::format("{},3,{},{}\n", 100 + i, plate.node_id(i, 0), plate.node_id(i + 1, 0));
    s += fmt::format("{},4,{},{}\n", 200 + i, plate.node_id(i, plate.ny),
                     plate.node_id(i + 1, plate.ny));
  }
  s += "*PART\nshells mat024 ihq4\n1,1,1,0,1\n*PART\nshells nip5 ihq5\n2,2,2,0,2\n";
  s += "*PART\nintegrated beams\n3,3,2\n*PART\nresultant beams\n4,4,3\n";
  s += "*SECTION_SHELL\n1,2,0.8333333333333334,3\n0.2,0.2,0.2,0.2\n";
  s += "*SECTION_SHELL\n2,2,0.8333333333333334,5\n0.2,0.2,0.2,0.2\n";
  s += "*SECTION_BEAM\n3,1,0.8333,2,0\n0.3,0.3,0.2,0.2\n";
  s += "*SECTION_BEAM\n4,2,0.8333\n0.06,2.0e-4,4.5e-4,0.0\n";
  s += "*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,7.85e-9,210000.0,0.3,0,0\n0,0,0,0,0\n"
       "0,0.01,0.02,0.05,0.1,0.2,0.5,1.0\n100,110,120,135,150,165,185,200\n";
  s += "*MAT_PLASTIC_KINEMATIC\n2,7.85e-9,210000.0,0.3,100.0,2000.0,0.5\n";
  s += "*MAT_ELASTIC\n3,7.85e-9,210000.0,0.3\n";
  s += "*HOURGLASS\n1,4,0.1\n2,5,0.1\n";
  s += "*INITIAL_VELOCITY_GENERATION\n0,2,1.0e5,1000.0,-500.0,200.0\n2.0,2.0,0.0,0.0,0.0,1.0\n";
  s += fmt::format("*LOAD_NODE_POINT\n{},3,1,5.0\n{},5,1,2.0\n{},6,2,-1.0\n",
                   plate.node_id(plate.nx, plate.ny), plate.node_id(plate.nx, 0),
                   plate.node_id(0, plate.ny));
  s += "*DEFINE_CURVE\n1\n0.0,0.0\n1.0e-5,1.0\n1.0,1.0\n";
  s += "*DEFINE_CURVE\n2\n0.0,1.0\n1.0e-5,0.0\n1.0,-1.0\n";
  s += fmt::format("*DATABASE_HISTORY_NODE\n{},{},{}\n", plate.node_id(plate.nx, plate.ny),
                   plate.node_id(2, 2), plate.node_id(0, 0));
  s += "*DATABASE_HISTORY_SHELL\n1,8,16\n*DATABASE_ELOUT\n2e-7\n";
  s += "*END\n";
  return s;
}

// The shells-and-beams deck with a strain criterion on the *MAT_024 shells (part 1): the
// integrated shell strain crosses the dump, and the elements whose effective strain reached
// EFFEPS by 20 us erode then (NCS 2 with FAILTM): the strain the dump carries decides which.
inline std::string shells_eroding_by_strain(double end_time, double effective_strain) {
  std::string s = shells_and_beams(end_time);
  s.replace(s.find("*END\n"), 5,
            fmt::format("*MAT_ADD_EROSION\n1,0,0,0,{},0,1,2\n0,0,0,0,0,0,0,2e-5\n*END\n",
                        effective_strain));
  return s;
}

// The shells-and-beams deck with part switching: part 2 (shells, NIP 5, IHQ 5, *MAT_003 with a
// back stress) and part 4 (resultant beams, sharing nodes with part 2) become one rigid body at
// 8 us (paired CODE 0 sets) and deformable again at 26 us, while part 1 (shells) and part 3
// (beams) stay deformable and attached to the body's nodes: the switching state, the frozen
// shell stresses and beam frames, and the body with its rotary inertia cross the dump taken in
// the rigid phase (12 us).
inline std::string shells_and_beams_switching(double end_time) {
  std::string s = shells_and_beams(end_time);
  s.insert(s.rfind("*END"),
           "*DEFORMABLE_TO_RIGID_AUTOMATIC\n10,0,8.0e-6,0,0,0,20,1\n0,0,0,0,2,0\n2\n4\n"
           "*DEFORMABLE_TO_RIGID_AUTOMATIC\n20,0,2.6e-5,0,0,0,10,-1\n0,0,0,0,0,2\n2\n4\n");
  return s;
}

}  // namespace rf::test::restart_decks
