// *MAT_ADD_EROSION: failure criteria added to a material by MID. Semantics: docs/materials.md
// ("Failure and erosion"); the criteria are attached to the parts of that material when the
// solver state is built (solver/erosion.cpp), so the card may come before or after the *MAT_.
#include <fmt/format.h>

#include <cmath>

#include "io/keyword/definition_ids.hpp"
#include "io/keyword/handlers.hpp"

namespace rf::io::handlers {

namespace {

const Layout kEightByTen = uniform_layout(8, 10);

}  // namespace

// Card 1: MID EXCL MXPRES MNEPS EFFEPS VOLEPS NUMFIP NCS; card 2: MNPRES SIGP1 SIGVM MXEPS EPSSH
// SIGTH IMPULSE FAILTM; card 3: IDAM (damage models) ... LCREGD; card 4: LCFLD NSFF EPSTHIN
// ENGCRT RADCRT LCEPS12 LCEPS13 LCEPSMX; card 5: DTEFLT VOLFRAC MXTMP DTMIN (LS-DYNA Keyword
// User's Manual Vol. II, *MAT_ADD_EROSION). A value equal to EXCL (default 0) leaves its
// criterion out; a criterion we do not evaluate is refused, never dropped.
void mat_add_erosion(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const int n = skip_title(block, cursor);
  const Card card = cursor.next(n, kEightByTen, "MID EXCL MXPRES MNEPS EFFEPS VOLEPS NUMFIP NCS");
  model::AddErosion erosion;
  erosion.mid = positive_id(card, 0, "MID", "material");
  erosion.where = card.location();
  const double excl = card.real(1, "EXCL", 0.0);
  // A criterion is on when its value is given, nonzero and not the exclusion number.
  auto criterion = [&](const Card& c, std::size_t i, const char* field) -> std::optional<double> {
    const double value = c.real(i, field, 0.0);
    if (!std::isfinite(value)) throw c.error(field, "must be a finite number");
    if (value == 0.0 || value == excl) return std::nullopt;
    return value;
  };
  // The strain criteria: LS-DYNA reads a negative MXEPS (and EPSSH, EFFEPS in some versions) as
  // a load curve of the limit against the strain rate, which is not supported; a positive MNEPS
  // would fail every element at rest.
  auto positive_strain = [&](const Card& c, std::size_t i, const char* field,
                             const char* what) -> std::optional<double> {
    const std::optional<double> value = criterion(c, i, field);
    if (value && *value < 0.0)
      throw c.error(field, fmt::format("{} {} must be positive (a negative value, a curve of the "
                                       "limit against the strain rate, is not supported)",
                                       what, *value));
    return value;
  };
  erosion.mxpres = criterion(card, 2, "MXPRES");
  erosion.mneps = criterion(card, 3, "MNEPS");
  if (erosion.mneps && *erosion.mneps > 0.0)
    throw card.error("MNEPS", fmt::format("minimum principal strain at failure {} must be negative "
                                          "(a compressive strain): a positive limit fails every "
                                          "element at rest",
                                          *erosion.mneps));
  erosion.effeps = positive_strain(card, 4, "EFFEPS", "effective strain at failure");
  erosion.voleps = criterion(card, 5, "VOLEPS");
  erosion.numfip = card.blank(6) ? 1.0 : card.real(6, "NUMFIP", 1.0);
  if (erosion.numfip == 0.0 || !std::isfinite(erosion.numfip))
    throw card.error("NUMFIP",
                     "must be a positive number of points or (shells) a negative "
                     "percentage");
  if (erosion.numfip < -100.0)
    throw card.error("NUMFIP",
                     "values below -100 (a count of points after -100) are not "
                     "supported: give the count as a positive NUMFIP");
  const double ncs = card.blank(7) ? 1.0 : card.real(7, "NCS", 1.0);
  if (!(ncs >= 1.0) || ncs != std::floor(ncs) || ncs > 6.0)
    throw card.error("NCS", fmt::format("number of criteria to meet at once {} must be an integer "
                                        "from 1 to 6",
                                        ncs));
  erosion.ncs = static_cast<int>(ncs);
  if (const auto c2 = cursor.next_optional(n + 1, kEightByTen)) {
    erosion.mnpres = criterion(*c2, 0, "MNPRES");
    erosion.sigp1 = criterion(*c2, 1, "SIGP1");
    erosion.sigvm = criterion(*c2, 2, "SIGVM");
    if (erosion.sigvm && *erosion.sigvm < 0.0)
      throw c2->error("SIGVM",
                      "a negative SIGVM (a curve of the failure stress against the "
                      "strain rate) is not supported");
    erosion.mxeps = positive_strain(*c2, 3, "MXEPS", "maximum principal strain at failure");
    erosion.epssh = positive_strain(*c2, 4, "EPSSH", "shear strain at failure");
    // Tuler-Butcher: on with IMPULSE (K_f > 0); SIGTH (sigma_0 >= 0) is its threshold and
    // means nothing alone (0 or EXCL: threshold 0).
    const std::optional<double> sigth = criterion(*c2, 5, "SIGTH");
    erosion.impulse = criterion(*c2, 6, "IMPULSE");
    if (sigth && *sigth < 0.0)
      throw c2->error("SIGTH", fmt::format("threshold stress {} of the Tuler-Butcher criterion "
                                           "must not be negative",
                                           *sigth));
    if (erosion.impulse && *erosion.impulse < 0.0)
      throw c2->error("IMPULSE", fmt::format("stress impulse for failure {} must be positive",
                                             *erosion.impulse));
    if (sigth && !erosion.impulse)
      throw c2->error("SIGTH",
                      "a threshold stress without IMPULSE defines no criterion: give the "
                      "stress impulse for failure (Tuler-Butcher) or leave SIGTH blank");
    if (erosion.impulse) erosion.sigth = sigth.value_or(0.0);
    erosion.failtm = criterion(*c2, 7, "FAILTM");
    if (erosion.failtm && *erosion.failtm < 0.0)
      throw c2->error("FAILTM", "failure time must not be negative");
  }
  // Cards 3-5: damage models (GISSMO, DIEM), forming limits, filtering. Refused when set.
  static const char* const kCard3[] = {"IDAM",     "(unused)", "(unused)", "(unused)",
                                       "(unused)", "(unused)", "(unused)", "LCREGD"};
  static const char* const kCard4[] = {"LCFLD",  "NSFF",    "EPSTHIN", "ENGCRT",
                                       "RADCRT", "LCEPS12", "LCEPS13", "LCEPSMX"};
  static const char* const kCard5[] = {"DTEFLT", "VOLFRAC", "MXTMP", "DTMIN"};
  const char* const* names[] = {kCard3, kCard4, kCard5};
  const int counts[] = {8, 8, 4};
  for (int k = 0; k < 3; ++k) {
    const auto c = cursor.next_optional(n + 2 + k, kEightByTen);
    if (!c) break;
    for (int i = 0; i < counts[k]; ++i) {
      if (k == 1 && i == 1) continue;  // NSFF: filtering steps of forming limits, unused alone
      if (c->blank(static_cast<std::size_t>(i)) ||
          c->real(static_cast<std::size_t>(i), names[k][i], 0.0) == 0.0)
        continue;
      throw c->error(names[k][i],
                     "is not supported: the damage models (IDAM), forming-limit and "
                     "thinning criteria and the filtering options of *MAT_ADD_EROSION cards 3-5 "
                     "are not implemented (leave them blank)");
    }
  }
  check_unique(context.model.add_erosions, erosion.mid, card, "MID",
               "*MAT_ADD_EROSION for material");
  context.model.add_erosions.emplace(erosion.mid, std::move(erosion));
  warn_unread_lines(block, cursor, context);
}

}  // namespace rf::io::handlers
