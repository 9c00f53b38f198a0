#pragma once
/// Bytes a command produces as it streams but may hand on only once it is done (all-or-nothing
/// outputs), held in an anonymous temporary file (std::tmpfile, removed when closed) instead of
/// memory.

#include <cstdio>
#include <functional>
#include <string>
#include <string_view>
#include <utility>

#include "compensator/support/error.hpp"

namespace roprec::api {

class TempSpill {
 public:
  /// `whose`: whose bytes they are, in the error messages ("the report", "standard output").
  explicit TempSpill(std::string whose) : whose_(std::move(whose)), f_(std::tmpfile()) {
    if (f_ == nullptr) throw InputError("", 0, "cannot create a temporary file for " + whose_);
  }
  ~TempSpill() { std::fclose(f_); }
  TempSpill(const TempSpill&) = delete;
  TempSpill& operator=(const TempSpill&) = delete;
  void write(std::string_view v) {
    if (std::fwrite(v.data(), 1, v.size(), f_) != v.size())
      throw InputError("", 0, "cannot write " + whose_ + "'s temporary file");
  }
  /// Hands everything written, in order, to `sink`, `chunk` bytes at a time.
  void replay(const std::function<void(std::string_view)>& sink, std::size_t chunk) {
    if (std::fflush(f_) != 0 || std::fseek(f_, 0, SEEK_SET) != 0) readFailed();
    std::string buf(chunk, '\0');
    std::size_t got = 0;
    while ((got = std::fread(buf.data(), 1, buf.size(), f_)) > 0) sink({buf.data(), got});
    if (std::ferror(f_) != 0) readFailed();
  }

 private:
  [[noreturn]] void readFailed() const {
    throw InputError("", 0, "cannot read " + whose_ + "'s temporary file");
  }
  std::string whose_;
  std::FILE* f_;
};

}  // namespace roprec::api
