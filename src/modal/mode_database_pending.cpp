// TEMPORARY: placeholder until branch `eigen` (mode database I/O) is merged; removed then.
#include <stdexcept>

#include "modal/mode_set.hpp"

namespace rf::modal {

void write_mode_database(const std::filesystem::path&, const ModeSet&) {
  throw std::runtime_error("the mode database writer is not in this build yet");
}

ModeSet read_mode_database(const std::filesystem::path&) {
  throw std::runtime_error("the mode database reader is not in this build yet");
}

}  // namespace rf::modal
