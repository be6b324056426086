// Sensor keywords: card layouts (fixed and free format, _TITLE), defaults, and bad input that must
// give an rf::InputError naming file, line, keyword and field.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "keyword_test_util.hpp"
#include "model/function.hpp"

namespace {

using rf::model::Model;

// One hexahedron (nodes 1-8, element 1) and the part it needs.
const std::string kMesh =
    "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
    "*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n*PART\np\n1,1,1\n*SECTION_SOLID\n1,1\n"
    "*MAT_ELASTIC\n1,1.0,100.0,0.3\n*DEFINE_VECTOR\n3,0,0,0,0,0,1\n";

Model read(const std::string& cards) {
  return rf::io::read_deck_text(kMesh + cards, "sensor.k");
}

// The InputError's context for a deck that must fail.
rf::InputErrorContext error_of(const std::string& cards) {
  try {
    read(cards);
  } catch (const rf::InputError& e) {
    return e.context();
  }
  ADD_FAILURE() << "no InputError for:\n" << cards;
  return {};
}

// Line number in the deck of line `line_in_cards` of the cards (kMesh has 21 lines).
int line_of(int line_in_cards) {
  return 21 + line_in_cards;
}

TEST(KeywordSensor, FixedFormatCardsAndDefaults) {
  // Fixed 10-column fields, as LS-DYNA writes them.
  const Model m = read(
      "*SENSOR_DEFINE_NODE_TITLE\nnode seven\n"
      "         1         7         0         3               COORD\n"
      "*SENSOR_DEFINE_NODE\n         2         7\n"
      "*SENSOR_DEFINE_ELEMENT\n         5     SOLID         1        VM    STRESS\n"
      "*SENSOR_SWITCH\n       601      TIME                  GT       0.5                 0.1"
      "       0.2\n"
      "*SENSOR_SWITCH_CALC-LOGIC\n       610       601       601\n"
      "*SENSOR_CONTROL\n       701   DEF2RIG        42                   3\n"
      "       OFF       601       601\n");
  const auto& s1 = m.sensors.at(1);
  EXPECT_EQ(s1.title, "node seven");
  EXPECT_EQ(s1.kind, rf::model::SensorKind::Node);
  EXPECT_EQ(s1.node1, 7);
  EXPECT_EQ(s1.node2, 0);
  EXPECT_EQ(s1.vid, 3);
  EXPECT_EQ(s1.node_quantity, rf::model::NodeQuantity::Coordinate);
  EXPECT_EQ(s1.where.line, line_of(3));
  EXPECT_EQ(m.sensors.at(2).node_quantity, rf::model::NodeQuantity::Acceleration);  // default
  EXPECT_EQ(m.sensors.at(2).vid, 0);
  const auto& s5 = m.sensors.at(5);
  EXPECT_EQ(s5.kind, rf::model::SensorKind::Element);
  EXPECT_EQ(s5.element, 1);
  EXPECT_EQ(s5.component, 6);
  EXPECT_EQ(s5.element_quantity, rf::model::ElementQuantity::Stress);
  const auto& w = m.sensor_switches.at(601);
  EXPECT_TRUE(w.time);
  EXPECT_TRUE(w.greater);
  EXPECT_EQ(w.value, 0.5);
  EXPECT_EQ(w.time_window, 0.1);
  EXPECT_EQ(w.delay, 0.2);
  EXPECT_EQ(m.sensor_switches.at(610).logic_inputs, (std::vector<rf::model::Id>{601, 601}));
  const auto& c = m.sensor_controls.at(701);
  EXPECT_EQ(c.type, "DEF2RIG");
  EXPECT_EQ(c.type_id, 42);
  EXPECT_EQ(c.nrep, 3);
  EXPECT_FALSE(c.initially_on);
  EXPECT_EQ(c.switches, (std::vector<rf::model::Id>{601, 601}));
}

TEST(KeywordSensor, FreeFormatFunctionsAndContinuations) {
  const Model m = read(
      "*SENSOR_DEFINE_NODE\n1,7\n2,8,1,,VEL\n"
      "*DEFINE_FUNCTION\n500,sum of nine\n"
      "f(a1,a2,a3,a4,a5,a6,a7,a8,a9)= a1+a2+a3+a4+a5\n+a6+a7+a8+a9\n"
      "*SENSOR_DEFINE_FUNCTION\n9,500,-9,1,2,1,2,1\n2,1,2,1\n"
      "*SENSOR_SWITCH\n601,,9,gt,1.0\n602,,9\n"
      "*SENSOR_SWITCH_CALC-LOGIC\n610,-601,-602\n+,-601\n"
      "*SENSOR_CONTROL\n701,def2rig,5\nON\n");
  EXPECT_EQ(m.sensors.at(9).inputs, (std::vector<rf::model::Id>{1, 2, 1, 2, 1, 2, 1, 2, 1}));
  const auto& f = m.defined_functions.at(500);
  EXPECT_EQ(f.heading, "sum of nine");
  ASSERT_TRUE(f.evaluator);
  const double args[9] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  EXPECT_EQ((*f.evaluator)(args, 0.0), 45.0);
  EXPECT_TRUE(m.sensor_switches.at(601).greater);
  EXPECT_FALSE(m.sensor_switches.at(602).greater);  // LOGIC blank: LT
  EXPECT_EQ(m.sensor_switches.at(602).value, 0.0);
  EXPECT_EQ(m.sensor_switches.at(610).logic_inputs, (std::vector<rf::model::Id>{-601, -602, -601}));
  EXPECT_TRUE(m.sensor_controls.at(701).initially_on);
  EXPECT_TRUE(m.sensor_controls.at(701).switches.empty());
}

TEST(KeywordSensor, FunctionTextFollowsC) {
  rf::model::ArgumentFunction f("g(x, y) = pow(x, 2) + log(y) + fabs(-1) + atan2(0, 1) + time;");
  EXPECT_EQ(f.name(), "g");
  EXPECT_EQ(f.arguments(), (std::vector<std::string>{"x", "y"}));
  const double args[2] = {3.0, std::exp(2.0)};
  EXPECT_NEAR(f(args, 0.5), 9.0 + 2.0 + 1.0 + 0.0 + 0.5, 1e-14);
  EXPECT_THROW(rf::model::ArgumentFunction("g(x) { return x; }"), std::runtime_error);
  EXPECT_THROW(rf::model::ArgumentFunction("g(x) = x + y"), std::runtime_error);
  EXPECT_THROW(rf::model::ArgumentFunction("g(x, x) = x"), std::runtime_error);
}

struct BadCase {
  const char* name;
  std::string cards;
  int line;  // line within `cards`, 1-based
  const char* keyword;
  const char* field;
  const char* says;
};

class KeywordSensorError : public ::testing::TestWithParam<BadCase> {};

TEST_P(KeywordSensorError, NamesFileLineKeywordAndField) {
  const BadCase& c = GetParam();
  try {
    read(c.cards);
    ADD_FAILURE() << "no InputError";
  } catch (const rf::InputError& e) {
    EXPECT_EQ(e.context().file, "sensor.k");
    EXPECT_EQ(e.context().line, line_of(c.line)) << e.what();
    EXPECT_EQ(e.context().keyword, c.keyword) << e.what();
    EXPECT_EQ(e.context().field, c.field) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.says), std::string::npos) << e.what();
  }
}

