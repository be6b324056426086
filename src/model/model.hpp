// The model: what a keyword deck describes, keyed by the user's IDs, exactly as read.
// Nothing here is solver state; solver/state.hpp turns a Model into dense arrays.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace rf::model {

using Id = std::int64_t;

// Where a definition came from, so that errors found after reading can still name
// file, line and keyword.
struct SourceLocation {
  std::string file;
  int line = 0;
  std::string keyword;
};

struct Node {
  Id id = 0;
  std::array<double, 3> x{};
  int tc = 0;  // translational constraint code from *NODE (0..7)
  int rc = 0;  // rotational constraint code (ignored for solids)
};

// 8-node hexahedron as written in *ELEMENT_SOLID. Degenerate shapes (wedge, pyramid,
// tetrahedron) are written with repeated node IDs per the LS-DYNA conventions.
// A 10-node tetrahedron (N1..N10 on the second card, for *SECTION_SOLID ELFORM 16) keeps its
// corners as the degenerate hexahedron N1 N2 N3 N4 N4 N4 N4 N4 in `nodes` and its mid-side nodes
// N5..N10 (edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4) in `midside`; `ten_node` says which it is.
struct SolidElement {
  Id id = 0;
  Id pid = 0;
  std::array<Id, 8> nodes{};
  std::array<Id, 6> midside{};
  bool ten_node = false;
  SourceLocation where;
};

