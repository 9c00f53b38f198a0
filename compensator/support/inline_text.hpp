#pragma once
/// \file inline_text.hpp
/// Text of at most N bytes stored inline (no heap), for the per-hole messages of a compensation
/// result (HoleCompensation::psi_reason, config_reason, note: their capacities and bounds are
/// stated there): building and keeping them allocates nothing (zero heap allocations
/// per hole). A text that would exceed N is never cut silently: it is clipped to N − 3 bytes at a
/// UTF-8 character boundary and ends with "..." (visible in every output); `clipped()` tells.
/// UTF-8 is kept valid.

#include <algorithm>
#include <array>
#include <cstdarg>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <ostream>
#include <string>
#include <string_view>

namespace roprec {

template <std::size_t N>
class InlineText {
 public:
  static_assert(N >= 4, "room for the clip marker");
  InlineText() = default;
  explicit InlineText(std::string_view s) { append(s); }

  InlineText& operator=(std::string_view s) {
    clear();
    return append(s);
  }
  /// Appends s; clips (see the file comment) when the capacity is exceeded.
  InlineText& append(std::string_view s) {
    if (clipped_) return *this;
    if (s.size() <= N - n_) {
      std::memcpy(buf_.data() + n_, s.data(), s.size());
      n_ += s.size();
    } else {
      clip(s);
    }
    return *this;
  }
  /// Appends printf-formatted text (same rule; the format comes from the code, not the input).
  [[gnu::format(printf, 2, 3)]] InlineText& appendf(const char* fmt, ...) {
    if (clipped_) return *this;
    char tmp[N + 2];  // one byte past the capacity: a longer text is clipped at the right place
    va_list ap;
    va_start(ap, fmt);
    const int k = std::vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (k < 0) return *this;
    return append(std::string_view(tmp, std::min<std::size_t>(static_cast<std::size_t>(k), N + 1)));
  }
  void clear() {
    n_ = 0;
    clipped_ = false;
  }
  [[nodiscard]] bool empty() const { return n_ == 0; }
  [[nodiscard]] std::size_t size() const { return n_; }
  [[nodiscard]] bool clipped() const { return clipped_; }
  [[nodiscard]] static constexpr std::size_t capacity() { return N; }
  [[nodiscard]] std::string_view view() const { return {buf_.data(), n_}; }
  [[nodiscard]] std::string str() const { return std::string(view()); }
  [[nodiscard]] std::size_t find(std::string_view s) const { return view().find(s); }
  operator std::string_view() const { return view(); }  // NOLINT: reads like a string

  friend bool operator==(const InlineText& a, const InlineText& b) { return a.view() == b.view(); }
  friend bool operator!=(const InlineText& a, const InlineText& b) { return !(a == b); }
  friend bool operator==(const InlineText& a, std::string_view b) { return a.view() == b; }
  friend bool operator!=(const InlineText& a, std::string_view b) { return a.view() != b; }
  friend bool operator==(std::string_view a, const InlineText& b) { return a == b.view(); }
  friend bool operator!=(std::string_view a, const InlineText& b) { return a != b.view(); }
  friend std::ostream& operator<<(std::ostream& os, const InlineText& t) { return os << t.view(); }

 private:
  /// The first N − 3 bytes of (this text + s), backed off to a UTF-8 character start, then "...".
  /// Precondition: size() + s.size() > N.
  void clip(std::string_view s) {
    constexpr std::size_t room = N - 3;
    char next = 0;  // the first byte not kept
    if (n_ > room) {
      next = buf_[room];
      n_ = room;
    } else {
      const std::size_t take = room - n_;
      std::memcpy(buf_.data() + n_, s.data(), take);
      n_ += take;
      next = s[take];
    }
    if (isContinuation(next)) {  // the cut is inside a character: drop its leading bytes
      while (n_ > 0 && isContinuation(buf_[n_ - 1])) --n_;
      if (n_ > 0) --n_;
    }
    std::memcpy(buf_.data() + n_, "...", 3);
    n_ += 3;
    clipped_ = true;
  }
  static bool isContinuation(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }
  std::array<char, N> buf_{};
  std::size_t n_{0};
  bool clipped_{false};
};

}  // namespace roprec
