// A program read a window at a time (postproc/program_stream.cpp), its motions retired behind the
// hole recogniser, gives the holes of the program read whole (readProgram + recognizeHoles): the
// same ids, points, axes, depths, frames, lines and evidence, whatever its line ends, while the
// window holds a bounded number of motions. Errors are readProgram's, in its order (a reader's
// error before a value out of range met earlier), also when each next window is read and lexed
// ahead on a task of its own, its motion lines' target aggregates parsed there as the reader
// parses them.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "compensator/support/error.hpp"
#include "postproc/dialects.hpp"
#include "postproc/drill.hpp"
#include "postproc/program_stream.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

/// A hole with what it refers to resolved (indices differ between a window and the whole).
struct SeenHole {
  std::string id;
  Vec3 position;
  Vec3 axis;
  Vec3 surface;
  double depth{0};
  int bottom_line{0};
  int base{-1};
  int tool{-1};
  std::string evidence;
};

SeenHole seen(const postproc::Program& p, const postproc::Hole& h) {
  return {h.id,      h.position, h.axis,
          h.surface, h.depth,    p.motions[static_cast<size_t>(h.bottom_motion)].line,
          h.base,    h.tool,     postproc::drillingEvidence(p, h)};
}

struct Streamed {
  std::vector<SeenHole> holes;
  size_t max_window_motions{0};
};

/// Reads `path` by windows of `window` bytes, retiring the motions before the last hole's bottom;
/// `ahead`: each next window read and lexed on a task of its own (ProgramStream's read_ahead).
/// `skip_ranges`: a second reading (ProgramStream::skipValueRanges).
Streamed readStreamed(const std::string& path, size_t window, bool ahead = false,
                      bool skip_ranges = false) {
  Streamed out;
  postproc::ProgramStream s(path, window, ahead);
  if (skip_ranges) s.skipValueRanges();
  postproc::HoleRecognizer rec;
  auto take = [&] {
    const postproc::Program& p = s.program();
    std::vector<postproc::Hole> holes = rec.take();
    for (const postproc::Hole& h : holes) out.holes.push_back(seen(p, h));
    out.max_window_motions = std::max(out.max_window_motions, p.motions.size());
    if (holes.empty()) return;
    const size_t keep = std::min(static_cast<size_t>(holes.back().bottom_motion),
                                 rec.nextMotion() > 0 ? rec.nextMotion() - 1 : 0);
    const postproc::Retired r = s.retire(keep);
    rec.retired(r.motions, r.target_begin, r.target_end);
  };
  while (s.next()) {
    rec.advance(s.program(), false);
    take();
  }
  rec.advance(s.program(), true);
  take();
  return out;
}

std::vector<SeenHole> readWhole(const std::string& path) {
  const postproc::Program p = postproc::readProgram(path);
  std::vector<SeenHole> out;
  for (const postproc::Hole& h : postproc::recognizeHoles(p)) out.push_back(seen(p, h));
  return out;
}

