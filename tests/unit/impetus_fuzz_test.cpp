// Damaged IMPETUS decks must end in a model or an rf::InputError that names the file and a
// line, never in another exception, a crash, a hang or a multi-gigabyte allocation. Models
// that read are also set up for the solver (mesh generation, p-elevation, seed-point
// surfaces and rigid bodies happen there): errors must then be rf::InputError or
// rf::SolverError. The mutations are those of keyword_fuzz_test.cpp plus IMPETUS syntax:
// [expressions], %parameters, quoted titles, comma fields, one-line decks.
#include <gtest/gtest.h>

#include <chrono>
#include <regex>

#include "deck_mutation.hpp"
#include "keyword_test_util.hpp"
#include "solver/boundary.hpp"
#include "solver/build_state.hpp"
#include "solver/rigid_bodies.hpp"

namespace {

using rf::test::input_error_of;

std::string seed_text() {
  return rf::test::read_text_file(std::string(RIGIDFLEX_EXAMPLES) + "/seed_rigid_body_update.k");
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t pos = text.find(from); pos != std::string::npos;
       pos = text.find(from, pos + to.size())) {
    text.replace(pos, from.size(), to);
  }
  return text;
}

// Spans of numbers, [expressions] and %names: the fields a mutation replaces.
std::vector<std::pair<std::size_t, std::size_t>> value_spans(const std::string& text) {
  static const std::regex value(R"(\[[^\]\n]*\]|%[A-Za-z_][A-Za-z0-9_]*|[-+]?[0-9][0-9.eE+-]*)");
  std::vector<std::pair<std::size_t, std::size_t>> spans;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), value);
       it != std::sregex_iterator(); ++it) {
    spans.emplace_back(static_cast<std::size_t>(it->position()),
                       static_cast<std::size_t>(it->length()));
  }
  return spans;
}

std::string mutate(const std::string& original, rf::test::DeckMutator& m) {
  const auto pick = [&](std::size_t n) { return m.pick(n); };
  std::string text = original;
  const int edits = 1 + static_cast<int>(pick(3));
  for (int e = 0; e < edits; ++e) {
    switch (pick(12)) {
      case 0:
        m.truncate(text);
        break;
      case 1:
        m.delete_line(text);
        break;
      case 2:
        m.duplicate_line(text);
        break;
      case 3:
        m.swap_lines(text);
        break;
      case 4:
        m.replace_character(text, "0123456789.,-+eE*/^%[]()\"# \tPGNSXYZ_=\n");
        break;
      case 5:
        m.insert_junk(text);
        break;
      case 6:
      case 7: {  // replace a value by something odd
        const auto spans = value_spans(text);
        if (spans.empty()) break;
        // Counts large enough to be refused, never large enough to be generated slowly.
        static const char* const odd[] = {
            "",
            "0",
            "-1",
            "-4",
            "1e308",
            "-1e308",
            "1e-320",
            "nan",
            "inf",
            "-inf",
            "abc",
            "1.5",
            "2.5e-1",
            "1e9",
            "4e7",
            "99999999999999999999",
            "[0/0]",
            "[1/0]",
            "[1e308*10]",
            "[sqrt(-1)]",
            "[%nope]",
            "%nope",
            "[",
            "[1",
            "[(1]",
            "[1)]",
            "(",
            "\"",
            "[\"1\"]",
            "[%L1/%dx",
            "%",
            "-%",
            "[]",
            "[ ]",
            "[%L1/0]",
            "[1e8]",
            "[-%D]",
            "1,2",
            "X",
            "P",
            "ALL",
            "0.0000001",
            "[%tend*1e12]",
            "[asin(2)]",
            "[mod(1,0)]",
            "[ln(0)]",
            "1e10",
        };
        const auto [pos, len] = spans[pick(spans.size())];
        text.replace(pos, len, odd[pick(std::size(odd))]);
        break;
      }
      case 8: {  // unbalanced bracket, parenthesis or quote
        static const char* const marks[] = {"[", "]", "(", ")", "\"", "[(", "\"[", "%", "*"};
        text.insert(pick(text.size() + 1), marks[pick(std::size(marks))]);
        break;
      }
      case 9: {  // join two lines (two commands on one line make the reader reflow)
        const auto nl = text.find('\n', pick(text.size() + 1));
        if (nl != std::string::npos) text[nl] = ' ';
        break;
      }
      case 10: {  // a command name replaced by another one
        static const char* const commands[] = {"*COMPONENT_BOX",
                                               "*COMPONENT_CYLINDER",
                                               "*MERGE_DUPLICATED_NODES",
                                               "*NODE",
                                               "*ELEMENT_SOLID",
                                               "*SET_NODE",
                                               "*SET_PART",
                                               "*INITIAL_VELOCITY",
                                               "*OUTPUT_NODE",
                                               "*BC_MOTION",
                                               "*GEOMETRY_SEED_COORDINATE",
                                               "*FUNCTION",
                                               "*PART",
                                               "*CHANGE_P-ORDER",
                                               "*PARAMETER",
                                               "*INCLUDE",
                                               "*MAT_RIGID",
                                               "*TIME",
                                               "*END",
                                               "*KEYWORD",
                                               "*RIGID_BODY_UPDATE"};
        auto lines = rf::test::DeckMutator::split_lines(text);
        std::vector<std::size_t> command_lines;
        for (std::size_t i = 0; i < lines.size(); ++i) {
          if (!lines[i].empty() && lines[i][0] == '*') command_lines.push_back(i);
        }
        if (!command_lines.empty()) {
          lines[command_lines[pick(command_lines.size())]] = commands[pick(std::size(commands))];
        }
        text = rf::test::DeckMutator::join_lines(lines);
        break;
      }
      case 11: {  // an undefined parameter
        const auto p = text.find('%', pick(text.size() + 1));
        if (p != std::string::npos) text.insert(p + 1, "undefined_");
        break;
      }
    }
  }
  return text;
}

