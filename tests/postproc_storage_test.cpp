// Compact program storage: blocks of fields stored only when written, motion indices
// with the first inline, offsets on the heap only when set, and the one-pass line lexer. Checked
// against hand-written expectations and std containers, not against the code itself.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "compensator/support/error.hpp"
#include "postproc/lexer.hpp"
#include "postproc/program.hpp"

namespace {

using namespace roprec::postproc;
using roprec::Pose;
using roprec::Vec3;

TEST(PostprocStorage, FieldBlockReadsAbsentUntilWrittenAndCopiesDeeply) {
  FieldBlock<6> b;
  const FieldBlock<6>& cb = b;
  EXPECT_FALSE(cb.stored());
  for (const NumberField& f : cb) EXPECT_FALSE(f.present());
  EXPECT_EQ(cb.end() - cb.begin(), 6);
  EXPECT_FALSE(cb.stored());  // reading never allocates
  NumberField f;
  f.file = 0;
  f.value = 12.5;
  b[3] = f;
  EXPECT_TRUE(cb.stored());
  EXPECT_TRUE(cb[3].present());
  EXPECT_DOUBLE_EQ(cb[3].value, 12.5);
  EXPECT_FALSE(cb[2].present());
  FieldBlock<6> copy = b;
  b[3].value = -1.0;
  EXPECT_DOUBLE_EQ(std::as_const(copy)[3].value, 12.5);  // a copy owns its fields
  FieldBlock<6> moved = std::move(copy);
  EXPECT_DOUBLE_EQ(std::as_const(moved)[3].value, 12.5);
}

TEST(PostprocStorage, IndexListBehavesLikeAVector) {
  IndexList l;
  std::vector<int> ref;
  EXPECT_TRUE(l.empty());
  EXPECT_EQ(l.begin(), l.end());
  for (const int v : {7, 3, 11, 0, 42}) {
    l.push_back(v);
    ref.push_back(v);
    ASSERT_EQ(l.size(), ref.size());
    EXPECT_EQ(l.front(), ref.front());
    for (std::size_t k = 0; k < ref.size(); ++k) EXPECT_EQ(l[k], ref[k]);
    std::vector<int> seen;
    for (const int x : l) seen.push_back(x);
    EXPECT_EQ(seen, ref);
  }
  const IndexList copy = l;
  l.push_back(5);
  EXPECT_EQ(copy.size(), 5u);
  EXPECT_EQ(l.size(), 6u);
  EXPECT_EQ(copy[4], 42);
}

TEST(PostprocStorage, SparsePoseIsIdentityUntilSet) {
  SparsePose p;
  EXPECT_TRUE(p.get().matrix().isIdentity(0.0));
  Pose T = Pose::Identity();
  T.translation() = Vec3(0.1, -0.2, 0.3);
  p.set(T);
  const SparsePose q = p;
  p.set(Pose::Identity());
  EXPECT_DOUBLE_EQ(q.get().translation().y(), -0.2);
  EXPECT_TRUE(p.get().matrix().isIdentity(0.0));
}

TEST(PostprocStorage, ProgramRecordsStayCompact) {
  // ~4 targets + 4 motions per drilled hole: a 100,000-hole predict within 200 MB
  EXPECT_LE(sizeof(NumberField), 16u);
  EXPECT_LE(sizeof(Target), 256u);
  EXPECT_LE(sizeof(Configuration), 40u);
  EXPECT_LE(sizeof(Motion), 80u);
}

TEST(PostprocStorage, ANumberLongerThanAFieldHoldsIsRefusedAtItsLine) {
  // a field keeps 16 bits of token length: a longer number is an input error, never a cut span
  const std::string digits = std::string(70000, '0') + "1.5";
  const std::vector<std::pair<Dialect, std::string>> cases = {
      {Dialect::kKrl, "DEF t ( )\n$BASE = {FRAME: X 0,Y 0,Z 0,A 0,B 0,C 0}\nLIN {X " + digits +
                          ",Y 0,Z 0,A 0,B 0,C 0}\nEND\n"},
      {Dialect::kCsv, "name,x,y,z,a,b,c\nP0,1,0,0,0,0,0\nP1," + digits + ",0,0,0,0,0\n"},
      {Dialect::kRapid,
       "MODULE m\nCONST robtarget p:=[[1,2,3],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,"
       "9E9,9E9,9E9]];\nCONST robtarget q:=[[" +
           digits + ",2,3],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\nENDMODULE\n"}};
  for (const auto& [dialect, text] : cases) {
    SCOPED_TRACE(dialectName(dialect));
    try {
      (void)parseProgram(dialect, "long.txt", text);
      ADD_FAILURE() << "a 70,003-character number was read";
    } catch (const roprec::InputError& e) {
      EXPECT_EQ(e.line(), 3);
      EXPECT_NE(e.message().find("a number of 70003 characters (at most 65535)"), std::string::npos)
          << e.what();
    }
  }
  // the longest number a field holds is read
  const Program p =
      parseProgram(Dialect::kCsv, "ok.csv",
                   "name,x,y,z,a,b,c\nP1," + std::string(65532, '0') + "1.5,0,0,0,0,0\n");
  ASSERT_EQ(p.targets().size(), 1u);
  EXPECT_EQ(p.targets()[0].pos[0].length, 65535u);
  EXPECT_DOUBLE_EQ(p.targets()[0].pos[0].value, 1.5);
}

struct Expected {
  std::uint32_t offset;
  std::uint32_t length;
  TokenKind kind;
};

TEST(PostprocStorage, LineLexerSplitsLinesAndTerminators) {
  SourceFile f;
  f.bytes =
      "\xEF\xBB\xBF"
      "A=1.5;c\r\nB 'x'\r\r\n\rLIN";
  f.indexLines();
  LexOptions o;
  o.comment = ';';
  o.single_quote_string = true;
  // line 1: BOM skipped, `A` `=` `1.5` `;c` CRLF
  std::vector<Token> t;
  std::size_t next = lexLine(f, o, 0, t);
  const std::vector<Expected> l1 = {{3, 1, TokenKind::kIdentifier},
                                    {4, 1, TokenKind::kPunct},
                                    {5, 3, TokenKind::kNumber},
                                    {8, 2, TokenKind::kComment},
                                    {10, 2, TokenKind::kNewline}};
  ASSERT_EQ(t.size(), l1.size());
  for (std::size_t k = 0; k < l1.size(); ++k) {
    EXPECT_EQ(t[k].offset, l1[k].offset) << k;
    EXPECT_EQ(t[k].length, l1[k].length) << k;
    EXPECT_EQ(t[k].kind, l1[k].kind) << k;
  }
  EXPECT_EQ(next, 12u);
  // line 2: `B` `'x'` CR CR LF (one terminator)
  t.clear();
  next = lexLine(f, o, next, t);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[1].kind, TokenKind::kString);
  EXPECT_EQ(t[2].offset, 17u);
  EXPECT_EQ(t[2].length, 3u);
  EXPECT_EQ(next, 20u);
  // line 3: a lone CR; line 4 has no terminator
  t.clear();
  next = lexLine(f, o, next, t);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].kind, TokenKind::kNewline);
  t.clear();
  next = lexLine(f, o, next, t);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].offset, 21u);
  EXPECT_EQ(t[0].length, 3u);
  EXPECT_EQ(next, f.bytes.size());
  // the whole-file lexer gives the same tokens in the same order
  lex(f, o);
  EXPECT_EQ(f.tokens.size(), 5u + 3u + 1u + 1u);
}

