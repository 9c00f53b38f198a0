// The readers' fast paths against independent references: parseNumber's exact decimal path
// against std::strtod (correctly rounded in glibc), NameMap against std::map on upper-cased keys,
// SourceFile::indexLines against line ends counted by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <random>
#include <string>

#include "postproc/lexer.hpp"
#include "postproc/program.hpp"
#include "tests/support/test_support.hpp"

namespace {

using roprec::postproc::LineEnd;
using roprec::postproc::NameMap;
using roprec::postproc::parseNumber;
using roprec::postproc::SourceFile;

double strtodRef(const std::string& s) { return std::strtod(s.c_str(), nullptr); }

using roprec::test::sameBits;

TEST(ParseNumber, DecimalsMatchStrtodBitForBit) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> ndig(1, 19);
  std::uniform_int_distribution<int> digit(0, 9);
  for (int trial = 0; trial < 200000; ++trial) {
    const int n = ndig(rng);
    std::string s;
    for (int i = 0; i < n; ++i) s += static_cast<char>('0' + digit(rng));
    const int point = std::uniform_int_distribution<int>(-1, n)(rng);  // -1: none
    if (point >= 0) s.insert(static_cast<std::size_t>(point), ".");
    if (trial % 3 == 0) s.insert(0, "-");
    if (s == "." || s == "-.") continue;
    const auto v = parseNumber(s);
    ASSERT_TRUE(v.has_value()) << s;
    ASSERT_TRUE(sameBits(*v, strtodRef(s))) << s << " " << *v << " vs " << strtodRef(s);
  }
}

TEST(ParseNumber, EdgeForms) {
  for (const char* s : {"0.0", "-0.0", "5.", ".5", "-.5", "+1.25", "000123.4500", "1e3", "-2.5E-3",
                        "123456789012345", "1234567890123456", "0.1234567890123456789012",
                        "0.00000000000000000000001", "9007199254740993", "- 12.5"}) {
    const auto v = parseNumber(s);
    ASSERT_TRUE(v.has_value()) << s;
    std::string ref(s);
    ref.erase(std::remove(ref.begin(), ref.end(), ' '), ref.end());
    EXPECT_TRUE(sameBits(*v, strtodRef(ref))) << s;
  }
  EXPECT_TRUE(std::signbit(*parseNumber("-0.000")));
  for (const char* s : {"", ".", "-", "1.2.3", "12a", "1e", "abc", "1,5", "nan", "inf"})
    EXPECT_FALSE(parseNumber(s).has_value()) << s;
}

TEST(NameMap, CaseInsensitiveLikeStdMapOnUpperKeys) {
  std::vector<std::string> names;  // the map keeps views: the bytes outlive it
  std::mt19937 rng(3);
  const std::string alphabet = "abcXYZ_$019";
  for (int i = 0; i < 20000; ++i) {
    std::string s;
    const int len = 1 + static_cast<int>(rng() % 6);
    for (int k = 0; k < len; ++k) s += alphabet[rng() % alphabet.size()];
    names.push_back(s);
  }
  NameMap<int> m;
  std::map<std::string, int> ref;
  for (std::size_t i = 0; i < names.size(); ++i) {
    m[names[i]] = static_cast<int>(i);
    ref[roprec::postproc::upper(names[i])] = static_cast<int>(i);
  }
  EXPECT_EQ(m.size(), ref.size());
  for (const auto& [key, value] : ref) {
    std::string lower = key;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const int* v = m.find(lower);
    ASSERT_NE(v, nullptr) << key;
    EXPECT_EQ(*v, value) << key;
  }
  EXPECT_EQ(m.find("not-a-name"), nullptr);
  EXPECT_EQ(NameMap<int>().find("X"), nullptr);
}

TEST(TextTable, SharesShortTextsKeepsIdsAcrossCopies) {
  roprec::postproc::TextTable t;
  EXPECT_EQ(t.add("").index, 0u);
  EXPECT_EQ(t[roprec::postproc::TextId{}], "");
  std::vector<roprec::postproc::TextId> ids;
  for (int i = 0; i < 5000; ++i) ids.push_back(t.add("T" + std::to_string(i % 700)));
  for (int i = 0; i < 5000; ++i) {
    EXPECT_EQ(t[ids[static_cast<std::size_t>(i)]], "T" + std::to_string(i % 700));
    EXPECT_EQ(ids[static_cast<std::size_t>(i)].index, ids[static_cast<std::size_t>(i % 700)].index);
  }
  EXPECT_EQ(t.size(), 701u);  // "" and the 700 distinct texts
  const std::string longer(40, 'x');
  const auto a = t.add(longer);
  const auto b = t.add(longer);  // long texts are appended, not looked up
  EXPECT_NE(a.index, b.index);
  EXPECT_EQ(t[a], longer);
  EXPECT_GT(t.append("T5").index, ids[5].index);  // append: a new entry even for a known text
  const roprec::postproc::TextTable copy = t;     // the copy's index points into its own texts
  EXPECT_EQ(copy[ids[42]], "T42");
  roprec::postproc::TextTable c2 = copy;
  EXPECT_EQ(c2.add("T42").index, ids[42].index);
  EXPECT_EQ(c2[c2.add("new")], "new");
}

TEST(Program, MarkersAreOneRunPerMotion) {
  roprec::postproc::Program p;
  p.addMarker("before any motion");  // ignored: no motion to attach it to
  p.motions.emplace_back();
  p.motions.emplace_back();
  p.addMarker("dwell 0.3 s");
  p.addMarker("call DRILL()");
  p.motions.emplace_back();
  p.motions.emplace_back();
  p.addMarker("dwell 0.3 s");
  const std::vector<std::vector<std::string>> want{
      {}, {"dwell 0.3 s", "call DRILL()"}, {}, {"dwell 0.3 s"}};
  for (std::size_t k = 0; k < p.motions.size(); ++k) {
    std::vector<std::string> got;
    for (const std::string& m : p.markers(p.motions[k])) got.push_back(m);
    EXPECT_EQ(got, want[k]) << k;
  }
  EXPECT_EQ(p.marker_texts.size(), 3u);
}

TEST(IndexLines, TerminatorsAndFractionStyle) {
  SourceFile f;
  f.bytes = "a\nb\r\nc\r\r\nd\re x .5";
  f.indexLines();
  const std::vector<std::uint32_t> starts{0, 2, 5, 9, 11};
  const std::vector<LineEnd> ends{LineEnd::kLf, LineEnd::kCrLf, LineEnd::kCrCrLf, LineEnd::kCr,
                                  LineEnd::kNone};
  EXPECT_EQ(f.line_starts, starts);
  EXPECT_EQ(f.line_ends, ends);
  EXPECT_TRUE(f.bare_fractions);
  EXPECT_FALSE(f.zero_fractions);
  EXPECT_EQ(f.lineOf(10), 4);
  SourceFile g;
  g.bytes = "x 0.000 y 10.5\n";
  g.indexLines();
  EXPECT_FALSE(g.zero_fractions);  // an exact 0.000 says nothing; 10.5 has no leading zero
  EXPECT_FALSE(g.bare_fractions);
  g.bytes = "x 0.044\n";
  g.indexLines();
  EXPECT_TRUE(g.zero_fractions);
  EXPECT_EQ(g.line_starts.size(), 1u);
}

}  // namespace
