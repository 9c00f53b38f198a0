// Replays fuzz inputs without libFuzzer: runs LLVMFuzzerTestOneInput once on every regular file
// of the directories (recursively, in sorted order) and files given on the command line. Linked
// with each harness in the normal build as the ctest fuzz_seed_<reader>: a seed that crashes,
// aborts or throws an undocumented exception fails the test. Exit 0 when every input ran; 1 when
// there was no input at all (an empty or missing seed folder is a mistake, not a pass).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  std::vector<fs::path> inputs;
  for (int i = 1; i < argc; ++i) {
    const fs::path arg(argv[i]);
    std::error_code ec;
    if (fs::is_directory(arg, ec)) {
      for (const auto& e : fs::recursive_directory_iterator(arg)) {
        if (e.is_regular_file()) inputs.push_back(e.path());
      }
    } else if (fs::is_regular_file(arg, ec)) {
      inputs.push_back(arg);
    } else {
      std::cerr << "replay: no such file or folder: " << arg.string() << "\n";
      return 1;
    }
  }
  std::sort(inputs.begin(), inputs.end());
  if (inputs.empty()) {
    std::cerr << "replay: no inputs (usage: " << argv[0] << " DIR|FILE...)\n";
    return 1;
  }
  for (const fs::path& p : inputs) {
    std::ifstream in(p, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::cout << "replay: " << p.string() << " (" << bytes.size() << " bytes)" << std::endl;
    std::vector<std::uint8_t> copy(bytes.begin(), bytes.end());  // own buffer, exact size (ASan)
    LLVMFuzzerTestOneInput(copy.data(), copy.size());
  }
  std::cout << "replay: " << inputs.size() << " inputs, no crash" << std::endl;
  return 0;
}
