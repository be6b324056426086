// *CONTROL_IMPLICIT_GENERAL and *CONTROL_IMPLICIT_EIGENVALUE: the deck asks for an eigen
// analysis (docs/eigen.md). Card layouts from the LS-DYNA manual as transcribed by PyDYNA
// (control_implicit_general.py, control_implicit_eigenvalue.py).
#include <fmt/format.h>

#include "io/keyword/handlers.hpp"

namespace rf::io::handlers {

namespace {

const Layout kEightByTen = uniform_layout(8, 10);

}  // namespace

void control_implicit_general(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  auto& c = context.model.implicit;
  c.general = true;
  context.implicit_general_where = block.location();
  if (const auto card = cursor.next_optional(1, kEightByTen)) {
    c.imflag = card->flag(0, "IMFLAG", 0);
    if (c.imflag != 0 && c.imflag != 1) {
      throw card->error("IMFLAG",
                        fmt::format("value {}: only 0 (explicit) and 1 (implicit, used for the "
                                    "eigen analysis of *CONTROL_IMPLICIT_EIGENVALUE) are "
                                    "supported",
                                    c.imflag));
    }
    c.dt0 = card->real(1, "DT0", 0.0);
    // IMFORM, NSBS, IGS, CNSTN, FORM, ZERO_V concern implicit time stepping and springback,
    // which an eigen analysis does not do.
  }
  warn_unread_lines(block, cursor, context);
}

void control_implicit_eigenvalue(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  auto& c = context.model.implicit;
  c.eigenvalue = true;
  const Card card = cursor.next(1, kEightByTen, "NEIG CENTER LFLAG LFTEND RFLAG RHTEND EIGMTH");
  c.where = card.location();
  c.neig = card.flag(0, "NEIG", 0);
  if (c.neig < 0) {
    throw card.error("NEIG", fmt::format("value {}: intermittent eigenvalue extraction (a curve "
                                         "ID) is not supported",
                                         c.neig));
  }
  if (c.neig == 0) throw card.error("NEIG", "the number of eigenvalues must be positive");
  c.center = card.real(1, "CENTER", 0.0);
  if (c.center < 0.0) throw card.error("CENTER", "the centre frequency must not be negative");
  c.lflag = card.flag(2, "LFLAG", 0);
  if (c.lflag != 0 && c.lflag != 1) throw card.error("LFLAG", "must be 0 or 1");
  c.lftend = card.real(3, "LFTEND", -1e29);
  c.rflag = card.flag(4, "RFLAG", 0);
  if (c.rflag != 0 && c.rflag != 1) throw card.error("RFLAG", "must be 0 or 1");
  c.rhtend = card.real(5, "RHTEND", 1e29);
  c.eigmth = card.flag(6, "EIGMTH", 2);
  if (c.eigmth == 0) c.eigmth = 2;
  if (c.eigmth == 101 || c.eigmth == 102 || c.eigmth == 103) {
    context.warn(card.location(),
                 fmt::format("EIGMTH {}: the same eigenproblem is solved with the shift-invert "
                             "Lanczos method of EIGMTH 2 (Card 3 parameters are ignored)",
                             c.eigmth));
  } else if (c.eigmth != 2) {
    throw card.error("EIGMTH", fmt::format("value {} is not supported: use 2 (block shift-and-"
                                           "invert Lanczos); 3 and 5 replace the mass matrix, 5 "
                                           "and 6 add dynamic terms, 111 needs sectoral "
                                           "symmetry",
                                           c.eigmth));
  }
  c.shfscl = card.real(7, "SHFSCL", 0.0);
  if (c.shfscl < 0.0) throw card.error("SHFSCL", "must not be negative");
  if (const auto card2 = cursor.next_optional(2, kEightByTen)) {
    if (card2->flag(0, "ISOLID", 0) != 0) {
      throw card2->error("ISOLID",
                         "replacing the solid formulation for the eigen analysis is "
                         "not supported (set ELFORM on *SECTION_SOLID)");
    }
    if (card2->flag(4, "MSTRES", 0) != 0) {
      context.warn(card2->location(), "MSTRES ignored: modal stresses are not computed");
    }
    if (card2->flag(5, "EVDUMP", 0) != 0) {
      context.warn(card2->location(),
                   "EVDUMP ignored: the eigenpairs are written to modes.h5 and eigout.csv");
    }
  }
  // Card 3 (EIGMTH 101-111 parameters) and card 4 (ROTSCL, EIGMSCL: rotational DOFs and mass
  // scaling, absent for solids) carry nothing for this solver.
  if (c.eigmth > 100) cursor.next_optional(3, kEightByTen);
  cursor.next_optional(4, kEightByTen);
  warn_unread_lines(block, cursor, context);
}

}  // namespace rf::io::handlers