TEST(ProgramStream, WindowsWithRetiredMotionsGiveTheHolesOfTheWholeProgram) {
  const std::string dir = test::tempDir("program_stream");
  const std::string big = test::krlDrillCycles(300, test::kHousingBase, true);
  test::writeFile(dir + "/big.src", big);
  // the same lines ended by CR LF (a window ends after LF) and by CR alone (no LF: one window)
  std::string crlf;
  std::string cr;
  for (const char c : big) {
    crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    cr += c == '\n' ? '\r' : c;
  }
  test::writeFile(dir + "/crlf.src", crlf);
  test::writeFile(dir + "/cr.src", cr);
  std::vector<std::string> programs = {dir + "/big.src", dir + "/crlf.src", dir + "/cr.src"};
  for (const char* f : {"housing_kr120.src", "housing_irb6640.mod", "housing_r2000.ls"})
    programs.push_back(test::sourceDir() + "/samples/emotor-housing/" + f);
  if (const std::string corpus = test::corpusDir(); !corpus.empty()) {
    for (const char* f : {"DRILLR30IA.LS", "DrillIRC5.mod", "DrillKRC2DAT.src", "DrillKRC4.src"})
      programs.push_back(corpus + "/robodk/" + f);
  }
  for (const std::string& path : programs) {
    SCOPED_TRACE(path);
    const std::vector<SeenHole> whole = readWhole(path);
    ASSERT_FALSE(whole.empty());
    for (const auto& [window, ahead] :
         {std::pair{size_t{4096}, false}, std::pair{size_t{4096}, true},
          std::pair{size_t{10000}, false}, std::pair{size_t{10000}, true},
          std::pair{postproc::ProgramStream::kWindowBytes, false}}) {
      SCOPED_TRACE(std::to_string(window) + (ahead ? " read ahead" : ""));
      const Streamed st = readStreamed(path, window, ahead);
      ASSERT_EQ(st.holes.size(), whole.size());
      for (size_t i = 0; i < whole.size(); ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(st.holes[i].id, whole[i].id);
        EXPECT_EQ(st.holes[i].position, whole[i].position);
        EXPECT_EQ(st.holes[i].axis, whole[i].axis);
        EXPECT_EQ(st.holes[i].surface, whole[i].surface);
        EXPECT_EQ(st.holes[i].depth, whole[i].depth);
        EXPECT_EQ(st.holes[i].bottom_line, whole[i].bottom_line);
        EXPECT_EQ(st.holes[i].base, whole[i].base);
        EXPECT_EQ(st.holes[i].tool, whole[i].tool);
        EXPECT_EQ(st.holes[i].evidence, whole[i].evidence);
      }
    }
  }
  // 300 cycles of 4 motions in 4 kB windows: the window never holds more than a few cycles'
  const Streamed st = readStreamed(dir + "/big.src", 4096);
  EXPECT_LT(st.max_window_motions, 200U);
}

/// What a motion and its targets read to, without file offsets (a window's are its own).
std::string motionText(const postproc::Program& p, const postproc::Motion& m) {
  std::string s = std::to_string(static_cast<int>(m.type)) + " line " + std::to_string(m.line) +
                  (m.fine ? " fine" : "") + (m.config_honoured ? " conf" : "") + " v " +
                  std::to_string(m.speed_mm_s) + " [" + p.text(m.instruction) + "|" +
                  p.text(m.zone_text) + "|" + p.text(m.target_text) + "|" + p.text(m.derivation) +
                  "|" + p.text(m.speed_text) + "] markers " + std::to_string(m.marker_count);
  const auto fields = [&s](const auto& block, std::size_t n) {
    for (std::size_t k = 0; k < n; ++k) {
      const postproc::NumberField& f = block[k];
      s += f.present() ? " " + std::to_string(f.value) + "/" + std::to_string(f.length) : " -";
    }
  };
  for (const int t : {m.aux, m.target}) {
    if (t < 0) continue;
    const postproc::Target& tg = p.targets()[static_cast<size_t>(t)];
    s += " {" + tg.name + " kind " + std::to_string(static_cast<int>(tg.kind)) + " orient " +
         std::to_string(static_cast<int>(tg.orientation)) + " line " + std::to_string(tg.line) +
         " S " + std::to_string(tg.config.status) + " T " + std::to_string(tg.config.turn);
    fields(tg.pos, 3);
    fields(tg.rot, 4);
    fields(tg.joints, 6);
    fields(tg.ext, 6);
    fields(tg.config_fields, 2);
    s += "}";
  }
  return s;
}

/// What the reader tells of the program's first file besides its motions (the style a writer
/// keeps).
std::string fileText(const postproc::Program& p) {
  return std::string("significant9 ") + (p.files[0].significant9 ? "yes" : "no");
}

/// Every motion of `path` read by windows of `window` bytes (none retired), as motionText.
std::vector<std::string> streamedMotions(const std::string& path, size_t window, bool ahead) {
  postproc::ProgramStream s(path, window, ahead);
  while (s.next()) {
  }
  std::vector<std::string> out;
  for (const postproc::Motion& m : s.program().motions) out.push_back(motionText(s.program(), m));
  out.push_back(fileText(s.program()));
  return out;
}

