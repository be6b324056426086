// Resolves a *MAT_JOHNSON_COOK part: the flow-stress constants of the card and the pressure law
// of the part's *EOS_ (EOSID), or, for EOSID 0, a linear bulk modulus from the card's E and PR.
// Also gives the elastic constants the element uses for its wave speed, hourglass and contact
// stiffness: shear modulus G of the card and the bulk modulus C1 of the EOS (or K from E, PR).
#pragma once

#include "material/elastic.hpp"
#include "material/johnson_cook.hpp"
#include "model/model.hpp"

namespace rf::material {

JohnsonCookParameters make_johnson_cook_parameters(const model::Model& model,
                                                   const model::Part& part,
                                                   const model::Material& mat,
                                                   ElasticConstants& elastic);

}  // namespace rf::material
