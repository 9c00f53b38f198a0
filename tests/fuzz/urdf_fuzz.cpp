// libFuzzer harness for the URDF loader (roprec::loadUrdfChain, urdfLinkNames). The loader takes
// a path: each input is written to a scratch file. The chain is loaded with the default base and
// tip, and again between the first and the last link of the file. Documented errors:
// roprec::InputError. Anything else, a crash or a sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "compensator/robot/urdf_loader.hpp"
#include "compensator/support/error.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file = roprec::fuzz::scratchDir("urdf") / "fuzz.urdf";
  const std::string path = roprec::fuzz::writeInput(file, data, size);
  std::vector<std::string> links;
  try {
    links = roprec::urdfLinkNames(path);
  } catch (const roprec::InputError& e) {
    roprec::fuzz::rejected(e);
  }
  try {
    static_cast<void>(roprec::loadUrdfChain(path));
  } catch (const roprec::InputError& e) {
    roprec::fuzz::rejected(e);
  }
  if (links.size() >= 2) {
    try {
      static_cast<void>(roprec::loadUrdfChain(path, {links.front(), links.back()}));
    } catch (const roprec::InputError& e) {
      roprec::fuzz::rejected(e);
    }
  }
  return 0;
}
