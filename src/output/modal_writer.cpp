#include "output/modal_writer.hpp"

#include <fmt/format.h>

namespace rf::output {

ModalWriter::ModalWriter(const std::filesystem::path& path, std::int64_t continue_at)
    : csv_(path, std::string(kModalHeader), continue_at) {}

void ModalWriter::write(double time, const solver::RigidSystem& rigid) {
  fmt::memory_buffer text;
  for (const auto& f : rigid.flexible) {
    for (std::size_t k = 0; k < f.mode_count; ++k) {
      fmt::format_to(std::back_inserter(text), "{:.17g},{},{},{:.17g},{:.17g}\n", time, f.part,
                     f.file_modes[k], f.q_previous[k], f.s_mid[k]);
    }
  }
  csv_.write_text(std::string_view(text.data(), text.size()));
}

}  // namespace rf::output