// The seed deck, a coarse copy of it (cheap to set up for the solver), the same as one line
// (reflow), and a deck with the other commands: boxes, nodes, elements, sets, velocities.
std::vector<std::string> seeds() {
  const std::string seed = seed_text();
  std::string coarse = replace_all(seed, "%L1 = 1.0", "%L1 = 0.1");
  coarse = replace_all(coarse, "ALL, 0, 3", "ALL, 0, 2");
  std::string flat;
  for (char c : coarse) flat += c == '\n' ? ' ' : c;
  const std::string other =
      "*UNIT_SYSTEM\nMMTONS\n"
      "*PARAMETER\n%n = 2, \"count\"\n%a = [%n*0.5]\n"
      "*TIME\n1e-3, 0.8, , 0\n"
      "*OUTPUT\n1e-4, 1e-5\n0, 0\n"
      "*COMPONENT_BOX\n\"block\"\n1, 1, %n, %n, [%n+1]\n0, 0, 0, 1, [%a*2], 3\n"
      "*COMPONENT_BOX\n2, 2, 1, 1, 1\n0, 0, 3, 1, 1, 4\n"
      "*MERGE_DUPLICATED_NODES\nP, 1, P, 2, 1e-6, 0\n"
      "*NODE\n1001, 5, 0, 0\n1002, 6, 0, 0, XY\n1003, 6, 1, 0\n1004, 5, 1, 0\n"
      "1005, 5, 0, 1\n1006, 6, 0, 1\n1007, 6, 1, 1\n1008, 5, 1, 1, Z\n"
      "*ELEMENT_SOLID\n501, 3, 1001, 1002, 1003, 1004, 1005, 1006, 1007, 1008\n"
      "*MAT_ELASTIC\n\"steel\"\n1, 7.8e-9, 210000, 0.3\n"
      "*MAT_RIGID\n2, 7.8e-9\n"
      "*PART\n1, 1\n2, 2, , , 30\n3, 1\n"
      "*SET_NODE\n7\n1001, 1002\n1003..1004\n"
      "*SET_PART\n8\n1, 3\n"
      "*INITIAL_VELOCITY\nPS, 8, 0, 0, -1000\n0, 0, 0\n"
      "*OUTPUT_NODE\nN, 1001\nNS, 7\n"
      "*CHANGE_P-ORDER\nP, 1, 2\n"
      "*GEOMETRY_SEED_COORDINATE\n\"bottom\"\n4\n0.5, 0.5, 0, 30, 1\n"
      "*BC_MOTION\n1\nG, 4, XYZ\n"
      "*BC_MOTION\nP, 2, XY, XYZ, , , 0, 1\nV, Z, 3, -2.0\n"
      "*FUNCTION\n\"ramp\"\n3\nmin(t/1e-4, 1)*cos(%n*0)\n"
      "*RIGID_BODY_UPDATE\n1\n"
      "*END\nafter the end\n";
  return {seed, coarse, flat, other};
}

// Sets a model up for the solver; returns an error text when it broke a rule, else "".
std::string set_up(const rf::model::Model& model) {
  try {
    const rf::solver::NodeIndex index(model);
    const auto state = rf::solver::build_state(model, index);
    const auto rigid = rf::solver::build_rigid_system(model, index, state);
    std::vector<rf::model::Warning> warnings;
    rf::solver::resolve_boundary(model, index, state, rigid.body_of_node, warnings);
  } catch (const rf::InputError& e) {
    if (e.context().file.empty() || e.context().line <= 0) {
      return std::string("InputError without file and line: ") + e.what();
    }
  } catch (const rf::SolverError& e) {
    if (std::string(e.what()).empty()) return "SolverError without a message";
  } catch (const std::exception& e) {
    return std::string("set-up threw a non-InputError/SolverError: ") + e.what();
  }
  return {};
}

}  // namespace