TEST(PostprocStorage, KrlNamedPositionIsAFrame) {
  // `$BASE = P1` with P1 a POS declaration: the base frame is P1's pose (mm, deg, Z-Y'-X'').
  const std::string src =
      "DEF t( )\n"
      "DECL POS P1={X 100.0,Y -20.0,Z 5.0,A 90.0,B 0.0,C 0.0}\n"
      "$BASE = P1\n"
      "$TOOL = {X 0,Y 0,Z 100,A 0,B 0,C 0}\n"
      "LIN {X 1,Y 2,Z 3,A 0,B 0,C 0}\n"
      "END\n";
  const Program p = parseProgram(Dialect::kKrl, "t.src", src);
  ASSERT_EQ(p.motions.size(), 1u);
  const Frame* base = targetBase(p, p.targets().back());
  ASSERT_NE(base, nullptr);
  EXPECT_TRUE(base->resolved);
  EXPECT_EQ(base->line, 3);  // where $BASE was set
  const Pose& T = base->pose;
  EXPECT_NEAR(T.translation().x(), 0.1, 1e-15);
  EXPECT_NEAR(T.translation().y(), -0.02, 1e-15);
  EXPECT_NEAR(T.translation().z(), 0.005, 1e-15);
  // A = 90 deg about z: x axis -> y axis
  EXPECT_NEAR(T.linear()(1, 0), 1.0, 1e-15);
  EXPECT_NEAR(T.linear()(0, 0), 0.0, 1e-15);
}

}  // namespace
