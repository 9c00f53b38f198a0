// EditedFileWriter: a program's file written piece by piece while its edits are made gives the
// bytes renderFiles gives once every edit is made, wherever the pieces end — an edit that
// reaches past a flush point stays for the next piece, an insertion at a flush point comes after
// the bytes before it — and the edits written are dropped from the program.
#include "postproc/edited_file_writer.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "postproc/program.hpp"

namespace roprec::postproc {
namespace {

/// A KRL program of `n` inline LIN targets, one a line.
Program linProgram(int n) {
  std::string src = "DEF job ( )\n";
  for (int k = 0; k < n; ++k)
    src += "LIN {X " + std::to_string(100 + k) +
           ".000,Y 20.000,Z 300.000,A 0.000,B 0.000,C 180.000}\n";
  src += "END\n";
  return parseProgram(Dialect::kKrl, "job.src", src);
}

/// Target k moved by (dx, 0, dz) mm (edits queued in p.edits).
void moveTarget(Program& p, int k, double dx, double dz) {
  Pose T = targetPose(p, p.targets()[static_cast<std::size_t>(k)]);
  T.translation() += Vec3(dx, 0.0, dz) * 1e-3;
  ASSERT_TRUE(replaceTargetPose(p, k, T).ok);
}

TEST(EditedFileWriter, PiecesWrittenWhileEditingAreTheRenderedFile) {
  Program ref = linProgram(30);
  ASSERT_EQ(ref.targets().size(), 30U);
  for (int k = 0; k < 30; k += 2) moveTarget(ref, k, 0.0123, -0.5);
  ASSERT_TRUE(markCompensated(ref, "test"));
  const std::string want = renderFiles(ref)[0];

  Program p = linProgram(30);
  ASSERT_TRUE(markCompensated(p, "test"));  // an insertion at the start of line 2
  std::string got;
  std::vector<std::size_t> pieces;
  EditedFileWriter w(p, 0, [&](std::string_view b) {
    got.append(b);
    pieces.push_back(b.size());
  });
  const SourceFile& f = p.files[0];
  w.flushBefore(f.line_starts[1]);  // the marker's offset: the insertion is not before it
  EXPECT_EQ(got, want.substr(0, f.line_starts[1]));
  for (int k = 0; k < 30; k += 2) {
    moveTarget(p, k, 0.0123, -0.5);
    // the next target's line: nothing before it changes any more; and once a point inside the
    // edited line (the edit reaching past it stays, with the bytes from its start)
    const std::size_t next = f.line_starts[static_cast<std::size_t>(k + 2)];
    w.flushBefore(k == 10 ? f.line_starts[static_cast<std::size_t>(k + 1)] + 9 : next);
    EXPECT_EQ(got, want.substr(0, got.size())) << k;
  }
  EXPECT_LT(p.edits.size(), 3U);  // the edits written are dropped
  w.finish();
  EXPECT_EQ(got, want);
  EXPECT_TRUE(p.edits.empty());
  EXPECT_GT(pieces.size(), 10U);
}

TEST(EditedFileWriter, AnEditBeforeTheBytesWrittenIsRefused) {
  Program p = linProgram(4);
  std::string got;
  EditedFileWriter w(p, 0, [&](std::string_view b) { got.append(b); });
  w.flushBefore(p.files[0].line_starts[3]);
  moveTarget(p, 0, 1.0, 0.0);  // target 0 lies in the bytes already written
  EXPECT_THROW(w.finish(), std::logic_error);
}

}  // namespace
}  // namespace roprec::postproc