/// KRL motion lines of every target shape the reader parses: joint and Cartesian aggregates,
/// typed or not, signed numbers (a space after the sign), exponents, literals, CIRC's two
/// targets (and a third expression), WITH lists, a relative motion, a `:` expression, lower case,
/// GLOBAL, trailing comments, and a position of 9 significant digits in the last window.
std::string krlTargetShapes(int n) {
  std::string s = "DEF shapes()\n" + std::string(test::kHousingBase) + "\n$VEL.CP = 0.2\n";
  for (int i = 0; i < n; ++i) {
    const std::string x = std::to_string(i % 97) + "." + std::to_string(i % 7);
    s += "PTP {A1 " + x + ",A2 -90,A3 90,A4 0,A5 " + x + ",A6 0}\n";
    s += "PTP {E6POS: X " + x + ",Y -2,Z 300,A 0,B 90,C 180,S 'B010',T 2,E1 0} C_PTP\n";
    s += "LIN {X 1, Y " + x + ", Z 3, A 0, B 0, C 0} C_DIS ; a comment {X 9}\n";
    s += "LIN {X - 5,Y +" + x + ",Z 7.25e1,A 0,B 0,C 0}\n";
    s += "CIRC {X 1,Y 2,Z 3},{X " + x + ",Y 5,Z 6,A 0,B 0,C 0} C_VEL\n";
    s += "SLIN {X 1,Y 2,Z " + x + ",A 0,B 0,C 0} WITH $VEL.CP = 0.1 C_SPL\n";
    s += "LIN_REL {X " + x + "} C_DIS\n";
    s += "lin {x 1,y 2,z " + x + ",a 4,b 5,c 6}\n";
    s += "PTP {POS: X 1,Y 2,Z 3,A 0,B 0,C 0,S 6,T 27}\n";
    s += "LIN {X 1,Y 2,Z 3,A 0,B 0,C 0}:{X " + x + ",Y 0,Z 10,A 0,B 0,C 0}\n";
    s += "SPTP {A1 10,A2 -80,A3 80,A4 0,A5 10,A6 0, E1 " + x + "}\n";
    s += "LIN {X 1,Y 2,Z 3,A 0,B 0,C 0,S 2,T 35}  C_DIS  ; " + x + "\n";
    s += "CIRC {X 1,Y 2,Z 3},{X " + x + ",Y 5,Z 6,A 0,B 0,C 0},{X 7} C_DIS\n";
    s += "LIN {X 1,Y 2,Z 3,A 0,B 0,C 0} WITH $APO.CDIS = 2, $VEL.CP = 0.3 C_DIS\n";
    s += "GLOBAL LIN {X 1,Y 2,Z " + x + ",A 0,B 0,C 0}\n";
    if (i + 1 == n) s += "LIN {X 1234.56789,Y 2,Z 3,A 0,B 0,C 0}\n";  // 9 digits, far in
  }
  return s + "END\n";
}

