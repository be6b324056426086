// Element erosion: criteria, deletion, node removal, ledger (erosion.hpp; docs/materials.md,
// "Failure and erosion").
#include "solver/erosion.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string_view>

#include "element/hex_geometry.hpp"
#include "element/kernel_partials.hpp"
#include "material/elastic_update.hpp"
#include "model/error.hpp"
#include "model/error_context.hpp"

namespace rf::solver {

namespace {

using model::context_of;

const material::HistoryArray* history_named(const std::vector<material::HistoryArray>& history,
                                            std::string_view name) {
  for (const auto& h : history)
    if (h.field.name == name) return &h;
  return nullptr;
}

// Stress invariants at one point from the six Voigt components (xx, yy, zz, xy, yz, zx).
struct PointStress {
  double pressure;   // -tr(sigma)/3, positive in compression
  double von_mises;  // sqrt(3/2 s:s), s the deviator
  double s[6];
};

PointStress point_stress(const double s[6]) {
  PointStress p{};
  for (int c = 0; c < 6; ++c) p.s[c] = s[c];
  const double mean = (s[0] + s[1] + s[2]) / 3.0;
  p.pressure = -mean;
  const double d0 = s[0] - mean, d1 = s[1] - mean, d2 = s[2] - mean;
  p.von_mises = std::sqrt(
      1.5 * (d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])));
  return p;
}

// sqrt(2/3 e':e') of the principal strains (e' the deviator): LS-DYNA's effective strain.
double effective_strain(const double e[3]) {
  const double mean = (e[0] + e[1] + e[2]) / 3.0;
  const double a = e[0] - mean, b = e[1] - mean, c = e[2] - mean;
  return std::sqrt(2.0 / 3.0 * (a * a + b * b + c * c));
}

// Principal logarithmic strains e_i = ln(lambda_i), descending, from the right Cauchy-Green
// tensor C = F^T F (Voigt) whose eigenvalues are lambda_i^2.
void log_strains_of_cauchy_green(const double c[6], double out[3]) {
  material::principal_values(c, out);
  for (int i = 0; i < 3; ++i) out[i] = out[i] > 0.0 ? 0.5 * std::log(out[i]) : -HUGE_VAL;
}

// Principal strains of a strain tensor whose thickness (or lateral) strain is not known: the
// in-plane (axial) components given, e_zz = -(e_xx + e_yy) as in a volume-preserving plastic
// flow (Voigt xx yy xy tensor components).
void volume_preserving_strains(double xx, double yy, double xy, double out[3]) {
  const double e[6] = {xx, yy, -(xx + yy), xy, 0.0, 0.0};
  material::principal_values(e, out);
}

// Per family: the principal logarithmic strains of every stress point of element e (the strain
// criteria), out[q] for q < points_per_element() (at most kMaxStrainPoints, checked at set-up).
// Solids: from the deformation gradient F = I + sum_n u_n (x) dN_n/dX on the reference geometry
// (the element's mean gradients for one point, each 2x2x2 Gauss point's for ELFORM 2), exact for
// any deformation. Shells: the integrated co-rotational rate of deformation (shell block
// `strain`), the thickness strain volume-preserving (also with ISTUPD 1/4, whose thickness is one
// per element, not per point).
// Trusses: ln(L/L0) along the axis, lateral strains volume-preserving.
constexpr int kMaxStrainPoints = 40;  // hexahedra 8, shells 4 x NIP <= 40 (ELFORM 16), trusses 1

void principal_strains(const element::HexBlock& b, const NodalState& nodes, std::size_t e,
                       double out[][3]) {
  double x0[3][8], u[3][8];
  for (int n = 0; n < 8; ++n) {
    const std::size_t i = static_cast<std::size_t>(b.conn[8 * e + static_cast<std::size_t>(n)]);
    x0[0][n] = nodes.x0.x[i];
    x0[1][n] = nodes.x0.y[i];
    x0[2][n] = nodes.x0.z[i];
    u[0][n] = nodes.x.x[i] - x0[0][n];
    u[1][n] = nodes.x.y[i] - x0[1][n];
    u[2][n] = nodes.x.z[i] - x0[2][n];
  }
  auto from_gradients = [&](const double dndx[3][8], double strain[3]) {
    double f[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        double sum = i == j ? 1.0 : 0.0;
        for (int n = 0; n < 8; ++n) sum += u[i][n] * dndx[j][n];
        f[i][j] = sum;
      }
    auto c = [&](int i, int j) {
      return f[0][i] * f[0][j] + f[1][i] * f[1][j] + f[2][i] * f[2][j];
    };
    const double cauchy_green[6] = {c(0, 0), c(1, 1), c(2, 2), c(0, 1), c(1, 2), c(2, 0)};
    log_strains_of_cauchy_green(cauchy_green, strain);
  };
  double dndx[3][8];
  if (b.points_per_element() == 1) {
    element::hex::Geometry g;
    element::hex::compute_geometry(x0, g);
    for (int j = 0; j < 3; ++j)
      for (int n = 0; n < 8; ++n) dndx[j][n] = g.b[j][n] / g.volume;
    from_gradients(dndx, out[0]);
    return;
  }
  double a[8][3];
  element::hex::base_vectors(x0, a);
  for (int q = 0; q < b.points_per_element(); ++q) {
    element::hex::gauss_gradients(a, q, dndx);
    from_gradients(dndx, out[q]);
  }
}
void principal_strains(const element::ShellBlock& b, const NodalState&, std::size_t e,
                       double out[][3]) {
  const int points = b.points_per_element();
  const double* s = &b.strain[3 * static_cast<std::size_t>(points) * e];
  for (int q = 0; q < points; ++q)
    volume_preserving_strains(s[3 * q], s[3 * q + 1], s[3 * q + 2], out[q]);
}
void principal_strains(const element::BeamBlock& b, const NodalState&, std::size_t e,
                       double out[][3]) {
  const double axial =
      b.length0[e] > 0.0 && b.length[e] > 0.0 ? std::log(b.length[e] / b.length0[e]) : 0.0;
  volume_preserving_strains(axial, -0.5 * axial, 0.0, out[0]);
}

