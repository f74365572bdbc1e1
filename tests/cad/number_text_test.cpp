#include "cad/number_text.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <limits>

#include "engine/core/random.h"

namespace plumb::cad {
namespace {

TEST(CadNumberText, ShortestFixedDecimalWithAPoint) {
  EXPECT_EQ(numberText(512000.1), "512000.1");
  EXPECT_EQ(numberText(250.0), "250.0");
  EXPECT_EQ(numberText(-0.0), "-0.0");
  EXPECT_EQ(numberText(1e-7), "0.0000001");
  EXPECT_EQ(numberText(5403000.987654321), "5403000.987654321");
  EXPECT_EQ(numberText(1e21).find('e'), std::string::npos) << "no exponent";
  const std::string tiny = numberText(std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(tiny.find('e'), std::string::npos);
  EXPECT_EQ(std::strtod(tiny.c_str(), nullptr), std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(std::strtod(numberText(std::numeric_limits<double>::max()).c_str(), nullptr),
            std::numeric_limits<double>::max());
}

// UTM coordinates come back bit for bit, whatever their digits.
TEST(CadNumberText, UtmCoordinatesReadBackExactly) {
  Random random(7);
  for (int i = 0; i < 10000; ++i) {
    const double x = 500000.0 + 1e6 * random.uniform();
    const std::string text = numberText(x);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), x) << text;
    EXPECT_LE(text.size(), 18u) << "no padding beyond a double's 17 significant digits";
  }
}

}  // namespace
}  // namespace plumb::cad
