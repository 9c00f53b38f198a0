#pragma once
/// Byte equality of two large texts for a test: gtest's own diff of two texts of megabytes does
/// not finish in reasonable time, so a mismatch names the first differing byte instead.

#include <gtest/gtest.h>

#include <cstddef>
#include <string>

namespace roprec::test {

/// a == b, else the sizes and where they first differ (80 bytes of each from there).
inline testing::AssertionResult sameBytes(const std::string& a, const std::string& b) {
  if (a == b) return testing::AssertionSuccess();
  std::size_t k = 0;
  while (k < a.size() && k < b.size() && a[k] == b[k]) ++k;
  return testing::AssertionFailure()
         << "sizes " << a.size() << " and " << b.size() << ", first difference at byte " << k
         << ": '" << a.substr(k, 80) << "' vs '" << b.substr(k, 80) << "'";
}

}  // namespace roprec::test
