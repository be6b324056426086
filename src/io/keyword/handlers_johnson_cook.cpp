// *MAT_JOHNSON_COOK (015) and *EOS_LINEAR_POLYNOMIAL (001). Semantics: material/johnson_cook.hpp,
// docs/materials.md. The part's EOSID is resolved when the solver state is built
// (material/johnson_cook_setup.cpp): the EOS may come later in the deck.
#include <fmt/format.h>

#include "io/keyword/definition_ids.hpp"
#include "io/keyword/handlers.hpp"
#include "model/error_context.hpp"

namespace rf::io::handlers {

namespace {

const Layout kEightByTen = uniform_layout(8, 10);

}  // namespace

// Card 1: MID RO G E PR DTF VP RATEOP; card 2: A B N C M TM TR EPSO; card 3: CP PC SPALL IT D1 D2
// D3 D4; card 4: D5 C2/P/XNP EROD EFMIN NUMINT.
void mat_johnson_cook(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const int n = skip_title(block, cursor);
  const Card card = cursor.next(n, kEightByTen, "MID RO G E PR DTF VP RATEOP");
  model::Material m;
  m.id = positive_id(card, 0, "MID", "material");
  m.kind = model::MaterialKind::JohnsonCook;
  m.keyword = block.keyword;
  m.where = card.location();
  m.rho = card.real(1, "RO", 0.0);
  if (!(m.rho > 0.0)) throw card.error("RO", fmt::format("density {} must be positive", m.rho));
  model::JohnsonCookCard& jc = m.johnson_cook;
  jc.g = card.real(2, "G", 0.0);
  if (!(jc.g > 0.0)) throw card.error("G", fmt::format("shear modulus {} must be positive", jc.g));
  m.e = card.real(3, "E", 0.0);
  m.pr = card.real(4, "PR", 0.0);
  if (m.e < 0.0) throw card.error("E", fmt::format("Young's modulus {} must not be negative", m.e));
  if (!(m.pr > -1.0 && m.pr < 0.5))
    throw card.error("PR", fmt::format("Poisson's ratio {} must lie in (-1, 0.5)", m.pr));
  if (card.real(5, "DTF", 0.0) != 0.0)
    context.warn(card.location(),
                 "DTF (element deletion by time step) acts on shells only: ignored for solids");
  const double vp = card.real(6, "VP", 0.0);
  if (vp != 0.0 && vp != 1.0)
    throw card.error("VP",
                     fmt::format("VP {} is not 0 (scale yield stress) or 1 (viscoplastic)", vp));
  jc.vp = static_cast<int>(vp);
  const double rateop = card.real(7, "RATEOP", 0.0);
  if (rateop != 0.0)
    throw card.error("RATEOP", fmt::format("RATEOP {} is not supported: only 0, the log-linear "
                                           "Johnson-Cook rate term 1 + C ln(rate*)",
                                           rateop));

  const Card c2 = cursor.next(n + 1, kEightByTen, "A B N C M TM TR EPSO");
  jc.a = c2.real(0, "A", 0.0);
  jc.b = c2.real(1, "B", 0.0);
  jc.n = c2.real(2, "N", 0.0);
  jc.c = c2.real(3, "C", 0.0);
  jc.m = c2.real(4, "M", 0.0);
  jc.tm = c2.real(5, "TM", 0.0);
  jc.tr = c2.real(6, "TR", 0.0);
  jc.epso = c2.real(7, "EPSO", 0.0);
  if (jc.a < 0.0) throw c2.error("A", fmt::format("yield stress A {} must not be negative", jc.a));
  if (jc.b < 0.0)
    throw c2.error("B", fmt::format("hardening modulus B {} must not be negative", jc.b));
  if (!(jc.a + jc.b > 0.0))
    throw c2.error("A", "A and B are both zero: the material has no strength");
  if (jc.b > 0.0 && !(jc.n > 0.0))
    throw c2.error("N",
                   fmt::format("hardening exponent N {} must be positive when B is given", jc.n));
  if (jc.c < 0.0)
    throw c2.error("C", fmt::format("strain rate constant C {} must not be negative", jc.c));
  if (jc.c > 0.0 && !(jc.epso > 0.0))
    throw c2.error("EPSO", fmt::format("reference strain rate EPSO {} must be positive when C is "
                                       "given (1 for seconds, 1e-3 for milliseconds, ...)",
                                       jc.epso));
  if (!(jc.epso > 0.0)) jc.epso = 1.0;  // C = 0: the rate term is 1 whatever EPSO is
  if (jc.tm != 0.0) {
    if (!(jc.tm > jc.tr))
      throw c2.error("TM", fmt::format("melt temperature TM {} must exceed room temperature TR {} "
                                       "(leave TM blank for no thermal softening)",
                                       jc.tm, jc.tr));
    if (!(jc.m > 0.0))
      throw c2.error("M", fmt::format("thermal softening exponent M {} must be positive when TM "
                                      "is given",
                                      jc.m));
  }

  model::SourceLocation spall_where = m.where;
  model::SourceLocation fracture_where = m.where;
  if (const auto c3 = cursor.next_optional(n + 2, kEightByTen)) {
    spall_where = c3->location();
    jc.cp = c3->real(0, "CP", 0.0);
    jc.pc = c3->real(1, "PC", 0.0);
    const double spall = c3->real(2, "SPALL", 0.0);
    const double it = c3->real(3, "IT", 0.0);
    if (jc.cp < 0.0)
      throw c3->error("CP", fmt::format("specific heat {} must not be negative", jc.cp));
    if (jc.pc > 0.0)
      throw c3->error("PC", fmt::format("pressure cutoff PC {} must not be positive (a tensile "
                                        "limit is a negative pressure)",
                                        jc.pc));
    if (spall != 0.0 && spall != 1.0 && spall != 2.0 && spall != 3.0)
      throw c3->error("SPALL", fmt::format("SPALL {} is not 0, 1, 2 or 3", spall));
    jc.spall = spall == 0.0 ? 2 : static_cast<int>(spall);

    // IT 0 asks LS-DYNA for a linearised (one-iteration) return; the return here is always
    // solved to round-off, which is IT 1's answer.
    if (it != 0.0 && it != 1.0) throw c3->error("IT", fmt::format("IT {} is not 0 or 1", it));
    static const char* const kD[] = {"D1", "D2", "D3", "D4"};
    for (std::size_t k = 0; k < 4; ++k) jc.d[k] = c3->real(4 + k, kD[k], 0.0);
    fracture_where = c3->location();
  }
  if (jc.pc == 0.0 && jc.spall != 1)
    context.warn(spall_where,
                 fmt::format("PC is 0 with SPALL {}: a point spalls (loses its deviatoric stress "
                             "and all tension) at the first tensile {}; give PC < 0 for a "
                             "material that carries tension",
                             jc.spall, jc.spall == 2 ? "principal stress" : "pressure"));
  if (const auto c4 = cursor.next_optional(n + 3, kEightByTen)) {
    jc.d[4] = c4->real(0, "D5", 0.0);
    // C2/P/XNP: only for RATEOP > 0 (refused above).
    jc.erod = c4->real(2, "EROD", 0.0);
    // EFMIN blank or 0: LS-DYNA's default 1e-6.
    if (const double efmin = c4->real(3, "EFMIN", 0.0); efmin != 0.0) jc.efmin = efmin;
    if (!(jc.efmin > 0.0))
      throw c4->error("EFMIN", fmt::format("lower bound of the failure strain EFMIN {} must be "
                                           "positive",
                                           jc.efmin));
    const double numint = c4->real(4, "NUMINT", 0.0);
    if (numint != 0.0 && numint != 1.0)
      throw c4->error("NUMINT", fmt::format("NUMINT {} is not supported: a solid element erodes "
                                            "when one of its points has failed (leave it blank "
                                            "or 1)",
                                            numint));
  }
  // Fracture strain D1 + D2 exp(D3 sigma*) must be positive at zero triaxiality at least.
  if ((jc.d[2] != 0.0 || jc.d[3] != 0.0 || jc.d[4] != 0.0) && !jc.fractures())
    throw InputError(model::context_of(fracture_where, "D1"),
                     "D3, D4 or D5 without D1 or D2: the fracture strain D1 + D2 exp(D3 sigma*) "
                     "would be zero");
  if (jc.fractures() && !(jc.d[0] + jc.d[1] > 0.0))
    throw InputError(model::context_of(fracture_where, "D1"),
                     fmt::format("fracture strain D1 + D2 = {} at zero triaxiality must be "
                                 "positive",
                                 jc.d[0] + jc.d[1]));
  check_unique(context.model.materials, m.id, card, "MID", "material");
  context.model.materials.emplace(m.id, std::move(m));
  warn_unread_lines(block, cursor, context);
}

// Card 1: EOSID C0 C1 C2 C3 C4 C5 C6; card 2: E0 V0.
void eos_linear_polynomial(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const int n = skip_title(block, cursor);
  const Card card = cursor.next(n, kEightByTen, "EOSID C0 C1 C2 C3 C4 C5 C6");
  model::EquationOfState eos;
  eos.id = positive_id(card, 0, "EOSID", "equation of state");
  eos.keyword = block.keyword;
  eos.where = card.location();
  static const char* const kC[] = {"C0", "C1", "C2", "C3", "C4", "C5", "C6"};
  for (std::size_t k = 0; k < 7; ++k) eos.c[k] = card.real(1 + k, kC[k], 0.0);
  if (!(eos.c[1] > 0.0))
    throw card.error("C1", fmt::format("C1 {} is the bulk modulus and must be positive", eos.c[1]));
  if (const auto c2 = cursor.next_optional(n + 1, kEightByTen)) {
    eos.e0 = c2->real(0, "E0", 0.0);
    const double v0 = c2->real(1, "V0", 0.0);
    if (v0 != 0.0 && v0 != 1.0)
      throw c2->error("V0", fmt::format("an initial relative volume V0 {} other than 1 is not "
                                        "supported (leave V0 blank or 1)",
                                        v0));
  }
  check_unique(context.model.equations_of_state, eos.id, card, "EOSID", "equation of state");
  context.model.equations_of_state.emplace(eos.id, std::move(eos));
  warn_unread_lines(block, cursor, context);
}

}  // namespace rf::io::handlers