TEST(ProgramStream, TargetsReadAheadAreThoseTheReaderReads) {
  // the read-ahead (KrlStream::lexWindow) parses the motion lines' target aggregates on a task
  // of its own; the reader takes them instead of parsing them again: every motion and target
  // reads as in the program read whole, on real programs and on every target shape
  const std::string dir = test::tempDir("program_stream_ahead");
  std::vector<std::string> programs = {dir + "/shapes.src"};
  test::writeFile(programs[0], krlTargetShapes(120));
  for (const char* f :
       {"emotor-housing/housing_kr120.src", "emotor-housing/housing_kr120_tools.src",
        "verification/test_kr120.src", "verification/geometry_kr120.src", "milling/wall_pass.src",
        "milling/box_passes.src"})
    programs.push_back(test::sourceDir() + "/samples/" + f);
  if (const std::string corpus = test::corpusDir(); !corpus.empty()) {
    for (const char* f : {"DrillKRC2DAT.src", "DrillKRC4.src"})
      programs.push_back(corpus + "/robodk/" + f);
  }
  for (const std::string& path : programs) {
    SCOPED_TRACE(path);
    const postproc::Program whole = postproc::readProgram(path);
    std::vector<std::string> expected;
    for (const postproc::Motion& m : whole.motions) expected.push_back(motionText(whole, m));
    ASSERT_FALSE(expected.empty());
    expected.push_back(fileText(whole));
    for (const size_t window : {size_t{4096}, size_t{10000}}) {
      SCOPED_TRACE(window);
      EXPECT_EQ(streamedMotions(path, window, true), expected);
      EXPECT_EQ(streamedMotions(path, window, false), expected);
    }
  }
  // the read-ahead does read the aggregates (the reader would otherwise read them alone): one
  // per target expression of the shapes' motion lines, none for a line that is not a motion
  postproc::SourceFile w;
  w.bytes = "LIN {X 1,Y 2}\nCIRC {X 1},{Y 2} C_DIS\n$BASE = {X 1}\nPTP {X 1\nPTP XP1\n";
  w.indexLines();
  std::shared_ptr<postproc::KrlAhead> a;
  postproc::KrlStream::lexWindow(w, a);
  EXPECT_EQ(postproc::aggregatesReadAhead(*a), 3U);
  EXPECT_EQ(postproc::targetsReadAhead(*a), 3U);  // each makes its target
  // an aggregate that reads but makes no target (a literal where a number belongs) is left to
  // the reader, which stops there with its error
  w.bytes = "LIN {X 'B01',Y 2}\nLIN {X 1,Y 2}\n";
  w.indexLines();
  postproc::KrlStream::lexWindow(w, a);
  EXPECT_EQ(postproc::aggregatesReadAhead(*a), 2U);
  EXPECT_EQ(postproc::targetsReadAhead(*a), 1U);
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ProgramStream, ErrorsAreThoseOfTheWholeReadInItsOrder) {
  const std::string dir = test::tempDir("program_stream_errors");
  const std::string cycles = test::krlDrillCycles(200, test::kHousingBase, true);
  // a value out of range in the first window, the END missing far after it: the reader's error
  std::string bad = cycles;
  const size_t z = bad.find("Z ", bad.find("LIN {"));
  ASSERT_NE(z, std::string::npos);
  bad.insert(z + 2, "9");
  bad.insert(z + 3, "99999");
  const size_t end = bad.rfind("END");
  ASSERT_NE(end, std::string::npos);
  const std::string truncated = bad.substr(0, end);
  // a NUL byte far into the file (a read error of a later window), an aggregate left open there
  std::string nul = cycles;
  nul.insert(nul.rfind("LIN {"), std::string(1, '\0'));
  std::string open = cycles;
  open.erase(open.find('}', open.rfind("LIN {")), 1);
  for (const auto& [name, text] : {std::pair<std::string, std::string>{"range.src", bad},
                                   {"truncated.src", truncated},
                                   {"nul.src", nul},
                                   {"open.src", open}}) {
    SCOPED_TRACE(name);
    const std::string path = dir + "/" + name;
    test::writeFile(path, text);
    const std::string whole = errorOf([&] { (void)postproc::readProgram(path); });
    ASSERT_NE(whole, "(no error)");
    EXPECT_EQ(errorOf([&] { (void)readStreamed(path, 4096); }), whole);
    EXPECT_EQ(errorOf([&] { (void)readStreamed(path, 4096, true); }), whole);
    // a second reading (the first one checked the values) stops at the reader's errors alone
    const std::string second = errorOf([&] { (void)readStreamed(path, 4096, true, true); });
    EXPECT_EQ(second, name == "range.src" ? "(no error)" : whole);
  }
}

