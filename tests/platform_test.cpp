// The operating-system layer (compensator/support/platform.hpp) and the tests' process helper
// (tests/support/process.hpp) with what differs between Linux and Windows: UTF-8 paths outside
// ASCII (the wide-character API on Windows) through the platform calls, the atomic writer, the
// CLI and the C ABI, and program arguments passed word for word (CreateProcessW's quoting on
// Windows). These run on both systems (scripts/windows.sh runs them under wine64).
#include "compensator/support/platform.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "compensator/support/atomic_file.hpp"
#include "plugin/c/roprec.h"
#include "tests/support/process.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

// A folder and file names with Latin-1, Greek, CJK and a 4-byte UTF-8 sequence, and a blank.
const std::string kFolder =
    "Pr\xC3\xBC"
    "fstand \xCE\xA9 \xE6\x97\xA5\xE6\x9C\xAC \xF0\x9F\x94\xA9";
const std::string kFile =
    "na\xC3\xAF"
    "ve \xC3\x98.txt";

std::string utf8Folder(const std::string& tag) {
  const std::string dir = test::tempDir(tag) + "/" + kFolder;
  std::filesystem::create_directories(platform::fromUtf8(dir));
  return dir;
}

TEST(Platform, Utf8PathsComeBackByteForByte) {
  for (const std::string& s : {kFolder, kFile, std::string("a/b/") + kFolder + "/" + kFile}) {
    EXPECT_EQ(platform::toUtf8(platform::fromUtf8(s)), s);
  }
  EXPECT_EQ(platform::toUtf8(platform::fromUtf8(kFolder + "/" + kFile).filename()), kFile);
}

TEST(Platform, FileCallsReachUtf8PathsOutsideAscii) {
  const std::string dir = utf8Folder("platform-utf8");
  const std::string path = dir + "/" + kFile;
  const std::string bytes = std::string("first line\r\nsecond \xC3\xA4\n") + std::string(1, '\0');
  writeFileAtomic(path, bytes);
  EXPECT_EQ(readFileBytes(path), bytes);  // no text-mode translation either way
  const platform::Status st = platform::fileStatus(path);
  EXPECT_EQ(st.kind, platform::Kind::kRegular);
  EXPECT_EQ(st.size, bytes.size());
  EXPECT_EQ(platform::fileStatus(dir).kind, platform::Kind::kFolder);
  const std::vector<std::string> names = platform::folderEntries(dir);
  EXPECT_NE(std::find(names.begin(), names.end(), kFile), names.end());
  // the atomic replace of an existing file, then its removal
  const std::string other = dir + "/\xE6\x97\xA5.tmp";
  writeFileAtomic(other, "replacement");
  ASSERT_EQ(platform::replaceFile(other, path), 0);
  EXPECT_EQ(readFileBytes(path), "replacement");
  EXPECT_EQ(platform::fileStatus(other).kind, platform::Kind::kMissing);
  platform::removeFile(path);
  EXPECT_EQ(platform::fileStatus(path).kind, platform::Kind::kMissing);
  std::filesystem::remove_all(platform::fromUtf8(dir).parent_path());
}

/// predict from a folder outside ASCII by the CLI and the C ABI: the same bytes as from an ASCII
/// folder (the JSON names the program by its file name only).
TEST(Platform, CliAndCApiReadAndWriteUtf8Paths) {
  const std::string src = test::sourceDir();
  const std::string cell = src + "/samples/cells/housing-kr120.xml";
  const std::string ascii = test::tempDir("platform-ascii");
  const std::string dir = utf8Folder("platform-cli");
  for (const std::string& d : {ascii, dir}) {
    for (const char* f : {"housing_kr120.src", "holes.csv"}) {
      writeFileAtomic(d + "/" + f, readFileBytes(src + "/samples/emotor-housing/" + f));
    }
  }
  const auto predict = [&](const std::string& d, const std::string& out) {
    return test::runRoprec("predict --cell '" + cell + "' '" + d + "/housing_kr120.src' --holes '" +
                           d + "/holes.csv' --json '" + out + "' --quiet");
  };
  const test::RunResult a = predict(ascii, ascii + "/out.json");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const std::string cli_out = dir + "/\xC3\xB6 cli.json";
  const test::RunResult u = predict(dir, cli_out);
  ASSERT_EQ(u.exit_code, 0) << u.err;
  const std::string expected = readFileBytes(ascii + "/out.json");
  EXPECT_EQ(readFileBytes(cli_out), expected);

  const std::string c_out = dir + "/\xC3\xB6 c.json";
  char summary[ROPREC_SUMMARY_LEN];
  char err[4096];
  ASSERT_EQ(roprec_predict_file(cell.c_str(), (dir + "/housing_kr120.src").c_str(),
                                (dir + "/holes.csv").c_str(), c_out.c_str(), summary,
                                sizeof summary, err, sizeof err),
            ROPREC_OK)
      << err;
  EXPECT_EQ(readFileBytes(c_out), expected);
  // an input that does not exist is named as given, in UTF-8
  const std::string missing = dir + "/\xE6\x97\xA5.src";
  const test::RunResult m =
      test::runRoprec("predict --cell '" + cell + "' '" + missing + "' --quiet");
  EXPECT_EQ(m.exit_code, 2);
  EXPECT_NE(m.err.find(missing), std::string::npos) << m.err;
  std::filesystem::remove_all(platform::fromUtf8(ascii));
  std::filesystem::remove_all(platform::fromUtf8(dir).parent_path());
}

/// The process helper passes each argument word for word (blanks, quotes, backslashes, UTF-8):
/// the CLI names an unknown command as it received it.
TEST(Platform, ProcessArgumentsArriveWordForWord) {
  for (const std::string& word :
       {std::string("plain"), std::string("two  blanks"), std::string("say \"hi\""),
        std::string("back\\slash\\"), std::string("trailing \\\""), std::string("\t tab"),
        std::string("\xC3\xBC \xE6\x97\xA5 \xF0\x9F\x94\xA9")}) {
    const test::ProcessResult r = test::runProcess({test::roprecBin(), word});
    EXPECT_EQ(r.exit_code, 2) << word;
    EXPECT_NE(r.err.find("unknown command '" + word + "'"), std::string::npos)
        << "[" << word << "] " << r.err;
  }
  EXPECT_EQ(test::shellWords("a 'b c' \"d \\\" e\" f\\ g"),
            (std::vector<std::string>{"a", "b c", "d \" e", "f g"}));
}

}  // namespace
}  // namespace roprec
