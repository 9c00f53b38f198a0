// Inline per-hole storage: InlineText (fixed bytes, clipped visibly at a
// UTF-8 boundary, never silently) and InlineVector (fixed capacity, overflow is an error).
// Expected values are written out by hand from the stated rule, not produced by the code.
#include <gtest/gtest.h>

#include <string>

#include "compensator/support/inline_text.hpp"
#include "compensator/support/inline_vector.hpp"
#include "tests/support/counting_new.hpp"

namespace roprec {
namespace {

TEST(InlineText, AppendsAndFormatsLikeStdString) {
  InlineText<64> t;
  EXPECT_TRUE(t.empty());
  t.append("axis ").appendf("%d by %.1f deg", 6, 181.0625);
  EXPECT_EQ(t, "axis 6 by 181.1 deg");
  EXPECT_EQ(t.str(), std::string("axis 6 by 181.1 deg"));
  EXPECT_FALSE(t.clipped());
  EXPECT_NE(t.find("181.1"), std::string::npos);
  t = "short";
  EXPECT_EQ(t.size(), 5u);
}

TEST(InlineText, FillsExactlyToCapacityWithoutClipping) {
  InlineText<8> t;
  t.append("0123").appendf("%s", "4567");
  EXPECT_EQ(t, "01234567");
  EXPECT_FALSE(t.clipped());
}

TEST(InlineText, ClipsVisiblyAtACharacterBoundary) {
  InlineText<10> a;  // 11 bytes: the first 7 kept, then "..."
  a.append("abcdefghijk");
  EXPECT_EQ(a, "abcdefg...");
  EXPECT_TRUE(a.clipped());
  a.append("more");  // nothing after a clip
  EXPECT_EQ(a, "abcdefg...");
  InlineText<10> b;  // "ψ" (2 bytes) cut after its first byte: the whole character goes
  b.append("abcdef\xcf\x88zzz");
  EXPECT_EQ(b, "abcdef...");
  InlineText<10> c;  // "ψ" ends exactly at the 7-byte mark: kept
  c.append("abcde\xcf\x88zzzz");
  EXPECT_EQ(c, "abcde\xcf\x88...");
  InlineText<10> d;  // a formatted text longer than the capacity
  d.appendf("%s-%d", "0123456789", 42);
  EXPECT_EQ(d, "0123456...");
  InlineText<10> e;  // clipped across two appends: the earlier text is cut too
  e.append("012345678").append("9x");
  EXPECT_EQ(e, "0123456...");
}

TEST(InlineText, AllocatesNothing) {
  InlineText<256> r;
  const long n = test::allocationsOf([&] {
    for (int k = 0; k < 100; ++k) {
      r.clear();
      r.appendf("keeping the programmed rotation would turn axis %d by %.1f deg after hole ", 6,
                180.0 + k);
      r.append("T001_12").appendf(" (jump threshold %.1f deg)", 60.0);
    }
  });
  EXPECT_EQ(n, 0);
  EXPECT_EQ(r,
            "keeping the programmed rotation would turn axis 6 by 279.0 deg after hole T001_12 "
            "(jump threshold 60.0 deg)");
}

TEST(InlineVector, HoldsUpToItsCapacityAndRefusesMore) {
  InlineVector<int, 3> v;
  v.reserve(3);
  v.push_back(1);
  v.push_back(2);
  v.push_back(3);
  ASSERT_EQ(v.size(), 3u);
  int sum = 0;
  for (const int x : v) sum += x;
  EXPECT_EQ(sum, 6);
  EXPECT_EQ(v.back(), 3);
  EXPECT_THROW(v.push_back(4), InternalError);
  EXPECT_THROW(v.reserve(4), InternalError);
  EXPECT_THROW((void)v.at(3), InternalError);
  v.clear();
  EXPECT_TRUE(v.empty());
  v = {7, 8};
  EXPECT_EQ(v.size(), 2u);
  EXPECT_EQ(v.at(1), 8);
  EXPECT_THROW((v = {1, 2, 3, 4}), InternalError);
}

}  // namespace
}  // namespace roprec
