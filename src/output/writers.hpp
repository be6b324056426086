// Result files. Names and columns are an interface (docs/output.md): change them only
// by adding columns at the end.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "solver/state.hpp"

namespace rf::output {

// One row of glstat.csv.
struct GlstatRow {
  double time = 0.0;
  double dt = 0.0;
  std::int64_t cycle = 0;
  double kinetic_energy = 0.0;
  double internal_energy = 0.0;  // elastic strain energy (excludes hourglass)
  double hourglass_energy = 0.0;
  double external_work = 0.0;  // loads + prescribed motion + SPC reactions
  double total_energy = 0.0;   // kinetic + internal + hourglass
  double energy_ratio = 1.0;   // total / (initial total + external work)
  double momentum[3] = {0, 0, 0};
  double angular_momentum[3] = {0, 0, 0};  // about the global origin
  double switch_energy = 0.0;              // kinetic energy removed by deformable-to-rigid switches
  double frozen_energy = 0.0;              // strain energy held by parts rigid by switching
  // The part of external_work done by rigid walls.
  double rigidwall_work = 0.0;
  // Minus the work of the contact forces (stored penalty energy + dissipation).
  double contact_energy = 0.0;
  double modal_energy = 0.0;       // elastic energy of flexible bodies' modes (in internal_energy)
  double damping_work = 0.0;       // the part of external_work done by *DAMPING_* (negative)
  double added_mass = 0.0;         // mass scaling: mass added to the deformable nodes so far
  double mass_scaling_work = 0.0;  // the part of external_work: 1/2 dm v^2 of mass added in the run
  double bulk_viscosity_energy = 0.0;  // dissipated by the bulk viscosity (not in internal)
  // Discrete elements (both in internal_energy): the energy springs hold relative to time zero
  // and the energy dampers have dissipated so far.
  double spring_energy = 0.0;
  double damper_energy = 0.0;
  // Element erosion (docs/materials.md): the work the deleted elements' forces did before they
  // left (not in internal_energy any more), the kinetic energy of the nodes removed with them
  // (not in kinetic_energy any more), and how many elements have eroded.
  double eroded_internal_energy = 0.0;
  double eroded_kinetic_energy = 0.0;
  double eroded_elements = 0.0;
};

// Plain CSV file with a fixed header; rows are buffered and reach the file whole (never a
// partial row, even when the process is ended by a second Ctrl-C); flushed at close. Numbers use
// %.9g or better so that histories can be differentiated downstream.
class CsvFile {
 public:
  CsvFile() = default;
  // continue_at < 0: a new file that starts with `header`. Otherwise the existing file is cut to
  // continue_at bytes and continued (restart: rows written after the dump are dropped); it must
  // exist and be at least that long.
  CsvFile(const std::filesystem::path& path, const std::string& header,
          std::int64_t continue_at = -1);
  CsvFile(const CsvFile&) = delete;
  CsvFile& operator=(const CsvFile&) = delete;
  CsvFile(CsvFile&& other) noexcept;
  CsvFile& operator=(CsvFile&& other) noexcept;
  ~CsvFile();
  // Appends line and a newline.
  void write_line(const std::string& line);
  // Appends text verbatim (one or more complete lines, each ending in '\n'); lets a writer
  // format a whole output time into one buffer and hand it over in a single call.
  void write_text(std::string_view text);
  void flush();
  // Flushes and returns the file's size: the cut point a restart dump records.
  std::int64_t flushed_size();
  bool is_open() const { return file_ != nullptr; }
  const std::filesystem::path& path() const { return path_; }

