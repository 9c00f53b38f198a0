#pragma once
/// \file lexer.hpp
/// Byte-level tokenizer shared by the KRL, RAPID and TP readers. Tokens keep byte offsets into
/// the verbatim file; nothing is copied or transcoded (non-ASCII bytes become kOther tokens).

#include <algorithm>
#include <cstdint>
#include <string_view>
#include <vector>

#include "postproc/program.hpp"

namespace roprec::postproc {

struct LexOptions {
  char comment{';'};                ///< comment to end of line (0: none)
  bool header_amp{false};           ///< KRL: a line starting with `&` is one comment token
  bool single_quote_string{false};  ///< `'...'` is a string (KRL binary/char, TP CONFIG)
  bool rapid_assign{false};         ///< `:=` is one token
  bool percent_header{false};       ///< RAPID: `%%%` lines are one comment token
};

/// Tokenizes f.bytes into f.tokens. Newline tokens mark every line end.
void lex(SourceFile& f, const LexOptions& o);
/// Appends to `out` the tokens of the line of f.bytes that starts at byte `from` (a line start),
/// its newline token included; returns the offset of the next line (f.bytes.size() at the end).
/// No token spans lines, so lexing line by line gives the tokens of lex() (one pass, no index of
/// the whole file).
std::size_t lexLine(const SourceFile& f, const LexOptions& o, std::size_t from,
                    std::vector<Token>& out);

constexpr bool isIdentStart(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == '$';
}
constexpr bool isDigit(char c) { return c >= '0' && c <= '9'; }
constexpr bool isIdentChar(char c) { return isIdentStart(c) || isDigit(c); }
/// `s == std::string_view(&c, 1)` without a length-generic compare (readers' punctuation tests).
inline bool is1(std::string_view s, char c) { return s.size() == 1 && s[0] == c; }

constexpr char asciiUpper(char c) {
  return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
}
/// ASCII case-insensitive equality.
inline bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (asciiUpper(a[i]) != asciiUpper(b[i])) return false;
  }
  return true;
}
/// ASCII upper case copy.
std::string upper(std::string_view s);
/// ASCII case-insensitive hash: FNV-1a (64 bit) over the upper-cased bytes; no allocation.
inline std::uint64_t ihash(std::string_view s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (const char c : s) h = (h ^ static_cast<unsigned char>(asciiUpper(c))) * 1099511628211ULL;
  return h;
}

/// Map from names to V, ASCII case-insensitive, for the readers' symbol tables (100,000
/// declarations: no node and no string allocated per name). Keys are views into bytes that
/// outlive the map (the program's files). Entries stay in insertion order; the hash index holds
/// 4-byte entry numbers only (open addressing, linear probing, load <= 1/2), so it stays in cache
/// and look-ups in declaration order read the entries sequentially.
template <class V>
class NameMap {
 public:
  /// Room for n names without rehashing.
  void reserve(std::size_t n) {
    entries_.reserve(n);
    if (2 * n > index_.size()) rehash(2 * n);
  }
  /// The value of `key`, V{} inserted when absent.
  V& operator[](std::string_view key) {
    if (2 * (entries_.size() + 1) > index_.size())
      rehash(std::max<std::size_t>(16, 2 * index_.size()));
    const auto h = static_cast<std::uint32_t>(ihash(key));
    std::uint32_t& slot = index_[probe(key, h)];
    if (slot == 0) {
      entries_.push_back(Entry{key, h, V{}});
      slot = static_cast<std::uint32_t>(entries_.size());
    }
    return entries_[slot - 1].value;
  }
  /// The value of `key`; nullptr when absent.
  [[nodiscard]] const V* find(std::string_view key) const {
    if (index_.empty()) return nullptr;
    const std::uint32_t slot = index_[probe(key, static_cast<std::uint32_t>(ihash(key)))];
    return slot != 0 ? &entries_[slot - 1].value : nullptr;
  }
  [[nodiscard]] std::size_t size() const { return entries_.size(); }
  /// Calls f(value) for every entry, in insertion order (the values may change).
  template <class F>
  void forEachValue(F&& f) {
    for (Entry& e : entries_) f(e.value);
  }

