// The JSON writer (plugin/report/json.hpp): a non-finite number is an internal error naming its
// path, never "null", "nan" or "inf" in the output.
#include "plugin/report/json.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "compensator/support/error.hpp"

namespace roprec {
namespace {

TEST(Json, NeverWritesNonFiniteNumbers) {
  api::Json root = api::Json::object();
  api::Json holes = api::Json::array();
  api::Json h = api::Json::object();
  h.set("id", api::Json::str("T001"));
  h.set("x_mm", api::Json::number(std::numeric_limits<double>::quiet_NaN(), 3));
  holes.push(api::Json::object());
  holes.push(h);
  root.set("holes", holes);
  try {
    (void)root.dump();
    FAIL() << "a NaN was written";
  } catch (const InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("$.holes[1].x_mm"), std::string::npos) << e.what();
  }
  api::Json inf = api::Json::array();
  inf.push(api::Json::number(std::numeric_limits<double>::infinity()));
  EXPECT_THROW((void)inf.dump(), InternalError);
  // formatNumber never produces "null"/"nan"/"inf", and huge numbers do not overflow it
  EXPECT_EQ(api::formatNumber(std::numeric_limits<double>::quiet_NaN(), 3), "not a number");
  EXPECT_EQ(api::formatNumber(1e300, 2).size(), 301u + 3u);
}

}  // namespace
}  // namespace roprec
