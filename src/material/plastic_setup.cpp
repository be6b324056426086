#include "material/plastic_setup.hpp"

#include <fmt/format.h>

#include <cmath>

#include "model/error_context.hpp"

namespace rf::material {

namespace {

using model::context_of;

// Points of a *DEFINE_CURVE with its scale factors and offsets applied (LS-DYNA:
// value(t) = SFO f(t / SFA - OFFA) + OFFO, so the point (a, o) sits at ((a + OFFA) SFA, SFO o +
// OFFO)).
void curve_points(const model::Curve& c, std::vector<double>& x, std::vector<double>& y) {
  x.clear();
  y.clear();
  for (std::size_t i = 0; i < c.abscissa.size(); ++i) {
    x.push_back((c.abscissa[i] + c.offa) * c.sfa);
    y.push_back(c.sfo * c.ordinate[i] + c.offo);
  }
}

const model::Curve& find_curve(const model::Model& model, model::Id id,
                               const model::SourceLocation& where, const char* field,
                               const char* what) {
  const auto it = model.curves.find(id);
  if (it == model.curves.end())
    throw InputError(
        context_of(where, field),
        fmt::format("{} {} is not a *DEFINE_CURVE of this deck ({}){}", field, id, what,
                    model.tables.count(id) ? "; it is a *DEFINE_TABLE, which only "
                                             "LCSS accepts"
                                           : ""));
  return it->second;
}

// Hardening points: strictly increasing strains, positive and non-decreasing stresses.
void check_hardening(const std::vector<double>& x, const std::vector<double>& y,
                     const model::SourceLocation& where, const char* field,
                     const std::string& source) {
  if (x.size() < 2)
    throw InputError(
        context_of(where, field),
        fmt::format("{}: a hardening law needs at least 2 points, got {}", source, x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(y[i] > 0.0))
      throw InputError(context_of(where, field),
                       fmt::format("{}: yield stress {} at plastic strain {} (point {}) must be "
                                   "positive",
                                   source, y[i], x[i], i + 1));
    if (x[i] < 0.0)
      throw InputError(context_of(where, field),
                       fmt::format("{}: plastic strain {} (point {}) must not be negative", source,
                                   x[i], i + 1));
    if (i > 0 && !(x[i] > x[i - 1]))
      throw InputError(context_of(where, field),
                       fmt::format("{}: plastic strains must increase (point {}: {} after {})",
                                   source, i + 1, x[i], x[i - 1]));
    if (i > 0 && y[i] < y[i - 1])
      throw InputError(context_of(where, field),
                       fmt::format("{}: yield stress decreases from {} to {} at point {} "
                                   "(softening is not supported)",
                                   source, y[i - 1], y[i], i + 1));
  }
}

// LCSS naming a *DEFINE_TABLE: one hardening curve per strain rate (RateTable).
void read_rate_table(const model::Model& model, const model::Table& t,
                     const model::SourceLocation& where, PlasticParameters& p) {
  const std::string source = fmt::format("table {}", t.id);
  if (t.curves.size() != t.values.size())
    throw InputError(
        context_of(t.where, "TBID"),
        fmt::format("{} has {} values but {} curves", source, t.values.size(), t.curves.size()));
  RateTable& r = p.table;
  for (std::size_t i = 0; i < t.values.size(); ++i) {
    // Scaled like a curve's abscissa: (value + OFFA) SFA.
    r.rates.push_back((t.values[i] + t.offa) * t.sfa);
    const auto it = model.curves.find(t.curves[i]);
    if (it == model.curves.end())
      throw InputError(context_of(t.where, "LCID"),
                       fmt::format("{}: curve {} (value {}) is not a *DEFINE_CURVE of this deck",
                                   source, t.curves[i], t.values[i]));
    if (it->second.function)
      throw InputError(context_of(it->second.where, "LCID"),
                       fmt::format("{}: curve {} is a *DEFINE_CURVE_FUNCTION; a hardening curve "
                                   "needs points",
                                   source, t.curves[i]));
    std::vector<double> x, y;
    curve_points(it->second, x, y);
    check_hardening(x, y, where, "LCSS", fmt::format("{}, curve {}", source, t.curves[i]));
    r.strain.push_back(std::move(x));
    r.stress.push_back(std::move(y));
  }
  for (std::size_t i = 1; i < r.rates.size(); ++i)
    if (!(r.rates[i] > r.rates[i - 1]))
      throw InputError(context_of(t.where, "SFA"),
                       fmt::format("{}: the scaled strain rates must increase ({} after {})",
                                   source, r.rates[i], r.rates[i - 1]));
  // LS-DYNA: a negative first value means every value is the natural logarithm of the rate.
  r.logarithmic = r.rates.front() < 0.0;
}

void set_linear(PlasticParameters& p, double sigy, double iso, double kin) {
  p.linear = true;
  p.sigy = sigy;
  p.isotropic_modulus = iso;
  p.kinematic_modulus = kin;
  p.strain = {0.0, 1.0};
  p.stress = {sigy, sigy + iso};
}

}  // namespace

PlasticParameters make_plastic_parameters(const model::Model& model, const model::Material& mat) {
  const model::PlasticCard& c = mat.plastic;
  PlasticParameters p;
  p.vp = c.vp;
  p.failure_strain = c.fail;
  if (mat.kind == model::MaterialKind::PlasticKinematic) {
    const double ep = mat.e * c.etan / (mat.e - c.etan);
    set_linear(p, c.sigy, c.beta * ep, (1.0 - c.beta) * ep);
    if (c.c > 0.0 && c.p > 0.0) {
      p.rate_model = RateModel::kCowperSymonds;
      p.rate_c = c.c;
      p.rate_p = c.p;
    }
    return p;
  }

  // *MAT_024: LCSS curve, else the EPS/ES table, else SIGY/ETAN.
  bool table = false;
  for (double s : c.es) table |= s != 0.0;
  const bool lcss_table = c.lcss > 0 && model.tables.count(c.lcss) > 0;
  if (lcss_table) {
    read_rate_table(model, model.tables.at(c.lcss), c.card2, p);
    // The first curve also serves as the static law (nothing evaluates it with a table).
    p.strain = p.table.strain.front();
    p.stress = p.table.stress.front();
    p.linear = false;
  } else if (c.lcss > 0) {
    const model::Curve& curve =
        find_curve(model, c.lcss, c.card2, "LCSS", "stress against effective plastic strain");
    curve_points(curve, p.strain, p.stress);
    check_hardening(p.strain, p.stress, c.card2, "LCSS", fmt::format("curve {}", c.lcss));
    p.linear = false;
  } else if (table) {
    for (std::size_t i = 0; i < c.eps.size(); ++i) {
      if (i > 0 && !(c.eps[i] > c.eps[i - 1])) {
        // The table ends at the first blank (non-increasing) strain; later stresses must be blank.
        for (std::size_t j = i; j < c.eps.size(); ++j)
          if (c.es[j] != 0.0 || c.eps[j] != 0.0)
            throw InputError(context_of(c.card3, "EPS"),
                             fmt::format("EPS{} = {} does not increase from EPS{} = {}", i + 1,
                                         c.eps[i], i, c.eps[i - 1]));
        break;
      }
      p.strain.push_back(c.eps[i]);
      p.stress.push_back(c.es[i]);
    }
    check_hardening(p.strain, p.stress, c.card3, "ES", "EPS/ES table");
    p.linear = false;
  } else {
    if (!(c.sigy > 0.0))
      throw InputError(context_of(mat.where, "SIGY"),
                       "give SIGY > 0 (with ETAN), the EPS/ES table or an LCSS curve");
    set_linear(p, c.sigy, mat.e * c.etan / (mat.e - c.etan), 0.0);
  }
  // A two-point law from zero strain is a straight line: keep the vectorised closed form.
  if (!lcss_table && !p.linear && p.strain.size() == 2 && p.strain[0] == 0.0) {
    const double s0 = p.stress[0];
    set_linear(p, s0, (p.stress[1] - s0) / p.strain[1], 0.0);
  }

  if (lcss_table) {
    // LS-DYNA ignores C, P and LCSR when LCSS is a table; say so rather than drop them silently
    // by refusing a card that gives both.
    if (c.lcsr > 0 || c.c > 0.0 || c.p > 0.0)
      throw InputError(context_of(c.card2, c.lcsr > 0 ? "LCSR" : (c.c > 0.0 ? "C" : "P")),
                       fmt::format("LCSS {} is a *DEFINE_TABLE of curves by strain rate, which "
                                   "already holds the rate effect; C, P and LCSR must be blank",
                                   c.lcss));
    p.rate_model = RateModel::kTable;
  } else if (c.lcsr > 0) {
    const model::Curve& curve =
        find_curve(model, c.lcsr, c.card2, "LCSR", "yield scale factor against strain rate");
    curve_points(curve, p.rate_curve_x, p.rate_curve_y);
    for (std::size_t i = 0; i < p.rate_curve_x.size(); ++i) {
      if (!(p.rate_curve_y[i] > 0.0))
        throw InputError(context_of(c.card2, "LCSR"),
                         fmt::format("curve {}: scale factor {} at strain rate {} must be positive",
                                     c.lcsr, p.rate_curve_y[i], p.rate_curve_x[i]));
      if (i > 0 && !(p.rate_curve_x[i] > p.rate_curve_x[i - 1]))
        throw InputError(context_of(c.card2, "LCSR"),
                         fmt::format("curve {}: strain rates must increase", c.lcsr));
    }
    p.rate_model = RateModel::kScaleCurve;
  } else if (c.c > 0.0 || c.p > 0.0) {
    if (!(c.c > 0.0 && c.p > 0.0))
      throw InputError(context_of(c.card2, c.c > 0.0 ? "P" : "C"),
                       "Cowper-Symonds rate effects need both C and P (or neither)");
    p.rate_model = RateModel::kCowperSymonds;
    p.rate_c = c.c;
    p.rate_p = c.p;
    if (c.vp == 1) {
      // LS-DYNA's VP 1 for 024: sigma_y = sigma_s(eps_p) + SIGY (rate / C)^(1/P).
      p.additive_overstress = true;
      if (!(c.sigy > 0.0))
        throw InputError(context_of(mat.where, "SIGY"),
                         "VP 1 with C and P scales the viscoplastic overstress by SIGY: give "
                         "SIGY > 0");
      p.overstress_scale = c.sigy;
    }
  }
  return p;
}

BarlatParameters make_barlat_parameters(const model::Model& model, const model::Material& mat) {
  const model::BarlatCard& b = mat.barlat;
  BarlatParameters p;
  p.m = b.m;
  if (b.pb > 0.0) {
    p.a = b.r00;
    p.c = b.r45;
    p.h = b.r90;
    p.p = b.pb;
  } else {
    // Barlat and Lian 1989: a, c, h from the R values in the rolling and transverse directions.
    const double r0 = b.r00 / (1.0 + b.r00), r90 = b.r90 / (1.0 + b.r90);
    p.c = 2.0 * std::sqrt(r0 * r90);
    p.a = 2.0 - p.c;
    p.h = std::sqrt(r0 / r90);
    // p: R45 grows monotonically with p; bisection on log p over [1e-3, 1e3].
    double lo = std::log(1e-3), hi = std::log(1e3);
    auto r45 = [&](double log_p) {
      BarlatParameters q = p;
      q.p = std::exp(log_p);
      return barlat::r45_of(q);
    };
    const double r_lo = r45(lo), r_hi = r45(hi);
    if (!(b.r45 > r_lo && b.r45 < r_hi))
      throw InputError(context_of(b.card2, "R45"),
                       fmt::format("no coefficient p of the Barlat 1989 yield function gives R45 "
                                   "= {} with R00 = {}, R90 = {}, M = {} (reachable: {:.4g} to "
                                   "{:.4g})",
                                   b.r45, b.r00, b.r90, b.m, r_lo, r_hi));
    for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
      const double mid = 0.5 * (lo + hi);
      (r45(mid) < b.r45 ? lo : hi) = mid;
    }
    p.p = std::exp(0.5 * (lo + hi));
  }
  switch (b.hr) {
    case 1:
      p.hardening = BarlatHardening::kLinear;
      p.sigy = b.p2;
      p.modulus = mat.e * b.p1 / (mat.e - b.p1);
      break;
    case 2: {
      // sigma_y = k (e0 + eps_p)^n. E0 > 0: e0 = E0; else SPI: 0 -> the elastic line meets the
      // power law, E e0 = k e0^n, e0 = (E / k)^(1 / (n - 1)); SPI <= 0.02 -> e0 = SPI; SPI > 0.02
      // -> SPI is the initial yield stress, e0 = (SPI / k)^(1 / n) (LS-DYNA manual, *MAT_036).
      p.hardening = BarlatHardening::kPower;
      p.k = b.p1;
      p.n = b.p2;
      if (b.e0 > 0.0)
        p.e0 = b.e0;
      else if (b.spi == 0.0)
        p.e0 = std::pow(mat.e / p.k, 1.0 / (p.n - 1.0));
      else if (b.spi <= 0.02)
        p.e0 = b.spi;
      else
        p.e0 = std::pow(b.spi / p.k, 1.0 / p.n);
      if (!(p.e0 > 0.0) || !std::isfinite(p.e0))
        throw InputError(
            context_of(b.card2, "E0"),
            fmt::format("the power law's strain offset e0 = {} is not positive", p.e0));
      break;
    }
    default: {
      p.hardening = BarlatHardening::kCurve;
      const model::Curve& curve = find_curve(model, b.lcid, b.card2, "LCID",
                                             "yield stress against effective plastic strain");
      curve_points(curve, p.strain, p.stress);
      check_hardening(p.strain, p.stress, b.card2, "LCID", fmt::format("curve {}", b.lcid));
      break;
    }
  }
  const double deg = std::acos(-1.0) / 180.0;
  switch (b.aopt) {
    case 2:
      p.axes = BarlatAxes::kVectorA;
      p.vector = b.a;
      break;
    case 3:
      p.axes = BarlatAxes::kVectorV;
      p.vector = b.v;
      p.beta = b.beta * deg;
      break;
    default:
      p.axes = BarlatAxes::kElement;
      p.beta = b.beta * deg;
      break;
  }
  return p;
}

}  // namespace rf::material
