// Malformed input: every error must name file, line, keyword, card and field.
#include <gtest/gtest.h>

#include "keyword_test_util.hpp"

namespace {

// A valid one-element model; cases append or replace pieces of it.
std::string deck(const std::string& mesh_extra = "", const std::string& tail = "",
                 const std::string& section = "         1         1\n",
                 const std::string& mat = "         1    7.8e-9     2.1e5       0.3\n",
                 const std::string& part = "         1         1         1\n") {
  return "*KEYWORD\n"
         "*NODE\n"
         "1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n" +
         mesh_extra +
         "*ELEMENT_SOLID\n"
         "       1       1       1       2       3       4       5       6       7       8\n"
         "*PART\n"
         "block\n" +
         part + "*SECTION_SOLID\n" + section + "*MAT_ELASTIC\n" + mat +
         "*DEFINE_CURVE\n"
         "         1\n"
         "0.0,0.0\n1.0,1.0\n" +
         tail;
}

struct ErrorCase {
  std::string name;
  std::string text;
  std::vector<std::string> expected;  // substrings of the message
};

class KeywordError : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(KeywordError, MessageLocatesTheProblem) {
  const ErrorCase& c = GetParam();
  const std::string message = rf::test::input_error_of(c.text, "bar.k");
  for (const auto& part : c.expected) {
    EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "' in: " << message;
  }
}

std::vector<ErrorCase> cases() {
  return {
      {"BadNumber",
       deck("*NODE\n       9             abc             0.0             0.0\n"),
       {"bar.k:12: *NODE card 1 field X: 'abc' is not a number"}},
      {"UnsupportedElform",
       deck("", "", "         1         7\n"),
       {"bar.k:17: *SECTION_SOLID card 1 field ELFORM: value 7 is not supported "
        "(supported: 1, 2, 10, 13, 16)"}},
      {"UnsupportedTetrahedronElform",
       deck("", "", "         1        17\n"),
       {"bar.k:17: *SECTION_SOLID card 1 field ELFORM: tetrahedron formulation 17 (the 10-node "
        "composite tetrahedron) is not supported (supported: 10, the one-point 4-node "
        "tetrahedron; 13, the nodal-pressure tetrahedron; 16, the 10-node quadratic "
        "tetrahedron)"}},
      {"UnknownNodeInElement",
       "*NODE\n1,0,0,0\n*ELEMENT_SOLID\n1,1,1,1,1,1,1,1,1,99\n*PART\np\n1,1,1\n"
       "*SECTION_SOLID\n1,1\n*MAT_ELASTIC\n1,1.0,1.0,0.3\n",
       {"bar.k:4: *ELEMENT_SOLID", "field N8", "node 99"}},
      {"UnknownPartInElement",
       "*NODE\n1,0,0,0\n*ELEMENT_SOLID\n1,5,1,1,1,1,1,1,1,1\n",
       {"bar.k:4: *ELEMENT_SOLID", "field PID", "part 5"}},
      {"MissingPartMaterial",
       deck("", "", "         1         1\n", "         2    7.8e-9     2.1e5       0.3\n"),
       {"bar.k:15: *PART", "field MID", "material 1"}},
      {"UndefinedParameter",
       deck("*NODE\n       9         &nosuch             0.0             0.0\n"),
       {"bar.k:12: *NODE card 1 field X", "'nosuch' is not defined"}},
      {"MissingInclude",
       "*KEYWORD\n*INCLUDE\nnot_there.k\n",
       {"bar.k:3: *INCLUDE card 1 field FILENAME", "not_there.k"}},
      {"DuplicateNode",
       deck("*NODE\n       5             0.0             0.0             0.0\n"),
       {"bar.k:12: *NODE card 1 field NID", "node 5 is already defined at bar.k:7"}},
      {"DuplicateElement",
       deck("", "*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n"),
       {"bar.k:25: *ELEMENT_SOLID card 1 field EID", "element 1 is already defined"}},
      {"DuplicatePart",
       deck("", "*PART\nagain\n1,1,1\n"),
       {"bar.k:26: *PART card 2 field PID", "part 1 is already defined at bar.k:15"}},
      {"NegativeDensity",
       deck("", "", "         1         1\n", "         1   -7.8e-9     2.1e5       0.3\n"),
       {"bar.k:19: *MAT_ELASTIC card 1 field RO", "must be positive"}},
      {"PoissonRatioTooLarge",
       deck("", "", "         1         1\n", "         1    7.8e-9     2.1e5       0.5\n"),
       {"bar.k:19: *MAT_ELASTIC card 1 field PR", "(-1, 0.5)"}},
      {"MassScalingFirstStepFlag",
       deck("",
            "*CONTROL_TIMESTEP\n       0.0       0.9         0       0.0   -1.0e-6         0"
            "         0         2\n"),
       {"bar.k:25: *CONTROL_TIMESTEP card 1 field MS1ST", "value 2 is not 0 or 1"}},
      {"SelectiveMassScaling",
       deck("",
            "*CONTROL_TIMESTEP\n       0.0       0.9         0       0.0   -1.0e-6\n"
            "       0.0         0        -5\n"),
       {"bar.k:26: *CONTROL_TIMESTEP card 2 field IMSCL", "selective mass scaling"}},
      {"UnsupportedDof",
       deck("", "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,12,0,1\n"),
       {"bar.k:25: *BOUNDARY_PRESCRIBED_MOTION_NODE card 1 field DOF",
        "value 12 is not supported"}},
      {"NegativeVectorDof",
       deck("", "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,-5,0,1\n"),
       {"bar.k:25: *BOUNDARY_PRESCRIBED_MOTION_NODE card 1 field DOF", "DOF -5 is not supported"}},
      {"UnsupportedVad",
       deck("", "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,1,3,1\n"),
       {"bar.k:25: *BOUNDARY_PRESCRIBED_MOTION_NODE card 1 field VAD"}},
      {"BoundaryUnknownCurve",
       deck("", "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,1,0,4\n"),
       {"bar.k:25: *BOUNDARY_PRESCRIBED_MOTION_NODE", "field LCID", "load curve 4"}},
      {"SpcUnknownSet",
       deck("", "*BOUNDARY_SPC_SET\n3,0,1,1,1\n"),
       {"bar.k:25: *BOUNDARY_SPC_SET", "field NSID", "node set 3"}},
      {"SetUnknownNode",
       deck("", "*SET_NODE_LIST\n1\n1,2,77\n"),
       {"bar.k:25: *SET_NODE_LIST", "field NID", "node 77"}},
      {"IntegerWithFraction",
       deck("", "*SET_NODE_LIST\n1\n1.5\n"),
       {"bar.k:26: *SET_NODE_LIST card 2 field NID", "'1.5' is not an integer"}},
      {"MissingCard",
       deck("", "*INITIAL_VELOCITY\n0\n"),
       {"bar.k:25: *INITIAL_VELOCITY card 2", "missing"}},
      {"UnsupportedOption",
       deck("", "*PART_CONTACT\np\n2,1,1\n"),
       {"bar.k:24: *PART_CONTACT: not supported: a part definition",
        "*PART is read, with the options _INERTIA"}},
      {"RotationalVelocity",
       deck("", "*INITIAL_VELOCITY\n0\n0,0,0,1.0\n"),
       {"bar.k:26: *INITIAL_VELOCITY card 2 field VXR"}},
      {"DecreasingCurve",
       deck("", "*DEFINE_CURVE\n2\n1.0,0\n0.5,0\n"),
       {"bar.k:27: *DEFINE_CURVE card 3 field A1", "increasing"}},
      {"HugeNumber",
       deck("*NODE\n       9          1e9999             0.0             0.0\n"),
       {"bar.k:12: *NODE card 1 field X", "out of range"}},
  };
}

// Rigid parts 2, 3 and 4 (lines 24-34 after the base deck); the next keyword is on line 35.
const std::string kRigid =
    "*MAT_RIGID\n2,7.8e-9,2.1e5,0.3\n*PART\nr2\n2,1,2\n*PART\nr3\n3,1,2\n*PART\nr4\n4,1,2\n";

std::vector<ErrorCase> rigid_cases() {
  return {
      {"MergeNonRigidPart",
       deck("", kRigid + "*CONSTRAINED_RIGID_BODIES\n2,1\n"),
       {"bar.k:36: *CONSTRAINED_RIGID_BODIES field PIDC",
        "part 1 is not rigid (material 1 is *MAT_ELASTIC)"}},
      {"MergeUnknownPart",
       deck("", kRigid + "*CONSTRAINED_RIGID_BODIES\n9,2\n"),
       {"bar.k:36: *CONSTRAINED_RIGID_BODIES field PIDL", "part 9 is not defined"}},
      {"MergeIntoItself",
       deck("", kRigid + "*CONSTRAINED_RIGID_BODIES\n2,2\n"),
       {"bar.k:36: *CONSTRAINED_RIGID_BODIES card 1 field PIDC", "merged into itself"}},
      {"MergeCycle",
       deck("", kRigid + "*CONSTRAINED_RIGID_BODIES\n2,3\n3,4\n4,2\n"),
       {"*CONSTRAINED_RIGID_BODIES field PIDC", "cycle: part 2 -> 4 -> 3 -> 2"}},
      {"MergeTwoLeads",
       deck("", kRigid + "*CONSTRAINED_RIGID_BODIES\n2,4\n3,4\n"),
       {"bar.k:37: *CONSTRAINED_RIGID_BODIES field PIDC",
        "part 4 is merged into part 3 here and into part 2 at bar.k:36"}},
      {"ExtraNodesNonRigidPart",
       deck("", "*CONSTRAINED_EXTRA_NODES_NODE\n1,5\n"),
       {"bar.k:25: *CONSTRAINED_EXTRA_NODES_NODE field PID", "part 1 is not rigid"}},
      {"ExtraNodesUnknownSet",
       deck("", kRigid + "*CONSTRAINED_EXTRA_NODES_SET\n2,7\n"),
       {"bar.k:36: *CONSTRAINED_EXTRA_NODES_SET field NSID", "node set 7 is not defined"}},
      {"ExtraNodesUnknownNode",
       deck("", kRigid + "*CONSTRAINED_EXTRA_NODES_NODE\n2,77\n"),
       {"bar.k:36: *CONSTRAINED_EXTRA_NODES_NODE field NID", "node 77 is not defined"}},
      {"RigidMotionNonRigidPart",
       deck("", "*BOUNDARY_PRESCRIBED_MOTION_RIGID\n1,1,0,1\n"),
       {"bar.k:25: *BOUNDARY_PRESCRIBED_MOTION_RIGID field PID", "part 1 is not rigid"}},
      {"RigidMotionUnknownVector",
       deck("", kRigid + "*BOUNDARY_PRESCRIBED_MOTION_RIGID\n2,8,0,1,1.0,5\n"),
       {"bar.k:36: *BOUNDARY_PRESCRIBED_MOTION_RIGID field VID", "vector 5 is not defined"}},
      {"RigidMotionUnknownCurve",
       deck("", kRigid + "*BOUNDARY_PRESCRIBED_MOTION_RIGID\n2,1,0,9\n"),
       {"bar.k:36: *BOUNDARY_PRESCRIBED_MOTION_RIGID field LCID", "load curve 9"}},
      {"RigidMotionUnsupportedOption",
       deck("", "*BOUNDARY_PRESCRIBED_MOTION_RIGID_BNDOUT\n2,1,0,1\n"),
       {"bar.k:24: *BOUNDARY_PRESCRIBED_MOTION_RIGID_BNDOUT: not supported: a boundary condition",
        "*BOUNDARY_PRESCRIBED_MOTION_RIGID is read, with the options _ID, _LOCAL"}},
      {"RigidMotionLocalNonRigidPart",
       deck("", "*BOUNDARY_PRESCRIBED_MOTION_RIGID_LOCAL\n1,1,0,1\n"),
       {"bar.k:25: *BOUNDARY_PRESCRIBED_MOTION_RIGID_LOCAL field PID", "part 1 is not rigid"}},
      {"RigidMotionBadDof",
       deck("", kRigid + "*BOUNDARY_PRESCRIBED_MOTION_RIGID\n2,9,0,1\n"),
       {"bar.k:36: *BOUNDARY_PRESCRIBED_MOTION_RIGID card 1 field DOF",
        "value 9 is not supported"}},
      {"RigidMotionBadVad",
       deck("", kRigid + "*BOUNDARY_PRESCRIBED_MOTION_RIGID\n2,1,3,1\n"),
       {"bar.k:36: *BOUNDARY_PRESCRIBED_MOTION_RIGID card 1 field VAD"}},
      {"RigidMotionVectorMissing",
       deck("", kRigid + "*BOUNDARY_PRESCRIBED_MOTION_RIGID\n2,4,0,1\n"),
       {"bar.k:36: *BOUNDARY_PRESCRIBED_MOTION_RIGID card 1 field VID", "DOF 4 needs a vector"}},
      {"RigidLoadLocalSystem",
       deck("", kRigid + "*LOAD_RIGID_BODY\n2,1,1,1.0,4\n"),
       {"bar.k:36: *LOAD_RIGID_BODY card 1 field CID", "not supported"}},
      {"RigidLoadNonRigidPart",
       deck("", "*LOAD_RIGID_BODY\n1,1,1\n"),
       {"bar.k:25: *LOAD_RIGID_BODY field PID", "part 1 is not rigid"}},
      {"RigidLoadFollower",
       deck("", kRigid + "*LOAD_RIGID_BODY\n2,4,1\n"),
       {"bar.k:36: *LOAD_RIGID_BODY card 1 field DOF", "follower"}},
      {"MatRigidUnknownLocalSystem",
       deck("", "*MAT_RIGID\n2,7.8e-9,2.1e5,0.3\n-1,8,100000\n"),
       {"bar.k:25: *MAT_RIGID field CON1", "coordinate system 8 is not defined"}},
      {"MatRigidBadLocalCode",
       deck("", "*MAT_RIGID\n2,7.8e-9,2.1e5,0.3\n-1,8,100200\n"),
       {"bar.k:26: *MAT_RIGID card 2 field CON2", "digit other than 0 or 1"}},
      {"MatRigidBadCmo",
       deck("", "*MAT_RIGID\n2,7.8e-9,2.1e5,0.3\n2\n"),
       {"bar.k:26: *MAT_RIGID card 2 field CMO", "must be -1, 0 or 1"}},
      {"MatRigidUnknownOutputSystem",
       deck("", "*MAT_RIGID\n2,7.8e-9,2.1e5,0.3\n0\n3\n"),
       {"bar.k:25: *MAT_RIGID field LCO", "coordinate system 3 is not defined"}},
      {"CoordinateNodesFlag",
       deck("", "*DEFINE_COORDINATE_NODES\n5,1,2,4,1\n"),
       {"bar.k:25: *DEFINE_COORDINATE_NODES card 1 field FLAG", "not supported"}},
      {"CoordinateNodesOnALine",
       deck("", "*NODE\n9,2,0,0\n*DEFINE_COORDINATE_NODES\n5,1,2,9\n"),
       {"bar.k:27: *DEFINE_COORDINATE_NODES field N3", "lie on one line"}},
      {"CoordinateNodesUnknownNode",
       deck("", "*DEFINE_COORDINATE_NODES\n5,1,2,99\n"),
       {"bar.k:25: *DEFINE_COORDINATE_NODES field N3", "node 99 is not defined"}},
      {"CoordinateNodesBadDir",
       deck("", "*DEFINE_COORDINATE_NODES\n5,1,2,4,0,Q\n"),
       {"bar.k:25: *DEFINE_COORDINATE_NODES card 1 field DIR", "X, Y or Z"}},
      {"CoordinateSystemDegenerate",
       deck("", "*DEFINE_COORDINATE_SYSTEM\n5,0,0,0,1,0,0\n2,0,0\n"),
       {"bar.k:26: *DEFINE_COORDINATE_SYSTEM card 2 field XP", "not on one line"}},
      {"CoordinateSystemDuplicate",
       deck("", "*DEFINE_COORDINATE_VECTOR\n5,1,0,0,0,1,0\n*DEFINE_COORDINATE_NODES\n5,1,2,4\n"),
       {"bar.k:27: *DEFINE_COORDINATE_NODES card 1 field CID",
        "coordinate system 5 is already defined at bar.k:25"}},
      {"CoordinateVectorRotating",
       deck("", "*DEFINE_COORDINATE_VECTOR\n5,1,0,0,0,1,0,3\n"),
       {"bar.k:25: *DEFINE_COORDINATE_VECTOR card 1 field NID", "not supported"}},
      {"VectorWithoutDirection",
       deck("", "*DEFINE_VECTOR\n1,1,1,1,1,1,1\n"),
       {"bar.k:25: *DEFINE_VECTOR card 1 field XH", "no direction"}},
      {"VectorUnknownSystem",
       deck("", "*DEFINE_VECTOR\n1,0,0,0,1,0,0,4\n"),
       {"bar.k:25: *DEFINE_VECTOR field CID", "coordinate system 4 is not defined"}},
      {"PartInertiaNotRigid",
       deck("", "*PART_INERTIA\np\n2,1,1\n0,0,0,1.0\n1,0,0,1,0,1\n0\n"),
       {"bar.k:26: *PART_INERTIA field MID", "need a *MAT_RIGID part"}},
      {"PartInertiaNoMass",
       deck("", "*PART_INERTIA\np\n2,1,1\n0,0,0,0\n"),
       {"bar.k:27: *PART_INERTIA card 3 field TM", "must be positive"}},
      {"PartInertiaNoInertia",
       deck("", "*PART_INERTIA\np\n2,1,1\n0,0,0,1\n1,0,0,0,0,1\n"),
       {"bar.k:28: *PART_INERTIA card 4 field IYY", "must be positive"}},
      {"PartInertiaUnknownNode",
       deck("", kRigid + "*PART_INERTIA\np\n5,1,2\n0,0,0,1,0,55\n1,0,0,1,0,1\n0\n"),
       {"bar.k:38: *PART_INERTIA field NODEID", "node 55 is not defined"}},
      {"PartInertiaPrincipalAxesMissing",
       deck("", kRigid + "*PART_INERTIA\np\n5,1,2\n0,0,0,1,1\n1,0,0,1,0,1\n0\n1,0,0,2,0,0\n"),
       {"bar.k:41: *PART_INERTIA card 6 field XL", "not parallel"}},
      {"NodalRigidUnknownSet",
       deck("", "*CONSTRAINED_NODAL_RIGID_BODY\n10\n"),
       {"bar.k:25: *CONSTRAINED_NODAL_RIGID_BODY field NSID",
        "node set 10 is not defined (NSID blank or 0 means NSID = PID)"}},
      {"NodalRigidRelease",
       deck("", "*CONSTRAINED_NODAL_RIGID_BODY\n10,0,0,0,0,1\n"),
       {"bar.k:25: *CONSTRAINED_NODAL_RIGID_BODY card 1 field DRFLAG", "not supported"}},
      {"NodalRigidPartId",
       deck("", "*SET_NODE_LIST\n1\n1,2\n*CONSTRAINED_NODAL_RIGID_BODY\n1\n"),
       {"bar.k:28: *CONSTRAINED_NODAL_RIGID_BODY field PID", "has the ID of the *PART"}},
      {"NodalRigidUnknownPnode",
       deck("", "*SET_NODE_LIST\n7\n1,2\n*CONSTRAINED_NODAL_RIGID_BODY\n7,0,7,-66\n"),
       {"bar.k:28: *CONSTRAINED_NODAL_RIGID_BODY field PNODE", "node 66 is not defined"}},
      {"NodalRigidSpcLocalSystem",
       deck("", "*SET_NODE_LIST\n7\n1,2\n*CONSTRAINED_NODAL_RIGID_BODY_SPC\n7\n-1,3,1\n"),
       {"bar.k:28: *CONSTRAINED_NODAL_RIGID_BODY_SPC field CON1",
        "coordinate system 3 is not defined"}},
      {"RigidBodyUpdateType",
       deck("", "*RIGID_BODY_UPDATE\n3\n"),
       {"bar.k:25: *RIGID_BODY_UPDATE card 1 field TYPE", "value 3 is not supported"}},
      {"GenerationIrigid",
       deck("", "*INITIAL_VELOCITY_GENERATION\n1,2\n0,0,0,0,0,0,0,5\n"),
       {"bar.k:26: *INITIAL_VELOCITY_GENERATION card 2 field IRIGID"}},
  };
}

INSTANTIATE_TEST_SUITE_P(Rigid, KeywordError, ::testing::ValuesIn(rigid_cases()),
                         [](const auto& info) { return info.param.name; });

INSTANTIATE_TEST_SUITE_P(Cases, KeywordError, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.name; });

TEST(KeywordErrorContext, ErrorCarriesStructuredContext) {
  try {
    rf::io::read_deck_text(deck("", "", "         1        17\n"), "bar.k");
    FAIL() << "no error";
  } catch (const rf::InputError& e) {
    EXPECT_EQ(e.context().file, "bar.k");
    EXPECT_EQ(e.context().line, 17);
    EXPECT_EQ(e.context().keyword, "*SECTION_SOLID");
    EXPECT_EQ(e.context().card, 1);
    EXPECT_EQ(e.context().field, "ELFORM");
  }
}

TEST(KeywordErrorContext, BaseDeckIsValid) {
  EXPECT_NO_THROW(rf::io::read_deck_text(deck(), "bar.k"));
}

}  // namespace
