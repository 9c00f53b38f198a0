// A program read a window at a time (postproc/program_stream.cpp), its motions retired behind the
// hole recogniser, gives the holes of the program read whole (readProgram + recognizeHoles): the
// same ids, points, axes, depths, frames, lines and evidence, whatever its line ends, while the
// window holds a bounded number of motions. Errors are readProgram's, in its order (a reader's
// error before a value out of range met earlier), also when each next window is read and lexed
// ahead on a task of its own.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "compensator/support/error.hpp"
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
Streamed readStreamed(const std::string& path, size_t window, bool ahead = false) {
  Streamed out;
  postproc::ProgramStream s(path, window, ahead);
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
  }
}

}  // namespace
}  // namespace roprec