// How many *MAT_ADD_EROSION criteria a point meets (element-level ones, the volumetric strain
// and the failure time, count at every point). `strain`: the point's principal logarithmic
// strains, descending (read only when a strain criterion is on).
int criteria_met(const element::ErosionCriteria& c, const double s[6], const double strain[3],
                 double log_volume_ratio, double time, double impulse) {
  int met = 0;
  if (c.has_tuler_butcher && impulse >= c.stress_impulse) ++met;
  if (c.strain_criteria()) {
    if (c.has_max_principal_strain && strain[0] >= c.max_principal_strain) ++met;
    if (c.has_min_principal_strain && strain[2] <= c.min_principal_strain) ++met;
    if (c.has_shear_strain && 0.5 * (strain[0] - strain[2]) >= c.shear_strain) ++met;
    if (c.has_effective_strain && effective_strain(strain) >= c.effective_strain) ++met;
  }
  if (c.has_max_pressure || c.has_min_pressure || c.has_von_mises) {
    const PointStress p = point_stress(s);
    if (c.has_max_pressure && p.pressure >= c.max_pressure) ++met;
    if (c.has_min_pressure && p.pressure <= c.min_pressure) ++met;
    if (c.has_von_mises && p.von_mises >= c.von_mises) ++met;
  }
  if (c.has_principal_stress && material::max_principal(s) >= c.principal_stress) ++met;
  if (c.has_volumetric_strain) {
    const double v = c.volumetric_strain;
    if ((v > 0.0 && log_volume_ratio >= v) || (v < 0.0 && log_volume_ratio <= v)) ++met;
  }
  if (c.has_failure_time && time >= c.failure_time) ++met;
  return met;
}

// Points that must fail before the element is deleted by *MAT_ADD_EROSION (NUMFIP).
int required_points(const element::ErosionCriteria& c, int points) {
  if (c.failed_points > 0.0)
    return std::clamp(static_cast<int>(std::ceil(c.failed_points - 1e-9)), 1, points);
  const double share = -c.failed_points / 100.0 * points;
  return std::clamp(static_cast<int>(std::ceil(share - 1e-9)), 1, points);
}

// Per family: the stress of point q of element e as six Voigt components, the points, the
// element's force slot size, and the rule of the material's own criterion.
void voigt_of(const element::HexBlock& b, std::size_t e, int q, double s[6]) {
  const double* p = &b.stress[6 * (static_cast<std::size_t>(b.points_per_element()) * e + q)];
  for (int c = 0; c < 6; ++c) s[c] = p[c];
}
void voigt_of(const element::ShellBlock& b, std::size_t e, int q, double s[6]) {
  // Co-rotational frame, plane stress: xx, yy, xy, yz, zx; sigma_zz = 0.
  const double* p =
      &b.stress[element::kShellStress * (static_cast<std::size_t>(b.points_per_element()) * e + q)];
  s[0] = p[0];
  s[1] = p[1];
  s[2] = 0.0;
  s[3] = p[2];
  s[4] = p[3];
  s[5] = p[4];
}
void voigt_of(const element::BeamBlock& b, std::size_t e, int q, double s[6]) {
  const double sigma = b.stress[static_cast<std::size_t>(b.points_per_element()) * e + q];
  s[0] = sigma;
  s[1] = s[2] = s[3] = s[4] = s[5] = 0.0;
}