// Mass properties given instead of computed from the elements: *PART_INERTIA and
// *CONSTRAINED_NODAL_RIGID_BODY_INERTIA share this layout.
struct RigidInertia {
  std::array<double, 3> xc{};  // centre of mass; the coordinates of NODEID when nodeid != 0
  double tm = 0.0;             // translational mass
  int ircs = 0;                // 0: tensor in global axes; 1: principal moments, see axes
  Id nodeid = 0;               // node at the centre of mass (0: none)
  // IXX IXY IXZ IYY IYZ IZZ as written. With IRCS 1 only IXX, IYY, IZZ (the principal
  // moments about principal_axes rows 0, 1, 2) are meaningful.
  std::array<double, 6> inertia{};
  std::array<double, 3> vt{};  // initial translational velocity VTX VTY VTZ
  std::array<double, 3> vr{};  // initial angular velocity VRX VRY VRZ (rad/time, global)
  // IRCS 1 card as written: local x axis XL YL ZL, in-plane vector XLIP YLIP ZLIP, or CID.
  std::array<double, 3> xl{};
  std::array<double, 3> xlip{};
  Id cid = 0;
  // Rows: principal directions in global coordinates, resolved after reading (identity
  // for IRCS 0).
  std::array<std::array<double, 3>, 3> principal_axes{
      {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};
  SourceLocation where;  // the XC YC ZC TM card
};

struct Part {
  Id id = 0;
  std::string title;
  Id secid = 0;
  Id mid = 0;
  Id eosid = 0;
  Id hgid = 0;
  // IMPETUS *PART alpha_max: higher-order faces meeting at less than this angle (degrees) are
  // smoothed into one curved surface. 0: none.
  double smoothing_angle = 0.0;
  SourceLocation where;
  std::optional<RigidInertia> inertia;  // *PART_INERTIA
};

struct SectionSolid {
  Id id = 0;
  int elform = 1;  // 1: one-point reduced + hourglass control; 2: selective-reduced 2x2x2
                   // 10: one-point 4-node tetrahedron (constant strain); 13: nodal-pressure
                   // tetrahedron; 16: 10-node quadratic tetrahedron, 4 points
  SourceLocation where;
};

// *ELEMENT_SHELL (N3 == N4: triangle). Nodal thicknesses from _THICKNESS (0: the section's).
struct ShellElement {
  Id id = 0;
  Id pid = 0;
  std::array<Id, 4> nodes{};
  std::array<double, 4> thickness{};
  SourceLocation where;
};

// *SECTION_SHELL as far as it is supported (docs/keywords.md lists the accepted values).
struct SectionShell {
  Id id = 0;
  int elform = 2;       // 2: Belytschko-Lin-Tsay; 16: fully integrated
  double shrf = 1.0;    // transverse shear factor (LS-DYNA default 1; 5/6 is the usual choice)
  int nip = 2;          // points through the thickness, 1..10
  int quadrature = -1;  // QR as written; -1 blank (then *CONTROL_SHELL INTGRD decides)
  std::array<double, 4> t{};  // T1..T4
  double nloc = 0.0;          // reference surface: 1 top, 0 mid, -1 bottom (only 0 supported)
  SourceLocation where;
};

// *ELEMENT_BEAM: two nodes and the third (orientation) node or vector.
struct BeamElement {
  Id id = 0;
  Id pid = 0;
  std::array<Id, 3> nodes{};                         // N1 N2 N3 (N3 0: default orientation)
  std::optional<std::array<double, 3>> orientation;  // _ORIENTATION VX VY VZ
  SourceLocation where;
};

// *SECTION_BEAM as far as it is supported.
struct SectionBeam {
  Id id = 0;
  int elform = 1;  // 1 Hughes-Liu, 2 Belytschko-Schwer resultant, 3 truss
  double shrf = 1.0;
  int cst = 0;                                              // 0 rectangular, 1 tubular (ELFORM 1)
  double ts1 = 0.0, ts2 = 0.0, tt1 = 0.0, tt2 = 0.0;        // ELFORM 1
  double a = 0.0, iss = 0.0, itt = 0.0, j = 0.0, sa = 0.0;  // ELFORM 2 (and A for 3)
  SourceLocation where;
};

// *ELEMENT_DISCRETE: a spring or damper between two nodes, acting along the current N1 -> N2
// line (VID 0, the only orientation supported).
struct DiscreteElement {
  Id id = 0;
  Id pid = 0;
  std::array<Id, 2> nodes{};
  double scale = 1.0;   // S: scale factor on the force
  double offset = 0.0;  // OFFSET: initial elongation (positive: tension at time zero)
  SourceLocation where;
};

// *SECTION_DISCRETE as far as it is supported: DRO 0 (translational), no clearance, failure or
// deflection limits, no dynamic magnification.
struct SectionDiscrete {
  Id id = 0;
  SourceLocation where;
};

// *CONTROL_CONTACT: the fields that change the physics of our contacts (the others are accepted
// where they cannot change it and refused where they would, io/keyword/handlers_contact.cpp).
struct ContactControl {
  double slsfac = 0.1;  // scale of the SOFT = 0 penalty stiffness (contact/contact.cpp)
  // PENOPT: which side's SOFT = 0 stiffness a pair takes: 1 the smaller of the master segment's
  // and the slave node's (0 reads as 1), 2 the master segment's, 3 the slave node's.
  int penopt = 1;
  // THKCHG: 1 (2) asks the contacts to follow the shells' thickness change. Our contacts keep the
  // initial thickness offset (THKCHG 0, LS-DYNA's default); refused with ISTUPD != 0.
  int thkchg = 0;
  SourceLocation where;
};

// *CONTROL_SHELL fields that change the physics (the others are accepted at their defaults).
struct ShellControl {
  int theory = 2;  // default ELFORM of *SECTION_SHELL ELFORM 0
  int bwc = 2;     // 1: Belytschko-Wong-Chiang warping correction on
  int istupd = 0;  // thickness update: 0 none, 1 membrane straining, 4 plastic strains only
  int intgrd = 0;  // 0 Gauss, 1 Lobatto (NIP 3..10)
  int miter = 1;   // plane-stress plasticity: 1, 2 iterative
  int proj = 0;
  double rotascl = 1.0;  // rotary inertia scale
  SourceLocation where;
};

// Material cards. Each kind is its own struct; the variant-like tag keeps dispatch out of
// per-element loops (the solver groups elements by material kind once).
enum class MaterialKind {
  Elastic,
  Rigid,
  PlasticKinematic,
  PiecewiseLinearPlasticity,
  MooneyRivlinRubber,    // *MAT_027
  OgdenRubber,           // *MAT_077_O
  ThreeParameterBarlat,  // *MAT_036 (shells only)
  JohnsonCook,           // *MAT_015 (solids; pressure from *EOS_ on the part, or K from E, PR)
  // Discrete-element materials (*ELEMENT_DISCRETE parts only, docs/elements.md): force laws,
  // not stress laws; they carry K, DC or LCD below and no density.
  SpringElastic,           // *MAT_SPRING_ELASTIC (S01): F = K (elongation)
  DamperViscous,           // *MAT_DAMPER_VISCOUS (S02): F = DC (elongation rate)
  SpringNonlinearElastic,  // *MAT_SPRING_NONLINEAR_ELASTIC (S04): F = curve LCD (elongation)
};

// True for the materials of discrete elements (springs and dampers).
inline bool is_discrete_material(MaterialKind kind) {
  return kind == MaterialKind::SpringElastic || kind == MaterialKind::DamperViscous ||
         kind == MaterialKind::SpringNonlinearElastic;
}

// The plasticity fields of *MAT_PLASTIC_KINEMATIC (003) and *MAT_PIECEWISE_LINEAR_PLASTICITY
// (024) as read; curves are resolved (and checked) when the solver state is built.
struct PlasticCard {
  double sigy = 0.0;
  double etan = 0.0;
  double beta = 0.0;  // 003 only
  double c = 0.0;     // SRC (003) / C (024)
  double p = 0.0;     // SRP (003) / P (024)
  double fail = 0.0;  // FS (003) / FAIL (024); 0: no failure
  double tdel = 0.0;  // TDEL (024): element step below which the element is deleted; 0: never
  SourceLocation fail_where;  // the card of FS / FAIL (for errors of the failure criterion)
  int vp = 0;
  Id lcss = 0;              // 024
  Id lcsr = 0;              // 024
  std::vector<double> eps;  // 024 EPS1..: the table's points (may be empty)
  std::vector<double> es;
  SourceLocation card2;  // where the second card is (C, P, LCSS, LCSR, VP)
  SourceLocation card3;  // EPS card (024)
};

// *MAT_ADD_EROSION (cards 1-2; the damage, forming-limit and later cards are refused when set):
// failure criteria evaluated at every integration point after its stress update. A criterion
// is on when its value is nonzero and differs from EXCL (LS-DYNA's rule). Signs as LS-DYNA:
// pressure p = -tr(sigma)/3 (positive in compression).
struct AddErosion {
  Id mid = 0;
  std::optional<double> mxpres;  // fail when p >= MXPRES
  std::optional<double> mnpres;  // fail when p <= MNPRES
  std::optional<double> sigp1;   // fail when the largest principal stress >= SIGP1
  std::optional<double> sigvm;   // fail when the von Mises stress >= SIGVM
  std::optional<double> voleps;  // fail when ln(V/V0) >= VOLEPS (> 0) or <= VOLEPS (< 0)
  // Strain criteria on the logarithmic principal strains e1 >= e2 >= e3 (docs/materials.md):
  std::optional<double> mxeps;   // fail when e1 >= MXEPS (> 0)
  std::optional<double> mneps;   // fail when e3 <= MNEPS (< 0)
  std::optional<double> effeps;  // fail when sqrt(2/3 e':e') >= EFFEPS (> 0)
  std::optional<double> epssh;   // fail when (e1 - e3) / 2 >= EPSSH (> 0)
  std::optional<double> failtm;  // fail when the time >= FAILTM
  // Tuler-Butcher: fail when int_0^t max(0, sigma_1 - SIGTH)^2 dt >= IMPULSE (sigma_1 the
  // largest principal stress of the point); on when IMPULSE is.
  std::optional<double> impulse;
  double sigth = 0.0;
  double numfip = 1.0;  // failed points before deletion (< 0 shells: percentage)
  int ncs = 1;          // criteria a point must meet at once
  SourceLocation where;
};

// The rubber constants of *MAT_MOONEY-RIVLIN_RUBBER (027) and *MAT_OGDEN_RUBBER (077_O) as read
// (E of the Material is set to the equivalent small-strain Young's modulus 2 G (1 + PR)).
struct RubberCard {
  double a = 0.0, b = 0.0;  // 027
  int terms = 0;            // 077_O: number of nonzero (MU, ALPHA) pairs
  std::array<double, 8> mu{};
  std::array<double, 8> alpha{};
};

// *MAT_3-PARAMETER_BARLAT (036) as read (curves resolved when the solver state is built,
// material/plastic_setup.cpp).
struct BarlatCard {
  int hr = 1;                              // hardening rule: 1 linear, 2 power law, 3 curve
  double p1 = 0.0, p2 = 0.0;               // HR 1: ETAN, SIGY; HR 2: k, n
  double m = 0.0;                          // yield function exponent M
  double r00 = 0.0, r45 = 0.0, r90 = 0.0;  // or AB, CB, HB with PB > 0
  double pb = 0.0;                         // > 0: a, c, h, p given directly
  Id lcid = 0;                             // HR 3
  double e0 = 0.0, spi = 0.0;              // HR 2
  int aopt = 0;                            // 0, 2, 3
  std::array<double, 3> a{};               // AOPT 2
  std::array<double, 3> v{};               // AOPT 3
  double beta = 0.0;                       // degrees, AOPT 0 and 3
  SourceLocation card2;                    // M R00 R45 R90 LCID E0 SPI
  SourceLocation card3;                    // AOPT ...
  SourceLocation card4;                    // A1 A2 A3
  SourceLocation card5;                    // V1 V2 V3 BETA
};

// The fields of *MAT_JOHNSON_COOK (015) as read (G is the Material's shear modulus; E and PR of
// the Material are those of the card, 0 when blank).
struct JohnsonCookCard {
  double g = 0.0;
  int vp = 0;
  double a = 0.0, b = 0.0, n = 0.0, c = 0.0, m = 0.0;
  double tm = 0.0, tr = 0.0, epso = 0.0;
  double cp = 0.0, pc = 0.0;
  int spall = 2;  // 1 pressure cutoff, 2 principal stress spall, 3 hydrostatic spall
  // Fracture (Johnson & Cook 1985): D1..D5, EROD (0: a failed element erodes), EFMIN.
  std::array<double, 5> d{};
  double erod = 0.0;
  double efmin = 1e-6;
  bool fractures() const { return d[0] != 0.0 || d[1] != 0.0; }
  bool erodes() const { return fractures() && erod == 0.0; }
};

struct Material {
  Id id = 0;
  MaterialKind kind = MaterialKind::Elastic;
  std::string keyword;  // e.g. "*MAT_ELASTIC"
  double rho = 0.0;
  double e = 0.0;
  double pr = 0.0;
  // *MAT_RIGID card 2: CMO 1 constrains the body globally with CON1 (translations) and
  // CON2 (rotations), codes 0..7 as on *NODE TC/RC. Zero for elastic materials.
  double cmo = 0.0;
  double con1 = 0.0;
  double con2 = 0.0;
  // CMO -1: constraints in a local system. CON1 is then the *DEFINE_COORDINATE_ ID (fixed in
  // time) copied to cmo_cid, and CON2 the six-digit code 'xyzXYZ' (translations x y z, then
  // rotations x y z of that system; a 1 digit constrains), decoded into cmo_local_fix.
  Id cmo_cid = 0;
  std::array<bool, 6> cmo_local_fix{};
  // *MAT_RIGID card 3 (output orientation only). Either LCO, a coordinate system ID (when
  // only the first field is given), or two body-fixed vectors a (A1..A3) and v (V1..V3).
  Id lco = 0;
  bool has_output_vectors = false;
  std::array<double, 3> output_a{};
  std::array<double, 3> output_v{};
  PlasticCard plastic;           // PlasticKinematic and PiecewiseLinearPlasticity
  RubberCard rubber;             // MooneyRivlinRubber and OgdenRubber
  BarlatCard barlat;             // ThreeParameterBarlat
  JohnsonCookCard johnson_cook;  // JohnsonCook
  // Discrete materials: K (S01, force per elongation), DC (S02, force per elongation rate),
  // LCD (S04, force vs elongation curve).
  double spring_k = 0.0;
  double damper_dc = 0.0;
  Id lcd = 0;
  SourceLocation where;
};

// *DEFINE_COORDINATE_SYSTEM / _VECTOR / _NODES. All are fixed in time.
enum class CoordinateKind { System, Vector, Nodes };

struct CoordinateSystem {
  Id id = 0;
  CoordinateKind kind = CoordinateKind::System;
  std::array<double, 3> origin{};
  // Rows: local x, y, z unit vectors in global coordinates (orthonormal, right-handed).
  // For _NODES they are computed from the node coordinates after the deck is read.
  std::array<std::array<double, 3>, 3> axes{{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};
  std::array<Id, 3> nodes{};  // _NODES: N1 (origin), N2 (along axis dir), N3 (in plane)
  char dir = 'X';             // _NODES: axis that points from N1 to N2
  SourceLocation where;
};

// *DEFINE_VECTOR: a direction from tail to head, in coordinate system cid.
struct Vector {
  Id id = 0;
  std::array<double, 3> tail{};
  std::array<double, 3> head{};
  Id cid = 0;
  std::array<double, 3> direction{};  // unit vector, global; resolved after reading
  SourceLocation where;
};

struct Hourglass {
  Id id = 0;
  int ihq = 0;      // 0: use *CONTROL_HOURGLASS default
  double qm = 0.1;  // hourglass coefficient
  // Bulk viscosity coefficients of the parts that use this card; NaN (field blank): the
  // *CONTROL_BULK_VISCOSITY value (docs/keywords.md).
  double q1 = std::numeric_limits<double>::quiet_NaN();
  double q2 = std::numeric_limits<double>::quiet_NaN();
  double qb = 0.0;
  double qw = 0.0;
  SourceLocation where;
};

// Curve with *DEFINE_CURVE scaling already stored separately so that errors and output
// can refer to the raw points. value(t) = SFO * f(t / SFA - OFFA) + OFFO, as LS-DYNA defines.
class ArgumentFunction;  // model/function.hpp

struct Curve {
  Id id = 0;
  int sidr = 0;
  double sfa = 1.0;
  double sfo = 1.0;
  double offa = 0.0;
  double offo = 0.0;
  std::vector<double> abscissa;
  std::vector<double> ordinate;
  // *DEFINE_CURVE_FUNCTION: f(time) instead of points (model/function.hpp), with the same
  // SFA SFO OFFA OFFO.
  std::shared_ptr<const ArgumentFunction> function;
  std::string function_text;
  SourceLocation where;
};

// *DEFINE_TABLE (and _2D): curves indexed by a value, e.g. hardening curves by strain rate for
// *MAT_024 LCSS. values[i] (raw, before SFA/OFFA) belongs to curves[i]. A plain *DEFINE_TABLE
// takes the *DEFINE_CURVE keywords that follow it, in order; _2D names them (LCID column).
struct Table {
  Id id = 0;
  double sfa = 1.0;
  double offa = 0.0;
  std::vector<double> values;
  std::vector<Id> curves;
  SourceLocation where;
};

// IMPETUS *FUNCTION: an expression of time t, parameters already substituted. `evaluator` is
// compiled when the deck is read (model/function.hpp), so a bad expression is an input error
// located at its card.
class ExpressionFunction;
struct Function {
  Id id = 0;
  std::string expression;
  std::shared_ptr<const ExpressionFunction> evaluator;
  SourceLocation where;
};

struct NodeSet {
  Id id = 0;
  std::vector<Id> nodes;
  SourceLocation where;
};

struct PartSet {
  Id id = 0;
  std::vector<Id> parts;
  SourceLocation where;
};

// *SET_SOLID, *SET_SHELL, *SET_BEAM: elements of one family by ID (*DATABASE_HISTORY_..._SET).
struct SolidSet {
  Id id = 0;
  std::vector<Id> elements;
  SourceLocation where;
};

struct SegmentSet {
  Id id = 0;
  std::vector<std::array<Id, 4>> segments;
  SourceLocation where;
};

// Which entity a boundary condition or load addresses. Geometry: the nodes of the model surface
// picked by an IMPETUS *GEOMETRY_SEED_COORDINATE (resolved on the solver's mesh, so nodes that
// *CHANGE_P-ORDER adds on those faces are included).
enum class Target { Node, NodeSet, Part, PartSet, All, Geometry };

// *GEOMETRY_SEED_COORDINATE: the boundary surface of the mesh that contains the face nearest
// to the point, grown across edges where neighbouring faces turn by less than the feature angle.
struct GeometrySeed {
  Id id = 0;
  std::array<double, 3> point{};
  double feature_angle_deg = 45.0;
  Id pid = 0;  // restricts the search to this part (0: all)
  SourceLocation where;
};

// *CHANGE_P-ORDER (IMPETUS; also accepted in LS-DYNA decks): interpolation order of the
// hexahedra of a part, part set or all parts.
struct POrderChange {
  Target target = Target::All;
  Id id = 0;
  int order = 1;
  SourceLocation where;
};

// A cylinder a mesh generator produced (*COMPONENT_CYLINDER): nodes that *CHANGE_P-ORDER
// creates on its mantle are placed on the exact surface, not on the flat facets.
struct CylinderSurface {
  Id pid = 0;
  std::array<double, 3> p1{};  // centre of one end
  std::array<double, 3> p2{};  // centre of the other end
  double radius = 0.0;
  double facet_angle_deg = 0.0;  // angle between neighbouring mantle faces of the linear mesh
};

struct Spc {
  Target target = Target::Node;
  Id id = 0;                      // node or node-set ID
  std::array<bool, 3> fix{};      // DOFX DOFY DOFZ
  std::array<bool, 3> fix_rot{};  // read, not used by solids
  Id cid = 0;
  SourceLocation where;
};

// *BOUNDARY_PRESCRIBED_MOTION_NODE/_SET.
struct PrescribedMotion {
  Target target = Target::Node;
  Id id = 0;
  int dof = 1;  // 1,2,3 translation x,y,z; -1..-3 the same with the curve reversed... see docs
  int vad = 0;  // 0 velocity, 1 acceleration, 2 displacement
  // DOF 9, 10, 11: rotation about an axis parallel to x, y, z through the point whose two other
  // coordinates are OFFSET1, OFFSET2 (DOF 9: y, z; 10: z, x; 11: x, y), value in radians.
  double offset1 = 0.0;
  double offset2 = 0.0;
  Id lcid = 0;
  Id function = 0;  // IMPETUS *FUNCTION ID used instead of a curve (lcid 0)
  double sf = 1.0;
  Id vid = 0;
  double death = 1e28;
  double birth = 0.0;
  SourceLocation where;
};

struct InitialVelocity {
  // A single generated velocity field: v = v_trans + omega * axis x (x - point).
  Target target = Target::Node;
  Id id = 0;                  // node, node set, part or part set; 0 with All
  std::array<double, 3> v{};  // translational velocity
  std::array<double, 3> w{};  // *INITIAL_VELOCITY_NODE VXR VYR VZR: nodes with rotations only
  double omega = 0.0;         // rad/time about axis through point
  std::array<double, 3> point{};
  std::array<double, 3> axis{};
  std::vector<Id> exempt_nodes;  // *INITIAL_VELOCITY IRIGID/NSIDEX exemptions
  int irigid = 0;                // IRIGID as written (-1, 0, 1); see docs/keywords.md
  int phase = 0;  // _GENERATION PHASE: 0 after dynamic relaxation, 1 before (not supported)
  SourceLocation where;
};

// *LOAD_NODE_POINT/_SET: a force (DOF 1-3) or a moment (DOF 5-7, nodes with rotations only)
// on each node of the target.
struct NodalLoad {
  Target target = Target::Node;
  Id id = 0;
  int dof = 1;  // 1,2,3 force x,y,z; 5,6,7 moment about x,y,z
  Id lcid = 0;
  double sf = 1.0;
  SourceLocation where;
};

// A follower pressure p(t) = SF curve(t - AT) for t >= AT (zero before) on quadrilateral
// segments (N3 = N4: triangles); positive pressure acts against the segment normal of the
// right-hand rule N1 -> N2 -> N3 (solver/pressure_loads.hpp). *LOAD_SEGMENT gives the nodes,
// *LOAD_SEGMENT_SET a *SET_SEGMENT, *LOAD_SHELL_ELEMENT a shell (its nodes in element order),
// *LOAD_SHELL_SET a *SET_SHELL.
enum class PressureTarget { Segment, SegmentSet, Shell, ShellSet };
struct PressureLoad {
  PressureTarget target = PressureTarget::Segment;
  Id id = 0;                  // segment set, shell or shell set ID (not for Segment)
  std::array<Id, 4> nodes{};  // Segment: N1..N4 (N4 = N3 for a triangle)
  Id lcid = 0;
  double sf = 1.0;
  double at = 0.0;  // arrival (birth) time
  SourceLocation where;
};

// *LOAD_BODY_X/Y/Z: a base acceleration; the body force on a node is -m * a(t).
struct BodyLoad {
  int direction = 0;  // 0,1,2 for X,Y,Z
  Id lcid = 0;
  double sf = 1.0;
  SourceLocation where;
};

// *CONSTRAINED_RIGID_BODIES: part `constrained` (PIDC) becomes part of rigid body `lead`
// (PIDL).
struct RigidBodyMerge {
  Id lead = 0;
  Id constrained = 0;
  int iflag = 0;  // 1: update *PART_INERTIA properties of the lead with the merged body
  SourceLocation where;
};

// *CONSTRAINED_EXTRA_NODES_NODE/_SET: nodes that move with rigid part pid.
struct ExtraNodes {
  Id pid = 0;
  Target target = Target::Node;  // Node or NodeSet
  Id id = 0;
  int iflag = 0;  // 1: update *PART_INERTIA properties with the nodal masses
  SourceLocation where;
};

// *CONSTRAINED_NODAL_RIGID_BODY (_SPC, _INERTIA): the nodes of a set move as one rigid body.
// pid is the body's own ID (not a *PART).
struct NodalRigidBody {
  Id pid = 0;
  Id cid = 0;    // output coordinate system (0: none)
  Id nsid = 0;   // node set; NSID 0 on the card means NSID = PID
  Id pnode = 0;  // optional node at the centre of mass, as written (negative: global output)
  int iprt = 0;
  // _SPC card, same meaning as on *MAT_RIGID (Material::cmo ... cmo_local_fix).
  double cmo = 0.0;
  double con1 = 0.0;
  double con2 = 0.0;
  Id cmo_cid = 0;
  std::array<bool, 6> cmo_local_fix{};
  std::optional<RigidInertia> inertia;  // _INERTIA
  SourceLocation where;
};

// *CONSTRAINED_SPOTWELD (_ID, _FILTERED_FORCE without filtering): a massless rigid link between
// two non-coincident nodes (a two-node nodal rigid body), failing by
// (|fn| / SN)^N + (|fs| / SS)^M >= 1 (a term with SN or SS = 0 is off) or at time TF.
struct SpotWeld {
  Id id = 0;  // WID of _ID, else the card's ordinal among the spot welds
  Id n1 = 0;
  Id n2 = 0;
  double sn = 0.0;
  double ss = 0.0;
  double n = 1.0;  // exponents (0 on the card means 1)
  double m = 1.0;
  double tf = 1e20;
  SourceLocation where;
};

// *CONSTRAINED_NODE_SET (_ID): the nodes of a set share their velocity in the DOF of `dof`
// (1 x, 2 y, 3 z, 4 xy, 5 yz, 6 zx, 7 xyz) until time TF.
struct NodeSetConstraint {
  Id id = 0;  // CNSID of _ID, else the card's ordinal
  Id nsid = 0;
  int dof = 7;
  double tf = 1e20;
  SourceLocation where;
};

// *BOUNDARY_PRESCRIBED_MOTION_RIGID: motion of a rigid body (rigid part or nodal rigid body).
// *PART_MODES: a rigid part that deforms in the modes of a mode database, superimposed on its
// rigid motion (docs/flexible_bodies.md).
struct PartModesDamping {
  int mstart = 0;  // first and last mode (1-based, among the kept modes) with this damping
  int mstop = 0;
  double dampf = 0.0;  // fraction of critical damping
  SourceLocation where;
};

struct PartModes {
  Id pid = 0;
  int nmfb = 0;
  int form = 0;  // 0 exact (inertia coupling kept), 1 fast
  Id ansid = 0;  // attachment node set: nodes reconstructed every cycle (optional)
  int format = 3;
  int kmflag = 0;
  std::string filename;    // as given on card 2
  std::string path;        // resolved against the directory of the file that gave it
  std::vector<int> modes;  // KMFLAG 1: kept modes, 1-based numbers in the file
  std::vector<PartModesDamping> damping;
  SourceLocation where;
};

struct RigidPrescribedMotion {
  Id pid = 0;
  // 1,2,3: translation x,y,z; 4: translation along vector vid; 5,6,7: rotation about the
  // global x,y,z axes through the centre of mass; 8: rotation about vector vid.
  int dof = 1;
  int vad = 0;  // 0 velocity, 1 acceleration, 2 displacement
  // DOF 9, 10, 11: rotation about an axis parallel to x, y, z through the point whose two other
  // coordinates are OFFSET1, OFFSET2 (DOF 9: y, z; 10: z, x; 11: x, y), value in radians.
  double offset1 = 0.0;
  double offset2 = 0.0;
  Id lcid = 0;
  Id function = 0;  // IMPETUS *FUNCTION ID used instead of a curve (lcid 0)
  double sf = 1.0;
  Id vid = 0;  // *DEFINE_VECTOR for DOF 4 and 8
  double death = 1e28;
  double birth = 0.0;
  // _LOCAL: DOF 1-3 and 5-7 act along the body's own axes (its *MAT_RIGID output system,
  // else the global axes at t = 0, carried along with the body); VID is given in them too.
  bool local = false;
  SourceLocation where;
};

// *LOAD_RIGID_BODY: force or moment on a rigid body at its centre of mass, global axes.
struct RigidLoad {
  Id pid = 0;
  int dof = 1;  // 1,2,3: force x,y,z; 5,6,7: moment about x,y,z
  Id lcid = 0;
  double sf = 1.0;
  SourceLocation where;
};

// *DEFINE_BOX: an axis-aligned box in global coordinates (selects nodes by their initial
// position).
struct Box {
  Id id = 0;
  std::array<double, 3> min{};  // XMN YMN ZMN
  std::array<double, 3> max{};  // XMX YMX ZMX
  SourceLocation where;
};

// *RIGIDWALL_PLANAR (_ID, _FINITE, _MOVING): a planar constraint wall, as written. The solver's
// form is contact::RigidWall (src/contact/rigid_wall.hpp); docs/keywords.md gives the rules.
struct RigidWall {
  int number = 0;  // 1-based position among the deck's rigid walls (reading order)
  Id id = 0;       // _ID card; 0 when the deck gives none
  std::string title;
  Id nsid = 0;          // tracked nodes; 0: all nodes
  Id nsidex = 0;        // nodes exempted from tracking
  Id boxid = 0;         // only nodes initially inside this *DEFINE_BOX
  double offset = 0.0;  // > 0: only nodes initially within this normal distance of the wall
  double birth = 0.0;
  double death = 1e20;
  double rwksf = 1.0;                 // penalty stiffness scale (no effect on a constraint wall)
  std::array<double, 3> tail{};       // XT YT ZT: a point of the wall
  std::array<double, 3> head{};       // XH YH ZH: tail + normal points to the tracked side
  double fric = 0.0;                  // 0 frictionless, (0,1) Coulomb coefficient, 1 stick
  double wvel = 0.0;                  // welding velocity (welding is not supported: must be 0)
  bool finite = false;                // _FINITE
  std::array<double, 3> edge_head{};  // XHEV YHEV ZHEV: tail -> edge_head is the l edge
  double lenl = 0.0;                  // 0: infinite along l
  double lenm = 0.0;                  // 0: infinite along m = n x l
  bool moving = false;                // _MOVING
  double mass = 0.0;                  // MASS of the moving wall
  double v0 = 0.0;                    // V0 along the normal
  // *RIGIDWALL_PLANAR_FORCES: SSID, a segment set whose nodes' share of the wall force is
  // reported in rwforc.csv (SOFT must be 0; N1..N4 only draw the wall in LS-DYNA's database).
  Id force_segments = 0;
  // *RIGIDWALL_GEOMETRIC_FLAT / _PRISM / _CYLINDER / _SPHERE (Planar: *RIGIDWALL_PLANAR). A
  // FLAT wall uses finite/edge_head/lenl/lenm as _FINITE does; a PRISM adds lenp, the depth
  // behind the face (along -normal); a CYLINDER has its axis from tail towards head, radius
  // and length (0: infinite); a SPHERE is centred on the tail.
  enum class Shape { Planar, Flat, Prism, Cylinder, Sphere };
  Shape shape = Shape::Planar;
  double lenp = 0.0;
  double radius = 0.0;
  double lencyl = 0.0;
  bool interior = false;  // _INTERIOR (cylinder): nodes are kept inside
  // _MOTION of a geometric wall: the wall translates along `motion_direction` (unit) with the
  // velocity (OPT 0) or displacement (OPT 1) of curve motion_lcid, shifted by BIRTH.
  bool motion = false;
  Id motion_lcid = 0;
  int motion_opt = 0;
  std::array<double, 3> motion_direction{};
  SourceLocation where;
};

// *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE / _NODES_TO_SURFACE / _ONE_WAY_SURFACE_TO_SURFACE /
// _SINGLE_SURFACE (with _ID), as written. The solver's form is contact::ContactSystem
// (src/contact/contact.hpp); docs/contact.md and docs/keywords.md give the rules.
enum class ContactKind { SurfaceToSurface, NodesToSurface, OneWaySurfaceToSurface, SingleSurface };

struct Contact {
  int number = 0;  // 1-based position among the deck's contacts (reading order)
  Id id = 0;       // CID of the _ID card, else equal to `number`
  std::string heading;
  ContactKind kind = ContactKind::SurfaceToSurface;
  Id ssid = 0;       // slave (SURFA) side: set or part ID per sstyp
  Id msid = 0;       // master (SURFB) side
  int sstyp = 0;     // 0 segment set, 2 part set, 3 part, 4 node set, 5 all parts
  int mstyp = 0;     // 0 segment set, 2 part set, 3 part, 5 all parts
  double fs = 0.0;   // static friction coefficient
  double fd = 0.0;   // dynamic friction coefficient
  double dc = 0.0;   // exponential decay coefficient: mu = FD + (FS - FD) exp(-DC |v_rel|)
  double vdc = 0.0;  // viscous damping, percent of critical, normal direction
  double birth = 0.0;
  double death = 1e20;
  double sfs = 1.0;     // penalty scale, slave side
  double sfm = 1.0;     // penalty scale, master side
  double sst = 0.0;     // contact thickness of the slave surface (0: shells their thickness)
  double mst = 0.0;     // contact thickness of the master surface
  double sfst = 1.0;    // scale of the slave side's shell thickness (SST = 0)
  double sfmt = 1.0;    // scale of the master side's shell thickness (MST = 0)
  double fsf = 1.0;     // friction coefficient scale
  int soft = 0;         // 0 segment-based (bulk modulus) stiffness, 1 mass/time-step based
  double sofscl = 0.1;  // SOFT = 1 scale
  SourceLocation where;
};

// ---- Deformable <-> rigid part switching (*DEFORMABLE_TO_RIGID*, docs/switching.md) ----

// One part (or part set) named on *DEFORMABLE_TO_RIGID or on a D2R / R2D card of
// *DEFORMABLE_TO_RIGID_AUTOMATIC (or on a restart deck's *RIGID_TO_DEFORMABLE).
struct PartSwitch {
  Id pid = 0;
  bool part_set = false;  // PTYPE PSET
  Id lrb = 0;             // lead rigid body (part ID) to merge into; 0: own body (D2R only)
  SourceLocation where;
};

// *DEFORMABLE_TO_RIGID_AUTOMATIC: one automatic switch set.
struct AutomaticSwitchSet {
  Id swset = 0;
  int code = 0;         // 0 time, 1/3 rigid wall force zero/nonzero, 2/4 contact, 5 sensor
  double time1 = 0.0;   // not before
  double time2 = 1e20;  // not after (0 on the card means 1e20)
  double time3 = 0.0;   // delay after this switch before any other automatic switch
  Id entno = 0;         // rigid wall ordinal (CODE 1, 3) or contact ID (CODE 2, 4)
  Id relsw = 0;         // related (paired) switch set
  int paired = 0;       // 1 first of a pair, -1 second, 0 not paired
  int nrbf = 0;         // nodal rigid bodies: 0 no change, 1 delete others, 2 activate
  int ncsf = 0;         // nodal constraint sets / spot welds: 0, 1 delete, 2 activate
  int rwf = 0;          // rigid walls: 0, 1 delete, 2 activate
  double dtmax = 0.0;   // step cap after the switch (0: none)
  double offset = 0.0;  // CODE 3/4: switch this far before contact
  std::vector<PartSwitch> to_rigid;       // D2R cards
  std::vector<PartSwitch> to_deformable;  // R2D cards
  SourceLocation where;
};

// *DEFORMABLE_TO_RIGID_INERTIA: the body a part becomes takes these properties.
struct SwitchInertia {
  Id pid = 0;
  std::array<double, 3> xc{};
  double tm = 0.0;
  std::array<double, 6> inertia{};  // IXX IXY IXZ IYY IYZ IZZ (global axes, about xc)
  SourceLocation where;
};

struct PartSwitching {
  bool flagged = false;              // any *DEFORMABLE_TO_RIGID* keyword (restart needs it)
  std::vector<PartSwitch> at_start;  // *DEFORMABLE_TO_RIGID
  std::vector<AutomaticSwitchSet> automatic;
  std::map<Id, SwitchInertia> inertia;  // by PID
};

// --- Sensors (*SENSOR_...; docs/sensors.md). Read as written; sensor/sensor.hpp evaluates them.

// *DEFINE_FUNCTION: "name(a, b, ...) = expression". The keyword that uses the function binds the
// arguments by position (sensor values for *SENSOR_DEFINE_FUNCTION). `evaluator` is compiled when
// the deck is read (model/function.hpp); when that fails, `compile_error` says why and using the
// function is an error located at its card (an unused one is only a warning).
struct DefinedFunction {
  Id id = 0;
  std::string heading;
  std::string text;  // as written, lines joined
  std::shared_ptr<const ArgumentFunction> evaluator;
  std::string compile_error;
  SourceLocation where;  // the FID card
  int text_line = 0;     // first line of the function text
};

enum class SensorKind { Node, Element, Function };
enum class NodeQuantity { Acceleration, Velocity, Coordinate };  // CTYPE ACC, VEL, COORD
enum class ElementQuantity { Stress, Strain };                   // CTYPE STRESS, STRAIN

// *SENSOR_DEFINE_NODE / _ELEMENT / _FUNCTION.
struct Sensor {
  Id id = 0;
  SensorKind kind = SensorKind::Node;
  std::string title;
  // Node: value of NODE1 minus value of NODE2 (NODE2 0: none), along *DEFINE_VECTOR VID or its
  // magnitude (VID 0).
  Id node1 = 0;
  Id node2 = 0;
  Id vid = 0;
  NodeQuantity node_quantity = NodeQuantity::Acceleration;
  // Element: solid ELEMID; component 0..5 = XX YY ZZ XY YZ ZX, 6 = von Mises (COMP VM).
  Id element = 0;
  ElementQuantity element_quantity = ElementQuantity::Strain;
  int component = 0;
  // Function: *DEFINE_FUNCTION FUNC of the values of `inputs` (sensor IDs, in argument order).
  Id function = 0;
  std::vector<Id> inputs;
  SourceLocation where;
};

// *SENSOR_SWITCH (compare a sensor or the time with VALUE) or *SENSOR_SWITCH_CALC-LOGIC
// (`logic_inputs`: positive IDs are combined with AND, negative with OR).
struct SensorSwitch {
  Id id = 0;
  std::string title;
  bool calc_logic = false;
  bool time = false;  // TYPE TIME: the time is compared, SENSID unused
  Id sensor = 0;
  bool greater = false;  // LOGIC GT (else LT)
  double value = 0.0;
  double time_window = 0.0;  // TIMWIN
  double delay = 0.0;        // TDELAY
  std::vector<Id> logic_inputs;
  SourceLocation where;
};

// *SENSOR_CONTROL. Only TYPE DEF2RIG is accepted by the reader (TYPEID = SWSET of
// *DEFORMABLE_TO_RIGID_AUTOMATIC with CODE 5).
struct SensorControl {
  Id id = 0;
  std::string title;
  std::string type;  // as written, upper case
  Id type_id = 0;
  int nrep = 0;              // passes over SWIT1..n: 0 or 1 once, N > 1 N times, -1 without end
  bool initially_on = true;  // INITSTT
  std::vector<Id> switches;  // SWIT1..SWIT7, blanks removed
  SourceLocation where;
};

// *ELEMENT_MASS: a point mass at a node.
struct PointMass {
  Id id = 0;    // EID
  Id node = 0;  // NID
  double mass = 0.0;
  Id part = 0;  // PID (optional; only for bookkeeping)
  SourceLocation where;
};

// *ELEMENT_MASS_PART(_SET): translational mass added to the nodes of a part (or part set), in
// proportion to their lumped mass (docs/keywords.md).
struct PartMassAddition {
  Id id = 0;  // PID, or PSID with _SET
  bool part_set = false;
  double addmass = 0.0;
  double finmass = 0.0;  // > 0: the added mass is FINMASS minus the mass the part has
  SourceLocation where;
};

// *DAMPING_GLOBAL and *DAMPING_PART_MASS(_SET): mass-proportional damping, the force
// f = -d(t) m v on each node (a rigid body: -d M v_c and the moment -d L), scaled per
// global direction by ST (forces) and SR (rigid-body moments).
struct MassDamping {
  bool global = true;
  Id id = 0;  // PID or PSID (part damping)
  bool part_set = false;
  Id lcid = 0;                              // curve d(t); global: 0 means the constant VALDMP
  double valdmp = 0.0;                      // global: constant d when LCID is 0
  double sf = 1.0;                          // part damping: scale factor on the curve
  std::array<double, 3> st{1.0, 1.0, 1.0};  // STX STY STZ
  std::array<double, 3> sr{1.0, 1.0, 1.0};  // SRX SRY SRZ
  SourceLocation where;
};

// *CONSTRAINED_JOINT_SPHERICAL / _REVOLUTE / _CYLINDRICAL / _TRANSLATIONAL: a penalty joint
// between coincident node pairs (N1,N2), (N3,N4), (N5,N6); odd nodes on body A, even on B.
struct Joint {
  enum class Type { Spherical, Revolute, Cylindrical, Translational, Universal, Locking };
  Type type = Type::Spherical;
  Id id = 0;  // JID of the _ID card, else the joint's 1-based position in the deck
  std::string title;
  std::array<Id, 6> nodes{};  // N1..N6, 0 where the type uses fewer
  double rps = 1.0;           // relative penalty stiffness
  double damp = 1.0;          // scale on the default damping; 0 < DAMP <= 0.01: none
  SourceLocation where;
};

// *CONSTRAINED_JOINT_STIFFNESS_GENERALIZED: moments between rigid bodies A and B about the
// axes of the relative rotation angles (phi, theta, psi) of the local systems CIDA (on A) and
// CIDB (on B). _TRANSLATIONAL: forces along the axes of CIDB from the relative displacement of
// the systems' origins. Index k = 0, 1, 2: PH, T, PS (GENERALIZED) or X, Y, Z (TRANSLATIONAL).
struct JointStiffness {
  enum class Type { Generalized, Translational };
  Type type = Type::Generalized;
  Id id = 0;  // JSID
  std::string title;
  Id pida = 0, pidb = 0;
  Id cida = 0, cidb = 0;                  // CIDB 0: CIDA
  Id jid = 0;                             // joint whose output rows it joins (0: none)
  std::array<Id, 3> lcid{};               // moment (force) vs angle (displacement); 0: none
  std::array<Id, 3> dlcid{};              // damping moment (force) vs rate; 0: none
  std::array<double, 3> stiffness{};      // ESPH EST ESPS (ESX ESY ESZ): friction and stops
  std::array<double, 3> friction{};       // FMPH FMT FMPS (FFX FFY FFZ); 0: none
  std::array<double, 3> negative_stop{};  // NSAPH NSAT NSAPS in degrees (NSDX..); 0: none
  std::array<double, 3> positive_stop{};  // PSAPH PSAT PSAPS in degrees (PSDX..); 0: none
  std::array<SourceLocation, 4> card;     // where each of the four cards is
  SourceLocation where;                   // the first card
};

struct Termination {
  double endtim = 0.0;
  int endcyc = 0;
  double dtmin = 0.0;
};

struct TimestepControl {
  double dtinit = 0.0;
  double tssfac = 0.9;
  double dt2ms = 0.0;  // mass scaling target (docs/keywords.md); 0: none
  int ms1st = 0;       // 1: mass scaling at the first step only
  // ERODE: digits 1 (solids), 10 (shells), 100 (beams): elements of those families whose step
  // brings the run's step below TSMIN (*CONTROL_TERMINATION DTMIN times the first step) erode
  // instead of stopping the run (solver/erosion.cpp).
  int erode = 0;
  SourceLocation where;  // the *CONTROL_TIMESTEP card (errors found at set-up)
  int isdo = 0;          // shell step option (0 only)
  Id lctm = 0;
  double dt_max = 0.0;  // IMPETUS *TIME dt_max; 0: no cap
};

// *CONTROL_DYNAMIC_RELAXATION (docs/keywords.md, docs/theory.md#dynamic-relaxation): a damped
// pseudo-dynamic phase before the transient that brings preloads (curves with SIDR 1 or 2) to
// static equilibrium. Active with IDRFLG 1 or -1, or IDRFLG 0 and a curve flagged SIDR 1/2;
// never with IDRFLG -999.
struct DynamicRelaxationControl {
  int nrcyck = 250;       // cycles between convergence checks
  double drtol = 1e-3;    // converged: distortional kinetic energy / its peak below this
  double drfctr = 0.995;  // velocities scaled by this every cycle
  double drterm = 0.0;    // pseudo-time at which the phase ends anyway; 0: no limit
  double tssfdr = 0.0;    // step scale factor during the phase; 0: TSSFAC
  int idrflg = 0;
  SourceLocation where;  // the keyword, when the deck has one
};

struct HourglassControl {
  int ihq = 1;
  double qh = 0.1;
};

// *CONTROL_BULK_VISCOSITY: artificial bulk viscosity of solid elements (docs/theory.md). On by
// default in LS-DYNA decks with LS-DYNA's defaults; IMPETUS decks have none (docs/impetus.md).
struct BulkViscosityControl {
  double q1 = 1.5;       // quadratic coefficient
  double q2 = 0.06;      // linear coefficient
  int type = 1;          // 1 (solids), -1/-2 (also shells ELFORM 2)
  int btype = 0;         // beams (0 only when the model has beams)
  SourceLocation where;  // the card, when the deck has one
};

// *DATABASE_CROSS_SECTION_PLANE(_ID) (docs/output.md#secforccsv): a cutting plane through the
// parts of a part set, whose transmitted force and moment go to secforc.csv.
struct CrossSection {
  Id id = 0;                     // CSID (_ID), else the position among the deck's cross sections
  std::string title;             // _ID heading
  Id part_set = 0;               // PSID; 0: every part
  std::array<double, 3> tail{};  // XCT YCT ZCT: a point of the plane, tail of the normal N
  std::array<double, 3> head{};  // XCH YCH ZCH: head of N
  // RADIUS > 0: the cut is the disc of this radius about the tail; < 0: |RADIUS|, and XCT and
  // XCH are node IDs (tail_node, head_node) whose initial positions give the tail and head.
  double radius = 0.0;
  Id tail_node = 0, head_node = 0;
  std::array<double, 3> edge_head{};  // XHEV YHEV ZHEV: head of the edge vector L (tail: XCT..)
  double length_l = 0.0;              // LENL; 0 or blank: unbounded along L
  double length_m = 0.0;              // LENM; 0 or blank: unbounded along M = N x L
  // *DATABASE_CROSS_SECTION_SET: the section's nodes and the elements whose nodal forces at
  // those nodes are summed are given as sets (NSID; HSID, BSID, SSID) instead of a plane.
  bool from_sets = false;
  Id node_set = 0, solid_set = 0, beam_set = 0, shell_set = 0;
  SourceLocation where;
};

struct OutputControl {
  double glstat_dt = 0.0;  // 0: about 1000 rows per run
  double nodout_dt = 0.0;  // 0: about 1000 rows per run when history nodes exist
  double d3plot_dt = 0.0;  // 0: 20 frames per run
  std::vector<Id> history_nodes;
  double rbdout_dt = 0.0;  // *DATABASE_RBDOUT DT; 0: no rigid body output requested
  bool rbdout = false;     // true when *DATABASE_RBDOUT is present
  double rwforc_dt = 0.0;  // *DATABASE_RWFORC DT; 0: about 1000 rows per run
  double rcforc_dt = 0.0;  // *DATABASE_RCFORC DT; 0: about 1000 rows per run
  // Per-part and per-element histories (docs/output.md): written only when the keyword is there.
  bool matsum = false;     // *DATABASE_MATSUM present
  double matsum_dt = 0.0;  // 0: about 1000 rows per run
  bool spcforc = false;    // *DATABASE_SPCFORC present
  double spcforc_dt = 0.0;
  double elout_dt = 0.0;           // *DATABASE_ELOUT DT; 0: about 1000 rows per run
  std::vector<Id> history_solids;  // *DATABASE_HISTORY_SOLID element IDs, in deck order
  std::vector<SourceLocation> history_solid_where;  // the card of each
  // *DATABASE_HISTORY_SOLID_SET: solid set IDs (members follow the IDs above in elout.csv).
  std::vector<Id> history_solid_sets;
  std::vector<SourceLocation> history_solid_set_where;
  // *DATABASE_HISTORY_SHELL(_ID, _SET): shells whose point stresses go to elout_shell.csv.
  std::vector<Id> history_shells;
  std::vector<SourceLocation> history_shell_where;
  std::vector<Id> history_shell_sets;
  std::vector<SourceLocation> history_shell_set_where;
  std::vector<CrossSection> cross_sections;  // secforc.csv rows, in this order
  double secforc_dt = 0.0;                   // *DATABASE_SECFORC DT; 0: about 1000 rows per run
  bool jntforc = false;                      // *DATABASE_JNTFORC present (jntforc.csv)
  double jntforc_dt = 0.0;                   // 0: about 1000 rows per run
  double swforc_dt = 0.0;                    // *DATABASE_SWFORC DT (0: about 1000 rows per run)
};

// *CONTROL_IMPLICIT_GENERAL and *CONTROL_IMPLICIT_EIGENVALUE (docs/eigen.md): with IMFLAG 1 and
// NEIG > 0 the deck asks for an eigen analysis instead of a transient run.
struct ImplicitControl {
  bool general = false;  // *CONTROL_IMPLICIT_GENERAL present
  int imflag = 0;
  double dt0 = 0.0;
  bool eigenvalue = false;  // *CONTROL_IMPLICIT_EIGENVALUE present
  int neig = 0;
  double center = 0.0;  // frequency (cycles per time unit)
  int lflag = 0;
  double lftend = -1e29;  // frequency
  int rflag = 0;
  double rhtend = 1e29;  // frequency
  int eigmth = 2;
  double shfscl = 0.0;
  SourceLocation where;  // the *CONTROL_IMPLICIT_EIGENVALUE card
};

// *EOS_LINEAR_POLYNOMIAL (001): p = C0 + C1 mu + C2 mu^2 + C3 mu^3 + (C4 + C5 mu + C6 mu^2) E,
// mu = rho / rho0 - 1, E internal energy per unit reference volume (E0 initially); the C2 and C6
// terms vanish in tension (mu < 0).
struct EquationOfState {
  Id id = 0;
  std::string keyword;
  std::array<double, 7> c{};  // C0 .. C6
  double e0 = 0.0;
  SourceLocation where;
};

struct Warning {
  SourceLocation where;
  std::string message;
};

struct Model {
  std::string title;
  std::string dialect = "lsdyna";      // "lsdyna" or "impetus"
  std::string dialect_reason;          // why (detected from content, or the command line)
  std::string unit_system;             // IMPETUS *UNIT_SYSTEM as written (no conversion is done)
  std::int64_t merged_node_count = 0;  // nodes removed by *MERGE_DUPLICATED_NODES
  std::vector<std::string> files;      // every file read, main deck first

