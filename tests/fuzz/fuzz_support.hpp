#pragma once
// Helpers shared by the harnesses: a per-process scratch folder for the readers that only take a
// path (cell, robot card, URDF), and the project's source folder (bundled URDFs).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "compensator/support/error.hpp"
#include "compensator/support/platform.hpp"

namespace roprec::fuzz {

/// A fresh folder, /tmp/roprec-fuzz-<tag>-<pid>, removed at exit.
inline const std::filesystem::path& scratchDir(const std::string& tag) {
  struct Dir {
    std::filesystem::path p;
    explicit Dir(const std::string& t)
        : p(std::filesystem::temp_directory_path() /
            ("roprec-fuzz-" + t + "-" + std::to_string(roprec::platform::processId()))) {
      std::filesystem::remove_all(p);
      std::filesystem::create_directories(p);
    }
    ~Dir() {
      std::error_code ec;
      std::filesystem::remove_all(p, ec);
    }
  };
  static const Dir d(tag);
  return d.p;
}

/// Writes the fuzz input to `path` (truncating) and returns the path as a string.
inline std::string writeInput(const std::filesystem::path& path, const std::uint8_t* data,
                              std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path.string();
}

/// A documented refusal. With ROPREC_FUZZ_VERBOSE set (e.g. when replaying the seeds by hand)
/// it is printed, to check that a seed gets past the reader's first checks.
inline void rejected(const roprec::InputError& e) {
  static const bool verbose = std::getenv("ROPREC_FUZZ_VERBOSE") != nullptr;
  if (verbose) std::fprintf(stderr, "rejected: %s\n", roprec::formatInputError(e).c_str());
}

inline std::string sourceDir() { return ROPREC_SOURCE_DIR; }

}  // namespace roprec::fuzz
