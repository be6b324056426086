// Shared by the libFuzzer targets (docs/verification.md, "Fuzzing"): what a finding is.
// A target may end in rf::InputError (bad input, reported to the user), rf::SolverError, or
// std::runtime_error (a file that cannot be read or written): the program reports those and
// exits non-zero. Anything else escaping — std::logic_error (out_of_range from .at(), a failed
// precondition), bad_alloc from a size taken on trust, another type — means the input reached
// code that assumed it had been checked: the target aborts so libFuzzer keeps the input.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <stdexcept>

#include "model/error.hpp"

namespace rf::fuzz {

template <class Body>
void expect_clean_failure(Body&& body) {
  try {
    body();
  } catch (const rf::InputError&) {
  } catch (const rf::SolverError&) {
  } catch (const std::logic_error& e) {
    std::fprintf(stderr, "fuzz finding: std::logic_error escaped: %s\n", e.what());
    std::abort();
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "fuzz finding: std::bad_alloc escaped\n");
    std::abort();
  } catch (const std::runtime_error&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz finding: exception escaped: %s\n", e.what());
    std::abort();
  }
}

}  // namespace rf::fuzz