  std::vector<Node> nodes;           // in input order
  std::vector<SolidElement> solids;  // in input order
  std::map<Id, Part> parts;
  std::map<Id, SectionSolid> solid_sections;
  std::vector<ShellElement> shells;  // in input order
  std::vector<BeamElement> beams;    // in input order
  std::map<Id, SectionShell> shell_sections;
  std::map<Id, SectionBeam> beam_sections;
  std::vector<DiscreteElement> discretes;  // *ELEMENT_DISCRETE, in input order
  std::map<Id, SectionDiscrete> discrete_sections;
  ShellControl shell_control;
  ContactControl contact_control;  // *CONTROL_CONTACT
  std::map<Id, Material> materials;
  std::map<Id, EquationOfState> equations_of_state;  // *EOS_, by EOSID
  std::map<Id, AddErosion> add_erosions;             // *MAT_ADD_EROSION, by MID
  std::map<Id, Hourglass> hourglass;
  std::map<Id, Curve> curves;
  std::map<Id, Table> tables;  // *DEFINE_TABLE; IDs distinct from the curves'
  std::map<Id, NodeSet> node_sets;
  std::map<Id, PartSet> part_sets;
  std::map<Id, SegmentSet> segment_sets;
  std::map<Id, SolidSet> solid_sets;
  std::map<Id, SolidSet> shell_sets;  // *SET_SHELL
  std::map<Id, SolidSet> beam_sets;   // *SET_BEAM
  std::map<Id, Function> functions;   // IMPETUS *FUNCTION
  std::map<Id, GeometrySeed> geometry_seeds;
  std::vector<POrderChange> p_order_changes;
  std::vector<CylinderSurface> cylinder_surfaces;

