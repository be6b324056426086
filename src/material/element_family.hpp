// Element families a material can serve (bit flags), for the registry's one table of which
// material runs on which element (material/registry.hpp).
#pragma once

namespace rf::material {

enum ElementFamily : unsigned {
  kHex8 = 1u << 0,         // 8-node hexahedra, ELFORM 1 and 2 (element/hex_block.hpp)
  kLagrangeHex = 1u << 1,  // p = 2, 3 Lagrange hexahedra (element/lagrange_hex.hpp)
  kShell = 1u << 2,        // 4-node shells, plane stress (element/shell_block.hpp)
  kBeam = 1u << 3,         // beams and trusses, uniaxial (element/beam_block.hpp)
};

}  // namespace rf::material
