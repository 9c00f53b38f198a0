// libFuzzer harness for the measured-hole readers (postproc::parseMeasured: roprec CSV, PC-DMIS
// CSV, DMIS; the format is detected from the content). On every input that parses, the holes are
// written back in each format and read again, and matched against themselves as program holes.
// Documented errors: roprec::InputError (readers, matchMeasured), std::invalid_argument (the DMIS
// writer, for a hole without an axis). Anything else, a crash or a sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "compensator/support/error.hpp"
#include "postproc/measured.hpp"
#include "tests/fuzz/fuzz_support.hpp"

using namespace roprec::postproc;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  static_cast<void>(detectMeasuredFormat(text));
  MeasuredHoles m;
  try {
    m = parseMeasured(text, "fuzz.meas");
  } catch (const roprec::InputError& e) {
    roprec::fuzz::rejected(e);
    return 0;
  }
  for (MeasuredFormat f : {MeasuredFormat::kCsv, MeasuredFormat::kPcDmis, MeasuredFormat::kDmis}) {
    std::string out;
    try {
      out = writeMeasured(m.holes, f);
    } catch (const std::invalid_argument&) {
      continue;  // DMIS: a hole without an axis
    }
    try {
      static_cast<void>(parseMeasured(out, std::string("fuzz.") + measuredFormatName(f)));
    } catch (const roprec::InputError& e) {
      roprec::fuzz::rejected(e);
    }
  }
  std::vector<ProgramHoleRef> refs;
  for (const MeasuredHole& h : m.holes) refs.push_back({h.id, h.p_mm});
  try {
    static_cast<void>(matchMeasured(m, refs));
  } catch (const roprec::InputError& e) {
    roprec::fuzz::rejected(e);
  }
  return 0;
}