  std::vector<Spc> spcs;
  std::vector<PrescribedMotion> prescribed_motions;
  std::vector<InitialVelocity> initial_velocities;
  std::vector<NodalLoad> nodal_loads;
  std::vector<PressureLoad> pressure_loads;  // *LOAD_SEGMENT*, *LOAD_SHELL*, in deck order
  std::vector<BodyLoad> body_loads;

  std::map<Id, CoordinateSystem> coordinate_systems;
  std::map<Id, Vector> vectors;
  std::vector<RigidBodyMerge> rigid_body_merges;
  std::vector<ExtraNodes> extra_nodes;
  std::map<Id, NodalRigidBody> nodal_rigid_bodies;  // by PID
  std::map<Id, PartModes> part_modes;               // by PID
  std::vector<RigidPrescribedMotion> rigid_prescribed_motions;
  std::vector<RigidLoad> rigid_loads;
  int rigid_body_update = 0;  // *RIGID_BODY_UPDATE type (0, 1, 2)
  PartSwitching switching;

  std::map<Id, DefinedFunction> defined_functions;  // *DEFINE_FUNCTION
  std::map<Id, Sensor> sensors;
  std::map<Id, SensorSwitch> sensor_switches;
  std::map<Id, SensorControl> sensor_controls;
  std::map<Id, Box> boxes;             // *DEFINE_BOX
  std::vector<RigidWall> rigid_walls;  // in deck order: rigid_walls[k].number == k + 1
  std::vector<Contact> contacts;       // in deck order: contacts[k].number == k + 1

