// Rigid walls as pictures: a patch of each wall's plane for walls_NNNN.vtu (docs/output.md).
#pragma once

#include <vector>

#include "contact/rigid_wall.hpp"
#include "output/writers.hpp"

namespace rf::contact {

// One quadrilateral per wall at its current position: a finite wall's rectangle; an unbounded
// direction spans 1.2 times the diagonal of the model's reference bounding box, centred on the
// model's centre projected onto the plane.
std::vector<output::WallPatch> wall_patches(const RigidWallSystem& walls,
                                            const solver::State& state);

}  // namespace rf::contact