int slot_size(const element::HexBlock& b) {
  return 3 * b.nodes_per_element();
}
int slot_size(const element::ShellBlock&) {
  return element::kShellSlot;
}
int slot_size(const element::BeamBlock&) {
  return element::kBeamSlot;
}
int nodes_per(const element::HexBlock& b) {
  return b.nodes_per_element();
}
int nodes_per(const element::ShellBlock&) {
  return 4;
}
int nodes_per(const element::BeamBlock&) {
  return 2;
}
const char* family_of(const element::HexBlock&) {
  return "solid";
}
const char* family_of(const element::ShellBlock&) {
  return "shell";
}
const char* family_of(const element::BeamBlock&) {
  return "beam";
}

// The plastic-strain rule: hexahedra and trusses fail with one point, shells when every point
// through the thickness at one in-plane point has failed (failed layers carry no stress, so the
// element goes when the last layer does, as LS-DYNA's *MAT_024 shells), Hughes-Liu beams when
// every section point has.
bool plastic_rule(const element::HexBlock&, const double* eps, int points, double limit) {
  for (int q = 0; q < points; ++q)
    if (eps[q] >= limit) return true;
  return false;
}
bool plastic_rule(const element::ShellBlock& b, const double* eps, int, double limit) {
  for (int i = 0; i < b.in_plane_points(); ++i) {
    int failed = 0;
    for (int k = 0; k < b.nip; ++k) failed += eps[i * b.nip + k] >= limit ? 1 : 0;
    if (failed == b.nip) return true;
  }
  return false;
}
bool plastic_rule(const element::BeamBlock&, const double* eps, int points, double limit) {
  for (int q = 0; q < points; ++q)
    if (eps[q] < limit) return false;
  return points > 0;
}

double log_volume_ratio(const element::HexBlock& b, std::size_t e) {
  return b.volume0[e] > 0.0 && b.volume[e] > 0.0 ? std::log(b.volume[e] / b.volume0[e]) : 0.0;
}
double log_volume_ratio(const element::ShellBlock&, std::size_t) {
  return 0.0;
}
double log_volume_ratio(const element::BeamBlock&, std::size_t) {
  return 0.0;
}

enum FailureCode : std::uint8_t {
  kAlive = 0,
  kPlasticStrain = 1,
  kDamage = 2,
  kAddErosion = 3,
  kTimeStep = 4,
  kMinimumStep = 5,
};

template <class Block>
std::uint8_t evaluate(const Block& b, const NodalState& nodes, std::size_t e, double time,
                      const double* eps, const double* damage, const double* step,
                      double minimum_step) {
  const element::ErosionCriteria& c = b.erosion.criteria;
  const int points = b.points_per_element();
  const std::size_t first = static_cast<std::size_t>(points) * e;
  if (c.plastic_strain > 0.0 && eps && plastic_rule(b, eps + first, points, c.plastic_strain))
    return kPlasticStrain;
  if (c.damage && damage) {
    for (int q = 0; q < points; ++q)
      if (damage[first + static_cast<std::size_t>(q)] >= 1.0) return kDamage;
  }
  if (c.add_erosion() && points > 0) {
    const double lv = log_volume_ratio(b, e);
    double strains[kMaxStrainPoints][3] = {};
    if (c.strain_criteria()) principal_strains(b, nodes, e, strains);
    int failed = 0;
    const double* impulse = b.erosion.impulse.empty() ? nullptr : &b.erosion.impulse[first];
    for (int q = 0; q < points; ++q) {
      double s[6];
      voigt_of(b, e, q, s);
      if (criteria_met(c, s, strains[q], lv, time, impulse ? impulse[q] : 0.0) >=
          c.criteria_at_once)
        ++failed;
    }
    if (failed >= required_points(c, points)) return kAddErosion;
  }
  if (c.tdel > 0.0 && step && step[e] > 0.0 && step[e] < c.tdel) return kTimeStep;
  // ERODE compares the step with mass scaling (TDEL above the raw one).
  if (c.below_minimum_step && minimum_step > 0.0 && step &&
      element::scaled_step(b.step_scale, static_cast<std::int64_t>(e), step[e]) < minimum_step)
    return kMinimumStep;
  return kAlive;
}

