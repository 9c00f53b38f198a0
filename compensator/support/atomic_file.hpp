#pragma once
/// \file atomic_file.hpp
/// Outputs are written atomically: a temporary file beside the target, then rename(2), so a
/// failed run never leaves a partial output (docs/contract.md §4).

#include <string>

namespace roprec {

/// Writes `bytes` to `path` through `path.tmp.<pid>` + rename. Throws InputError on failure.
void writeFileAtomic(const std::string& path, const std::string& bytes);

/// Reads a whole file as bytes. Throws InputError(path, 0, "cannot open file").
std::string readFileBytes(const std::string& path);

}  // namespace roprec
