// Pieces the solid kernels share (hex_block.cpp, tet13_block.cpp, tet10_block.cpp; the shells
// take the bulk viscosity too): the constants a material's update takes from a block, the size
// of its history buffer, and the artificial bulk viscosity and the critical step with it, for
// one element or a batch.
#pragma once

#include <cmath>
#include <type_traits>

#include "element/hex_block.hpp"
#include "material/registry.hpp"

namespace rf::element {

// The constants material M's update takes (material::ParametersOf).
template <class M>
inline const auto& update_parameters(const HexBlock& block) {
  using P = typename material::ParametersOf<M>::type;
  if constexpr (std::is_same_v<P, material::PlasticParameters>)
    return block.plastic;
  else if constexpr (std::is_same_v<P, material::JohnsonCookParameters>)
    return block.johnson_cook;
  else
    return block.hyperelastic;
}

// Length of a buffer for material M's history components (at least 1: no zero-length arrays).
template <class M>
constexpr int history_slots() {
  return material::history_size<M>() > 0 ? material::history_size<M>() : 1;
}

// Artificial bulk viscosity (LS-DYNA theory manual, "Artificial Bulk Viscosity"; von Neumann &
// Richtmyer 1950 quadratic term, Landshoff 1955 linear term):
//   q = rho l (Q1 l e_kk^2 - Q2 c e_kk)  for e_kk < 0,  q = 0 otherwise,
// e_kk the volumetric strain rate, c the P-wave speed, l the element length. The manual names
// l = V^{1/3}; we use the time-step length L_e = V / A_max (equal for a cube), because the
// step formula below, Q = Q2 c + Q1 L_e |e_kk|, is the stability limit of exactly this q: a
// 1-D element damped by q with length l has Q = (l / L_e)(Q2 c + Q1 l |e_kk|), so with
// V^{1/3} > L_e (flat elements) the LS-DYNA step would be unstable (seen: a bar of 10:1 plates
// blew up at TSSFAC 0.9). q is a pressure: it enters the nodal forces as -q on the diagonal of
// the stress, never the stored stress. The energy it dissipates over a step is
// q |e_kk| V dt >= 0 (V the mid-step volume, where e_kk is evaluated).
// T is double or a GCC vector of lanes (the batched hexahedron and shell kernels): the select
// is lane-wise there, and the formula is the same for every element family.
//
// "Compressing" means e_kk L_e < -1e-9 c: a volume change of more than 1e-9 per wave transit
// of the element. Below that e_kk is the round-off of a rigidly moving element (about 1e-16
// |omega| for a spin omega; c / L_e is 1e6 to 1e8 per second), and the step rule below jumps by
// 6 % (Q2 c) as e_kk crosses zero: with the plain e_kk < 0, an element released from a rigid
// body took the lower step or not by the sign of its round-off, and runs on different rank
// counts drifted apart by 0.1 % after a switch (docs/parallel.md). The pressure below that rate
// is below 1e-10 of rho c^2 and is dropped too, so q and the step agree on what compresses.
inline constexpr double kCompressionNoise = 1e-9;

template <class T>
inline T bulk_viscosity_pressure(const BulkViscositySettings& bv, double wave_speed, T density,
                                 T length, T ekk) {
  const T e = ekk * length < -kCompressionNoise * wave_speed ? ekk : T{};
  return density * length * (bv.q1 * length * e * e - bv.q2 * wave_speed * e);
}

// Critical step with bulk viscosity (LS-DYNA theory manual, "Time Step Control", solid
// elements): dt_e = L_e / (Q + sqrt(Q^2 + c^2)), Q = Q2 c + Q1 L_e |e_kk| while compressing,
// Q = 0 otherwise (then dt_e = L_e / sqrt(c^2) = L_e / c exactly, as without viscosity).
// `sqrt_of` takes T: std::sqrt for one element, the kernel's lane-wise root for a batch.
template <class T, class Sqrt>
inline T viscous_time_step(const BulkViscositySettings& bv, double c, T length, T ekk,
                           Sqrt&& sqrt_of) {
  const T q =
      ekk * length < -kCompressionNoise * c ? (T{} + bv.q2 * c) - bv.q1 * length * ekk : T{};
  return length / (q + sqrt_of(q * q + c * c));
}
inline double viscous_time_step(const BulkViscositySettings& bv, double c, double length,
                                double ekk) {
  return viscous_time_step(bv, c, length, ekk, [](double x) { return std::sqrt(x); });
}

}  // namespace rf::element
