#include "reco/otsu.h"

#include <gtest/gtest.h>

#include <vector>

namespace plumb::reco {
namespace {

std::size_t high(std::vector<double> values) {
  return otsuHighClassSize(values);
}

TEST(Otsu, DropsOnlyClearlySeparatedLowValues) {
  EXPECT_EQ(high({10000, 9000, 50}), 2u);  // two walls and a stray patch
  EXPECT_EQ(high({10000, 300, 250}), 1u);
  EXPECT_EQ(high({10000, 9000, 8000}), 3u);  // three good planes: no clear split
  EXPECT_EQ(high({5, 5, 5}), 3u);
  EXPECT_EQ(high({42}), 1u);
  EXPECT_EQ(high({}), 0u);
  EXPECT_EQ(high({2000, 1000}), 2u);  // a wall with half the floor's points is a wall
  EXPECT_EQ(otsuHighClassSize(std::vector<double>{100, 60}, 0.5), 2u);
  EXPECT_EQ(otsuHighClassSize(std::vector<double>{100, 40}, 0.5), 1u);
}

}  // namespace
}  // namespace plumb::reco