/// motionText, and the frames, markers and configuration numbers a motion refers to.
std::string rapidMotionText(const postproc::Program& p, const postproc::Motion& m) {
  std::string s = motionText(p, m);
  for (const int t : {m.target, m.aux}) {
    if (t < 0) continue;
    for (const postproc::NumberField& f : p.targets()[static_cast<size_t>(t)].cf_fields)
      s += " cf " + std::to_string(f.value) + "/" + p.exprText(f);
  }
  for (const int f : {m.tool, m.base}) {
    if (f < 0) continue;
    const postproc::Frame& fr = p.frames[static_cast<size_t>(f)];
    s += " frame " + fr.ref + (fr.resolved ? " resolved" : "") + " line " + std::to_string(fr.line);
    for (int k = 0; k < 12; ++k) s += " " + std::to_string(fr.pose.matrix()(k / 4, k % 4));
  }
  for (const std::string& mk : p.markers(m)) s += " marker " + mk;
  return s;
}

/// The motions, then the unresolved references and notes, of a program.
std::vector<std::string> programText(const postproc::Program& p,
                                     const std::vector<std::string>& motions) {
  std::vector<std::string> out = motions;
  for (const postproc::Unresolved& u : p.unresolved)
    out.push_back("unresolved " + u.ref + "@" + std::to_string(u.line) + ": " + u.what);
  for (const std::string& n : p.notes) out.push_back("note " + n);
  return out;
}

/// The first entry where `a` and `b` differ ("" when they are equal).
std::string firstDifference(const std::vector<std::string>& a, const std::vector<std::string>& b) {
  for (size_t k = 0; k < std::max(a.size(), b.size()); ++k) {
    const std::string x = k < a.size() ? a[k] : "(none)";
    const std::string y = k < b.size() ? b[k] : "(none)";
    if (x != y) return "entry " + std::to_string(k) + ":\n  " + x + "\n  " + y;
  }
  return "";
}

std::vector<std::string> rapidWhole(const std::string& path) {
  const postproc::Program p = postproc::readProgram(path);
  std::vector<std::string> motions;
  for (const postproc::Motion& m : p.motions) motions.push_back(rapidMotionText(p, m));
  return programText(p, motions);
}

/// `path` read by windows of `window` bytes (RAPID and TP too), every settled motion but the last
/// retired after each window; `most`: the most targets a window held, `most_motions` the most
/// motions.
std::vector<std::string> rapidStreamed(const std::string& path, size_t window, size_t* most,
                                       size_t* most_motions = nullptr) {
  postproc::ProgramStream s(path, window, false, true);
  std::vector<std::string> motions;
  size_t done = 0;  // the window's motions described
  while (s.next()) {
    const postproc::Program& p = s.program();
    if (most != nullptr) *most = std::max(*most, p.targets().size());
    if (most_motions != nullptr) *most_motions = std::max(*most_motions, p.motions.size());
    // the last motion may get a marker of the next window yet
    // (TP: the motions bound to their positions so far)
    for (; done + 1 < p.motions.size() && done < s.settledMotions(); ++done)
      motions.push_back(rapidMotionText(p, p.motions[done]));
    done -= s.retire(done).motions;
  }
  const postproc::Program& p = s.program();
  for (; done < p.motions.size(); ++done) motions.push_back(rapidMotionText(p, p.motions[done]));
  EXPECT_TRUE(s.windowed()) << path;
  return programText(p, motions);
}

/// The most targets and motions a window held.
struct WindowHeld {
  size_t targets{0};
  size_t motions{0};
};

/// Each of `programs`, and the corpus's `corpus_program`, read by windows of 4 KB and 10 KB:
/// the whole read's motions, unresolved references and notes; `held` checks what its windows
/// held.
void expectWindowsReadAsTheWhole(
    std::vector<std::string> programs, const std::string& corpus_program,
    const std::function<void(const std::string&, size_t, const WindowHeld&)>& held) {
  if (const std::string corpus = test::corpusDir(); !corpus.empty())
    programs.push_back(corpus + "/" + corpus_program);
  for (const std::string& path : programs) {
    SCOPED_TRACE(path);
    const std::vector<std::string> whole = rapidWhole(path);
    ASSERT_GT(whole.size(), 10U);
    for (const size_t window : {size_t{4096}, size_t{10000}}) {
      WindowHeld most;
      EXPECT_EQ(firstDifference(whole, rapidStreamed(path, window, &most.targets, &most.motions)),
                "")
          << "window " << window;
      held(path, window, most);
    }
  }
}