 private:
  void close() noexcept;
  void flush_pending();
  std::FILE* file_ = nullptr;
  std::filesystem::path path_;
  std::string pending_;  // whole rows not yet in the file
};

// Where a restart continues each CSV file: its size at the dump, or -1 to start it anew.
struct CsvContinuation {
  std::int64_t glstat = -1;
  std::int64_t nodout = -1;
  std::int64_t rbdout = -1;
  std::int64_t switches = -1;     // switch.csv
  std::int64_t sensor = -1;       // sensor.csv
  std::int64_t rwforc = -1;       // rwforc.csv
  std::int64_t rcforc = -1;       // rcforc.csv
  std::int64_t modal = -1;        // modal.csv
  std::int64_t matsum = -1;       // matsum.csv
  std::int64_t spcforc = -1;      // spcforc.csv
  std::int64_t elout = -1;        // elout.csv
  std::int64_t secforc = -1;      // secforc.csv
  std::int64_t elout_shell = -1;  // elout_shell.csv
  std::int64_t jntforc = -1;      // jntforc.csv
  std::int64_t swforc = -1;       // swforc.csv
  std::int64_t erosion = -1;      // erosion.csv
};

// Column headers, exactly as written (docs/output.md).
inline constexpr std::string_view kGlstatHeader =
    "time,dt,cycle,kinetic_energy,internal_energy,hourglass_energy,external_work,total_energy,"
    "energy_ratio,momentum_x,momentum_y,momentum_z,angular_momentum_x,angular_momentum_y,"
    "angular_momentum_z,switch_energy,frozen_energy,rigidwall_work,contact_energy,modal_energy,"
    "damping_work,added_mass,mass_scaling_work,bulk_viscosity_energy,spring_energy,damper_energy,"
    "eroded_internal_energy,eroded_kinetic_energy,eroded_elements";
// erosion.csv: one row per deleted element, in the order of deletion (docs/output.md).
inline constexpr std::string_view kErosionHeader = "time,part,element,family,criterion";
inline constexpr std::string_view kNodoutHeader = "time,node,x,y,z,vx,vy,vz,ax,ay,az";
inline constexpr std::string_view kRbdoutHeader =
    "time,body,mass,x,y,z,vx,vy,vz,ax,ay,az,wx,wy,wz,r11,r12,r13,r21,r22,r23,r31,r32,r33";

// One row of rbdout.csv: a rigid body at an output time t^n. Velocities are full-step values
// (means of the half steps), accelerations their difference quotients; w is in global axes
// and R (row-major r11..r33) maps the body's output axes to global axes.
struct RbdoutRow {
  double time = 0.0;
  std::int64_t body = 0;
  double mass = 0.0;
  std::array<double, 3> x{}, v{}, a{}, w{};
  std::array<double, 9> r{};
};

// rbdout.csv: one row per rigid body at each output time.
class RbdoutWriter {
 public:
  explicit RbdoutWriter(const std::filesystem::path& path, std::int64_t continue_at = -1);
  void write(const std::vector<RbdoutRow>& rows);
  void flush() { csv_.flush(); }
  std::int64_t flushed_size() { return csv_.flushed_size(); }