const std::string kSensor = "*SENSOR_DEFINE_NODE\n1,7,0,3,,COORD\n";
const std::string kSwitch = kSensor + "*SENSOR_SWITCH\n601,,1,LT,0.5\n";

INSTANTIATE_TEST_SUITE_P(
    Cases, KeywordSensorError,
    ::testing::Values(
        BadCase{"UnknownSensorInSwitch", "*SENSOR_SWITCH\n601,SENSOR,99,LT,0.5\n", 2,
                "*SENSOR_SWITCH", "SENSID", "sensor 99 is not defined"},
        BadCase{"UnknownSwitchInControl", kSwitch + "*SENSOR_CONTROL\n701,DEF2RIG,5\nOFF,601,602\n",
                6, "*SENSOR_CONTROL", "SWIT2", "switch 602 is not defined"},
        BadCase{"UnknownSwitchInLogic", kSwitch + "*SENSOR_SWITCH_CALC-LOGIC\n610,601,77\n", 6,
                "*SENSOR_SWITCH_CALC-LOGIC", "SWIT1", "switch 77 is not defined"},
        BadCase{"UnsupportedControlType", kSwitch + "*SENSOR_CONTROL\n701,CONTACT,5\nOFF,601\n", 6,
                "*SENSOR_CONTROL", "TYPE", "TYPE CONTACT is not supported yet"},
        BadCase{"BlankControlTypeIsAirbag", kSwitch + "*SENSOR_CONTROL\n701,,5\n", 6,
                "*SENSOR_CONTROL", "TYPE", "AIRBAG (the default of a blank TYPE)"},
        BadCase{"NotAControlType", kSwitch + "*SENSOR_CONTROL\n701,DEF2RIGID,5\n", 6,
                "*SENSOR_CONTROL", "TYPE", "is not a *SENSOR_CONTROL TYPE"},
        BadCase{"MissingSwitchSet", kSwitch + "*SENSOR_CONTROL\n701,DEF2RIG\n", 6,
                "*SENSOR_CONTROL", "TYPEID", "must be a positive integer"},
        BadCase{"BadInitialStatus", kSwitch + "*SENSOR_CONTROL\n701,DEF2RIG,5\nMAYBE,601\n", 7,
                "*SENSOR_CONTROL", "INITSTT", "is not ON or OFF"},
        BadCase{"BadNrep", kSwitch + "*SENSOR_CONTROL\n701,DEF2RIG,5,,-2\n", 6, "*SENSOR_CONTROL",
                "NREP", "is not -1"},
        BadCase{"DynamicRelaxationOnly", kSwitch + "*SENSOR_CONTROL\n701,DEF2RIG,5,,,,1\n", 6,
                "*SENSOR_CONTROL", "SIDR", "dynamic relaxation"},
        BadCase{"BadLogic", kSensor + "*SENSOR_SWITCH\n601,SENSOR,1,EQ,0.5\n", 4, "*SENSOR_SWITCH",
                "LOGIC", "'EQ' is not a comparison"},
        BadCase{"BadSwitchType", kSensor + "*SENSOR_SWITCH\n601,CURVE,1\n", 4, "*SENSOR_SWITCH",
                "TYPE", "is not a switch type"},
        BadCase{"Filter", kSensor + "*SENSOR_SWITCH\n601,SENSOR,1,LT,0.5,3\n", 4, "*SENSOR_SWITCH",
                "FILTRID", "not supported yet"},
        BadCase{"NegativeWindow", kSensor + "*SENSOR_SWITCH\n601,SENSOR,1,LT,0.5,,-1\n", 4,
                "*SENSOR_SWITCH", "TIMWIN", "must not be negative"},
        BadCase{"MixedLogic", kSwitch + "*SENSOR_SWITCH_CALC-LOGIC\n610,601,-601\n", 6,
                "*SENSOR_SWITCH_CALC-LOGIC", "SWIT2", "are mixed"},
        BadCase{"LogicCycle", kSwitch + "*SENSOR_SWITCH_CALC-LOGIC\n610,601,611\n611,610\n", 7,
                "*SENSOR_SWITCH_CALC-LOGIC", "SWIT1", "form a cycle"},
        BadCase{"UnknownNode", "*SENSOR_DEFINE_NODE\n1,77\n", 2, "*SENSOR_DEFINE_NODE", "NODE1",
                "node 77 is not defined"},
        BadCase{"UnknownSecondNode", "*SENSOR_DEFINE_NODE\n1,7,78\n", 2, "*SENSOR_DEFINE_NODE",
                "NODE2", "node 78 is not defined"},
        BadCase{"UnknownVector", "*SENSOR_DEFINE_NODE\n1,7,0,9\n", 2, "*SENSOR_DEFINE_NODE", "VID",
                "vector 9 is not defined"},
        BadCase{"Temperature", "*SENSOR_DEFINE_NODE\n1,7,0,0,,TEMP\n", 2, "*SENSOR_DEFINE_NODE",
                "CTYPE", "no thermal"},
        BadCase{"BadNodeType", "*SENSOR_DEFINE_NODE\n1,7,0,0,,DISP\n", 2, "*SENSOR_DEFINE_NODE",
                "CTYPE", "'DISP' is not a node sensor type"},
        BadCase{"DuplicateSensor", kSensor + "*SENSOR_DEFINE_NODE\n1,8\n", 4, "*SENSOR_DEFINE_NODE",
                "SENSID", "sensor 1 is already defined"},
        BadCase{"UnknownElement", "*SENSOR_DEFINE_ELEMENT\n5,SOLID,9\n", 2,
                "*SENSOR_DEFINE_ELEMENT", "ELEMID", "solid element 9 is not defined"},
        BadCase{"ShellElement", "*SENSOR_DEFINE_ELEMENT\n5,SHELL,1\n", 2, "*SENSOR_DEFINE_ELEMENT",
                "ETYPE", "SHELL elements are not supported"},
        BadCase{"BlankElementTypeIsBeam", "*SENSOR_DEFINE_ELEMENT\n5,,1\n", 2,
                "*SENSOR_DEFINE_ELEMENT", "ETYPE", "BEAM (the default of a blank ETYPE)"},
        BadCase{"BadComponent", "*SENSOR_DEFINE_ELEMENT\n5,SOLID,1,AXIAL\n", 2,
                "*SENSOR_DEFINE_ELEMENT", "COMP", "'AXIAL' is not a solid component"},
        BadCase{"ElementFailure", "*SENSOR_DEFINE_ELEMENT\n5,SOLID,1,XX,FAIL\n", 2,
                "*SENSOR_DEFINE_ELEMENT", "CTYPE", "'FAIL' is not supported"},
        BadCase{"ScaleFactor", "*SENSOR_DEFINE_ELEMENT\n5,SOLID,1,XX,STRESS,,2.0\n", 2,
                "*SENSOR_DEFINE_ELEMENT", "SF", "not supported yet"},
        BadCase{"UnknownFunction", kSensor + "*SENSOR_DEFINE_FUNCTION\n9,500,1\n", 4,
                "*SENSOR_DEFINE_FUNCTION", "FUNC", "function 500 is not defined"},
        BadCase{"ArgumentCount",
                kSensor + "*DEFINE_FUNCTION\n500\nf(a,b)=a+b\n*SENSOR_DEFINE_FUNCTION\n9,500,1\n",
                7, "*SENSOR_DEFINE_FUNCTION", "FUNC", "takes 2 argument(s) but 1 sensor(s)"},
        BadCase{
            "UnknownFunctionInput",
            kSensor + "*DEFINE_FUNCTION\n500\nf(a,b)=a+b\n*SENSOR_DEFINE_FUNCTION\n9,500,1,44\n", 7,
            "*SENSOR_DEFINE_FUNCTION", "SENS2", "sensor 44 is not defined"},
        BadCase{"BlankBeforeInput",
                kSensor + "*DEFINE_FUNCTION\n500\nf(a,b)=a+b\n*SENSOR_DEFINE_FUNCTION\n9,500,,1\n",
                7, "*SENSOR_DEFINE_FUNCTION", "SENS2", "an earlier SENSi is blank"},
        BadCase{"FunctionSensorCycle",
                "*DEFINE_FUNCTION\n500\nf(a)=a\n*SENSOR_DEFINE_FUNCTION\n8,500,9\n9,500,8\n", 6,
                "*SENSOR_DEFINE_FUNCTION", "SENS1", "form a cycle"},
        BadCase{"FunctionDoesNotCompile",
                kSensor + "*DEFINE_FUNCTION\n500\nf(a)=a+*2\n*SENSOR_DEFINE_FUNCTION\n9,500,1\n", 5,
                "*DEFINE_FUNCTION", "FUNCTION", "cannot be compiled"},
        BadCase{"FunctionSharesCurveId",
                "*DEFINE_CURVE\n500\n0,0\n1,1\n*DEFINE_FUNCTION\n500\nf(a)=a\n", 6,
                "*DEFINE_FUNCTION", "FID", "share one ID space"},
        BadCase{"NodeSetSensor", "*SENSOR_DEFINE_NODE_SET\n1,1\n", 1, "*SENSOR_DEFINE_NODE_SET", "",
                "not supported: a sensor; *SENSOR_DEFINE_NODE is read, with the options _TITLE"}),
    [](const ::testing::TestParamInfo<BadCase>& info) { return std::string(info.param.name); });

