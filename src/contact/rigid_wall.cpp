#include "contact/rigid_wall.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "model/error.hpp"
#include "model/error_context.hpp"

namespace rf::contact {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector2d;
using Eigen::Vector3d;

Vector3d vec(const std::array<double, 3>& a) {
  return {a[0], a[1], a[2]};
}

Vector3d node_position(const solver::NodalState& nodes, std::int32_t i) {
  return {nodes.x.x[i], nodes.x.y[i], nodes.x.z[i]};
}

Matrix3d cross_matrix(const Vector3d& r) {
  Matrix3d m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}

// Inside the rectangle of a finite wall (in-plane coordinates do not change as a moving wall
// moves along its normal).
bool within_extent(const RigidWall& wall, const Vector3d& relative) {
  if (!wall.finite) return true;
  const double a = relative.dot(wall.edge_l);
  const double b = relative.dot(wall.edge_m);
  return (wall.length_l == 0.0 || (a >= 0.0 && a <= wall.length_l)) &&
         (wall.length_m == 0.0 || (b >= 0.0 && b <= wall.length_m));
}

// Where a wall's reference point (the tail XT YT ZT) is now.
Vector3d wall_position(const RigidWall& wall) {
  return wall.origin + wall.displacement * wall.motion_direction;
}

// The point of a wall's surface nearest to a node: signed distance (> 0 on the side the node
// is kept on), the unit normal there (towards that side) and whether the node is over the
// wall's extent (a finite plane's rectangle, a finite cylinder's length; nodes beside it are
// left alone, as beside a *RIGIDWALL_PLANAR_FINITE).
struct SurfacePoint {
  double distance = 0.0;
  Vector3d normal = Vector3d::UnitZ();
  bool over = true;
};

// Prism: the box 0 <= a <= LENL, 0 <= b <= LENM, -LENP <= c <= 0 in the frame (l, m, n) of
// its face (LENL or LENM 0: unbounded that way). Outside, the nearest point is the clamped
// one (a face, an edge or a corner: an edge or corner pushes along the line from it to the
// node); a node inside is pushed out through the nearest face.
SurfacePoint prism_point(const RigidWall& wall, const Vector3d& r) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const Vector3d axes[3] = {wall.edge_l, wall.edge_m, wall.normal};
  const double lo[3] = {wall.length_l > 0.0 ? 0.0 : -kInf, wall.length_m > 0.0 ? 0.0 : -kInf,
                        -wall.depth};
  const double hi[3] = {wall.length_l > 0.0 ? wall.length_l : kInf,
                        wall.length_m > 0.0 ? wall.length_m : kInf, 0.0};
  double p[3];
  Vector3d q = Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    p[k] = r.dot(axes[k]);
    q += (p[k] - std::clamp(p[k], lo[k], hi[k])) * axes[k];
  }
  const double outside = q.norm();
  if (outside > 0.0) return {outside, q / outside, true};
  double depth = kInf;
  Vector3d normal = wall.normal;
  for (int k = 0; k < 3; ++k) {
    if (hi[k] - p[k] < depth) depth = hi[k] - p[k], normal = axes[k];
    if (p[k] - lo[k] < depth) depth = p[k] - lo[k], normal = -axes[k];
  }
  return {-depth, normal, true};
}

SurfacePoint surface_point(const RigidWall& wall, const Vector3d& position, const Vector3d& x,
                           bool inside) {
  const Vector3d r = x - position;
  switch (wall.shape) {
    case WallShape::Plane:
      return {r.dot(wall.normal), wall.normal, within_extent(wall, r)};
    case WallShape::Prism:
      return prism_point(wall, r);
    case WallShape::Cylinder:
    case WallShape::Sphere: {
      const bool cylinder = wall.shape == WallShape::Cylinder;
      const double h = cylinder ? r.dot(wall.normal) : 0.0;
      const Vector3d radial = r - h * wall.normal;
      const double rho = radial.norm();
      // On the axis (or at the centre) any direction normal to it serves.
      const Vector3d e = rho > 0.0 ? Vector3d(radial / rho) : wall.edge_l;
      SurfacePoint s;
      s.over = !cylinder || wall.length == 0.0 || (h >= 0.0 && h <= wall.length);
      s.distance = inside ? wall.radius - rho : rho - wall.radius;
      s.normal = inside ? -e : e;
      return s;
    }
  }
  return {};
}

