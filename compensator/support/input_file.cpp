#include "compensator/support/input_file.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/long_words.hpp"
#include "compensator/support/platform.hpp"

namespace roprec {

namespace {

constexpr std::size_t kMB = std::size_t{1} << 20U;

const char* kindName(InputKind kind) {
  switch (kind) {
    case InputKind::kCell:
      return "a cell";
    case InputKind::kRobotCard:
      return "a robot card";
    case InputKind::kUrdf:
      return "a URDF";
    case InputKind::kXml:
      return "an XML file";
    case InputKind::kProgram:
      return "a program";
    case InputKind::kHoleList:
      return "a hole list";
    case InputKind::kMeasured:
      return "a measured-holes file";
  }
  return "an input";
}

std::size_t defaultLimitMB(InputKind kind) {
  switch (kind) {
    case InputKind::kCell:
    case InputKind::kRobotCard:
    case InputKind::kUrdf:
    case InputKind::kXml:
      return 64;
    case InputKind::kProgram:
    case InputKind::kHoleList:
    case InputKind::kMeasured:
      return 2048;
  }
  return 64;
}

/// The line (1-based) and column of byte `at`.
std::pair<int, int> lineColumn(std::string_view bytes, std::size_t at) {
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < at; ++i) {
    if (bytes[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  }
  return {line, static_cast<int>(at - line_start + 1)};
}

/// "UTF-16" / "UTF-32" when the bytes start like one (a byte-order mark, or ASCII text with
/// NUL bytes between its characters); nullptr otherwise.
const char* wideEncoding(std::string_view b) {
  const auto u = [&](std::size_t i) {
    return i < b.size() ? static_cast<unsigned char>(b[i]) : 256U;
  };
  if (u(0) == 0x00 && u(1) == 0x00 && u(2) == 0xFE && u(3) == 0xFF) return "UTF-32";
  if (u(0) == 0xFF && u(1) == 0xFE && u(2) == 0x00 && u(3) == 0x00) return "UTF-32";
  if ((u(0) == 0xFE && u(1) == 0xFF) || (u(0) == 0xFF && u(1) == 0xFE)) return "UTF-16";
  if (b.size() < 4) return nullptr;
  const bool z0 = u(0) == 0;
  const bool z1 = u(1) == 0;
  const bool z2 = u(2) == 0;
  const bool z3 = u(3) == 0;
  if ((z0 && z1 && z2 && !z3) || (!z0 && z1 && z2 && z3)) return "UTF-32";
  if ((z0 && !z1 && z2 && !z3) || (!z0 && z1 && !z2 && z3)) return "UTF-16";
  return nullptr;
}

}  // namespace

std::size_t inputSizeLimit(InputKind kind) {
  if (const char* v = std::getenv("ROPREC_MAX_INPUT_MB")) {
    char* end = nullptr;
    const unsigned long long mb = std::strtoull(v, &end, 10);
    if (end != v && *end == '\0' && mb > 0 && mb < (std::size_t{1} << 40U)) return mb * kMB;
  }
  return defaultLimitMB(kind) * kMB;
}

void checkInputText(std::string_view bytes, const std::string& file) {
  if (const char* wide = wideEncoding(bytes)) {
    throw InputError(file, 1,
                     std::string("this file is ") + wide +
                         "; save it as UTF-8 (roprec reads UTF-8 text, a byte-order mark allowed)");
  }
  const void* nul = std::memchr(bytes.data(), '\0', bytes.size());
  if (nul != nullptr) {
    const auto at = static_cast<std::size_t>(static_cast<const char*>(nul) - bytes.data());
    const auto [line, column] = lineColumn(bytes, at);
    throw InputError(file, line,
                     "a NUL byte (code 0) in the text; roprec reads text files (is this a binary "
                     "file, or was it damaged?)",
                     column);
  }
}

std::string readInputFile(const std::string& path, InputKind kind) {
  platform::File f;
  if (const int e = f.openRead(path); e != 0) {
    throw InputError(
        path, 0,
        std::string(kind == InputKind::kUrdf ? "cannot open URDF file: " : "cannot open file: ") +
            platform::errorText(e));
  }
  const platform::Status st = f.status();
  if (st.kind == platform::Kind::kError) {
    throw InputError(path, 0, std::string("cannot read file: ") + platform::errorText(st.error));
  }
  if (st.kind == platform::Kind::kFolder)
    throw InputError(path, 0, std::string("is a directory; give ") + kindName(kind) + " file");
  if (st.kind != platform::Kind::kRegular) {
    throw InputError(path, 0,
                     std::string("is not a regular file (a device, FIFO or socket); give ") +
                         kindName(kind) + " file (no roprec command reads a stream)");
  }
  const std::size_t limit = inputSizeLimit(kind);
  const auto size = static_cast<std::size_t>(st.size);
  const auto too_large = [&](std::size_t n) {
    throw InputError(path, 0,
                     "the file is " + std::to_string((n + kMB - 1) / kMB) + " MB, more than the " +
                         std::to_string(limit / kMB) + " MB allowed for " + kindName(kind) +
                         " (set the environment variable ROPREC_MAX_INPUT_MB to raise the limit)");
  };
  if (size > limit) too_large(size);
  std::string bytes(size, '\0');
  std::size_t got = 0;
  const auto readSome = [&](char* into, std::size_t n) -> std::size_t {
    int e = 0;
    const long long r = f.read(into, n, &e);
    if (r >= 0) return static_cast<std::size_t>(r);
    throw InputError(path, 0, std::string("cannot read file: ") + platform::errorText(e));
  };
  while (got < size) {
    const std::size_t n = readSome(bytes.data() + got, size - got);
    if (n == 0) break;
    got += n;
  }
  bytes.resize(got);
  char more[65536];  // a file still growing: what its size did not foresee, up to the limit
  for (std::size_t n = readSome(more, sizeof more); n > 0; n = readSome(more, sizeof more)) {
    bytes.append(more, n);
    if (bytes.size() > limit) too_large(bytes.size());
  }
  checkInputText(bytes, path);
  noteInputFile(path);
  return bytes;
}

std::string clipLongWords(std::string_view message) {
  constexpr std::size_t kLongWord = 1000;
  std::string out;
  std::size_t i = 0;
  while (i < message.size()) {
    std::size_t j = i;
    while (j < message.size() && message[j] != ' ' && message[j] != '\n' && message[j] != '\t') ++j;
    const std::string_view word = message.substr(i, j - i);
    if (word.size() > kLongWord) {
      out += clipForMessage(word, 200);
    } else {
      out += word;
    }
    if (j < message.size()) out += message[j++];
    i = j;
  }
  return out;
}

std::string clipForMessage(std::string_view name, std::size_t max_bytes) {
  if (name.size() <= max_bytes) return std::string(name);
  std::size_t keep = max_bytes;
  while (keep > 0 && (static_cast<unsigned char>(name[keep]) & 0xC0U) == 0x80U) --keep;
  return std::string(name.substr(0, keep)) + "… (" + std::to_string(name.size()) + " bytes)";
}

}  // namespace roprec
