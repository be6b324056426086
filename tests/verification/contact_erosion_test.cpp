// Contact that follows element erosion (docs/contact.md, "Erosion"), against references that do
// not come from the contact code:
//  - the penalty force k |g| of LS-DYNA's formulas (Theory Manual, penalty method) with k from
//    the material's E and nu and the element's dimensions: k = SLSFAC K A^2 / V for a solid face,
//    SLSFAC K A / (shell diagonal) for a shell, SLSFAC = 0.1;
//  - the geometry of the mesh: which nodes lie on the exterior of the live elements (counted
//    here from the connectivity), the outward normal of an exposed face;
//  - conservation of momentum (the contact forces sum to zero);
//  - the forces of the code before erosion existed (bit for bit, for a model that cannot erode).
#include <gtest/gtest.h>
#include <omp.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>

#include "contact/contact.hpp"
#include "contact_fixture.hpp"
#include "deck_builder.hpp"
#include "shell_builder.hpp"
#include "solver/build_state.hpp"

namespace rf::test {
namespace {

constexpr double kH = 0.01;  // element size of the targets
constexpr double kRho = 1000.0, kE = 1e7, kNu = 0.3;
constexpr double kBulk = kE / (3.0 * (1.0 - 2.0 * kNu));
constexpr double kSlsfac = 0.1;  // LS-DYNA's default penalty scale (*CONTROL_CONTACT)

// Models come with ContactFixture (contact_fixture.hpp): the contacts are built by build(), after
// a test has enabled erosion on blocks (as the state builder does for failing materials).

template <class Block>
void enable_erosion(Block& block) {
  block.erosion.enabled = true;
  block.erosion.allocate(block.size());
}

template <class Block>
void erode(Block& block, std::size_t e, double t = 0.0) {
  block.erosion.time[e] = t;
  ++block.erosion.count;
}

// Element index of element ID `id` in its block.
template <class Block>
std::size_t element_index(const Block& block, model::Id id) {
  for (std::size_t e = 0; e < block.size(); ++e)
    if (block.element_id[e] == id) return e;
  throw std::runtime_error("no such element");
}

std::string elastic_target(int pid) {
  return elastic(pid, kRho, kE, kNu);
}
std::string termination_card(double t) {
  return fmt::format("*CONTROL_TERMINATION\n{},\n", t);
}

// ---------------------------------------------------------------------------------------
// (e) A model that cannot erode: the contact forces of the code before erosion was followed,
// bit for bit. Solid blocks pressed into each other with friction (surface to surface), a
// solid on a shell plate, and a single surface over everything, evaluated four times at
// perturbed positions with velocities (friction springs, side memory, node normals). The
// reference hash was computed by the unchanged code (commit 31aaac6).

std::string golden_deck() {
  Block target;  // part 1: 3 x 3 x 2 over [0, 3h]^2 x [0, 2h]
  target.nx = target.ny = 3;
  target.nz = 2;
  target.lx = target.ly = 3 * kH;
  target.lz = 2 * kH;
  Block punch;  // part 2: 2 x 2 x 1, 0.5 mm into the target's top
  punch.nx = punch.ny = 2;
  punch.lx = punch.ly = 2 * kH;
  punch.lz = kH;
  punch.local = Eigen::Vector3d(0.5 * kH, 0.5 * kH, 2 * kH - 5e-4);
  punch.pid = 2;
  punch.first_node = punch.first_element = 1001;
  ShellPlate plate;  // part 3: 2 x 2 shells, t = 4 mm, mid-surface 1 mm under the target
  plate.nx = plate.ny = 2;
  plate.lx = plate.ly = 4 * kH;
  plate.pid = 3;
  plate.first_node = plate.first_element = 2001;
  plate.place = [](double u, double v) { return Eigen::Vector3d(u - kH / 2, v - kH / 2, -1e-3); };
  return "*KEYWORD\n" + target.text() + punch.text() + plate.text() + elastic_target(1) +
         elastic(2, kRho, 2 * kE, 0.25) + shell_part(3, 4e-3, kRho, kE, kNu) +
         "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID\n1\n2,1,3,3\n0.3,0.2,0,0,10\n1,1\n"
         "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID\n2\n1,3,3,3\n0.1\n1,1\n"
         "*CONTACT_AUTOMATIC_SINGLE_SURFACE_ID\n3\n0,0,5\n\n1,1\n" +
         termination_card(1.0);
}

struct Hash {
  std::uint64_t value = 1469598103934665603ull;  // FNV-1a
  void add(double x) {
    const auto bits = std::bit_cast<std::uint64_t>(x);
    for (int b = 0; b < 8; ++b) {
      value ^= (bits >> (8 * b)) & 0xffu;
      value *= 1099511628211ull;
    }
  }
};

// Perturbs every node (deterministic pattern), gives it a velocity, and evaluates the contacts
// at t = 0 (dt 0) and after three steps; hashes after each evaluation every nodal contact force,
// each interface's resultant and count, and the per-pass state of the slave nodes that have one
// (by node, the segment by its nodes: independent of how the segments are numbered).
std::uint64_t golden_hash(ContactFixture& f) {
  auto& n = f.state.nodes;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const double s = static_cast<double>(i);
    n.x.x[i] += 2e-4 * std::sin(1.7 * s);
    n.x.y[i] += 2e-4 * std::sin(2.3 * s + 1.0);
    n.x.z[i] += 2e-4 * std::sin(3.1 * s + 2.0);
    n.v.x[i] = 0.5 * std::sin(0.9 * s);
    n.v.y[i] = 0.5 * std::cos(1.1 * s);
    n.v.z[i] = -0.3 + 0.2 * std::sin(0.7 * s);
  }
  Hash hash;
  const double dt = 1e-5;
  for (int step = 0; step < 4; ++step) {
    if (step > 0) {
      for (std::size_t i = 0; i < n.size(); ++i) {
        n.x.x[i] += dt * n.v.x[i];
        n.x.y[i] += dt * n.v.y[i];
        n.x.z[i] += dt * n.v.z[i];
      }
      f.state.time += dt;
    }
    contact::compute_contact_forces(f.contacts, f.state, step == 0 ? 0.0 : dt);
    for (std::size_t i = 0; i < n.size(); ++i) {
      hash.add(f.contacts.force.x[i]);
      hash.add(f.contacts.force.y[i]);
      hash.add(f.contacts.force.z[i]);
    }
    for (const auto& c : f.contacts.interfaces) {
      for (const double v : c.slave_force) hash.add(v);
      hash.add(static_cast<double>(c.active_nodes));
      for (const auto& pass : c.passes) {
        const auto& slave = c.sides[pass.slave_side];
        const auto& master = c.sides[pass.master_side];
        for (std::size_t j = 0; j < slave.nodes.size(); ++j) {
          const double* ft = &pass.tangential_force[3 * j];
          const double* normal = &pass.contact_normal[3 * j];
          const bool in_use = pass.results[j].segment >= 0 || pass.contact_segment[j] >= 0 ||
                              ft[0] != 0.0 || ft[1] != 0.0 || ft[2] != 0.0;
          if (!in_use) continue;
          hash.add(static_cast<double>(slave.nodes[j]));
          for (int d = 0; d < 3; ++d) {
            hash.add(ft[d]);
            hash.add(normal[d]);
          }
          for (const auto segment : {pass.results[j].segment, pass.contact_segment[j]}) {
            if (segment < 0) {
              hash.add(-1.0);
              continue;
            }
            for (const auto node : master.segments[segment]) hash.add(static_cast<double>(node));
          }
        }
      }
    }
  }
  return hash.value;
}

std::int64_t nodes_in_contact(const contact::ContactSystem& contacts) {
  std::int64_t count = 0;
  for (const auto& c : contacts.interfaces) count += c.active_nodes;
  return count;
}

TEST(ContactErosion, ModelWithoutErosionGivesTheForcesOfTheCodeBeforeErosion) {
  ContactFixture f(golden_deck());
  f.build();
  const std::uint64_t hash = golden_hash(f);
  EXPECT_EQ(nodes_in_contact(f.contacts), 60);
#if defined(__x86_64__) && !defined(__FMA__)
  // Computed by the code of commit 31aaac6 (before contact followed erosion), x86-64 without
  // FMA (the default build: no -march=native, so no contraction changes the rounding).
  EXPECT_EQ(hash, 0x53bf901ec3fea5c8ull);
#endif
  // The same model with erosion enabled on every block and nothing eroded: the interior faces
  // are candidates but inactive, and the forces are the same bit for bit.
  ContactFixture erodible(golden_deck());
  for (auto& b : erodible.state.hex_blocks) enable_erosion(b);
  for (auto& b : erodible.state.shell_blocks) enable_erosion(b);
  erodible.state.nodes.removed.assign(erodible.state.nodes.size(), 0);
  erodible.build();
  ASSERT_TRUE(erodible.contacts.interfaces[0].sides[1].erodible);
  EXPECT_GT(erodible.contacts.interfaces[0].sides[1].segments.size(),
            f.contacts.interfaces[0].sides[1].segments.size());
  contact::update_after_erosion(erodible.contacts, erodible.state);  // nothing has eroded
  EXPECT_EQ(golden_hash(erodible), hash);
}

// ---------------------------------------------------------------------------------------
// (a) A node pressed g = 0.1 mm into the middle of a 3 x 3 x 2 block of cubes (size h) from
// above, at the level of the top of the bottom layer. While the block is whole it is deep inside
// (released: more than half a segment from every face) and feels nothing; once the top middle
// element has eroded, the face it uncovered is the contact surface: force k g along +z (the
// outward normal of the remaining element below), k = SLSFAC K A^2 / V = 0.1 K h, reactions
// -k g / 4 on the face's four nodes (the node projects onto the face centre). The same with the
// bottom layer a separate part that cannot erode (the face then belongs to a block of no
// erosion), and the same when the contacts are built from a state that has already eroded (a
// restart).

constexpr double kGap = 1e-4;

std::string exposed_face_deck(bool bottom_separate_part) {
  BoxMesh target;
  target.nx = target.ny = 3;
  target.nz = 2;
  target.lx = target.ly = 3 * kH;
  target.lz = 2 * kH;
  const int bottom_pid = bottom_separate_part ? 3 : 1;
  Block carrier;  // part 2: a small cube whose first node is the slave node
  carrier.lx = carrier.ly = carrier.lz = 0.2 * kH;
  carrier.local = Eigen::Vector3d(1.5 * kH, 1.5 * kH, kH - kGap);
  carrier.pid = 2;
  carrier.first_node = carrier.first_element = 1001;
  std::string deck =
      "*KEYWORD\n" + target.keyword_text([&](int, int, int k) { return k == 1 ? 1 : bottom_pid; }) +
      carrier.text() + elastic_target(1) + elastic(2, kRho, kE, kNu) + node_set(10, {1001});
  if (bottom_separate_part) {
    deck += elastic_target(3) + "*SET_PART_LIST\n5\n1,3\n" +
            "*CONTACT_AUTOMATIC_NODES_TO_SURFACE_ID\n1\n10,5,4,2\n0\n1,1\n";
  } else {
    deck += "*CONTACT_AUTOMATIC_NODES_TO_SURFACE_ID\n1\n10,1,4,3\n0\n1,1\n";
  }
  return deck + termination_card(1.0);
}

TEST(ContactErosion, NodeMeetsFaceExposedByErodedTopElementWithPenaltyForce) {
  const double k = kSlsfac * kBulk * kH;  // SLSFAC K A^2 / V with A = h^2, V = h^3
  const double expected = k * kGap;
  const BoxMesh grid{.nx = 3, .ny = 3, .nz = 2};
  const std::array<int, 4> face_nodes = {grid.node_id(1, 1, 1), grid.node_id(2, 1, 1),
                                         grid.node_id(2, 2, 1), grid.node_id(1, 2, 1)};
  constexpr model::Id kTopMiddle = 1 + 1 + 3 * (1 + 3 * 1);  // element (1, 1, 1)
  for (const bool separate : {false, true}) {
    SCOPED_TRACE(separate ? "bottom layer a part without erosion" : "one erodible part");
    ContactFixture f(exposed_face_deck(separate));
    auto& top = f.hex_part(1);
    enable_erosion(top);
    f.state.nodes.removed.assign(f.state.nodes.size(), 0);
    f.build();
    const auto& side = f.contacts.interfaces[0].sides[1];
    ASSERT_TRUE(side.erodible);
    contact::compute_contact_forces(f.contacts, f.state, 0.0);
    EXPECT_EQ(f.contacts.interfaces[0].active_nodes, 0);
    EXPECT_EQ(f.force(1001).norm(), 0.0);
    EXPECT_EQ(contact::resultant_force(f.contacts, 1), 0.0);
    EXPECT_FALSE(contact::within_offset(f.contacts, 1, 0.5 * kH, {2}, f.state));

    erode(top, element_index(top, kTopMiddle));
    contact::update_after_erosion(f.contacts, f.state);
    contact::compute_contact_forces(f.contacts, f.state, 0.0);
    EXPECT_EQ(f.contacts.interfaces[0].active_nodes, 1);
    const Eigen::Vector3d on_node = f.force(1001);
    EXPECT_NEAR(on_node.z(), expected, 1e-12 * expected);
    EXPECT_NEAR(on_node.x(), 0.0, 1e-12 * expected);
    EXPECT_NEAR(on_node.y(), 0.0, 1e-12 * expected);
    for (const int id : face_nodes) {
      EXPECT_NEAR(f.force(id).z(), -0.25 * expected, 1e-12 * expected) << "face node " << id;
    }
    EXPECT_LT(f.total_force().norm(), 1e-12 * expected);
    // The contact normal of the pass: the outward normal of the element under the face.
    const auto& pass = f.contacts.interfaces[0].passes[0];
    EXPECT_NEAR(pass.contact_normal[2], 1.0, 1e-14);
    EXPECT_NEAR(contact::resultant_force(f.contacts, 1), expected, 1e-12 * expected);
    EXPECT_TRUE(contact::within_offset(f.contacts, 1, 0.5 * kH, {2}, f.state));

    // A restart: contacts built from a state that has already eroded, then the update the
    // solver runs after reading the dump. Same force, bit for bit.
    ContactFixture restarted(exposed_face_deck(separate));
    auto& top2 = restarted.hex_part(1);
    enable_erosion(top2);
    erode(top2, element_index(top2, kTopMiddle));
    restarted.state.nodes.removed.assign(restarted.state.nodes.size(), 0);
    restarted.build();
    contact::update_after_erosion(restarted.contacts, restarted.state);
    contact::compute_contact_forces(restarted.contacts, restarted.state, 0.0);
    EXPECT_EQ(restarted.force(1001), on_node);
    for (const int id : face_nodes) EXPECT_EQ(restarted.force(id), f.force(id));
  }
}

// ---------------------------------------------------------------------------------------
// (b) Two shells side by side (size h, t = 2 mm), a node above the middle of each, g = 0.1 mm
// into the upper contact surface (t/2 above the mid-surface). Both are pushed up with
// k g, k = SLSFAC K A / (shell diagonal) = 0.1 K h / sqrt(2). When the first shell erodes its
// node is released (its friction spring and side memory reset) and passes through the plane
// with zero force; the node over the second shell is still pushed with k g.

TEST(ContactErosion, ErodedShellLetsNodePassWhileNeighbourShellStillPushes) {
  constexpr double t = 2e-3;
  ShellPlate plate;
  plate.nx = 2;
  plate.ny = 1;
  plate.lx = 2 * kH;
  plate.ly = kH;
  auto carrier = [](int first, double x) {
    Block c;
    c.lx = c.ly = c.lz = 0.2 * kH;
    c.local = Eigen::Vector3d(x, 0.5 * kH, 0.5 * t - kGap);
    c.pid = 2;
    c.first_node = c.first_element = first;
    return c.text();
  };
  const std::string deck =
      "*KEYWORD\n" + plate.text() + carrier(1001, 0.5 * kH) + carrier(2001, 1.5 * kH) +
      shell_part(1, t, kRho, kE, kNu) + elastic(2, kRho, kE, kNu) + node_set(10, {1001, 2001}) +
      "*CONTACT_AUTOMATIC_NODES_TO_SURFACE_ID\n1\n10,1,4,3\n0.2\n1,1\n" + termination_card(1.0);
  ContactFixture f(deck);
  auto& shells = f.shell_part(1);
  enable_erosion(shells);
  f.state.nodes.removed.assign(f.state.nodes.size(), 0);
  f.build();
  const double k = kSlsfac * kBulk * kH * kH / (std::sqrt(2.0) * kH);
  const double expected = k * kGap;
  // A sideways velocity gives the nodes a friction spring (FS 0.2) to reset.
  for (const model::Id id : {1001, 2001}) {
    f.state.nodes.v.x[static_cast<std::size_t>(f.node(id))] = 1.0;
  }
  for (int step = 0; step < 2; ++step) contact::compute_contact_forces(f.contacts, f.state, 1e-7);
  for (const model::Id id : {1001, 2001}) {
    EXPECT_NEAR(f.force(id).z(), expected, 1e-9 * expected) << "node " << id;
  }
  const auto& pass = f.contacts.interfaces[0].passes[0];
  const auto& slave = f.contacts.interfaces[0].sides[0];
  const auto first_slot = static_cast<std::size_t>(
      std::lower_bound(slave.nodes.begin(), slave.nodes.end(), f.node(1001)) - slave.nodes.begin());
  ASSERT_EQ(pass.contact_segment[first_slot], 0);
  ASSERT_NE(pass.tangential_force[3 * first_slot], 0.0);

  const double both = contact::resultant_force(f.contacts, 1);
  erode(shells, element_index(shells, 1));
  contact::update_after_erosion(f.contacts, f.state);
  EXPECT_EQ(pass.contact_segment[first_slot], -1);
  for (int d = 0; d < 3; ++d) {
    EXPECT_EQ(pass.tangential_force[3 * first_slot + d], 0.0);
    EXPECT_EQ(pass.contact_normal[3 * first_slot + d], 0.0);
  }
  // The resultant is that of the node still in contact: half of both (the same situation,
  // shifted by h).
  EXPECT_NEAR(contact::resultant_force(f.contacts, 1), 0.5 * both, 1e-12 * both);
  for (const double z : {0.5 * t - kGap, 0.0, -(0.5 * t - kGap)}) {
    f.move_node(1001, {0.5 * kH, 0.5 * kH, z});
    for (const model::Id id : {1001, 2001}) {
      f.state.nodes.v.x[static_cast<std::size_t>(f.node(id))] = 0.0;
    }
    contact::compute_contact_forces(f.contacts, f.state, 0.0);
    EXPECT_EQ(f.force(1001).norm(), 0.0) << "z = " << z;
    EXPECT_NEAR(f.force(2001).z(), expected, 1e-12 * expected);
    EXPECT_EQ(f.contacts.interfaces[0].active_nodes, 1);
    EXPECT_LT(f.total_force().norm(), 1e-12 * expected);
  }
}

// ---------------------------------------------------------------------------------------
// (c) SINGLE_SURFACE over a 4 x 4 x 3 erodible block and a cube dropped on its top middle.
// After the cube touches the top, the four top middle elements under it erode; the cube falls
// into the crater and is stopped by the exposed floor (the top of the second layer, z = 2h).
// At every cycle: no node off the exterior of the live elements (counted here from the
// connectivity) has a contact force, the forces sum to zero, and the removed node (the one only
// the eroded elements shared) has none; the floor is hit. The same on 1 and 2 threads, bit for
// bit. The eroded elements keep their internal forces here (leaving the element loop is the
// solver's part); contact must ignore them all the same.

struct DropResult {
  std::vector<double> final_z;
  double penetration = 0.0;  // deepest of the cube below the floor's middle node
  double final_velocity = 0.0;
  double floor_force = 0.0;
  std::int64_t forces_off_surface = 0;
  double worst_imbalance = 0.0;
  int cycles_in_contact_before_erosion = 0;
};

DropResult drop_into_crater(int threads) {
  Block target;
  target.nx = target.ny = 4;
  target.nz = 3;
  target.lx = target.ly = 4 * kH;
  target.lz = 3 * kH;
  Block cube;
  cube.lx = cube.ly = 1.5 * kH;
  cube.lz = kH;
  cube.local = Eigen::Vector3d(1.25 * kH, 1.25 * kH, 3.1 * kH);
  cube.pid = 2;
  cube.first_node = cube.first_element = 1001;
  constexpr double v0 = 1.0;
  const std::string deck =
      "*KEYWORD\n" + target.text() + cube.text() + elastic_target(1) + elastic(2, kRho, kE, kNu) +
      fmt::format("*INITIAL_VELOCITY_GENERATION\n2,2,0,0,0,{}\n0,0,0,0,0,0\n", -v0) +
      "*CONTACT_AUTOMATIC_SINGLE_SURFACE_ID\n1\n0,0,5\n\n1,1\n" +
      // A free single element needs TSSFAC <= 0.55 (docs/verification.md).
      "*CONTROL_TIMESTEP\n0,0.5\n" + termination_card(1.6e-2);
  const model::Model model = read(deck);
  omp_set_num_threads(threads);
  solver::Simulation sim(model, {});
  auto& state = sim.mutable_state();
  auto& block = state.hex_blocks[0];
  EXPECT_EQ(block.part_id, 1);
  enable_erosion(block);
  state.nodes.removed.assign(state.nodes.size(), 0);
  const solver::NodeIndex index(model);
  sim.mutable_contacts() = contact::build_contacts(model, index, state);
  sim.mutable_contacts().parallel_minimum = 0;

  // Exterior of the live elements: nodes of faces that belong to exactly one live element.
  auto exterior_nodes = [&]() {
    std::map<std::array<std::int32_t, 4>, int> faces;
    static constexpr int kFace[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                        {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    for (const auto& b : state.hex_blocks) {
      for (std::size_t e = 0; e < b.size(); ++e) {
        if (b.erosion.is_eroded(e)) continue;
        for (const auto& face : kFace) {
          std::array<std::int32_t, 4> key{};
          for (int a = 0; a < 4; ++a) key[a] = b.conn[8 * e + face[a]];
          std::sort(key.begin(), key.end());
          ++faces[key];
        }
      }
    }
    std::vector<std::uint8_t> on(state.nodes.size(), 0);
    for (const auto& [key, count] : faces) {
      if (count != 1) continue;
      for (const auto n : key) on[n] = 1;
    }
    return on;
  };
  auto on_surface = exterior_nodes();
  const auto crater_centre = static_cast<std::size_t>(index.at(target.node(2, 2, 3), {}, ""));
  std::vector<std::size_t> floor;
  for (int i = 1; i <= 3; ++i)
    for (int j = 1; j <= 3; ++j)
      floor.push_back(static_cast<std::size_t>(index.at(target.node(i, j, 2), {}, "")));

  DropResult r;
  bool eroded = false;
  const auto& f = sim.contacts().force;
  while (!sim.finished()) {
    sim.cycle();
    double sum[3] = {0, 0, 0}, magnitude = 0.0;
    for (std::size_t i = 0; i < state.nodes.size(); ++i) {
      const double fi[3] = {f.x[i], f.y[i], f.z[i]};
      const bool pushed = fi[0] != 0.0 || fi[1] != 0.0 || fi[2] != 0.0;
      if (pushed && !on_surface[i]) ++r.forces_off_surface;
      for (int d = 0; d < 3; ++d) {
        sum[d] += fi[d];
        magnitude += std::abs(fi[d]);
      }
    }
    if (magnitude > 0.0) {
      r.worst_imbalance =
          std::max(r.worst_imbalance,
                   std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]) / magnitude);
    }
    double lowest = 1e300;
    for (std::size_t i = 0; i < state.nodes.size(); ++i) {
      if (state.nodes.id[i] > 1000) lowest = std::min(lowest, state.nodes.x.z[i]);
    }
    if (!eroded) {
      if (sim.contacts().interfaces[0].active_nodes > 0) ++r.cycles_in_contact_before_erosion;
      if (r.cycles_in_contact_before_erosion == 2) {
        // The four top middle elements under the cube fail; the node only they shared goes.
        for (int i = 1; i <= 2; ++i)
          for (int j = 1; j <= 2; ++j)
            erode(block, static_cast<std::size_t>(i + 4 * (j + 4 * 2)), state.time);
        state.nodes.removed[crater_centre] = 1;
        contact::update_after_erosion(sim.mutable_contacts(), state);
        on_surface = exterior_nodes();
        eroded = true;
      }
      continue;
    }
    r.penetration = std::max(r.penetration, state.nodes.x.z[floor[4]] - lowest);
    for (const auto i : floor) r.floor_force = std::max(r.floor_force, std::abs(f.z[i]));
    EXPECT_EQ(f.x[crater_centre], 0.0);
    EXPECT_EQ(f.y[crater_centre], 0.0);
    EXPECT_EQ(f.z[crater_centre], 0.0);
  }
  EXPECT_TRUE(eroded);
  double momentum = 0.0, mass = 0.0;
  for (std::size_t i = 0; i < state.nodes.size(); ++i) {
    if (state.nodes.id[i] <= 1000) continue;
    momentum += state.nodes.mass[i] * state.nodes.v.z[i];
    mass += state.nodes.mass[i];
  }
  r.final_velocity = momentum / mass;
  r.final_z = state.nodes.x.z;
  return r;
}

TEST(ContactErosion, SingleSurfaceOfErodibleBlockNeverPushesInteriorNodes) {
  const int saved = omp_get_max_threads();
  const DropResult one = drop_into_crater(1);
  const DropResult two = drop_into_crater(2);
  omp_set_num_threads(saved);
  EXPECT_EQ(one.cycles_in_contact_before_erosion, 2);
  EXPECT_EQ(one.forces_off_surface, 0);
  EXPECT_LT(one.worst_imbalance, 1e-12);
  EXPECT_GT(one.floor_force, 0.0);  // the cube reached the exposed floor ...
  // ... and did not sink into it by more than a penalty penetration: v0 sqrt(m / k) with the
  // cube's mass on its four bottom nodes' springs is 0.025 h.
  EXPECT_GT(one.penetration, 0.0);
  EXPECT_LT(one.penetration, 0.1 * kH);
  EXPECT_GT(one.final_velocity, 0.0);   // rebounding
  EXPECT_EQ(one.final_z, two.final_z);  // any thread count, bit for bit
}

// ---------------------------------------------------------------------------------------
// (d) Removed nodes. A 3 x 3 x 2 erodible block with a plate pressed g into its top corner
// (surface to surface), and two carrier nodes of a node set pressed g into its top elsewhere.
// The corner element erodes and its corner node (no element left) is removed; the first carrier
// cube erodes and its nodes are removed. The removed nodes get no force and exert none: the
// remaining forces are those before, less the removed nodes' own (k g each, k = 0.1 K h).

TEST(ContactErosion, RemovedNodesNeitherTakeNorExertForce) {
  Block target;
  target.nx = target.ny = 3;
  target.nz = 2;
  target.lx = target.ly = 3 * kH;
  target.lz = 2 * kH;
  Block plate;
  plate.lx = plate.ly = 2 * kH;
  plate.lz = kH;
  plate.local = Eigen::Vector3d(-0.5 * kH, -0.5 * kH, 2 * kH - kGap);
  plate.pid = 3;
  plate.first_node = plate.first_element = 3001;
  auto carrier = [](int first, double x, double y) {
    Block c;
    c.lx = c.ly = c.lz = 0.2 * kH;
    c.local = Eigen::Vector3d(x, y, 2 * kH - kGap);
    c.pid = 2;
    c.first_node = c.first_element = first;
    return c.text();
  };
  const std::string deck = "*KEYWORD\n" + target.text() + plate.text() +
                           carrier(1001, 2.5 * kH, 2.5 * kH) + carrier(2001, 2.5 * kH, 0.5 * kH) +
                           elastic_target(1) + elastic(2, kRho, kE, kNu) + elastic_target(3) +
                           node_set(10, {1001, 2001}) +
                           "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID\n1\n1,3,3,3\n0\n1,1\n"
                           "*CONTACT_AUTOMATIC_NODES_TO_SURFACE_ID\n2\n10,1,4,3\n0\n1,1\n" +
                           termination_card(1.0);
  ContactFixture f(deck);
  auto& block = f.hex_part(1);
  auto& carriers = f.hex_part(2);
  enable_erosion(block);
  enable_erosion(carriers);
  f.state.nodes.removed.assign(f.state.nodes.size(), 0);
  f.build();
  const double expected = kSlsfac * kBulk * kH * kGap;
  contact::compute_contact_forces(f.contacts, f.state, 0.0);
  const int corner = target.node(0, 0, 2);
  const std::vector<int> watched = {target.node(1, 0, 2), target.node(0, 1, 2),
                                    target.node(1, 1, 2), target.node(2, 1, 2)};
  std::map<int, Eigen::Vector3d> before;
  for (const int id : watched) before[id] = f.force(id);
  EXPECT_NEAR(f.force(corner).z(), -expected, 1e-12 * expected);
  EXPECT_NEAR(f.force(1001).z(), expected, 1e-12 * expected);
  EXPECT_NEAR(f.force(2001).z(), expected, 1e-12 * expected);
  const Eigen::Vector3d plate_before =
      f.force(3001) + f.force(3002) + f.force(3003) + f.force(3004);

  erode(block, element_index(block, 1 + 0 + 3 * (0 + 3 * 1)));  // element (0, 0, 1)
  f.state.nodes.removed[static_cast<std::size_t>(f.node(corner))] = 1;
  erode(carriers, element_index(carriers, 1001));
  for (int id = 1001; id <= 1008; ++id)
    f.state.nodes.removed[static_cast<std::size_t>(f.node(id))] = 1;
  contact::update_after_erosion(f.contacts, f.state);
  contact::compute_contact_forces(f.contacts, f.state, 0.0);
  EXPECT_EQ(f.force(corner).norm(), 0.0);
  EXPECT_EQ(f.force(1001).norm(), 0.0);
  EXPECT_NEAR(f.force(2001).z(), expected, 1e-12 * expected);
  for (const int id : watched) {
    // The target's remaining top nodes are pushed as before; the plate loses the corner's
    // reaction only.
    EXPECT_EQ(f.force(id), before[id]) << "node " << id;
  }
  const Eigen::Vector3d plate_after = f.force(3001) + f.force(3002) + f.force(3003) + f.force(3004);
  EXPECT_NEAR(plate_after.z(), plate_before.z() - expected, 1e-12 * expected);
  EXPECT_LT(f.total_force().norm(), 1e-12 * expected);
  for (const auto& c : f.contacts.interfaces) {
    for (const auto& side : c.sides) {
      for (std::size_t j = 0; j < side.nodes.size(); ++j) {
        if (f.state.nodes.is_removed(static_cast<std::size_t>(side.nodes[j]))) {
          EXPECT_FALSE(side.is_active_node(j));
        }
      }
    }
  }
}

}  // namespace
}  // namespace rf::test
