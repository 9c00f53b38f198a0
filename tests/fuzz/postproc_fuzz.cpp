// libFuzzer harness for the robot-program readers (scripts/fuzz.sh builds one binary per
// dialect with -DROPREC_FUZZ_DIALECT=n). Invariants checked on every input that parses:
// unchanged write-back is byte-identical; edits, drill recognition and conversion do not crash.
// Real errors must surface as roprec::InputError (anything else escapes and aborts the run).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "compensator/support/error.hpp"
#include "postproc/convert.hpp"
#include "postproc/drill.hpp"
#include "postproc/program.hpp"
#include "tests/fuzz/fuzz_support.hpp"

#ifndef ROPREC_FUZZ_DIALECT
#define ROPREC_FUZZ_DIALECT 0
#endif

using namespace roprec;
using namespace roprec::postproc;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string in(reinterpret_cast<const char*>(data), size);
  const Dialect d = static_cast<Dialect>(ROPREC_FUZZ_DIALECT);
  std::string src = in;
  std::optional<std::string> dat;
  if (d == Dialect::kKrl) {  // KRL: .src and .dat separated by a 0x01 byte
    const std::size_t cut = in.find('\x01');
    if (cut != std::string::npos) {
      src = in.substr(0, cut);
      dat = in.substr(cut + 1);
    }
  }
  try {
    Program p = parseProgram(d, "fuzz.in", src, dat, "fuzz.dat");
    const std::vector<std::string> out = renderFiles(p);
    if (out[0] != src || (dat && (out.size() < 2 || out[1] != *dat))) std::abort();
    (void)recognizeHoles(p);
    for (Dialect to :
         {Dialect::kKrl, Dialect::kRapid, Dialect::kTp, Dialect::kCsv, Dialect::kJson}) {
      ConversionReport rep;
      try {
        (void)convertProgram(p, to, "fuzz.out", rep);
      } catch (const InputError& e) {
        // unresolved frame: a reported refusal
        roprec::fuzz::rejected(e);
      }
    }
    for (std::size_t i = 0; i < p.targets().size() && i < 64; ++i) {
      const Target& t = p.targets()[i];
      Pose T = targetPose(p, t);
      T.translation().x() += 1e-4;
      (void)replaceTargetPose(
          p, static_cast<int>(i), T,
          t.config.present() ? std::optional<Configuration>(t.config) : std::nullopt);
    }
    (void)renderFiles(p);
  } catch (const InputError& e) {
    roprec::fuzz::rejected(e);
    return 0;
  }
  return 0;
}