// Translations of node i held by an SPC or a prescribed motion: the wall leaves them alone
// (the constraint's reaction takes the wall force's share along them).
std::vector<std::uint8_t> held_axes(const solver::Boundary& boundary, std::size_t node_count) {
  std::vector<std::uint8_t> held(node_count, 0);
  for (std::size_t i = 0; i < node_count && i < boundary.fixed.size(); ++i) {
    held[i] = boundary.fixed[i];
  }
  for (const auto& p : boundary.prescribed) held[p.node] |= static_cast<std::uint8_t>(1u << p.axis);
  return held;
}

// The motion a rigid body would have at n+1/2 without the walls of this cycle: the momentum
// update advance_rigid_bodies will make from the same forces (nodal f_ext - f_int, rigid-body
// loads and *LOAD_BODY at t^n). Constraints and prescribed motion of the body are not
// anticipated (docs/theory.md section 6).
void predict_body(BodyMotion& motion, const solver::RigidBody& body, std::int32_t body_index,
                  const solver::RigidSystem& rigid, const solver::Boundary& boundary, double t_n,
                  double dt_avg, const solver::State& state) {
  const solver::NodalState& nodes = state.nodes;
  const rigid::RigidBodyState& s = body.state;
  rigid::ForceAndTorque ft = rigid::gather_force_and_torque(
      s.centre, body.nodes, nodes.f_ext.x.data(), nodes.f_ext.y.data(), nodes.f_ext.z.data(),
      nodes.x.x.data(), nodes.x.y.data(), nodes.x.z.data());
  ft -= rigid::gather_force_and_torque(s.centre, body.nodes, nodes.f_int.x.data(),
                                       nodes.f_int.y.data(), nodes.f_int.z.data(), nodes.x.x.data(),
                                       nodes.x.y.data(), nodes.x.z.data());
  for (const auto& load : rigid.loads) {
    if (load.body != body_index) continue;
    (load.moment ? ft.torque : ft.force)[load.axis] += load.value(t_n);
  }
  for (const auto& base : boundary.body_accelerations) {
    ft.force[base.axis] -= s.mass * base.value(t_n);
  }
  motion.inverse_mass = 1.0 / s.mass;
  motion.centre = s.centre;
  motion.velocity = s.velocity + dt_avg * motion.inverse_mass * ft.force;
  motion.angular_momentum = s.angular_momentum + dt_avg * ft.torque;
  const Vector3d inverse_moments = s.principal_inertia.cwiseInverse();
  motion.inverse_inertia = s.rotation * inverse_moments.asDiagonal() * s.rotation.transpose();
}

// Coulomb friction on the tangential velocity u_t of a deformable node that received the
// normal impulse `normal_impulse`: stick if the impulse m |u_t| that stops it is within
// mu * normal_impulse (always for FRIC = 1), else slide with the tangential impulse at the limit.
Vector3d friction_velocity_change(const RigidWall& wall, const Vector3d& tangential, double mass,
                                  double normal_impulse) {
  const double speed = tangential.norm();
  if (!(speed > 0.0)) return Vector3d::Zero();
  if (wall.no_sliding || mass * speed <= wall.friction * normal_impulse) return -tangential;
  return -tangential * (wall.friction * normal_impulse / (mass * speed));
}