TEST(ImpetusFuzz, DamagedDecksGiveModelOrInputError) {
  const auto decks = seeds();
  // Every seed reads and sets up cleanly.
  for (const auto& deck : decks) {
    const auto model = rf::io::read_deck_text(deck, "fuzz.k", RIGIDFLEX_TEST_DECKS);
    EXPECT_EQ(model.dialect, "impetus");
    EXPECT_EQ(set_up(model), "");
  }
  rf::test::DeckMutator mutator(20250611);
  const auto start = std::chrono::steady_clock::now();
  double set_up_seconds = 0.0;
  int models = 0, errors = 0, set_ups = 0;
  constexpr int kVariants = 12000;
  for (int i = 0; i < kVariants; ++i) {
    // The full seed deck generates 32 000 nodes per read: one variant in 16 uses it.
    const std::size_t which = i % 16 == 0 ? 0 : 1 + static_cast<std::size_t>(i) % 3;
    const std::string text = mutate(decks[which], mutator);
    rf::model::Model model;
    try {
      model = rf::io::read_deck_text(text, "fuzz.k", RIGIDFLEX_TEST_DECKS);
      ++models;
    } catch (const rf::InputError& e) {
      // Every error must say where it happened: file and line.
      ASSERT_EQ(e.context().file, "fuzz.k") << "variant " << i << ": " << e.what() << "\n" << text;
      ASSERT_GT(e.context().line, 0) << "variant " << i << ": " << e.what() << "\n" << text;
      ASSERT_NE(std::string(e.what()).find("fuzz.k:"), std::string::npos) << e.what();
      ++errors;
      continue;
    } catch (const std::exception& e) {
      FAIL() << "variant " << i << " threw a non-InputError: " << e.what() << "\n--- deck ---\n"
             << text;
    }
    // Solver set-up where cheap: small models, and a bounded share of the run time.
    if (model.solids.size() > 5000 || set_up_seconds > 3.0) continue;
    const auto t0 = std::chrono::steady_clock::now();
    const std::string problem = set_up(model);
    set_up_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_EQ(problem, "") << "variant " << i << "\n--- deck ---\n" << text;
    ++set_ups;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("impetus fuzz: %d variants, %d models (%d set up), %d input errors, %.2f s\n",
              kVariants, models, set_ups, errors, seconds);
  EXPECT_GT(models, 0);
  EXPECT_GT(errors, 0);
}

// Element counts are checked before anything is allocated: a slip of the finger must not make
// the reader generate billions of elements.
TEST(ImpetusFuzz, HugeGeneratedMeshesAreRefusedBeforeAllocation) {
  const std::string box = "*COMPONENT_BOX\n1, 1, 1000000, 1000000, 1000000\n0, 0, 0, 1, 1, 1\n";
  EXPECT_NE(input_error_of(box, "big.k").find("big.k:2: *COMPONENT_BOX"), std::string::npos)
      << input_error_of(box, "big.k");
  const std::string cylinder = "*COMPONENT_CYLINDER\n1, 1, 1000000, 1000\n0, 0, 0, 0, 0, 1, 1\n";
  const std::string message = input_error_of(cylinder, "big.k");
  EXPECT_NE(message.find("big.k:2: *COMPONENT_CYLINDER"), std::string::npos) << message;
  EXPECT_NE(message.find("million"), std::string::npos) << message;
  // Several components that are each acceptable but too many together.
  std::string many;
  for (int k = 1; k <= 8; ++k) {
    many += "*COMPONENT_BOX\n" + std::to_string(k) + ", 1, 1000, 1000, 10\n0, 0, " +
            std::to_string(k) + ", 1, 1, " + std::to_string(k + 1) + "\n";
  }
  EXPECT_NE(input_error_of(many, "many.k").find("many.k:"), std::string::npos);
}

// A merge tolerance as large as the model would merge corner nodes of the same element.
TEST(ImpetusFuzz, MergeToleranceThatCollapsesElementsIsAnInputError) {
  const std::string deck =
      "*COMPONENT_BOX\n1, 1, 2, 2, 2\n0, 0, 0, 1, 1, 1\n"
      "*COMPONENT_BOX\n2, 2, 2, 2, 2\n0, 0, 1, 1, 1, 2\n"
      "*MERGE_DUPLICATED_NODES\nP, 1, P, 2, 1e30\n";
  const std::string message = input_error_of(deck, "merge.k");
  EXPECT_NE(message.find("merge.k:8: *MERGE_DUPLICATED_NODES"), std::string::npos) << message;
  EXPECT_NE(message.find("tol"), std::string::npos) << message;
  // A tiny tolerance next to huge coordinates does not overflow the spatial hash: the four
  // corners of the shared face z = 1 coincide exactly and merge, nothing else does.
  const auto m = rf::io::read_deck_text(
      "*MAT_ELASTIC\n1, 7800, 2e11, 0.3\n*PART\n1, 1\n2, 1\n"
      "*COMPONENT_BOX\n1, 1, 1, 1, 1\n1e300, 0, 0, 2e300, 1, 1\n"
      "*COMPONENT_BOX\n2, 2, 1, 1, 1\n1e300, 0, 1, 2e300, 1, 2\n"
      "*MERGE_DUPLICATED_NODES\nP, 1, P, 2, 1e-300\n",
      "tiny.k");
  EXPECT_EQ(m.merged_node_count, 4);
}
