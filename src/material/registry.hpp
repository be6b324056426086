// The material registry: which materials exist, which element families each serves, and the
// history each carries. Adding a material: write its struct in its own header (kKind,
// kFamilies, kHistory, a templated batched update, see plastic_kinematic.hpp) and add it to
// SolidMaterials below. The element kernels are instantiated once per (hourglass form, material)
// and chosen once per block (block.material_index), never per point.
//
// A material struct provides
//   kKind       the model::MaterialKind its keyword reader produces;
//   kFamilies   ElementFamily bits it runs on;
//   kHistory    its history fields (name, components, tensor or not), in the order of `h`;
//   update<T>(elastic, plastic, d[6], w[3], dt, s[6], h)   one step at a batch of points, T a
//               double or a GCC vector of doubles (one point per lane); h holds the history
//               components of the fields in kHistory order. A material whose constants are not
//               PlasticParameters names their type as M::Parameters (see ParametersOf).
#pragma once

#include <cstddef>
#include <span>
#include <type_traits>

#include "material/barlat.hpp"
#include "material/elastic_material.hpp"
#include "material/johnson_cook.hpp"
#include "material/mooney_rivlin.hpp"
#include "material/ogden.hpp"
#include "material/piecewise_linear_plasticity.hpp"
#include "material/plastic_kinematic.hpp"

namespace rf::material {

template <class... M>
struct MaterialList {};

// THE registration line.
using SolidMaterials =
    MaterialList<ElasticMaterial, PlasticKinematicMaterial, PiecewiseLinearPlasticityMaterial,
                 MooneyRivlinMaterial, OgdenMaterial, BarlatMaterial, JohnsonCookMaterial>;

// The constants a material's update takes: M::Parameters where the material names one (the
// rubbers: HyperelasticParameters), PlasticParameters otherwise. The kernels pass the block's
// member of that type (hex_block.cpp).
template <class M>
struct ParametersOf {
  using type = PlasticParameters;
};
template <class M>
requires requires {
  typename M::Parameters;
}
struct ParametersOf<M> {
  using type = typename M::Parameters;
};
template <class M>
constexpr bool takes_plastic_parameters() {
  return std::is_same_v<typename ParametersOf<M>::type, PlasticParameters>;
}

// Whether M serves `family` (compile time: kernels instantiate only the materials they run).
template <class M>
constexpr bool serves_family(ElementFamily family) {
  return (M::kFamilies & family) != 0;
}

// Plane-stress-only materials (M::kPlaneStressOnly, e.g. Barlat 1989) give shells
// M::plane_stress_update instead of a 3D update (shell_block.cpp).
template <class M>
constexpr bool plane_stress_only() {
  if constexpr (requires { M::kPlaneStressOnly; })
    return M::kPlaneStressOnly;
  else
    return false;
}

template <class M>
constexpr int history_size() {
  int n = 0;
  for (const auto& f : M::kHistory) n += f.components;
  return n;
}

namespace detail {
template <class F, class... M>
void dispatch(int index, F&& f, MaterialList<M...>) {
  int i = 0;
  ((i++ == index ? (f(std::type_identity<M>{}), true) : false) || ...);
}
template <class... M>
int index_of(model::MaterialKind kind, MaterialList<M...>) {
  int i = 0, found = -1;
  ((found < 0 && M::kKind == kind ? (found = i) : 0, ++i), ...);
  return found;
}
}  // namespace detail

// Calls f(std::type_identity<M>{}) for the material at `index` in SolidMaterials.
template <class F>
void with_material(int index, F&& f) {
  detail::dispatch(index, f, SolidMaterials{});
}

// Index in SolidMaterials of the material a keyword kind produces; -1 if none (e.g. *MAT_RIGID).
inline int material_index(model::MaterialKind kind) {
  return detail::index_of(kind, SolidMaterials{});
}

// History fields of the material at `index`.
inline std::span<const HistoryField> history_fields(int index) {
  std::span<const HistoryField> out;
  with_material(index, [&]<class M>(std::type_identity<M>) { out = M::kHistory; });
  return out;
}

// Whether the material at `index` runs on the element family.
inline bool serves(int index, ElementFamily family) {
  bool out = false;
  with_material(index, [&]<class M>(std::type_identity<M>) { out = (M::kFamilies & family) != 0; });
  return out;
}

}  // namespace rf::material
