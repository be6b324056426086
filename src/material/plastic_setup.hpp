// Resolves the plasticity card of a *MAT_003 / *MAT_024 material into the parameters the stress
// update uses: hardening law (linear, 8-point table or LCSS curve), rate model and failure
// strain. Curves are checked here (they may follow the material in the deck): non-increasing
// strains, negative or decreasing stresses and missing curves are input errors naming the
// material card's file, line, keyword and field.
#pragma once

#include "material/barlat.hpp"
#include "material/elastic.hpp"
#include "material/plastic_parameters.hpp"
#include "model/model.hpp"

namespace rf::material {

PlasticParameters make_plastic_parameters(const model::Model& model, const model::Material& mat);

// *MAT_036: yield function coefficients a, c, h, p from R00, R45, R90 (Barlat and Lian 1989; p
// solved so that the 45-degree plastic strain ratio is R45) or as given (PB > 0), hardening law
// (HR 1 linear, 2 power law with E0/SPI, 3 curve LCID with its scale factors), material axes.
BarlatParameters make_barlat_parameters(const model::Model& model, const model::Material& mat);

}  // namespace rf::material
