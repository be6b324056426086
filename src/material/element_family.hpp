// Element families a material can serve (bit flags), for the registry's one table of which
// material runs on which element (material/registry.hpp).
#pragma once

namespace rf::material {

enum ElementFamily : unsigned {
  kHex8 = 1u << 0,         // 8-node hexahedra, ELFORM 1 and 2 (element/hex_block.hpp)
  kLagrangeHex = 1u << 1,  // p = 2, 3 Lagrange hexahedra (element/lagrange_hex.hpp)
  // 4-node shells (element/shell_block.hpp): plane stress at each through-thickness point. The
  // elastic law runs in closed form there; the J2 laws run their 3D update with the thickness
  // strain rate iterated until sigma_zz = 0 (shell_block.cpp).
  kShell = 1u << 2,
  kBeam = 1u << 3,  // beams and trusses, uniaxial (element/beam_block.hpp)
  // Nodal-pressure tetrahedra (*SECTION_SOLID ELFORM 13, element/tet13_block.hpp): the
  // material gets the element's velocity gradient with a nodally averaged trace. Serves laws
  // whose pressure follows the volume change alone (elastic, J2, the rubbers' F-bar form).
  kTet13 = 1u << 4,
  // 10-node quadratic tetrahedra (*SECTION_SOLID ELFORM 16, element/tet10_block.hpp): the
  // material runs at each of the four integration points with that point's velocity gradient,
  // as at the eight points of ELFORM 2.
  kTet10 = 1u << 5,
};

}  // namespace rf::material
