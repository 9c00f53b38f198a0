#include "compensator/support/str_cat.hpp"

#include <gtest/gtest.h>

#include <string>
#include <string_view>

namespace roprec {
namespace {

TEST(StrCat, JoinsEveryKindOfPieceInOrder) {
  const std::string a = "joint '";
  const char* b = "a1";
  const std::string_view c = "': unknown";
  EXPECT_EQ(strCat(a, b, c, " link ", std::string("'x'")), "joint 'a1': unknown link 'x'");
  EXPECT_EQ(strCat(), "");
  EXPECT_EQ(strCat(std::string(), ""), "");
}

TEST(StrAppend, AppendsToWhatIsThere) {
  std::string s = "MoveL ";
  strAppend(s, "p10", ",", "v100");
  EXPECT_EQ(s, "MoveL p10,v100");
  std::string t(1000, 'x');  // a long string: the reserve reallocates
  strAppend(t, std::string(2000, 'y'), "z");
  EXPECT_EQ(t.size(), 3001U);
  EXPECT_EQ(t.substr(998, 4), "xxyy");
  EXPECT_EQ(t.back(), 'z');
}

}  // namespace
}  // namespace roprec
