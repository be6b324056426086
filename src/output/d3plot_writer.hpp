// LS-DYNA binary result database ("d3plot"), so that LS-PrePost, ParaView's LS-DYNA reader and
// lasso-python open RigidFlex results. Layout (docs/output.md#d3plot): the database of the
// LS-DYNA manual ("LS-DYNA Database Binary Output Files"), 4-byte words in host byte order,
// written as a file family:
//   d3plot:   control words (64) | node coordinates | solid connectivity + material |
//             beams (N1 N2 N3 0 0 material) | shells (N1..N4 material) | user IDs (NARBS) |
//             end-of-file marker -999999.0 | part titles (90001, NUMPROP, per part: ID + 72
//             characters) | end-of-file marker
//   d3plot01, d3plot02, ...: state | state | ... | end-of-file marker -999999.0
// Each state: time, 6 global values, current coordinates, velocities, accelerations of every
// node, 7 values per solid (6 stresses + effective plastic strain), 6 resultants per beam, 25
// values per shell (3 points x (6 stresses + plastic strain), thickness, 2 element variables,
// internal energy) and one deletion flag per solid, shell and beam (1 = active).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "solver/state.hpp"

namespace rf::output {

// The six global values of a state (LS-DYNA order).
struct D3plotGlobals {
  double kinetic_energy = 0.0;
  double internal_energy = 0.0;
  double total_energy = 0.0;
  double velocity[3] = {0, 0, 0};  // momentum / total mass
};

// Effective plastic strain of solid element e of a block, the 7th solid value of every state:
// the material's "effective_plastic_strain" history, mean over the element's points (0 for
// materials without it).
double d3plot_effective_plastic_strain(const element::HexBlock& block, std::size_t e);

class D3plotWriter {
 public:
  // `family_bytes`: largest size of one state file of the family (a state is never split; a
  // member holds at least one state).
  D3plotWriter(std::filesystem::path directory, std::string title,
               std::int64_t family_bytes = kDefaultFamilyBytes);

  // Appends one state. The first call writes the control words and geometry from `state`
  // (reference coordinates x0, connectivity, parts), after removing family members left by an
  // earlier run in the directory.
  void write_state(const solver::State& state, const D3plotGlobals& globals);

  // Restart: `states` states were written before the dump. The family in the directory is cut
  // back to them at the next write_state; when it is missing or shorter, a new family is
  // started (it then holds only the later states).
  void resume(std::int64_t states) { resume_states_ = states; }
  std::int64_t states() const { return states_; }

  static constexpr std::int64_t kDefaultFamilyBytes = std::int64_t{1} << 30;  // 1 GiB
  static constexpr float kEndOfFile = -999999.0f;

  // File name of family member k: d3plot, d3plot01, d3plot02, ...
  static std::string member_name(int k);

 private:
  struct Layout {
    std::int64_t header_words = 0;  // control words through user IDs
    std::int64_t state_words = 0;
    std::int64_t states_per_member = 1;  // in d3plot01, d3plot02, ... (d3plot: none)
  };
  void write_header(const solver::State& state);
  void write_beam_values(const element::BeamBlock& block, std::size_t e);
  void write_shell_values(const solver::NodalState& nodes, const element::ShellBlock& block,
                          std::size_t e);
  // Member and byte offset where state number `index` (0-based) starts.
  std::pair<int, std::int64_t> position_of(std::int64_t index) const;
  bool cut_back_to(std::int64_t states);

  std::filesystem::path directory_;
  std::string title_;
  std::int64_t family_bytes_;
  Layout layout_;
  bool header_written_ = false;
  std::int64_t states_ = 0;
  std::int64_t resume_states_ = -1;
  std::int64_t element_count_ = 0;  // written solids (p > 1 elements as p^3 sub-hexes)
  std::int64_t beam_count_ = 0;
  std::int64_t shell_count_ = 0;
  std::vector<float> buffer_;
};

}  // namespace rf::output