template <class Block>
std::string describe(const Block& b, const NodalState& nodes, std::size_t e, std::uint8_t code,
                     double time, const double* eps, const double* damage, const double* step,
                     double minimum_step) {
  const element::ErosionCriteria& c = b.erosion.criteria;
  const int points = b.points_per_element();
  const std::size_t first = static_cast<std::size_t>(points) * e;
  switch (code) {
    case kPlasticStrain: {
      double largest = 0.0;
      for (int q = 0; q < points; ++q) largest = std::max(largest, eps[first + q]);
      return fmt::format("plastic strain {:.6g} >= {:.6g}", largest, c.plastic_strain);
    }
    case kDamage:
      return "Johnson-Cook damage reached 1";
    case kTimeStep:
      return fmt::format("element step {:.6g} < TDEL {:.6g}", step[e], c.tdel);
    case kMinimumStep:
      return fmt::format("element step {:.6g} below TSMIN / TSSFAC = {:.6g} (ERODE)",
                         element::scaled_step(b.step_scale, static_cast<std::int64_t>(e), step[e]),
                         minimum_step);
    case kAddErosion: {
      double s[6];
      voigt_of(b, e, 0, s);
      const PointStress p = point_stress(s);
      std::string text = fmt::format(
          "*MAT_ADD_EROSION (point 1: pressure {:.6g}, von Mises {:.6g}, ln V/V0 "
          "{:.6g}, time {:.6g}",
          p.pressure, p.von_mises, log_volume_ratio(b, e), time);
      if (c.strain_criteria()) {
        double strains[kMaxStrainPoints][3];
        principal_strains(b, nodes, e, strains);
        const double* strain = strains[0];
        text += fmt::format(", principal strains {:.6g} {:.6g} {:.6g}, effective {:.6g}", strain[0],
                            strain[1], strain[2], effective_strain(strain));
      }
      if (c.has_tuler_butcher) {
        const double* impulse = &b.erosion.impulse[first];
        text += fmt::format(", largest stress impulse {:.6g} (IMPULSE {:.6g})",
                            *std::max_element(impulse, impulse + points), c.stress_impulse);
      }
      return text + ")";
    }
    default:
      return "";
  }
}

// Tuler-Butcher (*MAT_ADD_EROSION SIGTH, IMPULSE; LS-DYNA Keyword User's Manual): every stress
// point of the computed elements gains max(0, sigma_1 - sigma_0)^2 dt, sigma_1 its largest
// principal stress at the end of the step (first order in dt, as the criteria are checked once
// per step).
template <class Block>
void add_stress_impulse(Block& block, double dt) {
  const element::ErosionCriteria& c = block.erosion.criteria;
  const int points = block.points_per_element();
  const std::int64_t items = block.owned.count(static_cast<std::int64_t>(block.size()));
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < items; ++i) {
    const std::size_t e = static_cast<std::size_t>(block.owned.element(i));
    for (int q = 0; q < points; ++q) {
      double s[6];
      voigt_of(block, e, q, s);
      const double excess = std::max(0.0, material::max_principal(s) - c.threshold_stress);
      block.erosion.impulse[static_cast<std::size_t>(points) * e + static_cast<std::size_t>(q)] +=
          excess * excess * dt;
    }
  }
}

const model::Material& material_of(const model::Model& model, model::Id pid) {
  return model.materials.at(model.parts.at(pid).mid);
}

}  // namespace

