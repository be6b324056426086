// Element partition of distributed runs (src/parallel/partition.hpp, docs/parallel.md).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <numeric>
#include <string>

#include "element/element_ownership.hpp"
#include "io/keyword/reader.hpp"
#include "parallel/communicator.hpp"
#include "parallel/partition.hpp"
#include "solver/build_state.hpp"

namespace {

// An nx x ny x nz block of unit hexahedra (ELFORM `elform`), elastic steel.
std::string block_deck(int nx, int ny, int nz, int elform = 1) {
  std::string d = "*KEYWORD\n*CONTROL_TERMINATION\n1e-3\n";
  d += fmt::format("*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,{}\n", elform);
  d += "*MAT_ELASTIC\n1,7800,2.1e11,0.3\n*NODE\n";
  auto nid = [&](int i, int j, int k) { return 1 + i + (nx + 1) * (j + (ny + 1) * k); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) d += fmt::format("{},{},{},{}\n", nid(i, j, k), i, j, k);
  d += "*ELEMENT_SOLID\n";
  int e = 1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        d += fmt::format("{},1,{},{},{},{},{},{},{},{}\n", e++, nid(i, j, k), nid(i + 1, j, k),
                         nid(i + 1, j + 1, k), nid(i, j + 1, k), nid(i, j, k + 1),
                         nid(i + 1, j, k + 1), nid(i + 1, j + 1, k + 1), nid(i, j + 1, k + 1));
      }
  return d + "*END\n";
}

rf::solver::State state_of(const std::string& deck) {
  const auto model = rf::io::read_deck_text(deck, "block.k");
  const rf::solver::NodeIndex index(model);
  return rf::solver::build_state(model, index);
}

}  // namespace

// A 12 x 4 x 4 bar cut in two: the cheapest cut of the element graph is a plane across the
// long axis, which leaves 24 x 4 x 4 / 2 elements on each side and (4 + 1)^2 = 25 nodes on the
// cut. METIS k-way allows 3 % imbalance by default (ufactor 30): asserted.
TEST(Partition, BarSplitInTwoIsBalancedWithOnePlaneOfInterfaceNodes) {
  if (!rf::parallel::built_with_mpi()) GTEST_SKIP() << "built without MPI and METIS";
  const rf::solver::State state = state_of(block_deck(12, 4, 4));
  const rf::parallel::Partition p = rf::parallel::partition_elements(state, 2);
  ASSERT_EQ(p.elements.size(), 2u);
  EXPECT_EQ(p.total_elements(), 192);
  EXPECT_LE(p.imbalance(), 1.03);
  EXPECT_EQ(p.interface_nodes, 25);
  // Every element has an owner in range, and the weights are 10 per ELFORM 1 element.
  for (const auto o : p.hex.at(0)) EXPECT_TRUE(o == 0 || o == 1);
  EXPECT_EQ(p.weight[0] + p.weight[1], 1920);
  // The same partition every time (fixed METIS seed).
  const rf::parallel::Partition again = rf::parallel::partition_elements(state, 2);
  EXPECT_EQ(again.hex, p.hex);
}

TEST(Partition, ThreeRanksCoverEveryElementOnce) {
  if (!rf::parallel::built_with_mpi()) GTEST_SKIP() << "built without MPI and METIS";
  const rf::solver::State state = state_of(block_deck(6, 6, 3));
  const rf::parallel::Partition p = rf::parallel::partition_elements(state, 3);
  EXPECT_EQ(p.total_elements(), 108);
  EXPECT_LE(p.imbalance(), 1.03 + 1e-12);
  EXPECT_GT(p.interface_nodes, 0);
  for (const auto e : p.elements) EXPECT_GT(e, 0);
  // The flattened owners round-trip (the broadcast from rank 0).
  rf::parallel::Partition copy;
  copy.ranks = 3;
  rf::parallel::unflatten_owners(rf::parallel::flatten_owners(p), state, copy);
  EXPECT_EQ(copy.hex, p.hex);
  EXPECT_EQ(copy.interface_nodes, p.interface_nodes);
  EXPECT_EQ(copy.weight, p.weight);
}

TEST(Partition, OneRankOwnsEverythingWithoutMetis) {
  const rf::solver::State state = state_of(block_deck(2, 2, 2, 2));
  const rf::parallel::Partition p = rf::parallel::partition_elements(state, 1);
  EXPECT_EQ(p.total_elements(), 8);
  EXPECT_EQ(p.interface_nodes, 0);
  EXPECT_EQ(p.weight.at(0), 8 * 85);  // ELFORM 2 weighs 85
  EXPECT_DOUBLE_EQ(p.imbalance(), 1.0);
}

TEST(Partition, MoreRanksThanElementsNamesBothNumbers) {
  const rf::solver::State state = state_of(block_deck(2, 1, 1));
  try {
    rf::parallel::partition_elements(state, 3);
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("3 ranks for 2 deformable elements"), std::string::npos) << what;
  }
  EXPECT_THROW(rf::parallel::partition_elements(state, 0), std::invalid_argument);
}

// Applying a partition restricts the kernel loops: the owned elements, cut into runs of
// consecutive indices of at most `lanes`; the other elements' force slots zeroed.
TEST(Partition, ApplyRestrictsTheBlockToItsRanksElements) {
  rf::solver::State state = state_of(block_deck(4, 1, 1));
  rf::parallel::Partition p;
  p.ranks = 2;
  p.hex = {{0, 1, 1, 0}};
  p.shell.clear();
  p.beam.clear();
  auto& block = state.hex_blocks.at(0);
  std::fill(block.force.begin(), block.force.end(), 1.0);
  rf::parallel::apply_partition(p, 1, state);
  EXPECT_TRUE(block.owned.partitioned);
  EXPECT_EQ(block.owned.elements, (std::vector<std::int64_t>{1, 2}));
  EXPECT_EQ(block.owned.count(4), 2);
  EXPECT_EQ(block.owned.element(1), 2);
  for (std::size_t s = 0; s < block.force.size(); ++s) {
    const std::size_t e = s / 24;
    EXPECT_EQ(block.force[s], (e == 1 || e == 2) ? 1.0 : 0.0) << s;
  }
  block.owned.prepare_batches(8);
  ASSERT_EQ(block.owned.batches.size(), 1u);
  EXPECT_EQ(block.owned.batches[0].first, 1);
  EXPECT_EQ(block.owned.batches[0].count, 2);
  rf::element::ElementOwnership o;
  o.partitioned = true;
  o.elements = {0, 1, 2, 5, 6, 9};
  o.prepare_batches(2);
  ASSERT_EQ(o.batches.size(), 4u);  // {0,1} {2} {5,6} {9}
  EXPECT_EQ(o.batches[1].first, 2);
  EXPECT_EQ(o.batches[1].count, 1);
  EXPECT_EQ(o.batches[3].first, 9);
}
