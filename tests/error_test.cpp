// Error texts (compensator/support/error.hpp): numbers in messages are bounded and never
// "nan" or "inf".
#include "compensator/support/error.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace roprec {
namespace {

TEST(Error, NumberTextIsBoundedAndHasNoNanOrInf) {
  EXPECT_EQ(numberText(1e300), "1e+300");
  EXPECT_EQ(numberText(0.1 + 0.2), "0.3");
  EXPECT_EQ(numberText(-2.5), "-2.5");
  EXPECT_EQ(numberText(std::numeric_limits<double>::quiet_NaN()), "not a number");
  EXPECT_EQ(numberText(std::numeric_limits<double>::infinity()), "infinite");
  EXPECT_EQ(numberText(-std::numeric_limits<double>::infinity()), "-infinite");
}

}  // namespace
}  // namespace roprec