 private:
  CsvFile csv_;
};

inline constexpr std::string_view kRwforcHeader =
    "time,wall,normal_force,force_x,force_y,force_z,wall_displacement,wall_velocity,"
    "normal_impulse,work,segment_force_x,segment_force_y,segment_force_z";

// One row of rwforc.csv: a rigid wall at an output time t^n. The force is the one the wall
// applied to the model in the cycle at t^n (global axes); displacement and velocity are the
// wall's motion along its normal (moving walls; 0 for fixed ones), velocity as the mean of the
// half steps; impulse and work are totals since t = 0.
struct RwforcRow {
  double time = 0.0;
  std::int64_t wall = 0;
  double normal_force = 0.0;
  std::array<double, 3> force{};
  double displacement = 0.0;
  double velocity = 0.0;
  double normal_impulse = 0.0;
  double work = 0.0;
  // *RIGIDWALL_PLANAR_FORCES SSID: the part of `force` on the segment set's nodes (0 without).
  std::array<double, 3> segment_force{};
};

inline constexpr std::string_view kJntforcHeader =
    "time,joint,force_x,force_y,force_z,force_resultant,moment_x,moment_y,moment_z,"
    "moment_resultant,stiffness,phi,theta,psi,moment_phi,moment_theta,moment_psi,"
    "stiffness_elastic_energy,stiffness_dissipated_energy";

// swforc.csv: per spot weld and output time, the force it carries (normal: tension > 0 along
// N1 -> N2; shear: magnitude), its status (0 active, 1 failed, 2 deleted by NCSF, 3 merged into
// a rigid body by switching) and when it failed (-1: it has not).
inline constexpr std::string_view kSwforcHeader =
    "time,weld,normal_force,shear_force,status,failure_time";

// One row of jntforc.csv: a joint at an output time t^n. The force and moment the joint exerts
// on its body B (the nodes N2, N4, N6), global axes, from the last evaluation of the penalty
// springs (t^n); the moment is taken about the joint's first node pair (N1).
struct JntforcRow {
  double time = 0.0;
  std::int64_t joint = 0;
  std::array<double, 3> force{};
  std::array<double, 3> moment{};
  // The *CONSTRAINED_JOINT_STIFFNESS_GENERALIZED whose JID is this joint (0: none, and zeros):
  // its angles phi, theta, psi (radians), the moments it resists them with (the generalized
  // moments conjugate to the angles), its elastic energy and the energy it has dissipated.
  std::int64_t stiffness = 0;
  std::array<double, 3> angle{};
  std::array<double, 3> stiffness_moment{};
  double elastic_energy = 0.0;
  double dissipated_energy = 0.0;
};

// The jntforc.csv lines of one output time (src/output/jntforc_writer.cpp).
std::string jntforc_text(const std::vector<JntforcRow>& rows);

inline constexpr std::string_view kRcforcHeader =
    "time,contact,slave_fx,slave_fy,slave_fz,master_fx,master_fy,master_fz,contact_nodes";

// One row of rcforc.csv: a contact interface at an output time t^n. slave_force is the resultant
// of the contact forces on the slave (SURFA) side's nodes at the last evaluation (t^n, global
// axes); the master side's resultant is its negative (written too). contact_nodes counts the
// nodes in contact over all passes.
struct RcforcRow {
  double time = 0.0;
  std::int64_t contact = 0;
  std::array<double, 3> slave_force{};
  std::int64_t active_nodes = 0;
};

// rcforc.csv: one row per contact interface at each output time (src/output/rcforc_writer.cpp).
class RcforcWriter {
 public:
  explicit RcforcWriter(const std::filesystem::path& path, std::int64_t continue_at = -1);
  void write(const std::vector<RcforcRow>& rows);
  void flush() { csv_.flush(); }
  std::int64_t flushed_size() { return csv_.flushed_size(); }

 private:
  CsvFile csv_;
};

// rwforc.csv: one row per rigid wall at each output time (src/output/rwforc_writer.cpp).
class RwforcWriter {
 public:
  explicit RwforcWriter(const std::filesystem::path& path, std::int64_t continue_at = -1);
  void write(const std::vector<RwforcRow>& rows);
  void flush() { csv_.flush(); }
  std::int64_t flushed_size() { return csv_.flushed_size(); }

 private:
  CsvFile csv_;
};

inline constexpr std::string_view kSwitchHeader =
    "time,swset,direction,parts,kinetic_energy_before,kinetic_energy_after,momentum_x,"
    "momentum_y,momentum_z";

// One row of switch.csv: a part switch event. `parts` are written space-separated.
struct SwitchRow {
  double time = 0.0;
  std::int64_t swset = 0;
  bool to_rigid = true;
  std::vector<std::int64_t> parts;
  double kinetic_energy_before = 0.0, kinetic_energy_after = 0.0;
  std::array<double, 3> momentum{};
};

// switch.csv: one row per switch event, written when it happens.
class SwitchWriter {
 public:
  explicit SwitchWriter(const std::filesystem::path& path, std::int64_t continue_at = -1);
  void write(const SwitchRow& row);
  void flush() { csv_.flush(); }
  std::int64_t flushed_size() { return csv_.flushed_size(); }

