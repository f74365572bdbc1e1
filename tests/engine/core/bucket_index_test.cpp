// Grouping items by key against a std::map of the same keys.

#include "engine/core/bucket_index.h"

#include <gtest/gtest.h>

#include <map>
#include <vector>

#include "engine/core/random.h"

namespace plumb {
namespace {

// A hash with poor low bits on purpose: keys that collide in the table must still be told apart.
struct CoarseHash {
  std::size_t operator()(int key) const { return static_cast<std::size_t>(key / 16); }
};

TEST(BucketIndex, GroupsEveryItemUnderItsKeyInAscendingOrder) {
  Random random(7);
  std::vector<int> keys;
  for (int i = 0; i < 20000; ++i) keys.push_back(static_cast<int>(random.uniform() * 3000.0) - 1500);
  std::map<int, std::vector<std::uint32_t>> expected;
  for (std::uint32_t i = 0; i < keys.size(); ++i) expected[keys[i]].push_back(i);
  const BucketIndex<int, CoarseHash> index(keys);
  std::size_t runs = 0;
  index.forEachRun([&](const auto& run) {
    ++runs;
    const auto items = index.items(run);
    EXPECT_EQ(std::vector<std::uint32_t>(items.begin(), items.end()), expected.at(run.key));
  });
  EXPECT_EQ(runs, expected.size());
  for (const auto& [key, items] : expected) {
    const auto found = index.at(key);
    EXPECT_EQ(std::vector<std::uint32_t>(found.begin(), found.end()), items);
  }
  EXPECT_TRUE(index.at(5000).empty());
  EXPECT_EQ(index.find(5000), nullptr);
  EXPECT_EQ(index.order().size(), keys.size());
}

TEST(BucketIndex, NoItemsNoRuns) {
  const BucketIndex<int, CoarseHash> index(std::span<const int>{});
  EXPECT_TRUE(index.at(0).empty());
  EXPECT_TRUE(index.order().empty());
  const BucketIndex<int, CoarseHash> empty;
  EXPECT_TRUE(empty.at(0).empty());
}

}  // namespace
}  // namespace plumb