void Erosion::setup(const model::Model& model, State& state) {
  for (const auto& [mid, card] : model.add_erosions) {
    if (!model.materials.count(mid))
      throw InputError(context_of(card.where, "MID"),
                       fmt::format("material {} is not defined (*MAT_ADD_EROSION adds failure "
                                   "criteria to an existing *MAT_)",
                                   mid));
    if (model.materials.at(mid).kind == model::MaterialKind::Rigid)
      throw InputError(context_of(card.where, "MID"),
                       fmt::format("material {} is *MAT_RIGID: rigid parts cannot erode", mid));
  }
  // *CONTROL_TIMESTEP ERODE: the units digit names solids, the tens shells, the hundreds beams.
  const int erode = model.timestep.erode;
  auto erodes_by_step = [&](std::string_view family) {
    const int digit = family == "solid"   ? erode % 10
                      : family == "shell" ? erode / 10 % 10
                                          : erode / 100;
    return digit == 1;
  };
  auto resolve = [&](auto& block, const char* family) {
    if (block.rigid) return;  // *MAT_RIGID (criteria on a rigid material are refused above)
    const model::Material& mat = material_of(model, block.part_id);
    element::ErosionCriteria c;
    c.below_minimum_step = erodes_by_step(family) && model.termination.dtmin > 0.0;
    if (mat.kind == model::MaterialKind::PlasticKinematic ||
        mat.kind == model::MaterialKind::PiecewiseLinearPlasticity) {
      c.plastic_strain = mat.plastic.fail;
      c.tdel = mat.plastic.tdel;
    }
    if (mat.kind == model::MaterialKind::JohnsonCook) c.damage = mat.johnson_cook.erodes();
    if (const auto it = model.add_erosions.find(mat.id); it != model.add_erosions.end()) {
      const model::AddErosion& a = it->second;
      auto take = [](const std::optional<double>& v, bool& has, double& value) {
        has = v.has_value();
        value = v.value_or(0.0);
      };
      take(a.mxpres, c.has_max_pressure, c.max_pressure);
      take(a.mnpres, c.has_min_pressure, c.min_pressure);
      take(a.sigp1, c.has_principal_stress, c.principal_stress);
      take(a.sigvm, c.has_von_mises, c.von_mises);
      take(a.voleps, c.has_volumetric_strain, c.volumetric_strain);
      take(a.failtm, c.has_failure_time, c.failure_time);
      take(a.mxeps, c.has_max_principal_strain, c.max_principal_strain);
      take(a.mneps, c.has_min_principal_strain, c.min_principal_strain);
      take(a.effeps, c.has_effective_strain, c.effective_strain);
      take(a.epssh, c.has_shear_strain, c.shear_strain);
      take(a.impulse, c.has_tuler_butcher, c.stress_impulse);
      c.threshold_stress = a.sigth;
      c.criteria_at_once = a.ncs;
      c.failed_points = a.numfip;
      const std::string_view f = family;
      if (c.has_volumetric_strain && f != "solid")
        throw InputError(context_of(a.where, "VOLEPS"),
                         fmt::format("part {} ({} elements) uses material {}: the volumetric "
                                     "strain criterion needs solid elements (shells and beams "
                                     "keep their thickness and section)",
                                     block.part_id, family, mat.id));
      if (c.failed_points < 0.0 && f != "shell")
        throw InputError(context_of(a.where, "NUMFIP"),
                         fmt::format("a negative NUMFIP (percentage of points) applies to shells "
                                     "only; part {} has {} elements",
                                     block.part_id, family));
      if (c.add_erosion() && block.points_per_element() == 0)
        throw InputError(context_of(a.where, "MID"),
                         fmt::format("part {} (resultant beams, ELFORM 2) has no stress points "
                                     "for the *MAT_ADD_EROSION criteria (use ELFORM 1 or 3)",
                                     block.part_id));
      bool has_strain_tensor = true;
      if constexpr (std::is_same_v<std::remove_cvref_t<decltype(block)>, element::BeamBlock>)
        has_strain_tensor = block.elform == 3;
      if (c.strain_criteria() && !has_strain_tensor)
        throw InputError(
            context_of(a.where, a.mxeps    ? "MXEPS"
                                : a.mneps  ? "MNEPS"
                                : a.effeps ? "EFFEPS"
                                           : "EPSSH"),
            fmt::format("part {} uses material {}: the strain criteria run on solids, shells and "
                        "trusses (beam ELFORM 3); the section points of this beam carry no strain "
                        "tensor",
                        block.part_id, mat.id));
      if (c.strain_criteria() && block.points_per_element() > kMaxStrainPoints)
        throw InputError(context_of(a.where, "MID"),
                         fmt::format("part {} has {} stress points per element; the strain "
                                     "criteria handle at most {}",
                                     block.part_id, block.points_per_element(), kMaxStrainPoints));
      if (c.criteria_at_once > 1) {
        const int defined = c.defined();
        if (defined < c.criteria_at_once)
          throw InputError(context_of(a.where, "NCS"),
                           fmt::format("NCS {} asks for more criteria at once than the {} this "
                                       "card defines: no element could ever fail",
                                       c.criteria_at_once, defined));
      }
    }
    block.erosion.criteria = c;
    block.erosion.enabled = c.plastic_strain > 0.0 || c.damage || c.tdel > 0.0 ||
                            c.below_minimum_step || c.add_erosion();
    if constexpr (std::is_same_v<std::remove_cvref_t<decltype(block)>, element::ShellBlock>) {
      // The shell kernel integrates the strain only when a criterion reads it.
      if (c.strain_criteria())
        block.strain.assign(3 * static_cast<std::size_t>(block.points_per_element()) * block.size(),
                            0.0);
    }
    if (block.erosion.enabled) {
      block.erosion.allocate(block.size());
      if (c.has_tuler_butcher)
        block.erosion.impulse.assign(
            static_cast<std::size_t>(block.points_per_element()) * block.size(), 0.0);
      enabled_ = true;
    }
  };
  for (auto& b : state.hex_blocks) {
    if (!b.rigid && b.quadratic_tetrahedra()) {
      // Erosion would need the removed element's nodes and faces in the 10-node layout
      // (principal strains, contact surface updates): not written yet, so refused.
      resolve(b, "solid");
      if (b.erosion.enabled) {
        const model::Material& mat = material_of(model, b.part_id);
        const auto it = model.add_erosions.find(mat.id);
        throw InputError(
            context_of(it != model.add_erosions.end() ? it->second.where : mat.where, "MID"),
            fmt::format("part {} has 10-node tetrahedra (*SECTION_SOLID ELFORM 16), "
                        "which do not erode in this version, but its material {} ({}) "
                        "or *CONTROL_TIMESTEP asks for erosion (FAIL, *MAT_ADD_EROSION, "
                        "ERODE)",
                        b.part_id, mat.id, mat.keyword));
      }
      continue;
    }
    if (!b.rigid && b.order > 1) {
      const model::Material& mat = material_of(model, b.part_id);
      if (const auto it = model.add_erosions.find(mat.id); it != model.add_erosions.end())
        throw InputError(context_of(it->second.where, "MID"),
                         fmt::format("part {} has order {} elements (*CHANGE_P-ORDER), which do "
                                     "not erode",
                                     b.part_id, b.order));
      continue;
    }
    resolve(b, "solid");
  }
  for (auto& b : state.shell_blocks) resolve(b, "shell");
  for (auto& b : state.beam_blocks) resolve(b, "beam");
  if (!enabled_) return;

  const std::size_t n = state.nodes.size();
  live_elements_.assign(n, 0);
  erodible_node_.assign(n, 0);
  auto count = [&](const auto& block) {
    for (const std::int32_t node : block.conn) {
      if (node < 0) continue;
      ++live_elements_[static_cast<std::size_t>(node)];
      if (block.erosion.enabled) erodible_node_[static_cast<std::size_t>(node)] = 1;
    }
  };
  for (const auto& b : state.hex_blocks) count(b);
  for (const auto& b : state.shell_blocks) count(b);
  for (const auto& b : state.beam_blocks) count(b);
  for (const auto& b : state.discrete_blocks)
    for (const std::int32_t node : b.conn)
      if (node >= 0) ++live_elements_[static_cast<std::size_t>(node)];
  state.nodes.removed.assign(n, 0);
}

