// Sensors: *SENSOR_DEFINE_NODE / _ELEMENT / _FUNCTION, *SENSOR_SWITCH (_CALC-LOGIC),
// *SENSOR_CONTROL, and *DEFINE_FUNCTION, which function sensors evaluate. Card layouts follow
// the LS-DYNA keyword manual as transcribed in ansys/pydyna's keyword classes (sensor/*.py,
// define/define_function.py); the TITLE option puts the title card before card 1. References
// between these definitions and to nodes, elements and vectors are checked in finish_sensors.
// What the solver does with them is in sensor/sensor.hpp and docs/sensors.md.
#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "io/keyword/definition_ids.hpp"
#include "io/keyword/handlers.hpp"
#include "io/keyword/number.hpp"
#include "model/function.hpp"

namespace rf::io::handlers {

namespace {

using model::Id;

const Layout kEightByTen = uniform_layout(8, 10);

bool only_blank_lines_left(const CardCursor& cursor, const Block& block) {
  for (std::size_t i = block.lines.size() - cursor.remaining(); i < block.lines.size(); ++i) {
    if (!trim(block.lines[i].text).empty()) return false;
  }
  return true;
}

// The _TITLE option's card comes first (pydyna: OptionSpec("TITLE", "pre/1")).
std::string read_title(const Block& block, CardCursor& cursor, int& n) {
  if (!block.has_option("TITLE")) return {};
  return cursor.next_text(n++, "title");
}

// A character field, trimmed and upper case; `fallback` when blank.
std::string word(const Card& card, std::size_t i, const char* fallback) {
  const std::string_view t = card.text(i);
  return t.empty() ? std::string(fallback) : to_upper(t);
}

void check_unique_sensor(const model::Model& m, Id id, const Card& card) {
  check_unique(m.sensors, id, card, "SENSID", "sensor");
}

// Sensor and switch fields that RigidFlex would have to reject if they were not default.
void require_default_real(const Card& card, std::size_t i, const char* field, double expected,
                          const char* why) {
  if (card.blank(i)) return;
  const double v = card.real(i, field, expected);
  if (v != expected) {
    throw card.error(field,
                     fmt::format("value {} is not supported yet ({}); leave it blank", v, why));
  }
}

// Every TYPE the manual lists for *SENSOR_CONTROL, so that a typo and an unsupported entity get
// different messages.
bool known_control_type(const std::string& type) {
  static const char* const kTypes[] = {
      "AIRBAG",   "BAGVENTPOP", "BELTPRET",  "BELTRETRA",  "BELTSLIP", "CONTACT",   "CONTACT2D",
      "CONSTRL",  "CNRB",       "CPM",       "DEF2RIG",    "ELESET",   "EM",        "FUNCTION",
      "JOINT",    "JOINTSTIF",  "LOADTHM",   "M PRESSURE", "POREAIR",  "PRESC-MOT", "PRESC-ORI",
      "PRESSURE", "PZBC",       "RWALL",     "SPC",        "SPOTWELD", "BPWPN",     "CURVE",
      "DISC-ELE", "DISC-ELES",  "JOINTSTIFF"};
  return std::find(std::begin(kTypes), std::end(kTypes), type) != std::end(kTypes);
}

}  // namespace

void define_function(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 1;
  const std::string title = read_title(block, cursor, n);
  const Card card = cursor.next(n, {10, 70}, "FID HEADING");
  model::DefinedFunction f;
  f.id = positive_id(card, 0, "FID", "function");
  f.heading = title.empty() ? std::string(card.text(1)) : title;
  check_unique(context.model.defined_functions, f.id, card, "FID", "*DEFINE_FUNCTION");
  // The function text runs to the end of the block; LS-DYNA allows it on several lines.
  f.where = card.location();
  f.text_line = cursor.peek() ? cursor.peek()->number : card.line_number();
  while (!cursor.at_end()) {
    const std::string line = cursor.next_text(n + 1, "function");
    if (line.empty()) continue;
    if (!f.text.empty()) f.text += ' ';
    f.text += line;
  }
  if (f.text.empty()) {
    throw card.error("FUNCTION", "the function text (card 2, e.g. f(a,b)= a+b) is missing");
  }
  try {
    f.evaluator = std::make_shared<const model::ArgumentFunction>(f.text);
  } catch (const std::runtime_error& e) {
    // Only an error when a keyword RigidFlex supports uses the function (finish_sensors).
    f.compile_error = e.what();
    context.warn(
        {block.file, f.text_line, block.keyword},
        fmt::format("*DEFINE_FUNCTION {}: cannot compile '{}': {}", f.id, f.text, f.compile_error));
  }
  context.model.defined_functions.emplace(f.id, std::move(f));
}

void skip_unsupported(const Block& block, ReaderContext& context) {
  ++context.model.unknown_keywords[block.keyword];
  context.warn(block.location(),
               fmt::format("keyword {} is not supported; its {} data line(s) were "
                           "skipped",
                           block.keyword, block.lines.size()));
}

void sensor_define_node(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  do {
    int n = 1;
    model::Sensor s;
    s.kind = model::SensorKind::Node;
    s.title = read_title(block, cursor, n);
    const Card card = cursor.next(n, kEightByTen, "SENSID NODE1 NODE2 VID - CTYPE");
    s.id = positive_id(card, 0, "SENSID", "sensor");
    check_unique_sensor(context.model, s.id, card);
    s.node1 = positive_id(card, 1, "NODE1", "node");
    s.node2 = card.id(2, "NODE2");
    if (s.node2 < 0) throw card.error("NODE2", "node ID must not be negative");
    s.vid = card.id(3, "VID");
    if (s.vid < 0) throw card.error("VID", "vector ID must not be negative");
    const std::string ctype = word(card, 5, "ACC");
    if (ctype == "ACC") {
      s.node_quantity = model::NodeQuantity::Acceleration;
    } else if (ctype == "VEL") {
      s.node_quantity = model::NodeQuantity::Velocity;
    } else if (ctype == "COORD") {
      s.node_quantity = model::NodeQuantity::Coordinate;
    } else if (ctype == "TEMP") {
      throw card.error("CTYPE", "TEMP is not supported: RigidFlex has no thermal solution");
    } else {
      throw card.error("CTYPE", fmt::format("'{}' is not a node sensor type (supported: ACC, VEL, "
                                            "COORD)",
                                            ctype));
    }
    s.where = card.location();
    context.model.sensors.emplace(s.id, std::move(s));
  } while (!only_blank_lines_left(cursor, block));
}

void sensor_define_element(const Block& block, ReaderContext& context) {
  static const char* const kComponents[] = {"XX", "YY", "ZZ", "XY", "YZ", "ZX", "VM"};
  CardCursor cursor(block, context.parameters);
  do {
    int n = 1;
    model::Sensor s;
    s.kind = model::SensorKind::Element;
    s.title = read_title(block, cursor, n);
    const Card card = cursor.next(n, kEightByTen, "SENSID ETYPE ELEMID COMP CTYPE LAYER SF PWR");
    s.id = positive_id(card, 0, "SENSID", "sensor");
    check_unique_sensor(context.model, s.id, card);
    const std::string etype = word(card, 1, "BEAM");
    if (etype != "SOLID") {
      throw card.error("ETYPE",
                       fmt::format("{}{} elements are not supported (supported: SOLID)", etype,
                                   card.blank(1) ? " (the default of a blank ETYPE)" : ""));
    }
    s.element = positive_id(card, 2, "ELEMID", "element");
    const std::string comp = word(card, 3, "XX");
    const auto it = std::find(std::begin(kComponents), std::end(kComponents), comp);
    if (it == std::end(kComponents)) {
      throw card.error("COMP", fmt::format("'{}' is not a solid component (supported: XX YY ZZ "
                                           "XY YZ ZX, and VM for von Mises)",
                                           comp));
    }
    s.component = static_cast<int>(it - std::begin(kComponents));
    const std::string ctype = word(card, 4, "STRAIN");
    if (ctype == "STRESS") {
      s.element_quantity = model::ElementQuantity::Stress;
    } else if (ctype == "STRAIN") {
      s.element_quantity = model::ElementQuantity::Strain;
    } else {
      throw card.error("CTYPE", fmt::format("'{}' is not supported for solids (supported: STRESS, "
                                            "STRAIN)",
                                            ctype));
    }
    // LAYER concerns shells. SF and PWR rescale the value; the manual text available to us does
    // not say how they combine, so only their neutral value is accepted.
    require_default_real(card, 6, "SF", 1.0, "scaling of the sensor value");
    require_default_real(card, 7, "PWR", 1.0, "power of the sensor value");
    s.where = card.location();
    context.model.sensors.emplace(s.id, std::move(s));
  } while (!only_blank_lines_left(cursor, block));
}

void sensor_define_function(const Block& block, ReaderContext& context) {
  static const char* const kSens[] = {"SENS1", "SENS2", "SENS3", "SENS4", "SENS5", "SENS6"};
  CardCursor cursor(block, context.parameters);
  do {
    int n = 1;
    model::Sensor s;
    s.kind = model::SensorKind::Function;
    s.title = read_title(block, cursor, n);
    const Card card = cursor.next(n, kEightByTen, "SENSID FUNC SENS1 ... SENS6");
    s.id = positive_id(card, 0, "SENSID", "sensor");
    check_unique_sensor(context.model, s.id, card);
    s.function = positive_id(card, 1, "FUNC", "*DEFINE_FUNCTION");
    const Id first = card.id(2, "SENS1");
    if (first < 0) {
      // |SENS1| sensors follow: up to five in SENS2..SENS6, the rest 8 per card (the manual
      // allows 15 in all). Fields are named by position, SENS1 being the count.
      const Id count = -first;
      if (count > 15) {
        throw card.error("SENS1", fmt::format("{} sensors: at most 15 are allowed", count));
      }
      for (Id k = 0; k < std::min<Id>(count, 5); ++k) {
        const std::string name = fmt::format("SENS{}", k + 2);
        s.inputs.push_back(
            positive_id(card, static_cast<std::size_t>(3 + k), name.c_str(), "sensor"));
      }
      int card_number = n;
      while (static_cast<Id>(s.inputs.size()) < count) {
        const Card more = cursor.next(++card_number, kEightByTen, "further sensor IDs");
        const Id here = std::min<Id>(count - static_cast<Id>(s.inputs.size()), 8);
        for (Id k = 0; k < here; ++k) {
          const std::string name = fmt::format("SENS{}", s.inputs.size() + 2);
          s.inputs.push_back(
              positive_id(more, static_cast<std::size_t>(k), name.c_str(), "sensor"));
        }
      }
    } else {
      bool blank_seen = false;
      for (std::size_t k = 0; k < 6; ++k) {
        const Id id = card.id(2 + k, kSens[k]);
        if (id == 0) {
          blank_seen = true;
          continue;
        }
        if (id < 0) throw card.error(kSens[k], "only SENS1 may be negative (a sensor count)");
        if (blank_seen) {
          throw card.error(kSens[k], "an earlier SENSi is blank: arguments are bound by position");
        }
        s.inputs.push_back(id);
      }
    }
    s.where = card.location();
    context.model.sensors.emplace(s.id, std::move(s));
  } while (!only_blank_lines_left(cursor, block));
}

void sensor_switch(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  do {
    int n = 1;
    model::SensorSwitch w;
    w.title = read_title(block, cursor, n);
    const Card card =
        cursor.next(n, kEightByTen, "SWITID TYPE SENSID LOGIC VALUE FILTRID TIMWIN TDELAY");
    w.id = positive_id(card, 0, "SWITID", "switch");
    check_unique(context.model.sensor_switches, w.id, card, "SWITID", "switch");
    const std::string type = word(card, 1, "SENSOR");
    if (type == "TIME") {
      w.time = true;
    } else if (type != "SENSOR") {
      throw card.error("TYPE",
                       fmt::format("'{}' is not a switch type (supported: SENSOR, TIME)", type));
    }
    if (!w.time) w.sensor = positive_id(card, 2, "SENSID", "sensor");
    const std::string logic = word(card, 3, "LT");
    if (logic == "GT") {
      w.greater = true;
    } else if (logic != "LT") {
      throw card.error("LOGIC", fmt::format("'{}' is not a comparison (supported: LT, GT)", logic));
    }
    w.value = card.real(4, "VALUE", 0.0);
    if (card.id(5, "FILTRID") != 0) {
      throw card.error("FILTRID",
                       "filters (*DEFINE_FILTER) are not supported yet; leave FILTRID "
                       "blank (TIMWIN requires the condition to hold over a window)");
    }
    w.time_window = card.real(6, "TIMWIN", 0.0);
    if (w.time_window < 0.0) throw card.error("TIMWIN", "the time window must not be negative");
    w.delay = card.real(7, "TDELAY", 0.0);
    if (w.delay < 0.0) throw card.error("TDELAY", "the delay must not be negative");
    w.where = card.location();
    context.model.sensor_switches.emplace(w.id, std::move(w));
  } while (!only_blank_lines_left(cursor, block));
}

void sensor_switch_calc_logic(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  do {
    int n = 1;
    model::SensorSwitch w;
    w.calc_logic = true;
    w.title = read_title(block, cursor, n);
    const Card card = cursor.next(n, kEightByTen, "SWITID SWIT1 ... SWIT7");
    w.id = positive_id(card, 0, "SWITID", "switch");
    check_unique(context.model.sensor_switches, w.id, card, "SWITID", "switch");
    w.where = card.location();
    auto take = [&](const Card& c, std::size_t first_field, int first_index) {
      for (std::size_t k = 0; k < 7; ++k) {
        const std::string name = fmt::format("SWIT{}", first_index + static_cast<int>(k));
        const Id id = c.id(first_field + k, name.c_str());
        if (id == 0) continue;
        if (!w.logic_inputs.empty() && (id > 0) != (w.logic_inputs.front() > 0)) {
          throw c.error(name.c_str(),
                        "positive (AND) and negative (OR) switch IDs are mixed; the order in "
                        "which LS-DYNA combines them is not documented, so RigidFlex accepts one "
                        "kind per card (combine two *SENSOR_SWITCH_CALC-LOGIC instead)");
        }
        w.logic_inputs.push_back(id);
      }
    };
    take(card, 1, 1);
    // Optional continuation: "+" in the first field, SWIT8..SWIT14 (pydyna's card 2).
    if (const DataLine* next = cursor.peek(); next && trim(next->text).starts_with('+')) {
      const Card more = cursor.next(n + 1, kEightByTen, "+ SWIT8 ... SWIT14");
      take(more, 1, 8);
    }
    if (w.logic_inputs.empty()) throw card.error("SWIT1", "no switch is given");
    context.model.sensor_switches.emplace(w.id, std::move(w));
  } while (!only_blank_lines_left(cursor, block));
}

void sensor_control(const Block& block, ReaderContext& context) {
  static const char* const kSwit[] = {"SWIT1", "SWIT2", "SWIT3", "SWIT4",
                                      "SWIT5", "SWIT6", "SWIT7"};
  CardCursor cursor(block, context.parameters);
  do {
    int n = 1;
    model::SensorControl c;
    c.title = read_title(block, cursor, n);
    const Card c1 = cursor.next(n, kEightByTen, "CNTLID TYPE TYPEID TIMEOFF NREP ESTYP SIDR");
    c.id = positive_id(c1, 0, "CNTLID", "sensor control");
    check_unique(context.model.sensor_controls, c.id, c1, "CNTLID", "sensor control");
    c.type = word(c1, 1, "AIRBAG");
    if (!known_control_type(c.type)) {
      throw c1.error("TYPE", fmt::format("'{}' is not a *SENSOR_CONTROL TYPE", c.type));
    }
    if (c.type != "DEF2RIG") {
      throw c1.error("TYPE",
                     fmt::format("TYPE {}{} is not supported yet (supported: DEF2RIG, which "
                                 "drives *DEFORMABLE_TO_RIGID_AUTOMATIC with CODE 5)",
                                 c.type, c1.blank(1) ? " (the default of a blank TYPE)" : ""));
    }
    c.type_id =
        positive_id(c1, 2, "TYPEID", "switch set (SWSET of *DEFORMABLE_TO_RIGID_AUTOMATIC)");
    const int timeoff = c1.flag(3, "TIMEOFF", 0);
    if (timeoff != 0 && timeoff != 1) {
      throw c1.error("TIMEOFF", fmt::format("value {} is not 0 or 1", timeoff));
    }
    if (timeoff == 1) {
      context.warn(c1.location(),
                   "TIMEOFF ignored: it offsets time-dependent curves (TYPE CURVE, "
                   "FUNCTION) and has no meaning for DEF2RIG");
    }
    c.nrep = c1.flag(4, "NREP", 0);
    if (c.nrep < -1) {
      throw c1.error("NREP", fmt::format("value {} is not -1 (repeat without end) or a number of "
                                         "passes >= 0",
                                         c.nrep));
    }
    if (!c1.blank(5)) {
      context.warn(c1.location(), fmt::format("ESTYP/DEFCV '{}' ignored: it concerns TYPE ELESET "
                                              "and CURVE only",
                                              c1.text(5)));
    }
    const int sidr = c1.flag(6, "SIDR", 0);
    if (sidr == 1) {
      throw c1.error("SIDR",
                     "SIDR 1 (a sensor control for dynamic relaxation only) is not supported: "
                     "sensors act in the transient (0 or 2)");
    }
    if (sidr != 0 && sidr != 2) {
      throw c1.error("SIDR", fmt::format("value {} is not 0, 1 or 2", sidr));
    }
    const Card c2 = cursor.next(n + 1, kEightByTen, "INITSTT SWIT1 ... SWIT7");
    const std::string initial = word(c2, 0, "ON");
    if (initial == "OFF") {
      c.initially_on = false;
    } else if (initial != "ON") {
      throw c2.error("INITSTT", fmt::format("'{}' is not ON or OFF", initial));
    }
    for (std::size_t k = 0; k < 7; ++k) {
      const Id id = c2.id(1 + k, kSwit[k]);
      if (id < 0) throw c2.error(kSwit[k], "switch ID must not be negative");
      if (id > 0) c.switches.push_back(id);
    }
    c.where = c1.location();
    context.model.sensor_controls.emplace(c.id, std::move(c));
  } while (!only_blank_lines_left(cursor, block));
}

void finish_sensors(ReaderContext& context, const std::unordered_set<Id>& nodes) {
  model::Model& m = context.model;
  for (const auto& [id, f] : m.defined_functions) {
    if (const auto it = m.curves.find(id); it != m.curves.end()) {
      throw located_error(f.where, "FID",
                          fmt::format("*DEFINE_FUNCTION {} has the ID of the load curve defined at "
                                      "{}:{}; functions and curves share one ID space",
                                      id, it->second.where.file, it->second.where.line));
    }
  }
  if (m.sensors.empty() && m.sensor_switches.empty() && m.sensor_controls.empty()) return;

  const bool skipped_sensors = [&] {
    for (const auto& [keyword, count] : m.unknown_keywords) {
      if (keyword.starts_with("*SENSOR_DEFINE")) return true;
    }
    return false;
  }();
  const auto undefined_sensor = [&](Id sid) {
    return fmt::format("sensor {} is not defined{}", sid,
                       skipped_sensors ? " (unsupported *SENSOR_DEFINE keywords were skipped; see "
                                         "the warnings)"
                                       : "");
  };
  std::unordered_set<Id> solids;
  for (const auto& e : m.solids) solids.insert(e.id);
  for (const auto& [id, s] : m.sensors) {
    switch (s.kind) {
      case model::SensorKind::Node:
        if (!nodes.count(s.node1)) {
          throw located_error(s.where, "NODE1", fmt::format("node {} is not defined", s.node1));
        }
        if (s.node2 != 0 && !nodes.count(s.node2)) {
          throw located_error(s.where, "NODE2", fmt::format("node {} is not defined", s.node2));
        }
        if (s.vid != 0 && !m.vectors.count(s.vid)) {
          throw located_error(s.where, "VID",
                              fmt::format("vector {} is not defined (*DEFINE_VECTOR)", s.vid));
        }
        break;
      case model::SensorKind::Element:
        if (!solids.count(s.element)) {
          throw located_error(s.where, "ELEMID",
                              fmt::format("solid element {} is not defined", s.element));
        }
        break;
      case model::SensorKind::Function: {
        const auto f = m.defined_functions.find(s.function);
        if (f == m.defined_functions.end()) {
          throw located_error(
              s.where, "FUNC",
              fmt::format("function {} is not defined (*DEFINE_FUNCTION)", s.function));
        }
        if (!f->second.evaluator) {
          const model::SourceLocation text{f->second.where.file, f->second.text_line,
                                           f->second.where.keyword};
          throw located_error(text, "FUNCTION",
                              fmt::format("function {} used by sensor {} cannot be compiled: '{}': "
                                          "{}",
                                          s.function, id, f->second.text, f->second.compile_error));
        }
        const std::size_t arguments = f->second.evaluator->arguments().size();
        if (arguments != s.inputs.size()) {
          throw located_error(s.where, "FUNC",
                              fmt::format("function {} ({}) takes {} argument(s) but {} sensor(s) "
                                          "are given",
                                          s.function, f->second.text, arguments, s.inputs.size()));
        }
        for (std::size_t k = 0; k < s.inputs.size(); ++k) {
          if (!m.sensors.count(s.inputs[k])) {
            throw located_error(s.where, fmt::format("SENS{}", k + 1).c_str(),
                                undefined_sensor(s.inputs[k]));
          }
        }
        break;
      }
    }
  }
  // Function sensors must not depend on themselves (they are evaluated in dependency order).
  std::unordered_map<Id, int> mark;  // 1: on the current path, 2: done
  std::function<void(Id, const model::Sensor&)> visit_sensor = [&](Id id, const model::Sensor& s) {
    mark[id] = 1;
    for (const Id input : s.inputs) {
      const int state = mark[input];
      if (state == 1) {
        throw located_error(
            s.where, "SENS1",
            fmt::format("function sensors form a cycle through sensors {} and {}", id, input));
      }
      if (state == 0) visit_sensor(input, m.sensors.at(input));
    }
    mark[id] = 2;
  };
  for (const auto& [id, s] : m.sensors) {
    if (mark[id] == 0) visit_sensor(id, s);
  }

  for (const auto& [id, w] : m.sensor_switches) {
    if (!w.calc_logic && !w.time && !m.sensors.count(w.sensor)) {
      throw located_error(w.where, "SENSID", undefined_sensor(w.sensor));
    }
    for (std::size_t k = 0; k < w.logic_inputs.size(); ++k) {
      const Id input = std::abs(w.logic_inputs[k]);
      if (!m.sensor_switches.count(input)) {
        throw located_error(w.where, "SWIT1",
                            fmt::format("switch {} is not defined (*SENSOR_SWITCH)", input));
      }
    }
  }
  mark.clear();
  std::function<void(Id, const model::SensorSwitch&)> visit_switch =
      [&](Id id, const model::SensorSwitch& w) {
        mark[id] = 1;
        for (const Id signed_input : w.logic_inputs) {
          const Id input = std::abs(signed_input);
          const int state = mark[input];
          if (state == 1) {
            throw located_error(w.where, "SWIT1",
                                fmt::format("*SENSOR_SWITCH_CALC-LOGIC switches form a cycle "
                                            "through switches {} and {}",
                                            id, input));
          }
          if (state == 0) visit_switch(input, m.sensor_switches.at(input));
        }
        mark[id] = 2;
      };
  for (const auto& [id, w] : m.sensor_switches) {
    if (mark[id] == 0) visit_switch(id, w);
  }

  for (const auto& [id, c] : m.sensor_controls) {
    for (std::size_t k = 0; k < c.switches.size(); ++k) {
      if (!m.sensor_switches.count(c.switches[k])) {
        throw located_error(
            c.where, fmt::format("SWIT{}", k + 1).c_str(),
            fmt::format("switch {} is not defined (*SENSOR_SWITCH)", c.switches[k]));
      }
    }
  }
}

}  // namespace rf::io::handlers
