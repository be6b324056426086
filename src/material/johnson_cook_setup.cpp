#include "material/johnson_cook_setup.hpp"

#include <fmt/format.h>

#include "model/error_context.hpp"

namespace rf::material {

using model::context_of;

JohnsonCookParameters make_johnson_cook_parameters(const model::Model& model,
                                                   const model::Part& part,
                                                   const model::Material& mat,
                                                   ElasticConstants& elastic) {
  const model::JohnsonCookCard& c = mat.johnson_cook;
  JohnsonCookParameters p;
  p.rho0 = mat.rho;
  p.a = c.a;
  p.b = c.b;
  p.n = c.n;
  p.c = c.c;
  p.m = c.m;
  p.tm = c.tm;
  p.tr = c.tr;
  p.epso = c.epso;
  p.cp = c.cp;
  p.vp = c.vp;
  p.pmin = c.pc;
  p.spall = c.spall;
  p.fracture = c.fractures();
  p.d = c.d;
  p.efmin = c.efmin;
  const double g = c.g;
  double bulk = 0.0;
  if (part.eosid != 0) {
    const auto it = model.equations_of_state.find(part.eosid);
    if (it == model.equations_of_state.end())
      throw InputError(context_of(part.where, "EOSID"),
                       fmt::format("part {} refers to equation of state {}, which is not defined "
                                   "(*EOS_LINEAR_POLYNOMIAL)",
                                   part.id, part.eosid));
    const model::EquationOfState& eos = it->second;
    p.eos = true;
    p.eos_c = eos.c;
    p.e0 = eos.e0;
    // The small-compression bulk modulus dp/dmu at mu = 0 and E = E0.
    bulk = eos.c[1] + eos.c[5] * eos.e0;
    if (!(bulk > 0.0))
      throw InputError(context_of(eos.where, "C1"),
                       fmt::format("equation of state {} has a bulk modulus C1 + C5 E0 = {} at "
                                   "the reference state; it must be positive for part {} "
                                   "(*MAT_JOHNSON_COOK needs a stiff pressure law)",
                                   eos.id, bulk, part.id));
  } else {
    // No EOS: K from the card's E and PR (LS-DYNA reads them for shells; we accept them for
    // solids as the linear pressure law and refuse a card that has neither).
    if (!(mat.e > 0.0) || !(mat.pr > -1.0 && mat.pr < 0.5))
      throw InputError(context_of(part.where, "EOSID"),
                       fmt::format("part {} uses *MAT_JOHNSON_COOK (material {}) on solids without "
                                   "an equation of state: give EOSID (*EOS_LINEAR_POLYNOMIAL), or "
                                   "E and PR on the material card for a linear bulk modulus",
                                   part.id, mat.id));
    bulk = mat.e / (3.0 * (1.0 - 2.0 * mat.pr));
    p.bulk = bulk;
  }
  // Equivalent isotropic constants with exactly this G and K.
  const double young = 9.0 * bulk * g / (3.0 * bulk + g);
  const double poisson = (3.0 * bulk - 2.0 * g) / (2.0 * (3.0 * bulk + g));
  elastic = make_elastic(mat.rho, young, poisson);
  return p;
}

}  // namespace rf::material
