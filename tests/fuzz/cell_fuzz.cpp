// libFuzzer harness for the cell file as predict and compensate read it
// (api::loadPredictionContext with no job: loadCell, the robot it names, the tool, the process,
// <uncertainty>, <capability>, <controller>, and the prediction model built from them). The cell
// takes a path: each input is written to a scratch file. Documented errors: roprec::InputError.
// Anything else, a crash or a sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "compensator/support/error.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file = roprec::fuzz::scratchDir("cell") / "cell.xml";
  const std::string path = roprec::fuzz::writeInput(file, data, size);
  try {
    static_cast<void>(roprec::api::loadPredictionContext(path, "", std::nullopt, "", 0.5,
                                                         /*load_holes=*/false));
  } catch (const roprec::InputError& e) {
    roprec::fuzz::rejected(e);
  }
  return 0;
}