// An ABB RAPID module read by windows of 4 KB (statements over two lines cut by a window's end,
// targets declared before and after their motions, markers, a statement longer than two
// windows after a %%% header) and of 10 KB, its motions retired
// window by window: the motions, targets, frames, unresolved references and notes of the whole
// read, in its order; the inline targets go with their motions (a window holds the declared
// ones and a window's worth of the others).
TEST(ProgramStream, RapidModuleByWindowsReadsAsTheWholeModule) {
  const std::string dir = test::tempDir("program_stream_rapid");
  test::writeFile(dir + "/wall.mod", test::rapidWallPass(600));
  // a statement longer than two windows (comment lines inside it) after the %%% header
  std::string padded = test::rapidWallPass(100);
  std::string comments;
  for (int k = 0; k < 300; ++k) comments += "      ! a comment line inside a statement\n";
  padded.insert(padded.find("v60", padded.find("MoveL [[")), comments + "      ");
  test::writeFile(dir + "/long.mod", "%%%\n  VERSION:1\n  LANGUAGE:ENGLISH\n%%%\n\n" + padded);
  expectWindowsReadAsTheWhole({dir + "/wall.mod", dir + "/long.mod",
                               test::sourceDir() + "/samples/emotor-housing/housing_irb6640.mod"},
                              "robodk/DrillIRC5.mod",
                              [&](const std::string& path, size_t window, const WindowHeld& held) {
                                if (path != dir + "/wall.mod") return;
                                EXPECT_LT(held.targets, 300U + 90U) << "window " << window;
                              });
}

/// Each faulty program (file name, text), written to `dir` and read by windows of every size in
/// `windows`, gives the error of its whole read.
void expectStreamedErrorsOfTheWholeRead(
    const std::string& dir, const std::vector<std::pair<std::string, std::string>>& programs,
    const std::vector<size_t>& windows) {
  for (const auto& [name, text] : programs) {
    SCOPED_TRACE(name);
    const std::string path = dir + "/" + name;
    test::writeFile(path, text);
    const std::string whole = errorOf([&] { (void)postproc::readProgram(path); });
    ASSERT_NE(whole, "(no error)");
    for (const size_t window : windows)
      EXPECT_EQ(errorOf([&] { (void)rapidStreamed(path, window, nullptr); }), whole) << window;
  }
}

/// Faulty RAPID modules from a wall pass of `points` points: a missing ';', an aggregate of the
/// wrong shape and a truncated module far into the file, a module without MODULE; a value out of
/// range in the first window before a reader's error in a later one (the reader's error, as the
/// whole read gives it), a motion's before a target's (the target's). Each read by windows of
/// every size in `windows` gives the whole read's error.
void expectRapidErrorsOfTheWholeRead(const std::string& dir, int points,
                                     const std::vector<size_t>& windows) {
  const std::string wall = test::rapidWallPass(points);
  const size_t late = wall.rfind("MoveL p");
  std::string semicolon = wall;
  semicolon.erase(semicolon.find(';', late), 1);
  std::string shape = wall;
  shape.replace(shape.find("[0,1,0,0]", late), 9, "[0,1,0]");
  std::string range = shape;
  range.replace(range.find("[0,1,0,0]"), 9, "[0,2,0,0]");
  // a speed out of range in the first window, a quaternion far after it: the quaternion (the
  // whole read checks the targets before the motions)
  std::string kinds = wall;
  kinds.replace(kinds.find("v60"), 3, "v99999");
  kinds.replace(kinds.find("[0,1,0,0]", kinds.rfind("MoveL [[")), 9, "[0,2,0,0]");
  const std::string truncated = wall.substr(0, wall.rfind("ENDMODULE"));
  std::string nomodule = wall;
  nomodule.erase(0, nomodule.find('\n') + 1);
  nomodule.erase(nomodule.rfind("ENDMODULE"));
  expectStreamedErrorsOfTheWholeRead(dir,
                                     {{"semicolon.mod", semicolon},
                                      {"shape.mod", shape},
                                      {"range.mod", range},
                                      {"kinds.mod", kinds},
                                      {"truncated.mod", truncated},
                                      {"nomodule.mod", nomodule}},
                                     windows);
}

