// format_number: what the config errors, `rovctl params` and the ArduSub verdicts print.
#include "hal/primitives/number_format.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace rovctl::hal {
namespace {

TEST(NumberFormat, SixSignificantDigitsWithoutTrailingZeros) {
  EXPECT_EQ(format_number(0.25), "0.25");
  EXPECT_EQ(format_number(33.0), "33");
  EXPECT_EQ(format_number(-1.5), "-1.5");
  EXPECT_EQ(format_number(1234567.0), "1.23457e+06");
  EXPECT_EQ(format_number(1e-7), "1e-07");
  EXPECT_EQ(format_number(0.1 + 0.2), "0.3");
}

TEST(NumberFormat, AFloatReadsAsItsValue) {
  EXPECT_EQ(format_number(0.1F), "0.1");
  EXPECT_EQ(format_number(2.0F), "2");
}

TEST(NumberFormat, InfinityAndNaN) {
  EXPECT_EQ(format_number(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(format_number(-std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(format_number(std::numeric_limits<double>::quiet_NaN()), "nan");
}

}  // namespace
}  // namespace rovctl::hal
