// Translational springs and dampers (discrete_block.hpp for the force laws and conventions).
#include "element/discrete_block.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "model/error.hpp"
#include "model/error_context.hpp"

namespace rf::element {

namespace {

// f(d) of a piecewise linear curve, extrapolated linearly with the first and last segments (a
// spring keeps its end stiffness past the tabulated range instead of suddenly holding a
// constant force).
double curve_force(const DiscreteBlock& block, double d) {
  const auto& x = block.curve_elongation;
  const auto& f = block.curve_force;
  const std::size_t n = x.size();
  if (n == 1) return f[0];
  std::size_t k = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), d) - x.begin());
  k = std::clamp<std::size_t>(k, 1, n - 1);  // segment [k-1, k]
  const double slope = (f[k] - f[k - 1]) / (x[k] - x[k - 1]);
  return f[k - 1] + slope * (d - x[k - 1]);
}

// Integral of f from 0 to d (the same extrapolation), piecewise exact: the energy a nonlinear
// elastic spring stores.
double curve_integral(const DiscreteBlock& block, double d) {
  const auto& x = block.curve_elongation;
  // Trapezoids between the breakpoints that lie between 0 and d, in either direction.
  const double lo = std::min(0.0, d), hi = std::max(0.0, d);
  double a = lo, sum = 0.0;
  for (const double xk : x) {
    if (xk <= a) continue;
    if (xk >= hi) break;
    sum += 0.5 * (curve_force(block, a) + curve_force(block, xk)) * (xk - a);
    a = xk;
  }
  sum += 0.5 * (curve_force(block, a) + curve_force(block, hi)) * (hi - a);
  return d >= 0.0 ? sum : -sum;
}

double largest_slope(const DiscreteBlock& block) {
  double k = 0.0;
  for (std::size_t i = 1; i < block.curve_elongation.size(); ++i) {
    const double s = (block.curve_force[i] - block.curve_force[i - 1]) /
                     (block.curve_elongation[i] - block.curve_elongation[i - 1]);
    k = std::max(k, std::abs(s));
  }
  return k;
}

// Energy stored relative to the elongation d0 at time zero.
double stored_energy(const DiscreteBlock& block, double s, double d, double d0) {
  if (block.law == DiscreteLaw::kLinearSpring) return 0.5 * s * block.stiffness * (d * d - d0 * d0);
  if (block.law == DiscreteLaw::kNonlinearSpring) {
    return s * (curve_integral(block, d) - curve_integral(block, d0));
  }
  return 0.0;
}

}  // namespace

void initialize_discrete_block(DiscreteBlock& block, const NodalView& nodes,
                               const model::SourceLocation& where) {
  const std::size_t n = block.size();
  if (block.conn.size() != 2 * n || block.scale.size() != n || block.offset.size() != n) {
    throw InputError(model::context_of(where, "PID"),
                     fmt::format("discrete part {}: inconsistent element arrays", block.part_id));
  }
  if (block.law == DiscreteLaw::kNonlinearSpring) {
    const auto& x = block.curve_elongation;
    if (x.empty() || x.size() != block.curve_force.size()) {
      throw InputError(
          model::context_of(where, "LCD"),
          fmt::format("discrete part {}: the force curve has no points", block.part_id));
    }
    for (std::size_t i = 1; i < x.size(); ++i) {
      if (!(x[i] > x[i - 1])) {
        throw InputError(model::context_of(where, "LCD"),
                         fmt::format("discrete part {}: the force vs elongation curve must have "
                                     "strictly increasing elongations",
                                     block.part_id));
      }
    }
  }
  block.length0.assign(n, 0.0);
  block.inverse_mass.assign(n, 0.0);
  block.axial_force.assign(n, 0.0);
  block.force.assign(kDiscreteSlot * n, 0.0);
  block.spring_energy = 0.0;
  block.damper_energy = 0.0;
  block.preload_energy = 0.0;
  for (std::size_t e = 0; e < n; ++e) {
    block.preload_energy += stored_energy(block, block.scale[e], block.offset[e], 0.0);
  }
  for (std::size_t e = 0; e < n; ++e) {
    const std::int32_t a = block.conn[2 * e], b = block.conn[2 * e + 1];
    const double dx = nodes.x[b] - nodes.x[a], dy = nodes.y[b] - nodes.y[a],
                 dz = nodes.z[b] - nodes.z[a];
    block.length0[e] = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (!(block.length0[e] > 0.0)) {
      throw InputError(model::context_of(where, "N2"),
                       fmt::format("discrete element {}: nodes N1 and N2 coincide, so the line "
                                   "of action N1 -> N2 is undefined (orientation vectors, VID, "
                                   "are not supported: move the nodes apart)",
                                   block.element_id[e]));
    }
  }
}