// RAPID errors by windows of 4 KB (expectRapidErrorsOfTheWholeRead) on a 400-point module.
TEST(ProgramStream, RapidErrorsAreThoseOfTheWholeRead) {
  expectRapidErrorsOfTheWholeRead(test::tempDir("program_stream_rapid_errors"), 400, {4096});
}

// The same errors by windows of 20 sizes from 16 bytes (a window a fraction of a statement) to 3 KB
// (the whole module), on a 40-point module: a window's end falls at every kind of place.
TEST(ProgramStream, RapidErrorsByWindowsOfAnySizeAreThoseOfTheWholeRead) {
  std::vector<size_t> windows;
  for (size_t window = 16; window < 3000; window += 157) windows.push_back(window);
  expectRapidErrorsOfTheWholeRead(test::tempDir("program_stream_rapid_errors_sizes"), 40, windows);
}

// A module read by windows of 20 sizes from 16 bytes to 3 KB (a statement over several windows,
// a window's end at every kind of place: in a number, a name, a comment, between a statement's
// lines): the whole read's motions, targets, frames, unresolved references and notes.
TEST(ProgramStream, RapidWindowsOfAnySizeReadAsTheWholeModule) {
  const std::string dir = test::tempDir("program_stream_rapid_sizes");
  std::string padded = test::rapidWallPass(60);
  std::string comments;
  for (int k = 0; k < 30; ++k) comments += "      ! a comment line inside a statement\n";
  padded.insert(padded.find("v60", padded.find("MoveL [[")), comments + "      ");
  test::writeFile(dir + "/long.mod", "%%%\n  VERSION:1\n  LANGUAGE:ENGLISH\n%%%\n\n" + padded);
  std::vector<std::string> programs = {
      dir + "/long.mod", test::sourceDir() + "/samples/emotor-housing/housing_irb6640.mod"};
  if (const std::string corpus = test::corpusDir(); !corpus.empty())
    programs.push_back(corpus + "/robodk/DrillIRC5.mod");
  for (const std::string& path : programs) {
    SCOPED_TRACE(path);
    const std::vector<std::string> whole = rapidWhole(path);
    for (size_t window = 16; window < 3000; window += 157) {
      EXPECT_EQ(firstDifference(whole, rapidStreamed(path, window, nullptr)), "")
          << "window " << window;
    }
  }
}

// FANUC TP programs read by windows of 4 KB and 10 KB (a /POS record cut by a window's end, a
// header and /MN over several windows, every shape tpWallPass writes: swapped records, one record
// last, a position never taught, one not in /POS, a register, a circular motion) in LF and CRLF,
// the samples' and the corpus's: the motions, targets, frames, unresolved references and notes of
// the whole read, in its order. /MN is read again behind the scan of the file, so a program whose
// records follow the order of its motions holds about a window's worth of motions and targets.
TEST(ProgramStream, TpProgramByWindowsReadsAsTheWholeProgram) {
  const std::string dir = test::tempDir("program_stream_tp");
  test::writeFile(dir + "/wall.ls", test::tpWallPass(300));
  test::writeFile(dir + "/crlf.ls", test::tpWallPass(300, "\r\n"));
  test::writeFile(dir + "/ordered.ls", test::tpWallPass(600, "\n", false));
  expectWindowsReadAsTheWhole({dir + "/wall.ls", dir + "/crlf.ls", dir + "/ordered.ls",
                               test::sourceDir() + "/samples/emotor-housing/housing_r2000.ls"},
                              "robodk/DRILLR30IA.LS",
                              [&](const std::string& path, size_t window, const WindowHeld& held) {
                                if (path != dir + "/ordered.ls") return;
                                // a record is about 150 bytes, a motion line 30
                                EXPECT_LT(held.targets, window / 100) << "window " << window;
                                EXPECT_LT(held.motions, window / 20) << "window " << window;
                              });
}

