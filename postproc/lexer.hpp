#pragma once
/// \file lexer.hpp
/// Byte-level tokenizer shared by the KRL, RAPID and TP readers. Tokens keep byte offsets into
/// the verbatim file; nothing is copied or transcoded (non-ASCII bytes become kOther tokens).

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

inline bool isIdentStart(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == '$';
}
inline bool isDigit(char c) { return c >= '0' && c <= '9'; }
inline bool isIdentChar(char c) { return isIdentStart(c) || isDigit(c); }
/// `s == std::string_view(&c, 1)` without a length-generic compare (readers' punctuation tests).
inline bool is1(std::string_view s, char c) { return s.size() == 1 && s[0] == c; }

/// ASCII case-insensitive equality.
bool iequals(std::string_view a, std::string_view b);
/// ASCII upper case copy.
std::string upper(std::string_view s);

/// Cursor over a file's tokens with helpers for the recursive-descent readers.
class TokenCursor {
 public:
  TokenCursor(const SourceFile& f, std::size_t begin, std::size_t end)
      : f_(f), i_(begin), end_(end) {}
  [[nodiscard]] bool done() const { return i_ >= end_; }
  [[nodiscard]] std::size_t index() const { return i_; }
  void seek(std::size_t i) { i_ = i; }
  [[nodiscard]] const Token& peek(std::size_t k = 0) const;
  [[nodiscard]] std::string_view text(std::size_t k = 0) const;
  [[nodiscard]] bool isPunct(char c, std::size_t k = 0) const;
  [[nodiscard]] bool isIdent(std::string_view word, std::size_t k = 0) const;
  [[nodiscard]] bool isKind(TokenKind kind, std::size_t k = 0) const;
  const Token& next();
  [[nodiscard]] int line() const;
  [[nodiscard]] const SourceFile& file() const { return f_; }

 private:
  const SourceFile& f_;
  std::size_t i_;
  std::size_t end_;
};

}  // namespace roprec::postproc