TEST(KeywordSensor, UnusedFunctionThatDoesNotCompileIsAWarning) {
  const Model m = read(
      "*DEFINE_FUNCTION\n500\nfloat f(float a) { return a; }\n"
      "*DEFINE_FUNCTION_TABULATED\n501\n1,2\n");
  ASSERT_EQ(m.defined_functions.count(500), 1u);
  EXPECT_FALSE(m.defined_functions.at(500).evaluator);
  int warnings = 0;
  for (const auto& w : m.warnings) {
    warnings += w.message.find("cannot compile") != std::string::npos;
    warnings += w.message.find("*DEFINE_FUNCTION_TABULATED is not supported") != std::string::npos;
  }
  EXPECT_EQ(warnings, 2);
}

TEST(KeywordSensor, SkippedSensorKeywordsAreNamedInTheError) {
  // *SENSOR_DEFINE_FORCE is unsupported physics (an error of its own); skipped on request, the
  // switch that names its sensor says why the sensor is missing.
  const std::string cards = "*SENSOR_DEFINE_FORCE\n1,1\n*SENSOR_SWITCH\n601,,1\n";
  EXPECT_NE(std::string(rf::test::input_error_of(kMesh + cards, "sensor.k"))
                .find("sensor.k:22: *SENSOR_DEFINE_FORCE: not supported: a sensor"),
            std::string::npos);
  rf::io::ReadOptions options;
  options.ignore_unsupported = true;
  try {
    rf::io::read_deck_text(kMesh + cards, "sensor.k", ".", options);
    ADD_FAILURE() << "no InputError";
  } catch (const rf::InputError& e) {
    EXPECT_EQ(e.context().field, "SENSID");
    EXPECT_NE(std::string(e.what()).find("unsupported *SENSOR_DEFINE keywords were skipped"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