 private:
  CsvFile csv_;
};

class GlstatWriter {
 public:
  explicit GlstatWriter(const std::filesystem::path& path, std::int64_t continue_at = -1);
  void write(const GlstatRow& row);
  void flush() { csv_.flush(); }
  std::int64_t flushed_size() { return csv_.flushed_size(); }

 private:
  CsvFile csv_;
};

// nodout.csv: time,node,x,y,z,vx,vy,vz,ax,ay,az for every history node at each output time.
class NodoutWriter {
 public:
  NodoutWriter(const std::filesystem::path& path, std::vector<std::int32_t> dense_nodes,
               std::int64_t continue_at = -1);
  void write(const solver::State& state);
  // Writes the full-step velocity v^n = (v^{n-1/2} + v^{n+1/2}) / 2, the solver's best
  // estimate at the output time, from the previous half-step velocity and state.nodes.v.
  void write(const solver::State& state, const solver::Vec3Array& v_previous);
  void flush() { csv_.flush(); }
  std::int64_t flushed_size() { return csv_.flushed_size(); }

 private:
  void write_rows(const solver::State& state, const solver::Vec3Array* v_previous);
  CsvFile csv_;
  std::vector<std::int32_t> nodes_;
};

// VTK linear cell types used for solids.
enum class VtkCellType : std::uint8_t {
  kTetra = 10,
  kHexahedron = 12,
  kWedge = 13,
  kPyramid = 14,
  kQuadraticTetra = 24,      // VTK_QUADRATIC_TETRA: 10 points, LS-DYNA's ELFORM 16 node order
  kLagrangeHexahedron = 72,  // VTK_LAGRANGE_HEXAHEDRON: (p+1)^3 points, order from the count
};

// Position of tensor node (i, j, k) of an order-p hexahedron in VTK's Lagrange hexahedron point
// order: 8 corners, then the edge, face and interior nodes (vtkHigherOrderHexahedron's
// PointIndexFromIJK for equal orders in the three directions).
int vtk_lagrange_hex_index(int i, int j, int k, int p);

// A solid element as VTK wants it: cell type and the distinct nodes in VTK order.
struct VtkCell {
  VtkCellType type = VtkCellType::kHexahedron;
  int node_count = 8;
  std::array<std::int32_t, 8> nodes{};
};

// Maps an 8-node LS-DYNA solid connectivity (possibly degenerate by repeated nodes) to a
// VTK cell: N1..N8 all distinct -> hexahedron; N1 N2 N3 N4 N4 N4 N4 N4 or
// N1 N2 N3 N3 N4 N4 N4 N4 -> tetra; N1 N2 N3 N4 N5 N5 N6 N6 -> wedge; N1 N2 N3 N4 N5 N5 N5 N5
// -> pyramid. Any other repetition is kept as a (degenerate) hexahedron.
VtkCell vtk_cell_from_solid(const std::int32_t* conn8);

// Co-rotational frame of shell element `conn` (4 dense nodes) at the current configuration, rows
// e1 e2 e3, the frame in which the shell kernel keeps its stresses.
std::array<std::array<double, 3>, 3> shell_frame(const solver::NodalState& nodes,
                                                 const std::int32_t* conn);
// A shell point's co-rotational stress (xx yy xy yz zx, sigma_zz = 0) in global axes, Voigt order
// xx yy zz xy yz zx.
void shell_stress_to_global(const double* local, const std::array<std::array<double, 3>, 3>& frame,
                            double out[6]);
// Von Mises stress of a Voigt stress (xx,yy,zz,xy,yz,zx).
double von_mises(const double* voigt6);
// Cauchy stress of element e of a block for output: the mean over its integration points
// (zero before the first force evaluation, when the block has no stress storage yet).
void element_mean_stress(const element::HexBlock& block, std::size_t e, double out[6]);
// Pressure -(xx + yy + zz) / 3 (positive in compression, as LS-DYNA).
double pressure_of(const double* voigt6);
// Principal stresses of a Voigt stress, largest first.
std::array<double, 3> principal_stresses(const double* voigt6);

// A rigid wall drawn in walls_NNNN.vtu: a quadrilateral patch of its plane (corners in order
// around the patch) and the force it applied at the frame's time.
struct WallPatch {
  std::int64_t id = 0;
  std::array<std::array<double, 3>, 4> corners{};
  double normal_force = 0.0;
};

// How a frame shows its nodes. Frames of a run: the points are the current coordinates x
// (scale 1). Mode shapes: the points are x0 + scale (x - x0), so that a shape stored with its
// true (mass-normalised) size is drawn at a visible size; the scale is written as field data
// `scale_name` so that Warp By Vector with -scale on `displacement` recovers x0.
struct FrameOptions {
  double point_displacement_scale = 1.0;
  std::string scale_name;  // empty: no field data for the scale
  // Rigid walls: written as walls_NNNN.vtu beside frame NNNN (and listed in walls.pvd) when
  // not null.
  const std::vector<WallPatch>* walls = nullptr;
};

// frames.pvd + frames_NNNN.vtu (VTK XML UnstructuredGrid, appended raw binary, Float64/Int64)
// per frame: point data displacement, velocity, node_id; cell data stress (6 components, Voigt
// xx,yy,zz,xy,yz,zx, mean over integration points), effective_stress (von Mises), part_id,
// element_id, pressure, principal_stress. Creates the directory if needed. (Until issue 20 the
// series was called d3plot.pvd; that name now belongs to the LS-DYNA binary database.)
class FieldWriter {
 public:
  explicit FieldWriter(const std::filesystem::path& directory, std::string stem = "frames");
  void write_frame(const solver::State& state);
  void write_frame(const solver::State& state, const FrameOptions& options);
  // Writes/refreshes the .pvd collection; called after every frame so a crashed run is readable.
  void write_collection() const;
  int frames() const { return static_cast<int>(times_.size()); }
  // The frames written so far (time and file name); a restart continues from them.
  const std::vector<double>& frame_times() const { return times_; }
  const std::vector<std::string>& frame_files() const { return files_; }
  void resume(std::vector<double> times, std::vector<std::string> files);
  // Name of the walls file that goes with frame file `frame_file` (frames_0003.vtu ->
  // walls_0003.vtu).
  static std::string walls_file_of(const std::string& frame_file);

 private:
  void write_walls(const std::vector<WallPatch>& walls, double time, const std::string& file);
  void write_walls_collection() const;
  bool walls_ = false;  // a walls series is written (set by the first frame with walls)
  std::filesystem::path directory_;
  std::string stem_;
  std::vector<double> times_;
  std::vector<std::string> files_;
};

struct RunSummary {
  std::string status;   // "normal termination" or "error termination"
  std::string message;  // reason when not normal
  double final_time = 0.0;
  std::int64_t cycles = 0;
  std::int64_t nodes = 0;
  std::int64_t elements = 0;
  double wall_seconds = 0.0;
  double ns_per_element_cycle = 0.0;
  int threads = 1;  // per rank
  int ranks = 1;    // MPI ranks of a distributed run (docs/parallel.md)
  std::vector<std::string> warnings;
  // --ignore-unsupported: the physics keywords skipped ("file:line: *KEYWORD ..."); written as
  // "ignore_unsupported": true and "ignored_unsupported_keywords" only when the flag was given.
  bool ignore_unsupported = false;
  std::vector<std::string> ignored_unsupported;
};

void write_run_json(const std::filesystem::path& path, const RunSummary& summary);

}  // namespace rf::output
