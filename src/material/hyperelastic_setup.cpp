#include "material/hyperelastic_setup.hpp"

namespace rf::material {

double rubber_shear_modulus(const model::RubberCard& card, model::MaterialKind kind) {
  if (kind == model::MaterialKind::MooneyRivlinRubber) return 2.0 * (card.a + card.b);
  double twice = 0.0;
  for (int j = 0; j < card.terms; ++j) twice += card.mu[j] * card.alpha[j];
  return 0.5 * twice;
}

HyperelasticParameters make_hyperelastic_parameters(const model::Material& mat) {
  HyperelasticParameters p;
  const model::RubberCard& card = mat.rubber;
  const double nu = mat.pr;
  if (mat.kind == model::MaterialKind::MooneyRivlinRubber) {
    p.a = card.a;
    p.b = card.b;
    p.c = 0.5 * card.a + card.b;
    p.d = (card.a * (5.0 * nu - 2.0) + card.b * (11.0 * nu - 5.0)) / (2.0 * (1.0 - 2.0 * nu));
  } else {
    p.terms = card.terms;
    p.mu = card.mu;
    p.alpha = card.alpha;
  }
  const double g = rubber_shear_modulus(card, mat.kind);
  p.bulk = 2.0 * g * (1.0 + nu) / (3.0 * (1.0 - 2.0 * nu));
  return p;
}

}  // namespace rf::material
