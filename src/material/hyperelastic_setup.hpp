// Resolves the rubber cards (*MAT_027, *MAT_077_O) into the constants their updates use.
#pragma once

#include "material/hyperelastic.hpp"
#include "model/model.hpp"

namespace rf::material {

// Mooney-Rivlin C, D from A, B, PR (LS-DYNA *MAT_027); Ogden K from sum(mu alpha)/2 and PR.
HyperelasticParameters make_hyperelastic_parameters(const model::Material& mat);

// Small-strain shear modulus of a rubber card: 2 (A + B), or sum_j mu_j alpha_j / 2.
double rubber_shear_modulus(const model::RubberCard& card, model::MaterialKind kind);

}  // namespace rf::material
