// Element families a material can serve (bit flags), for the registry's one table of which
// material runs on which element (material/registry.hpp).
#pragma once

namespace rf::material {

enum ElementFamily : unsigned {
  kHex8 = 1u << 0,         // 8-node hexahedra, ELFORM 1 and 2 (element/hex_block.hpp)
  kLagrangeHex = 1u << 1,  // p = 2, 3 Lagrange hexahedra (element/lagrange_hex.hpp)
  kBeam = 1u << 3,         // 2-node beams and trusses (element/beam_block.hpp)
};

}  // namespace rf::material
