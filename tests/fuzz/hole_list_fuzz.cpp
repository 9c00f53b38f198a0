// libFuzzer harness for the hole-list CSV reader (postproc::parseHoleList). Documented errors:
// roprec::InputError. Any other exception, a crash or a sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "compensator/support/error.hpp"
#include "postproc/drill.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    const auto specs = roprec::postproc::parseHoleList("fuzz.csv", bytes);
    double sink = 0.0;  // touch every field the reader filled in
    for (const auto& s : specs) {
      sink += s.position_mm.sum() + s.direction.sum() + s.diameter_mm.value_or(0.0) +
              s.depth_mm.value_or(0.0) + s.tolerance_mm.value_or(0.0) + s.line +
              static_cast<double>(s.id.size());
    }
    static_cast<void>(sink);
  } catch (const roprec::InputError& e) {
    roprec::fuzz::rejected(e);
  }
  return 0;
}