 private:
  struct Entry {
    std::string_view key;
    std::uint32_t hash{0};
    V value{};
  };
  // The index slot holding `key`, or the empty slot where it goes (size a power of two).
  [[nodiscard]] std::size_t probe(std::string_view key, std::uint32_t h) const {
    const std::size_t mask = index_.size() - 1;
    std::size_t i = h & mask;
    while (index_[i] != 0) {
      const Entry& e = entries_[index_[i] - 1];
      if (e.hash == h && iequals(e.key, key)) break;
      i = (i + 1) & mask;
    }
    return i;
  }
  void rehash(std::size_t want) {
    std::size_t n = 16;
    while (n < want) n *= 2;
    index_.assign(n, 0);
    for (std::size_t k = 0; k < entries_.size(); ++k) {
      std::size_t i = entries_[k].hash & (n - 1);
      while (index_[i] != 0) i = (i + 1) & (n - 1);
      index_[i] = static_cast<std::uint32_t>(k + 1);
    }
  }
  std::vector<Entry> entries_;
  std::vector<std::uint32_t> index_;  ///< entry number + 1; 0: empty
};

/// Cursor over a file's tokens with helpers for the recursive-descent readers (inline: they run
/// several times per token).
class TokenCursor {
 public:
  TokenCursor(const SourceFile& f, std::size_t begin, std::size_t end)
      : f_(f), i_(begin), end_(end) {
    // past the end: a newline token where the statement's last token ends, so that an error
    // at the end of a statement names the statement's line
    if (end > begin && end <= f.tokens.size())
      end_token_.offset = f.tokens[end - 1].offset + f.tokens[end - 1].length;
  }
  [[nodiscard]] bool done() const { return i_ >= end_; }
  [[nodiscard]] std::size_t index() const { return i_; }
  void seek(std::size_t i) { i_ = i; }
  /// Token k ahead (past the end: a newline token at the end of the statement's last token).
  [[gnu::always_inline]] [[nodiscard]] const Token& peek(std::size_t k = 0) const {
    return i_ + k < end_ ? f_.tokens[i_ + k] : end_token_;
  }
  [[gnu::always_inline]] [[nodiscard]] std::string_view text(std::size_t k = 0) const {
    return i_ + k < end_ ? f_.text(f_.tokens[i_ + k]) : std::string_view();
  }
  [[gnu::always_inline]] [[nodiscard]] bool isPunct(char c, std::size_t k = 0) const {
    if (i_ + k >= end_) return false;
    const Token& t = f_.tokens[i_ + k];
    return t.kind == TokenKind::kPunct && t.length == 1 && f_.bytes[t.offset] == c;
  }
  [[gnu::always_inline]] [[nodiscard]] bool isIdent(std::string_view word,
                                                    std::size_t k = 0) const {
    if (i_ + k >= end_) return false;
    const Token& t = f_.tokens[i_ + k];
    return t.kind == TokenKind::kIdentifier && iequals(f_.text(t), word);
  }
  [[gnu::always_inline]] [[nodiscard]] bool isKind(TokenKind kind, std::size_t k = 0) const {
    return i_ + k < end_ && f_.tokens[i_ + k].kind == kind;
  }
  const Token& next() {
    const Token& t = peek();
    if (i_ < end_) ++i_;
    return t;
  }
  [[nodiscard]] int line() const;
  [[nodiscard]] const SourceFile& file() const { return f_; }

 private:
  const SourceFile& f_;
  std::size_t i_;
  std::size_t end_;
  Token end_token_{0, 0, TokenKind::kNewline};
};

}  // namespace roprec::postproc
