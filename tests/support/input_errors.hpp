#pragma once
// Helpers of the input-validation tests (krl, rapid, tp, urdf_loader, robot_card, cell): text
// edits and their lines, the text of the InputError a reader throws, and the bundled KR 120
// copied with one edit.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "compensator/support/error.hpp"
#include "postproc/program.hpp"
#include "tests/support/test_support.hpp"

namespace roprec::test {

/// 1-based line of the first occurrence of `needle` in `text` (-1: none).
inline int lineOf(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  if (at == std::string::npos) return -1;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

/// `text` with the first `from` replaced by `to` (a test failure when there is none).
inline std::string replaced(const std::string& text, const std::string& from,
                            const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  std::string out = text;
  if (at != std::string::npos) out.replace(at, from.size(), to);
  return out;
}

/// The what() of the InputError `load` throws ("FILE:LINE: message"), or "(accepted)".
inline std::string inputErrorText(const std::function<void()>& load) {
  try {
    load();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

/// "FILE: message" of the InputError of parsing `text` (read as `path`, a KRL .dat `dat` as
/// p.dat) in dialect `d`, or "(accepted)"; the line the error names in *line.
inline std::string programReadError(postproc::Dialect d, const std::string& path,
                                    const std::string& text,
                                    std::optional<std::string> dat = std::nullopt,
                                    int* line = nullptr) {
  try {
    (void)postproc::parseProgram(d, path, text, std::move(dat), "p.dat");
  } catch (const InputError& e) {
    if (line) *line = e.line();
    return e.file() + ": " + e.message();
  }
  return "(accepted)";
}

/// The bundled KR 120 folder (robot.xml, kr120r2500pro.urdf) copied into a fresh temporary
/// folder with `from` replaced by `to` in `file` (once, after `anchor`); returns the folder.
inline std::string editedKr120(const std::string& file, const std::string& anchor,
                               const std::string& from, const std::string& to) {
  const std::string src = sourceDir() + "/robots/kuka-kr120-r2500-pro";
  const std::string dir = tempDir("kr120-edited") + "/kuka-kr120-r2500-pro";
  std::filesystem::create_directories(dir);
  for (const char* f : {"robot.xml", "kr120r2500pro.urdf"}) {
    std::string text = readFile(src + "/" + f);
    if (file == f) {
      const std::size_t a = text.find(anchor);
      const std::size_t at = a == std::string::npos ? a : text.find(from, a);
      EXPECT_NE(at, std::string::npos) << anchor << " / " << from;
      if (at != std::string::npos) text.replace(at, from.size(), to);
    }
    writeFile(dir + "/" + f, text);
  }
  return dir;
}

}  // namespace roprec::test