// Sequential impulses (projected Gauss-Seidel) on the contacts [begin, end) of one rigid body:
// non-negative normal impulses with zero normal gap rate where positive, tangential impulses
// inside the Coulomb disc. Converges to the solution of the contact problem of the body.
// `wall_velocity` and `wall_inverse_mass` couple a moving wall (0 for a fixed one).
void solve_body_contacts(const RigidWall& wall, BodyMotion& motion, BodyContact* begin,
                         BodyContact* end, double& wall_velocity, double wall_inverse_mass,
                         const Vector3d& wall_motion) {
  Eigen::Matrix<double, 3, 2> tangents;
  const bool friction = wall.no_sliding || wall.friction > 0.0;
  for (BodyContact* c = begin; c != end; ++c) {
    const Vector3d& n = c->normal;
    tangents.col(0) = c->tangent_l;
    tangents.col(1) = c->tangent_m;
    const Matrix3d r = cross_matrix(c->arm);
    c->response = motion.inverse_mass * Matrix3d::Identity() - r * motion.inverse_inertia * r;
    c->normal_inverse_mass = n.dot(c->response * n) + wall_inverse_mass;
    // Friction steps use one scalar for both tangent directions, the stiffest response (the
    // largest eigenvalue of T^T K T): then the projected impulse of a sliding contact points
    // against its slip, as Coulomb's law of maximum dissipation requires (a matrix step
    // projected on the disc would tilt it by the anisotropy of K), and no step overshoots.
    const Eigen::Matrix2d k_tt = tangents.transpose() * c->response * tangents;
    const double mean = 0.5 * (k_tt(0, 0) + k_tt(1, 1));
    const double half_gap = 0.5 * (k_tt(0, 0) - k_tt(1, 1));
    c->tangent_inverse_mass = mean + std::sqrt(half_gap * half_gap + k_tt(0, 1) * k_tt(0, 1));
    c->normal_impulse = 0.0;
    c->tangent_impulse.setZero();
  }
  auto apply = [&](const BodyContact& c, const Vector3d& impulse) {
    motion.velocity += motion.inverse_mass * impulse;
    motion.angular_momentum += c.arm.cross(impulse);
  };
  constexpr int kMaxSweeps = 200;
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    double change = 0.0, largest = 0.0;
    for (BodyContact* c = begin; c != end; ++c) {
      const Vector3d& n = c->normal;
      tangents.col(0) = c->tangent_l;
      tangents.col(1) = c->tangent_m;
      Vector3d w = motion.inverse_inertia * motion.angular_momentum;
      Vector3d u = motion.velocity + w.cross(c->arm);
      // A wall moved by the nodes (_MOVING) has one normal and the velocity solved here; a
      // fixed or prescribed one moves at c->wall_speed along this contact's normal.
      const double wall_speed = wall.moving ? wall_velocity : c->wall_speed;
      const double gap_rate = u.dot(n) - wall_speed + c->gap_rate;
      const double previous = c->normal_impulse;
      c->normal_impulse = std::max(0.0, previous - gap_rate / c->normal_inverse_mass);
      const double dn = c->normal_impulse - previous;
      if (dn != 0.0) {
        apply(*c, dn * n);
        wall_velocity -= wall_inverse_mass * dn;
      }
      change = std::max(change, std::abs(dn));
      largest = std::max(largest, c->normal_impulse);
      if (!friction) continue;
      w = motion.inverse_inertia * motion.angular_momentum;
      u = motion.velocity + w.cross(c->arm);
      const Vector2d slip = tangents.transpose() * (u - wall_motion);
      const Vector2d before = c->tangent_impulse;
      Vector2d wanted = before - slip / c->tangent_inverse_mass;
      const double limit = c->normal_impulse > 0.0
                               ? (wall.no_sliding ? std::numeric_limits<double>::infinity()
                                                  : wall.friction * c->normal_impulse)
                               : 0.0;
      const double magnitude = wanted.norm();
      if (magnitude > limit) wanted *= limit / magnitude;
      c->tangent_impulse = wanted;
      const Vector2d dt_impulse = wanted - before;
      if (dt_impulse.squaredNorm() > 0.0) apply(*c, tangents * dt_impulse);
      change = std::max(change, dt_impulse.norm());
      largest = std::max(largest, wanted.norm());
    }
    if (change <= 1e-12 * largest) break;
  }
}

}  // namespace

