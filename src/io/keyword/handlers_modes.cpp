// *PART_MODES: flexible rigid bodies (docs/flexible_bodies.md, card layout from the LS-DYNA
// manual as PyDYNA's part_modes.py gives it). References to parts and sets are checked in
// finish_part_modes once the whole deck is read.
#include <fmt/format.h>

#include <filesystem>

#include "io/keyword/handlers.hpp"
#include "io/keyword/number.hpp"

namespace rf::io::handlers {

namespace {

const Layout kEightByTen = uniform_layout(8, 10);

}  // namespace

void part_modes(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const Card card = cursor.next(1, kEightByTen, "PID NMFB FORM ANSID FORMAT KMFLAG NUPDF SIGREC");
  model::PartModes modes;
  modes.where = card.location();
  modes.pid = card.id(0, "PID");
  if (modes.pid <= 0) throw card.error("PID", "part ID must be a positive integer");
  const auto nmfb = card.integer(1, "NMFB", 0);
  if (nmfb <= 0 || nmfb > 100000) {
    throw card.error("NMFB", fmt::format("number of kept modes {} must be positive", nmfb));
  }
  modes.nmfb = static_cast<int>(nmfb);
  modes.form = card.flag(2, "FORM", 0);
  if (modes.form != 0 && modes.form != 1) {
    throw card.error("FORM", fmt::format("FORM {}: must be 0 (exact) or 1 (fast)", modes.form));
  }
  modes.ansid = card.id(3, "ANSID");
  if (modes.ansid < 0) throw card.error("ANSID", "node set ID must not be negative");
  modes.format = card.flag(4, "FORMAT", 0);
  if (modes.format != 3) {
    const char* what = modes.format == 0   ? "NASTRAN .pch punch file"
                       : modes.format == 2 ? "LS-DYNA binary copy of a NASTRAN .pch file"
                       : modes.format == 4 ? "d3mode constraint/attachment mode database"
                       : modes.format == 5 ? "d3eigv + d3mode databases"
                                           : "unknown format";
    throw card.error(
        "FORMAT",
        fmt::format("FORMAT {} ({}) is not supported: use FORMAT 3, the eigen database of an "
                    "eigenvalue analysis, as RigidFlex's modes.h5 (docs/flexible_bodies.md)",
                    modes.format, what));
  }
  modes.kmflag = card.flag(5, "KMFLAG", 0);
  if (modes.kmflag != 0 && modes.kmflag != 1) {
    throw card.error("KMFLAG", fmt::format("KMFLAG {}: must be 0 or 1", modes.kmflag));
  }
  const int nupdf = card.flag(6, "NUPDF", 0);
  if (nupdf != 0) {
    throw card.error("NUPDF", fmt::format("NUPDF {} is not supported: every node that needs it is "
                                          "reconstructed each cycle and the others at output times "
                                          "(docs/flexible_bodies.md); use NUPDF 0",
                                          nupdf));
  }
  const int sigrec = card.flag(7, "SIGREC", 0);
  if (sigrec != 0) {
    throw card.error("SIGREC", fmt::format("SIGREC {}: stress recovery of flexible bodies is not "
                                           "supported; use SIGREC 0",
                                           sigrec));
  }
  modes.filename = std::string(trim(cursor.next_text(2, "FILENAME")));
  if (modes.filename.empty()) {
    throw block_error(block, 2, "FILENAME", "the mode database file name is blank");
  }
  std::filesystem::path path(modes.filename);
  if (path.is_relative()) path = std::filesystem::path(block.file).parent_path() / path;
  modes.path = path.lexically_normal().string();

  int n = 2;
  if (modes.kmflag == 1) {
    while (static_cast<int>(modes.modes.size()) < modes.nmfb) {
      if (cursor.at_end()) {
        throw block_error(block, n + 1, "MODE1",
                          fmt::format("KMFLAG 1: {} kept modes listed, NMFB asks for {}",
                                      modes.modes.size(), modes.nmfb));
      }
      const Card list = cursor.next(++n, kEightByTen, "MODE1 ... MODE8");
      for (std::size_t i = 0; i < 8 && static_cast<int>(modes.modes.size()) < modes.nmfb; ++i) {
        static const char* const kNames[] = {"MODE1", "MODE2", "MODE3", "MODE4",
                                             "MODE5", "MODE6", "MODE7", "MODE8"};
        if (list.blank(i)) continue;
        const auto m = list.integer(i, kNames[i], 0);
        if (m <= 0) {
          throw list.error(kNames[i], fmt::format("mode number {} must be positive", m));
        }
        for (const int previous : modes.modes) {
          if (previous == m) {
            throw list.error(kNames[i], fmt::format("mode {} is listed twice", m));
          }
        }
        modes.modes.push_back(static_cast<int>(m));
      }
    }
  }
  // Optional modal damping cards, as many as given.
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card damp = cursor.next(++n, kEightByTen, "MSTART MSTOP DAMPF");
    model::PartModesDamping d;
    d.where = damp.location();
    d.mstart = damp.flag(0, "MSTART", 0);
    d.mstop = damp.flag(1, "MSTOP", 0);
    d.dampf = damp.real(2, "DAMPF", 0.0);
    if (d.mstart < 1 || d.mstart > modes.nmfb) {
      throw damp.error(
          "MSTART", fmt::format("MSTART {} must be between 1 and NMFB = {}", d.mstart, modes.nmfb));
    }
    if (d.mstop < d.mstart || d.mstop > modes.nmfb) {
      throw damp.error("MSTOP", fmt::format("MSTOP {} must be between MSTART = {} and NMFB = {}",
                                            d.mstop, d.mstart, modes.nmfb));
    }
    if (!(d.dampf >= 0.0)) {
      throw damp.error("DAMPF", fmt::format("damping ratio {} must not be negative", d.dampf));
    }
    modes.damping.push_back(d);
  }
  auto& all = context.model.part_modes;
  if (const auto it = all.find(modes.pid); it != all.end()) {
    throw card.error("PID", fmt::format("part {} already has *PART_MODES at {}:{}", modes.pid,
                                        it->second.where.file, it->second.where.line));
  }
  all.emplace(modes.pid, std::move(modes));
}

}  // namespace rf::io::handlers
