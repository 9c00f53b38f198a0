// The reports' element builder: escaping of text and attributes in one place, locale-free numbers.
#include "plugin/report/html.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace roprec::report {
namespace {

TEST(Html, TextAndAttributeValuesFromInputsAreEscaped) {
  std::string o;
  Html h(o);
  h.element("td", {{"title", "a<b & \"c\" 'd'"}}, "<script>x</script> & y");
  EXPECT_EQ(o,
            "<td title=\"a&lt;b &amp; &quot;c&quot; &#39;d&#39;\">&lt;script&gt;x&lt;/script&gt; "
            "&amp; y</td>");
}

TEST(Html, MarkupIsWrittenAsItIs) {
  std::string o;
  Html h(o);
  h.open("p", {Attr::markup("style", "width:5%")}).markup("U<sub>95</sub> &amp;").close("p");
  EXPECT_EQ(o, "<p style=\"width:5%\">U<sub>95</sub> &amp;</p>");
}

TEST(Html, LeafElementsAndAttributeOrder) {
  std::string o;
  Html h(o);
  h.leaf("line", {{"x1", fixed(1.25, 1)}, {"y1", fixed(-0.04, 1)}, {"n", 7}, {"k", size_t{3}}});
  // 1.25 is exactly representable: round half to even, as std::to_chars does
  EXPECT_EQ(o, "<line x1=\"1.2\" y1=\"0.0\" n=\"7\" k=\"3\"/>");
}

TEST(Html, NumbersHaveFixedDecimalsNoNegativeZeroAndADashForNonFinite) {
  EXPECT_EQ(num(2.0 / 3.0, 3), "0.667");
  EXPECT_EQ(num(-0.0004, 3), "0.000");
  EXPECT_EQ(num(-12.5, 0), "-12");
  EXPECT_EQ(num(std::numeric_limits<double>::quiet_NaN(), 2), kDash);
  EXPECT_EQ(num(std::numeric_limits<double>::infinity(), 2), kDash);
}

TEST(Html, SvgPointsJoinCoordinatePairs) {
  const std::vector<Eigen::Vector2d> pts{{1.0, 2.0}, {3.25, -4.5}};
  EXPECT_EQ(svgPoints(pts, 2), "1.00,2.00 3.25,-4.50");
  EXPECT_EQ(svgPoints(std::vector<Eigen::Vector2d>{}, 1), "");
}

}  // namespace
}  // namespace roprec::report