// A TP program read by windows of 20 sizes from 16 bytes to 3 KB (a record over many windows, a
// window's end at every kind of place): the whole read's motions, targets, frames, unresolved
// references and notes.
TEST(ProgramStream, TpWindowsOfAnySizeReadAsTheWholeProgram) {
  const std::string dir = test::tempDir("program_stream_tp_sizes");
  test::writeFile(dir + "/wall.ls", test::tpWallPass(12));
  test::writeFile(dir + "/crlf.ls", test::tpWallPass(12, "\r\n"));
  for (const std::string& path : {dir + "/wall.ls", dir + "/crlf.ls"}) {
    SCOPED_TRACE(path);
    const std::vector<std::string> whole = rapidWhole(path);
    for (size_t window = 16; window < 3000; window += 157) {
      EXPECT_EQ(firstDifference(whole, rapidStreamed(path, window, nullptr)), "")
          << "window " << window;
    }
  }
}

/// Faulty TP programs from a wall pass of `points` points: a damaged /MN line, a broken number in
/// a record and a record defined twice far into the file, no /END, no /PROG; a value out of range
/// in an early record before a reader's error in a later one (the reader's error), a motion's
/// speed before a record's value (the record's). Each read by windows of every size in `windows`
/// gives the whole read's error.
void expectTpErrorsOfTheWholeRead(const std::string& dir, int points,
                                  const std::vector<size_t>& windows) {
  const std::string wall = test::tpWallPass(points);
  const size_t last_motion = wall.rfind("60mm/sec CNT100", wall.find("/POS"));
  std::string line = wall;
  line.replace(line.rfind('\n', last_motion) + 1, 4, " x 1");
  const size_t late_record = wall.rfind("Z = ");
  std::string number = wall;
  number.replace(late_record, 10, "Z = -5.0.0");
  std::string twice = wall;
  const size_t rec = twice.rfind("P[", twice.rfind("GP1"));
  twice.insert(twice.find("/END"), twice.substr(rec, twice.find("};", rec) + 3 - rec));
  const std::string truncated = wall.substr(0, wall.rfind("/END"));
  std::string noprog = wall;
  noprog.erase(0, noprog.find('\n') + 1);
  std::string range = number;
  range.replace(range.find("Z = ", range.find("/POS")), 10, "Z = 9e9   ");
  std::string kinds = wall;
  kinds.replace(kinds.find("60mm/sec"), 8, "99999mm/sec");
  kinds.replace(kinds.rfind("Z = "), 9, "Z = 9e9  ");
  expectStreamedErrorsOfTheWholeRead(dir,
                                     {{"line.ls", line},
                                      {"number.ls", number},
                                      {"twice.ls", twice},
                                      {"truncated.ls", truncated},
                                      {"noprog.ls", noprog},
                                      {"range.ls", range},
                                      {"kinds.ls", kinds}},
                                     windows);
}

// TP errors by windows of 4 KB on a 400-point program, and by windows of 20 sizes from 16 bytes to
// 3 KB on a 30-point one.
TEST(ProgramStream, TpErrorsByWindowsAreThoseOfTheWholeRead) {
  expectTpErrorsOfTheWholeRead(test::tempDir("program_stream_tp_errors"), 400, {4096});
  std::vector<size_t> windows;
  for (size_t window = 16; window < 3000; window += 157) windows.push_back(window);
  expectTpErrorsOfTheWholeRead(test::tempDir("program_stream_tp_errors_sizes"), 30, windows);
}

}  // namespace
}  // namespace roprec