void Erosion::add_step_work(State& state, const Vec3Array& vp, double dt_avg) {
  if (!enabled_) return;
  const NodalState& nodes = state.nodes;
  const RotationalState& rot = state.rotations;
  const double h = 0.5 * dt_avg;
  auto run = [&](auto& block) {
    if (!block.erosion.enabled || block.rigid || block.force.empty()) return;
    const int npe = nodes_per(block);
    const int slot = slot_size(block);
    const int per_node = slot / npe;  // 3 (forces) or 6 (forces and moments)
    const std::int64_t items = block.owned.count(static_cast<std::int64_t>(block.size()));
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < items; ++i) {
      const std::size_t e = static_cast<std::size_t>(block.owned.element(i));
      const double* f = &block.force[static_cast<std::size_t>(slot) * e];
      double work = 0.0;
      for (int a = 0; a < npe; ++a) {
        const std::size_t node =
            static_cast<std::size_t>(block.conn[static_cast<std::size_t>(npe) * e + a]);
        const double* fa = f + per_node * a;
        work +=
            h * (fa[0] * (vp.x[node] + nodes.v.x[node]) + fa[1] * (vp.y[node] + nodes.v.y[node]) +
                 fa[2] * (vp.z[node] + nodes.v.z[node]));
        if constexpr (!std::is_same_v<std::remove_cvref_t<decltype(block)>, element::HexBlock>) {
          if (block.rotation_conn.empty()) continue;  // trusses of a model without rotations
          const std::int32_t r = block.rotation_conn[static_cast<std::size_t>(npe) * e + a];
          if (r < 0) continue;
          const std::size_t ur = static_cast<std::size_t>(r);
          work += h * (fa[3] * (rot.w_previous.x[ur] + rot.w.x[ur]) +
                       fa[4] * (rot.w_previous.y[ur] + rot.w.y[ur]) +
                       fa[5] * (rot.w_previous.z[ur] + rot.w.z[ur]));
        }
      }
      block.erosion.work[e] += work;
    }
  };
  for (auto& b : state.hex_blocks) run(b);
  for (auto& b : state.shell_blocks) run(b);
  for (auto& b : state.beam_blocks) run(b);
}

std::int64_t Erosion::erode_failed_elements(State& state, double time,
                                            const std::vector<std::int32_t>* body_of) {
  events_.clear();
  if (!enabled_) return 0;
  return delete_elements(state, time, find_failed_elements(state, time), body_of);
}