KernelResult compute_discrete_forces(DiscreteBlock& block, const NodalView& nodes) {
  KernelResult result;
  const std::size_t n = block.size();
  // Few elements per model, and each writes only its own slot: a serial loop in element order
  // keeps the sums (energies) independent of the thread count.
  for (std::size_t e = 0; e < n; ++e) {
    const std::int32_t a = block.conn[2 * e], b = block.conn[2 * e + 1];
    const double dx = nodes.x[b] - nodes.x[a], dy = nodes.y[b] - nodes.y[a],
                 dz = nodes.z[b] - nodes.z[a];
    const double length = std::sqrt(dx * dx + dy * dy + dz * dz);
    double* f = block.force.data() + kDiscreteSlot * e;
    // A line of action needs two distinct points: a spring squeezed to zero length (or a
    // non-finite position) stops the run with the element named.
    if (!(length > 1e-12 * block.length0[e]) || !std::isfinite(length)) {
      if (!result.failed) {
        result.failed = true;
        result.failed_element = static_cast<std::int64_t>(e);
        result.failed_volume = length;
      }
      std::fill(f, f + kDiscreteSlot, 0.0);
      block.axial_force[e] = 0.0;
      continue;
    }
    const double nx = dx / length, ny = dy / length, nz = dz / length;
    const double s = block.scale[e];
    double axial = 0.0;
    if (block.law == DiscreteLaw::kViscousDamper) {
      const double rate = nx * (nodes.vx[b] - nodes.vx[a]) + ny * (nodes.vy[b] - nodes.vy[a]) +
                          nz * (nodes.vz[b] - nodes.vz[a]);
      axial = s * block.damping * rate;
    } else {
      const double d = length - block.length0[e] + block.offset[e];
      axial = block.law == DiscreteLaw::kLinearSpring ? s * block.stiffness * d
                                                      : s * curve_force(block, d);
    }
    block.axial_force[e] = axial;
    f[0] = -axial * nx;
    f[1] = -axial * ny;
    f[2] = -axial * nz;
    f[3] = axial * nx;
    f[4] = axial * ny;
    f[5] = axial * nz;
  }
  const KernelResult step = discrete_critical_timestep(block);
  result.min_dt = step.min_dt;
  result.min_dt_element = step.min_dt_element;
  return result;
}

KernelResult discrete_critical_timestep(const DiscreteBlock& block) {
  KernelResult result;
  const double k = block.law == DiscreteLaw::kLinearSpring      ? block.stiffness
                   : block.law == DiscreteLaw::kNonlinearSpring ? largest_slope(block)
                                                                : 0.0;
  for (std::size_t e = 0; e < block.size(); ++e) {
    const double inv_m = block.inverse_mass[e];
    const double s = std::abs(block.scale[e]);
    if (!(inv_m > 0.0) || !(s > 0.0)) continue;
    double dt = 1e300;
    if (block.law == DiscreteLaw::kViscousDamper) {
      dt = 2.0 / (s * block.damping * inv_m);
    } else if (k > 0.0) {
      dt = 2.0 / std::sqrt(s * k * inv_m);
    }
    if (dt < result.min_dt) {
      result.min_dt = dt;
      result.min_dt_element = static_cast<std::int64_t>(e);
    }
  }
  return result;
}

}  // namespace rf::element