RigidWallSystem build_rigid_walls(const model::Model& model, const solver::NodeIndex& node_index,
                                  const solver::State& state, const solver::Boundary& boundary,
                                  std::vector<model::Warning>& warnings) {
  RigidWallSystem system;
  if (model.rigid_walls.empty()) return system;
  const solver::NodalState& nodes = state.nodes;
  const std::size_t n = nodes.size();
  // Round-off scale of the model: nodes this close behind a wall count as on it.
  Vector3d low = Vector3d::Constant(std::numeric_limits<double>::max());
  Vector3d high = -low;
  for (std::size_t i = 0; i < n; ++i) {
    const Vector3d x(nodes.x0.x[i], nodes.x0.y[i], nodes.x0.z[i]);
    low = low.cwiseMin(x);
    high = high.cwiseMax(x);
  }
  const double tolerance = n > 0 ? 1e-9 * (high - low).norm() : 0.0;
  const std::vector<std::uint8_t> held = held_axes(boundary, n);
  std::size_t most_tracked = 0;

  for (const model::RigidWall& in : model.rigid_walls) {
    RigidWall wall;
    wall.number = in.number;
    wall.id = in.id != 0 ? in.id : in.number;
    wall.title = in.title;
    wall.where = in.where;
    wall.origin = vec(in.tail);
    const Vector3d axis = vec(in.head) - vec(in.tail);
    // A sphere needs no direction (its XH YH ZH may repeat the centre).
    wall.normal = axis.norm() > 0.0 ? Vector3d(axis.normalized()) : Vector3d::UnitZ();
    const Vector3d& normal = wall.normal;
    if (in.finite) {
      const Vector3d edge = vec(in.edge_head) - vec(in.tail);
      wall.edge_l = (edge - edge.dot(normal) * normal).normalized();
      wall.finite = in.lenl > 0.0 || in.lenm > 0.0;
      wall.length_l = in.lenl;
      wall.length_m = in.lenm;
    } else {
      // Any in-plane pair: the tangent basis of the friction solve.
      const Vector3d axis = std::abs(normal.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY();
      wall.edge_l = (axis - axis.dot(normal) * normal).normalized();
    }
    wall.edge_m = normal.cross(wall.edge_l);
    wall.no_sliding = in.fric == 1.0;
    wall.friction = wall.no_sliding ? 0.0 : in.fric;
    wall.birth = in.birth;
    wall.death = in.death;
    wall.moving = in.moving;
    wall.mass = in.mass;
    wall.velocity = wall.velocity_before = in.moving ? in.v0 : 0.0;
    using InShape = model::RigidWall::Shape;
    wall.geometric = in.shape != InShape::Planar;
    wall.shape = in.shape == InShape::Prism      ? WallShape::Prism
                 : in.shape == InShape::Cylinder ? WallShape::Cylinder
                 : in.shape == InShape::Sphere   ? WallShape::Sphere
                                                 : WallShape::Plane;
    wall.depth = in.lenp;
    wall.radius = in.radius;
    wall.length = in.lencyl;
    wall.motion_direction = normal;
    if (in.motion) {
      wall.prescribed = true;
      wall.prescribed_displacement = in.motion_opt == 1;
      wall.motion_direction = vec(in.motion_direction).normalized();
      // The curve's abscissa counts from BIRTH (LS-DYNA manual, BIRTH of *RIGIDWALL_GEOMETRIC).
      wall.motion = solver::make_time_function(model, in.motion_lcid, 0, 1.0, in.birth, in.where);
    }
    const bool closed = wall.shape == WallShape::Cylinder || wall.shape == WallShape::Sphere;

    // The reader checks these references; models built in code get the same message.
    auto node_set = [&](model::Id sid, const char* field) -> const model::NodeSet& {
      const auto it = model.node_sets.find(sid);
      if (it == model.node_sets.end()) {
        throw InputError(model::context_of(in.where, field),
                         fmt::format("node set {} is not defined", sid));
      }
      return it->second;
    };
    std::vector<char> take(n, in.nsid == 0 ? 1 : 0);
    if (in.nsid != 0) {
      for (const model::Id id : node_set(in.nsid, "NSID").nodes) {
        take[node_index.at(id, in.where, "NSID")] = 1;
      }
    }
    if (in.nsidex != 0) {
      for (const model::Id id : node_set(in.nsidex, "NSIDEX").nodes) {
        take[node_index.at(id, in.where, "NSIDEX")] = 0;
      }
    }
    const model::Box* box = nullptr;
    if (in.boxid != 0) {
      const auto it = model.boxes.find(in.boxid);
      if (it == model.boxes.end()) {
        throw InputError(model::context_of(in.where, "BOXID"),
                         fmt::format("box {} is not defined (*DEFINE_BOX)", in.boxid));
      }
      box = &it->second;
    }
    std::int64_t behind = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (!take[i]) continue;
      const Vector3d x(nodes.x0.x[i], nodes.x0.y[i], nodes.x0.z[i]);
      if (box) {
        bool inside = true;
        for (int k = 0; k < 3; ++k) inside &= x[k] >= box->min[k] && x[k] <= box->max[k];
        if (!inside) continue;
      }
      // A cylinder keeps nodes outside (inside with _INTERIOR); a sphere keeps each node on
      // the side it starts on.
      const bool inside = wall.shape == WallShape::Sphere
                              ? (x - wall.origin).norm() < wall.radius
                              : wall.shape == WallShape::Cylinder && in.interior;
      const double distance = surface_point(wall, wall.origin, x, inside).distance;
      // OFFSET (manual): only nodes within this normal distance of the wall are tracked.
      if (in.offset > 0.0 && std::abs(distance) > in.offset) continue;
      const bool front = distance >= -tolerance;
      if (!front) ++behind;
      wall.nodes.push_back(static_cast<std::int32_t>(i));
      wall.locked_axes.push_back(held[i]);
      wall.in_front.push_back(front ? 1 : 0);
      if (closed) wall.kept_inside.push_back(inside ? 1 : 0);
    }
    if (in.force_segments != 0) {
      const auto it = model.segment_sets.find(in.force_segments);
      if (it == model.segment_sets.end()) {
        throw InputError(model::context_of(in.where, "SSID"),
                         fmt::format("segment set {} is not defined", in.force_segments));
      }
      wall.segment_nodes.assign(n, 0);
      for (const auto& segment : it->second.segments) {
        for (const model::Id id : segment) {
          if (id != 0) wall.segment_nodes[node_index.at(id, in.where, "SSID")] = 1;
        }
      }
    }
    wall.contacts.reserve(wall.nodes.size());
    most_tracked = std::max(most_tracked, wall.nodes.size());
    if (wall.nodes.empty()) {
      warnings.push_back({in.where, fmt::format("rigid wall {} tracks no node (check NSID, "
                                                "NSIDEX, BOXID and OFFSET)",
                                                wall.id)});
    } else if (behind > 0) {
      const char* side =
          wall.shape == WallShape::Prism ? "inside the prism"
          : wall.shape == WallShape::Cylinder
              ? (in.interior ? "outside the cylinder (_INTERIOR)" : "inside the cylinder")
              : "behind the wall (opposite to its normal XT->XH)";
      warnings.push_back({in.where, fmt::format("rigid wall {}: {} of its {} tracked nodes start "
                                                "{}; it acts on them only once they are on the "
                                                "side it keeps nodes on",
                                                wall.id, behind, wall.nodes.size(), side)});
    }
    system.walls.push_back(std::move(wall));
  }
  system.tolerance = tolerance;
  system.candidates.reserve(most_tracked);
  system.body_contacts.reserve(most_tracked);
  return system;
}