std::vector<ElementFailure> Erosion::find_failed_elements(State& state, double time) {
  std::vector<ElementFailure> failures;
  if (!enabled_) return failures;
  const element::NodalView view = view_of(state.nodes);
  // Tuler-Butcher: the stress impulse of the step since the last evaluation, with the stress at
  // its end (a switch's re-evaluation within a cycle adds nothing; after dynamic relaxation the
  // clock starts again at 0).
  const double impulse_step = time >= impulse_time_ ? time - impulse_time_ : time;
  impulse_time_ = time;
  auto run = [&](auto& block, std::int32_t family, std::size_t b) {
    if (!block.erosion.enabled || block.rigid) return;
    const element::ErosionCriteria& c = block.erosion.criteria;
    if (c.has_tuler_butcher && impulse_step > 0.0) add_stress_impulse(block, impulse_step);
    const auto* eps_array = history_named(block.history, "effective_plastic_strain");
    const auto* damage_array = history_named(block.history, "damage");
    const double* eps = eps_array ? eps_array->values.data() : nullptr;
    const double* damage = damage_array ? damage_array->values.data() : nullptr;
    const double* step = nullptr;
    if (c.tdel > 0.0 || (c.below_minimum_step && minimum_step_ > 0.0)) {
      using B = std::remove_cvref_t<decltype(block)>;
      if constexpr (std::is_same_v<B, element::HexBlock>)
        element::hex_critical_timestep(block, view, &scratch_steps_);
      else if constexpr (std::is_same_v<B, element::ShellBlock>)
        element::shell_critical_timestep(block, view, &scratch_steps_);
      else
        element::beam_critical_timestep(block, view, &scratch_steps_);
      step = scratch_steps_.data();
    }
    const std::int64_t items = block.owned.count(static_cast<std::int64_t>(block.size()));
    // Failures are rare: each thread scans its share, the elements found are then listed in
    // ascending order on one thread (the same result for any thread count).
    std::int64_t first_failed = items;
#pragma omp parallel for schedule(static) reduction(min : first_failed)
    for (std::int64_t i = 0; i < items; ++i) {
      const std::size_t e = static_cast<std::size_t>(block.owned.element(i));
      if (evaluate(block, state.nodes, e, time, eps, damage, step, minimum_step_) != kAlive)
        first_failed = std::min(first_failed, i);
    }
    for (std::int64_t i = first_failed; i < items; ++i) {
      const std::size_t e = static_cast<std::size_t>(block.owned.element(i));
      const std::uint8_t code =
          evaluate(block, state.nodes, e, time, eps, damage, step, minimum_step_);
      if (code == kAlive) continue;
      failures.push_back(
          {family, static_cast<std::int32_t>(b), static_cast<std::int64_t>(e),
           block.erosion.work[e] - block.erosion.artificial_work[e],
           describe(block, state.nodes, e, code, time, eps, damage, step, minimum_step_)});
    }
  };
  for (std::size_t b = 0; b < state.hex_blocks.size(); ++b) run(state.hex_blocks[b], 0, b);
  for (std::size_t b = 0; b < state.shell_blocks.size(); ++b) run(state.shell_blocks[b], 1, b);
  for (std::size_t b = 0; b < state.beam_blocks.size(); ++b) run(state.beam_blocks[b], 2, b);
  return failures;
}

std::int64_t Erosion::delete_elements(State& state, double time,
                                      const std::vector<ElementFailure>& failures,
                                      const std::vector<std::int32_t>* body_of) {
  events_.clear();
  if (failures.empty()) return 0;
  auto remove = [&](auto& block, const ElementFailure& failure) {
    const std::size_t e = static_cast<std::size_t>(failure.element);
    events_.push_back(
        {time, block.part_id, block.element_id[e], family_of(block), failure.criterion});
    block.erosion.time[e] = time;
    ++block.erosion.count;
    ledger_.internal_energy += failure.internal_energy;
    ++ledger_.elements;
    const int slot = slot_size(block);
    const int npe = nodes_per(block);
    std::fill_n(block.force.begin() + static_cast<std::ptrdiff_t>(slot * e), slot, 0.0);
    const std::size_t points = static_cast<std::size_t>(block.points_per_element());
    using B = std::remove_cvref_t<decltype(block)>;
    if constexpr (std::is_same_v<B, element::HexBlock>) {
      std::fill_n(block.stress.begin() + static_cast<std::ptrdiff_t>(6 * points * e), 6 * points,
                  0.0);
      if (!block.hourglass_state.empty())
        std::fill_n(block.hourglass_state.begin() + static_cast<std::ptrdiff_t>(12 * e), 12, 0.0);
    } else if constexpr (std::is_same_v<B, element::ShellBlock>) {
      std::fill_n(
          block.stress.begin() + static_cast<std::ptrdiff_t>(element::kShellStress * points * e),
          element::kShellStress * points, 0.0);
      std::fill_n(block.hourglass_state.begin() + static_cast<std::ptrdiff_t>(5 * e), 5, 0.0);
    } else {
      if (points > 0)
        std::fill_n(block.stress.begin() + static_cast<std::ptrdiff_t>(points * e), points, 0.0);
      std::fill_n(block.resultant.begin() + static_cast<std::ptrdiff_t>(6 * e), 6, 0.0);
    }
    for (int a = 0; a < npe; ++a) {
      const std::int32_t node = block.conn[static_cast<std::size_t>(npe) * e + a];
      if (node >= 0) --live_elements_[static_cast<std::size_t>(node)];
    }
  };
  auto own = [&](auto& block) { own_remaining_elements(block, distributed_); };
  std::size_t k = 0;
  while (k < failures.size()) {
    const ElementFailure& first = failures[k];
    std::size_t end = k;
    while (end < failures.size() && failures[end].family == first.family &&
           failures[end].block == first.block)
      ++end;
    const std::size_t b = static_cast<std::size_t>(first.block);
    for (std::size_t i = k; i < end; ++i) {
      if (first.family == 0)
        remove(state.hex_blocks[b], failures[i]);
      else if (first.family == 1)
        remove(state.shell_blocks[b], failures[i]);
      else
        remove(state.beam_blocks[b], failures[i]);
    }
    if (first.family == 0)
      own(state.hex_blocks[b]);
    else if (first.family == 1)
      own(state.shell_blocks[b]);
    else
      own(state.beam_blocks[b]);
    k = end;
  }
  remove_orphan_nodes(state, body_of, true);
  return static_cast<std::int64_t>(failures.size());
}

