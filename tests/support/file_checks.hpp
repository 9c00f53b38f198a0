#pragma once
/// Helpers the output-set and input-file tests share (their portable and POSIX-only files alike).

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/input_file.hpp"

namespace roprec::test {

/// The names in a folder, sorted.
inline std::vector<std::string> listDir(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// How many output temporaries (isOutputTemporaryName) a folder holds.
inline int temporariesIn(const std::string& dir) {
  int n = 0;
  for (const auto& name : listDir(dir)) n += isOutputTemporaryName(name) ? 1 : 0;
  return n;
}

/// The message readInputFile refuses `path` with, "" when it reads it.
inline std::string inputErrorOf(const std::string& path, InputKind kind) {
  try {
    readInputFile(path, kind);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace roprec::test
