/// The one loader of input files (compensator/support/input_file.hpp): what it refuses before a
/// reader sees the bytes (folders, devices, FIFOs, files above their kind's limit, UTF-16/32, NUL
/// bytes), through the library, the CLI and the C ABI. What needs POSIX (devices, FIFOs, setenv)
/// is in input_file_posix_test.cpp.
#include "compensator/support/input_file.hpp"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "compensator/support/error.hpp"
#include "compensator/support/long_words.hpp"
#include "compensator/support/utf8.hpp"
#include "plugin/c/roprec.h"
#include "tests/support/file_checks.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

std::string errorOf(const std::string& path, InputKind kind) {
  return test::inputErrorOf(path, kind);
}

bool validUtf8(const std::string& s) {
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t n = utf8SequenceLength(s, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

const std::string kCell = test::sourceDir() + "/samples/cells/housing-kr120.xml";

TEST(InputFile, CliAndCApiSayAFolderIsADirectoryNotOutOfMemory) {
  const std::string dir = test::tempDir("input-folder-cli");
  const auto r = test::runRoprec("predict --cell '" + kCell + "' '" + dir + "' --json -");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(dir + ": is a directory"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("memory"), std::string::npos) << r.err;
  const auto c = test::runRoprec("predict --cell '" + dir + "' '" + dir + "' --json -");
  EXPECT_NE(c.err.find(dir + ": is a directory; give a cell file"), std::string::npos) << c.err;
  char summary[ROPREC_SUMMARY_LEN];
  char err[2048];
  const int rc = roprec_predict_file(kCell.c_str(), dir.c_str(), nullptr, nullptr, summary,
                                     sizeof summary, err, sizeof err);
  EXPECT_EQ(rc, ROPREC_BAD_INPUT);
  EXPECT_NE(std::string(err).find("is a directory"), std::string::npos) << err;
}

TEST(InputFile, Utf16AndUtf32AreRefusedWithWhatToDoAndAUtf8MarkIsAccepted) {
  const std::string dir = test::tempDir("input-utf16");
  const std::string cell = test::readFile(kCell);
  auto widen = [](const std::string& s, bool big_endian, int width) {
    std::string w;
    for (const char c : s) {
      std::string unit(static_cast<std::size_t>(width), '\0');
      unit[big_endian ? unit.size() - 1 : 0] = c;
      w += unit;
    }
    return w;
  };
  const struct {
    std::string bytes;
    const char* name;
  } cases[] = {
      {"\xFF\xFE" + widen(cell, false, 2), "UTF-16"},
      {"\xFE\xFF" + widen(cell, true, 2), "UTF-16"},
      {widen(cell, false, 2), "UTF-16"},
      {widen(cell, true, 2), "UTF-16"},
      {std::string("\xFF\xFE\0\0", 4) + widen(cell, false, 4), "UTF-32"},
      {widen(cell, true, 4), "UTF-32"},
  };
  for (const auto& c : cases) {
    test::writeFile(dir + "/cell.xml", c.bytes);
    const auto r = test::runRoprec("predict --cell '" + dir + "/cell.xml' '" + test::sourceDir() +
                                   "/samples/emotor-housing/holes.csv' --json -");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(
        r.err.find(dir + "/cell.xml:1: this file is " + std::string(c.name) + "; save it as UTF-8"),
        std::string::npos)
        << r.err;
  }
  test::writeFile(dir + "/holes.csv",
                  "\xFF\xFE" + widen("id,x,y,z,i,j,k\nH1,1,2,3,0,0,-1\n", false, 2));
  EXPECT_NE(errorOf(dir + "/holes.csv", InputKind::kHoleList).find("this file is UTF-16"),
            std::string::npos);
  test::writeFile(dir + "/bom.xml", "\xEF\xBB\xBF" + cell);
  EXPECT_EQ(errorOf(dir + "/bom.xml", InputKind::kCell), "");
}

TEST(InputFile, ANulByteIsRefusedAtItsLineAndColumn) {
  const std::string dir = test::tempDir("input-nul");
  test::writeFile(dir + "/holes.csv",
                  std::string("id,x,y,z,i,j,k\nH1,1,2,3,0,0,-1\nH\0002,1,2,3,0,0,-1\n", 46));
  EXPECT_NE(
      errorOf(dir + "/holes.csv", InputKind::kHoleList).find(dir + "/holes.csv:3:2: a NUL byte"),
      std::string::npos)
      << errorOf(dir + "/holes.csv", InputKind::kHoleList);
  const auto r = test::runRoprec("predict --cell '" + kCell + "' '" + dir + "/holes.csv' --json -");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("holes.csv:3:2: a NUL byte"), std::string::npos) << r.err;
}

// Bytes that are not UTF-8 (a Latin-1 hole id) are kept by the readers and escaped in JSON and
// HTML (their Latin-1 character): the outputs stay valid UTF-8.
TEST(InputFile, Latin1BytesInAHoleIdComeOutAsValidUtf8JsonAndHtml) {
  const std::string dir = test::tempDir("input-latin1");
  test::writeFile(dir + "/holes.csv",
                  "id,x,y,z,i,j,k\nT\xE4"
                  "001,150,0,250,0,0,-1\n");
  const auto r = test::runRoprec("predict --cell '" + kCell + "' '" + dir + "/holes.csv' --json '" +
                                 dir + "/p.json' --report '" + dir + "/p.html' --quiet");
  ASSERT_LE(r.exit_code, 1) << r.err;
  const std::string json = test::readFile(dir + "/p.json");
  const std::string html = test::readFile(dir + "/p.html");
  EXPECT_NE(json.find("\"T\\u00e4001\""), std::string::npos);
  EXPECT_NE(html.find("T&#xE4;001"), std::string::npos);
  EXPECT_TRUE(validUtf8(json));
  EXPECT_TRUE(validUtf8(html));
}

TEST(InputFile, LongNamesAreClippedForMessages) {
  EXPECT_EQ(clipForMessage("short"), "short");
  const std::string name(10'000'000, 'x');
  EXPECT_EQ(clipForMessage(name), std::string(80, 'x') + "… (10000000 bytes)");
  // never cuts a UTF-8 sequence: 79 ASCII bytes then 'ä' (2 bytes) at the cut
  const std::string u = std::string(79, 'a') + "\xC3\xA4" + std::string(100, 'b');
  EXPECT_EQ(clipForMessage(u), std::string(79, 'a') + "… (181 bytes)");
}

// Any message that echoes a 1 MB value (an attribute value, a link name, a program statement) is
// cut to a readable length, in the library's errors and on the CLI's stderr.
TEST(InputFile, MessagesNeverEchoAHugeWordWhole) {
  const std::string huge(1'000'000, 'q');
  EXPECT_EQ(clipLongWords("got '" + huge + "' here"),
            "got '" + std::string(199, 'q') + "… (1000002 bytes) here");
  const std::string list = "lines " + std::string(900, '1');  // 900 bytes: kept
  EXPECT_EQ(clipLongWords(list), list);
  EXPECT_LT(InputError("f", 1, "value '" + huge + "'").message().size(), 300u);
  const std::string dir = test::tempDir("input-huge-word");
  std::string cell = test::readFile(test::sourceDir() + "/samples/cells/alu-drilling-6061.xml");
  const std::string at = "tool_material=\"carbide\"";
  ASSERT_NE(cell.find(at), std::string::npos);
  cell.replace(cell.find(at), at.size(), "tool_material=\"" + huge + "carbide\"");
  test::writeFile(dir + "/cell.xml", cell);
  const auto r = test::runRoprec("forces --cell '" + dir + "/cell.xml' --csv /dev/null");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_LT(r.err.size(), 2000u) << r.err.substr(0, 300);
  std::string src = test::readFile(test::sourceDir() + "/samples/emotor-housing/housing_kr120.src");
  src.replace(src.find("SPINDLE_ON()"), 12, huge + "_ON()");
  test::writeFile(dir + "/p.src", src);
  const auto c = test::runRoprec("convert '" + dir + "/p.src' --to rapid -o '" + dir + "/p.mod'");
  EXPECT_LE(c.exit_code, 1) << c.err.substr(0, 300);
  EXPECT_LT(c.err.size(), 20000u) << c.err.substr(0, 300);
}

}  // namespace
}  // namespace roprec
