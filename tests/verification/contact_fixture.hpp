// A model's contacts built and evaluated directly, without the solver's time loop (tests of the
// penalty force of one configuration): the deck's model, its dense state and its contacts.
#pragma once

#include <Eigen/Dense>

#include <stdexcept>
#include <string>

#include "contact/contact.hpp"
#include "deck_builder.hpp"
#include "solver/build_state.hpp"

namespace rf::test {

struct ContactFixture {
  model::Model model;
  solver::NodeIndex index;
  solver::State state;
  contact::ContactSystem contacts;

  explicit ContactFixture(const std::string& deck)
      : model(read(deck)), index(model), state(solver::build_state(model, index)) {}
  void build() { contacts = contact::build_contacts(model, index, state); }

  std::int32_t node(model::Id id) const { return index.at(id, {}, "node"); }
  element::HexBlock& hex_part(model::Id pid) {
    for (auto& b : state.hex_blocks)
      if (b.part_id == pid) return b;
    throw std::runtime_error("no such hex part");
  }
  element::ShellBlock& shell_part(model::Id pid) {
    for (auto& b : state.shell_blocks)
      if (b.part_id == pid) return b;
    throw std::runtime_error("no such shell part");
  }
  Eigen::Vector3d force(model::Id id) const {
    const auto i = static_cast<std::size_t>(index.at(id, {}, "node"));
    return {contacts.force.x[i], contacts.force.y[i], contacts.force.z[i]};
  }
  Eigen::Vector3d total_force() const {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const auto i : contacts.nodes) {
      sum += Eigen::Vector3d(contacts.force.x[i], contacts.force.y[i], contacts.force.z[i]);
    }
    return sum;
  }
  void move_node(model::Id id, const Eigen::Vector3d& p) {
    const auto i = static_cast<std::size_t>(index.at(id, {}, "node"));
    state.nodes.x.x[i] = p.x();
    state.nodes.x.y[i] = p.y();
    state.nodes.x.z[i] = p.z();
  }
};

}  // namespace rf::test
