// Resolved parameters of the J2 (von Mises) plasticity models, as the stress update uses them.
// build_state fills them from the *MAT_ cards (curves resolved, units checked).
#pragma once

#include <vector>

namespace rf::material {

// How the yield stress depends on the strain rate.
enum class RateModel {
  kNone,
  kCowperSymonds,  // factor 1 + (rate / C)^(1/P)
  kScaleCurve,     // *MAT_024 LCSR: factor = curve(rate)
  kTable,          // *MAT_024 LCSS table: one hardening curve per strain rate (RateTable)
};

// *MAT_024 LCSS naming a *DEFINE_TABLE: hardening curves sigma_k(eps_p) at strain rates r_k.
// Between two rates the yield stress is interpolated linearly (in ln r when the table's first
// value is negative: its values are then natural logarithms of the rate); outside the range the
// first or last curve holds (LS-DYNA's manual, *MAT_024 LCSS). Each curve is extrapolated in
// eps_p with its end segments' slopes, like a single LCSS curve.
struct RateTable {
  std::vector<double> rates;  // increasing; ln(rate) if logarithmic
  bool logarithmic = false;
  std::vector<std::vector<double>> strain;  // per rate: the curve's plastic strains
  std::vector<std::vector<double>> stress;  // and yield stresses
};

struct PlasticParameters {
  // Hardening: sigma_y(eps_p) piecewise linear through (strain[i], stress[i]), i >= 2 points,
  // extrapolated beyond both ends with the end segments' slopes. A linear law (SIGY, ETAN)
  // is the two points (0, SIGY), (1, SIGY + Ep) with Ep = E ETAN / (E - ETAN).
  // These points are the ISOTROPIC part: the radius of the yield surface. *MAT_003 splits its
  // plastic modulus Ep = E ETAN / (E - ETAN) with BETA: isotropic BETA Ep (the curve is then
  // (0, SIGY), (1, SIGY + BETA Ep)) and kinematic (1 - BETA) Ep (Prager's rule, back stress).
  std::vector<double> strain;
  std::vector<double> stress;
  bool linear = true;              // two-point law: closed-form return (vectorised)
  double sigy = 0.0;               // sigma_y(0) of a linear law
  double isotropic_modulus = 0.0;  // slope of a linear law
  double kinematic_modulus = 0.0;  // (1 - BETA) Ep; 0 for *MAT_024
  RateModel rate_model = RateModel::kNone;
  double rate_c = 0.0;
  double rate_p = 0.0;
  std::vector<double> rate_curve_x;  // LCSR: strain rate -> yield scale factor (held at ends)
  std::vector<double> rate_curve_y;
  RateTable table;  // kTable only (strain/stress above then hold its first curve)
  // 0: scale the yield stress with the total effective strain rate sqrt(2/3 D:D); -1 (*MAT_024):
  // the same with the deviatoric rate sqrt(2/3 D':D'). 1: viscoplastic, the rate is the
  // effective plastic strain rate of the step (solved with the return).
  int vp = 0;
  // *MAT_024 VP 1 with C, P: sigma_y = sigma_s(eps_p) + SIGY (rate / C)^(1/P) (additive);
  // *MAT_003 VP 1: sigma_y = [1 + (rate / C)^(1/P)] (SIGY + beta Ep eps_p) (multiplicative).
  bool additive_overstress = false;
  double overstress_scale = 0.0;  // SIGY of the *MAT_024 card
  // Effective plastic strain at which the element is deleted (FS, FAIL). 0: never.
  double failure_strain = 0.0;
};

}  // namespace rf::material