  std::vector<PointMass> point_masses;                  // *ELEMENT_MASS
  std::vector<PartMassAddition> part_mass_additions;    // *ELEMENT_MASS_PART
  std::vector<MassDamping> mass_damping;                // *DAMPING_GLOBAL, *DAMPING_PART_MASS
  std::vector<Joint> joints;                            // *CONSTRAINED_JOINT_..., deck order
  std::vector<JointStiffness> joint_stiffnesses;        // *CONSTRAINED_JOINT_STIFFNESS_...
  std::vector<SpotWeld> spot_welds;                     // *CONSTRAINED_SPOTWELD, deck order
  std::vector<NodeSetConstraint> node_set_constraints;  // *CONSTRAINED_NODE_SET, deck order

  Termination termination;
  TimestepControl timestep;
  DynamicRelaxationControl dynamic_relaxation;
  HourglassControl hourglass_control;
  BulkViscosityControl bulk_viscosity;
  OutputControl output;
  ImplicitControl implicit;

  std::map<std::string, double> parameters;     // *PARAMETER values, final
  std::vector<Warning> warnings;                // unknown keywords and other notices
  std::map<std::string, int> unknown_keywords;  // keyword -> occurrences
  // Keywords that change the physics, skipped because the user passed --ignore-unsupported
  // (run.json and the log list them).
  std::vector<Warning> ignored_physics;
};

}  // namespace rf::model