std::string pack_failures(const std::vector<ElementFailure>& failures) {
  std::string bytes;
  auto put = [&](const auto& value) {
    bytes.append(reinterpret_cast<const char*>(&value), sizeof(value));
  };
  for (const ElementFailure& f : failures) {
    put(f.family);
    put(f.block);
    put(f.element);
    put(f.internal_energy);
    put(static_cast<std::uint32_t>(f.criterion.size()));
    bytes += f.criterion;
  }
  return bytes;
}

void unpack_failures(const std::string& bytes, std::vector<ElementFailure>& out) {
  std::size_t at = 0;
  auto get = [&](auto& value) {
    std::memcpy(&value, bytes.data() + at, sizeof(value));
    at += sizeof(value);
  };
  while (at < bytes.size()) {
    ElementFailure f;
    get(f.family);
    get(f.block);
    get(f.element);
    get(f.internal_energy);
    std::uint32_t length = 0;
    get(length);
    f.criterion.assign(bytes.data() + at, length);
    at += length;
    out.push_back(std::move(f));
  }
}

void Erosion::remove_orphan_nodes(State& state, const std::vector<std::int32_t>* body_of,
                                  bool book) {
  NodalState& nodes = state.nodes;
  RotationalState& rot = state.rotations;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!erodible_node_[i] || live_elements_[i] > 0 || nodes.removed[i]) continue;
    if (body_of && !body_of->empty() && (*body_of)[i] >= 0) continue;  // moves with its body
    nodes.removed[i] = 1;
    ++ledger_.nodes;
    const double m = nodes.mass[i];
    const double v[3] = {nodes.v.x[i], nodes.v.y[i], nodes.v.z[i]};
    const double x[3] = {nodes.x.x[i], nodes.x.y[i], nodes.x.z[i]};
    const std::int32_t r = rot.index(static_cast<std::int32_t>(i));
    if (book) {
      ledger_.kinetic_energy += 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      for (int k = 0; k < 3; ++k) ledger_.momentum[k] += m * v[k];
      ledger_.angular_momentum[0] += m * (x[1] * v[2] - x[2] * v[1]);
      ledger_.angular_momentum[1] += m * (x[2] * v[0] - x[0] * v[2]);
      ledger_.angular_momentum[2] += m * (x[0] * v[1] - x[1] * v[0]);
      if (r >= 0) {
        const std::size_t ur = static_cast<std::size_t>(r);
        const double inertia = rot.inertia[ur];
        const double w[3] = {rot.w.x[ur], rot.w.y[ur], rot.w.z[ur]};
        ledger_.kinetic_energy += 0.5 * inertia * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        for (int k = 0; k < 3; ++k) ledger_.angular_momentum[k] += inertia * w[k];
      }
    }
    nodes.mass[i] = 0.0;
    nodes.v.x[i] = nodes.v.y[i] = nodes.v.z[i] = 0.0;
    nodes.a.x[i] = nodes.a.y[i] = nodes.a.z[i] = 0.0;
    if (r >= 0) {
      const std::size_t ur = static_cast<std::size_t>(r);
      rot.inertia[ur] = 0.0;
      rot.w.x[ur] = rot.w.y[ur] = rot.w.z[ur] = 0.0;
    }
  }
}

void Erosion::restore(State& state, const std::vector<std::int32_t>* body_of) {
  if (!enabled_) return;
  auto recount = [&](auto& block) {
    if (!block.erosion.enabled) return;
    block.erosion.count = 0;
    const int npe = nodes_per(block);
    for (std::size_t e = 0; e < block.size(); ++e) {
      if (!block.erosion.is_eroded(e)) continue;
      ++block.erosion.count;
      for (int a = 0; a < npe; ++a) {
        const std::int32_t node = block.conn[static_cast<std::size_t>(npe) * e + a];
        if (node >= 0) --live_elements_[static_cast<std::size_t>(node)];
      }
    }
    // On ranks the partition's elements were set up before the dump was read.
    own_remaining_elements(block, distributed_);
  };
  for (auto& b : state.hex_blocks) recount(b);
  for (auto& b : state.shell_blocks) recount(b);
  for (auto& b : state.beam_blocks) recount(b);
  const std::int64_t booked = ledger_.nodes;
  remove_orphan_nodes(state, body_of, false);
  ledger_.nodes = booked;  // the dump's count already has them
}

}  // namespace rf::solver