void apply_rigid_walls(RigidWallSystem& system, const solver::RigidSystem& rigid,
                       const solver::Boundary& boundary, double t_n, double dt_avg, double dt,
                       double dt_previous, solver::State& state) {
  if (system.walls.empty()) return;
  ++system.cycle_stamp;
  solver::NodalState& nodes = state.nodes;
  if (system.body_motion.size() < rigid.bodies.size()) {
    system.body_motion.resize(rigid.bodies.size());  // once (or when switching adds bodies)
  }
  const std::int32_t* body_of = rigid.empty() ? nullptr : rigid.body_of_node.data();

  for (RigidWall& wall : system.walls) {
    if (wall.moving || wall.prescribed) {
      wall.displacement += dt_previous * wall.velocity;  // s^n = s^{n-1} + dt V^{n-1/2}
      wall.velocity_before = wall.velocity;
    }
    if (wall.prescribed) {
      // V^{n+1/2}: the curve's velocity at mid-step, or the one that lands the wall on the
      // curve's displacement at t^{n+1}; at rest before BIRTH and after DEATH.
      double v = 0.0;
      if (dt > 0.0 && t_n >= wall.birth && t_n <= wall.death) {
        v = wall.prescribed_displacement ? (wall.motion(t_n + dt) - wall.displacement) / dt
                                         : wall.motion(t_n + 0.5 * dt);
      }
      wall.velocity = v;
    }
    wall.force.setZero();
    wall.segment_force.setZero();
    wall.normal_force = 0.0;
    wall.contacts.clear();
    const Vector3d position = wall_position(wall);
    const bool closed = !wall.kept_inside.empty();
    auto surface = [&](std::size_t k, std::int32_t i) {
      return surface_point(wall, position, node_position(nodes, i),
                           closed && wall.kept_inside[k] != 0);
    };
    const bool active =
        wall.active && t_n >= wall.birth && t_n <= wall.death && dt > 0.0 && dt_avg > 0.0;
    if (!active) {
      // Keep track of which side the nodes are on, so that a wall switched on later leaves
      // alone the nodes that went behind it meanwhile.
      for (std::size_t k = 0; k < wall.nodes.size(); ++k) {
        wall.in_front[k] = surface(k, wall.nodes[k]).distance >= -system.tolerance ? 1 : 0;
      }
      continue;
    }
    // The wall's velocity: a _MOVING wall's normal speed before the nodes push it, else the
    // prescribed translation (zero for a fixed wall).
    const double predicted_wall_velocity = wall.velocity_before;  // nothing but nodes push it
    const Vector3d wall_motion =
        wall.prescribed ? Vector3d(wall.velocity * wall.motion_direction) : Vector3d::Zero();
    const double wall_inverse_mass = wall.moving ? 1.0 / wall.mass : 0.0;
    const double inv_dt = 1.0 / dt;
    system.candidates.clear();
    system.body_contacts.clear();

    // Which nodes would end behind the wall: deformable ones as candidates, rigid-body ones
    // (with their neighbours in reach) for their body's contact solve.
    for (std::size_t k = 0; k < wall.nodes.size(); ++k) {
      const std::int32_t i = wall.nodes[k];
      const SurfacePoint sp = surface(k, i);
      const double d = sp.distance;
      const Vector3d& n = sp.normal;
      const bool inside = sp.over;
      if (d >= 0.0) {
        wall.in_front[k] = 1;
      } else if (!inside) {
        wall.in_front[k] = 0;  // went behind the plane beside the wall
      }
      if (!wall.in_front[k] || !inside) continue;
      const double wall_speed = wall.moving ? predicted_wall_velocity : wall_motion.dot(n);
      const std::int32_t b = body_of ? body_of[i] : -1;
      if (b >= 0) {
        BodyMotion& motion = system.body_motion[b];
        if (motion.stamp != system.cycle_stamp) {
          predict_body(motion, rigid.bodies[b], b, rigid, boundary, t_n, dt_avg, state);
          motion.stamp = system.cycle_stamp;
        }
        const Vector3d arm = node_position(nodes, i) - motion.centre;
        const Vector3d w = motion.inverse_inertia * motion.angular_momentum;
        const Vector3d u = motion.velocity + w.cross(arm);
        const double closing = u.dot(n) - wall_speed + d * inv_dt;
        // Nodes that could reach the wall this step once the body's other contacts act.
        const double reach = dt * (u.norm() + std::abs(predicted_wall_velocity) +
                                   wall_motion.norm() + w.norm() * arm.norm());
        if (closing < 0.0 || d < reach) {
          BodyContact c;
          c.node = i;
          c.body = b;
          c.arm = arm;
          c.gap_rate = d * inv_dt;
          c.wall_speed = wall_speed;
          c.normal = n;
          if (wall.shape == WallShape::Plane) {
            c.tangent_l = wall.edge_l;
            c.tangent_m = wall.edge_m;
          } else {
            const Vector3d axis = std::abs(n.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY();
            c.tangent_l = (axis - axis.dot(n) * n).normalized();
            c.tangent_m = n.cross(c.tangent_l);
          }
          system.body_contacts.push_back(c);
        }
        continue;
      }
      const std::uint8_t held = wall.locked_axes[k];
      const double m = nodes.mass[i];
      if (held == 7 || !(m > 0.0)) continue;
      const double limit =
          nodes.v.x[i] * n.x() + nodes.v.y[i] * n.y() + nodes.v.z[i] * n.z() + d * inv_dt;
      if (limit >= wall_speed) continue;
      double normal_share = 1.0;  // |P n|^2 with P the projection on the free axes
      if (held) {
        normal_share = 0.0;
        for (int a = 0; a < 3; ++a) {
          if (!(held & (1u << a))) normal_share += n[a] * n[a];
        }
        if (normal_share < 1e-12) continue;
      }
      system.candidates.push_back(
          {i, static_cast<std::int32_t>(k), limit, m / normal_share, wall_speed, n});
    }

    // Deformable nodes. A fixed wall stops each node independently: it ends with normal
    // velocity -d/dt (on the wall at t^{n+1}); a prescribed wall, with the wall's normal
    // velocity V.n - d/dt. A moving wall of mass M is pushed by all of them: with the set S
    // of nodes in contact its velocity becomes
    //   V = (M V_pred + sum_S m_i l_i) / (M + sum_S m_i),   l_i = v_i.n + d_i/dt,
    // and S = {i : l_i < V}; sorting by l_i finds S exactly (adding a node only lowers V).
    double wall_velocity = predicted_wall_velocity;
    std::size_t in_contact = system.candidates.size();
    if (wall.moving && in_contact > 0) {
      std::sort(system.candidates.begin(), system.candidates.end(),
                [](const NodeCandidate& a, const NodeCandidate& b) {
                  return a.limit < b.limit || (a.limit == b.limit && a.node < b.node);
                });
      double momentum = wall.mass * predicted_wall_velocity, mass = wall.mass;
      in_contact = 0;
      while (in_contact < system.candidates.size() &&
             system.candidates[in_contact].limit < momentum / mass) {
        momentum += system.candidates[in_contact].mass * system.candidates[in_contact].limit;
        mass += system.candidates[in_contact].mass;
        ++in_contact;
      }
      wall_velocity = momentum / mass;
    }
    const bool friction = wall.no_sliding || wall.friction > 0.0;
    const double inv_dt_avg = 1.0 / dt_avg;
    double normal_sum = 0.0;  // sum of the forces along their contact normals
    for (std::size_t c = 0; c < in_contact; ++c) {
      const NodeCandidate& cand = system.candidates[c];
      const std::int32_t i = cand.node;
      const Vector3d& n = cand.normal;
      const std::uint8_t held = wall.locked_axes[cand.slot];
      const double m = nodes.mass[i];
      const double target = wall.moving ? wall_velocity : cand.wall_speed;
      const double normal_impulse = cand.mass * (target - cand.limit);
      Vector3d dv = (normal_impulse / m) * n;
      if (held) {
        for (int a = 0; a < 3; ++a) {
          if (held & (1u << a)) dv[a] = 0.0;
        }
      } else if (friction) {
        // Friction acts on the slip relative to the wall.
        const Vector3d v = Vector3d(nodes.v.x[i], nodes.v.y[i], nodes.v.z[i]) + dv - wall_motion;
        dv += friction_velocity_change(wall, v - v.dot(n) * n, m, normal_impulse);
      }
      nodes.v.x[i] += dv.x();
      nodes.v.y[i] += dv.y();
      nodes.v.z[i] += dv.z();
      nodes.a.x[i] += dv.x() * inv_dt_avg;
      nodes.a.y[i] += dv.y() * inv_dt_avg;
      nodes.a.z[i] += dv.z() * inv_dt_avg;
      // The wall pushes along n with the normal impulse; a held DOF's constraint takes the
      // share along it (its reaction is computed from the velocity change).
      Vector3d force = (m * inv_dt_avg) * dv;
      if (held) force = (normal_impulse * inv_dt_avg) * n;
      nodes.f_ext.x[i] += force.x();
      nodes.f_ext.y[i] += force.y();
      nodes.f_ext.z[i] += force.z();
      wall.force += force;
      normal_sum += force.dot(n);
      wall.contacts.push_back({i, -1, force});
    }

    // Rigid bodies: contacts grouped by body, one contact solve per body.
    auto& contacts = system.body_contacts;
    std::sort(contacts.begin(), contacts.end(), [](const BodyContact& a, const BodyContact& b) {
      return a.body < b.body || (a.body == b.body && a.node < b.node);
    });
    for (std::size_t first = 0; first < contacts.size();) {
      std::size_t last = first;
      while (last < contacts.size() && contacts[last].body == contacts[first].body) ++last;
      BodyMotion& motion = system.body_motion[contacts[first].body];
      solve_body_contacts(wall, motion, contacts.data() + first, contacts.data() + last,
                          wall_velocity, wall_inverse_mass, wall_motion);
      for (std::size_t c = first; c < last; ++c) {
        const BodyContact& bc = contacts[c];
        if (bc.normal_impulse == 0.0 && bc.tangent_impulse.squaredNorm() == 0.0) continue;
        const Vector3d force =
            inv_dt_avg * (bc.normal_impulse * bc.normal + bc.tangent_impulse.x() * bc.tangent_l +
                          bc.tangent_impulse.y() * bc.tangent_m);
        nodes.f_ext.x[bc.node] += force.x();
        nodes.f_ext.y[bc.node] += force.y();
        nodes.f_ext.z[bc.node] += force.z();
        wall.force += force;
        normal_sum += inv_dt_avg * bc.normal_impulse;
        wall.contacts.push_back({bc.node, bc.body, force});
      }
      first = last;
    }
    if (wall.moving) wall.velocity = wall_velocity;
    wall.normal_force = wall.shape == WallShape::Plane ? wall.force.dot(wall.normal) : normal_sum;
    wall.normal_impulse += wall.normal_force * dt_avg;
    if (!wall.segment_nodes.empty()) {
      for (const WallContact& c : wall.contacts) {
        if (wall.segment_nodes[c.node]) wall.segment_force += c.force;
      }
    }
  }
}

double rigid_wall_work(RigidWallSystem& system, const solver::RigidSystem& rigid,
                       const solver::Vec3Array& v_previous, const solver::State& state,
                       double dt_avg) {
  const solver::NodalState& nodes = state.nodes;
  double total = 0.0;
  for (RigidWall& wall : system.walls) {
    double work = 0.0;
    for (const WallContact& c : wall.contacts) {
      const std::int32_t i = c.node;
      Vector3d d;
      if (c.body >= 0) {
        // As in the energy sum: the body's displacement at the node over the half steps.
        const solver::RigidBody& body = rigid.bodies[c.body];
        const Vector3d arm = node_position(nodes, i) - body.state.previous_centre;
        d = dt_avg * (body.mid_velocity + body.mid_angular_velocity.cross(arm));
      } else {
        d = 0.5 * dt_avg *
            Vector3d(v_previous.x[i] + nodes.v.x[i], v_previous.y[i] + nodes.v.y[i],
                     v_previous.z[i] + nodes.v.z[i]);
      }
      work += c.force.dot(d);
    }
    wall.work += work;
    total += work;
  }
  return total;
}

double wall_normal_force(const RigidWallSystem& system, int number) {
  if (number < 1 || number > static_cast<int>(system.walls.size())) return -1.0;
  return std::abs(system.walls[number - 1].normal_force);
}

bool wall_within_offset(const RigidWallSystem& system, int number, double offset,
                        const std::vector<model::Id>& parts, const solver::State& state) {
  if (number < 1 || number > static_cast<int>(system.walls.size())) return false;
  const RigidWall& wall = system.walls[number - 1];
  const Vector3d position = wall_position(wall);
  auto near = [&](const auto& blocks) {  // every element family
    for (const auto& block : blocks) {
      if (std::find(parts.begin(), parts.end(), block.part_id) == parts.end()) continue;
      for (const std::int32_t i : block.conn) {
        const Vector3d x = node_position(state.nodes, i);
        // Closed shapes: measured from the side the wall keeps nodes on by default.
        const bool inside = wall.shape == WallShape::Cylinder && !wall.kept_inside.empty() &&
                            wall.kept_inside.front() != 0;
        const SurfacePoint sp = surface_point(wall, position, x, inside);
        if (sp.distance >= -system.tolerance && sp.distance <= offset && sp.over) return true;
      }
    }
    return false;
  };
  return near(state.hex_blocks) || near(state.shell_blocks) || near(state.beam_blocks);
}

void set_wall_active(RigidWallSystem& system, int number, bool active) {
  if (number < 1 || number > static_cast<int>(system.walls.size())) return;
  system.walls[number - 1].active = active;
}

}  // namespace rf::contact
