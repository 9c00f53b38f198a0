#pragma once
/// \file html.hpp
/// The reports' element builder: HTML and inline SVG written straight into a string, with the
/// escaping in one place. Text and attribute values that come from the inputs are escaped here
/// (escapeXml: `&`, `<`, `>`, both quotes; invalid UTF-8 as its Latin-1 character); markup the
/// renderer writes itself (`<sub>`, entities, the CSS) goes in as `markup`. Numbers are fixed
/// decimals through appendFixed (locale-free, "-0.0" written "0.0"), so the bytes are the same on
/// every platform and in every host locale.
///
///   Html h(out);
///   h.open("g", {{"class", "tol"}});
///   h.leaf("line", {{"x1", fixed(x, 1)}, {"y1", fixed(y, 1)}, ...});   // <line x1=".." .../>
///   h.element("text", {{"x", fixed(x, 1)}}, label);                    // <text
///   x="..">label</text> h.close("g");

#include <functional>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>

namespace roprec::report {

inline constexpr const char* kDash = "\u2014";  ///< the reports' "no value"

/// `s` escaped for HTML text and attribute values (escapeXml).
std::string esc(std::string_view s);

/// v with `decimals` places (appendFixed: locale-free, no "-0"); a non-finite v as an em dash.
std::string num(double v, int decimals);

/// A number to write with a fixed number of decimals.
struct Fixed {
  double v;
  int decimals;
};
inline Fixed fixed(double v, int decimals) { return {v, decimals}; }

/// One attribute: its name and its value as written between the quotes.
class Attr {
 public:
  Attr(std::string_view name, std::string_view text);  ///< text: escaped
  Attr(std::string_view name, const char* text) : Attr(name, std::string_view(text)) {}
  Attr(std::string_view name, const std::string& text) : Attr(name, std::string_view(text)) {}
  Attr(std::string_view name, Fixed n);  ///< num(n.v, n.decimals)
  Attr(std::string_view name, long long n);
  Attr(std::string_view name, int n) : Attr(name, static_cast<long long>(n)) {}
  Attr(std::string_view name, long n) : Attr(name, static_cast<long long>(n)) {}
  Attr(std::string_view name, size_t n) : Attr(name, static_cast<long long>(n)) {}
  /// A value the renderer built from trusted pieces (numbers, escaped text): written as it is.
  static Attr markup(std::string_view name, std::string value);

  [[nodiscard]] std::string_view name() const { return name_; }
  [[nodiscard]] const std::string& value() const { return value_; }

 private:
  Attr() = default;
  std::string_view name_;
  std::string value_;
};

using Attrs = std::initializer_list<Attr>;

/// Appends elements to a string it does not own; with a sink, large pieces (bulk()) and the
/// string so far (flush()) go on to the sink instead of staying in the string.
class Html {
 public:
  using Sink = std::function<void(std::string_view)>;
  explicit Html(std::string& out, const Sink* sink = nullptr) : out_(out), sink_(sink) {}

  /// `<tag a="v" …>`
  Html& open(std::string_view tag, std::span<const Attr> attrs);
  Html& open(std::string_view tag, Attrs attrs = {}) { return open(tag, span(attrs)); }
  /// `</tag>`
  Html& close(std::string_view tag);
  /// `<tag a="v" …/>` (SVG's empty elements)
  Html& leaf(std::string_view tag, std::span<const Attr> attrs);
  Html& leaf(std::string_view tag, Attrs attrs) { return leaf(tag, span(attrs)); }
  /// `<tag a="v" …>text</tag>`, the text escaped
  Html& element(std::string_view tag, Attrs attrs, std::string_view text);
  /// `<tag a="v" …>markup</tag>`, the content written as it is
  Html& markupElement(std::string_view tag, Attrs attrs, std::string_view markup);
  /// Escaped text.
  Html& text(std::string_view s);
  /// Markup written as it is (the renderer's own tags, entities, prose).
  Html& markup(std::string_view s);
  /// num(v, decimals) as text.
  Html& number(double v, int decimals);
  /// Markup written as it is, a large piece: with a sink, the string so far and then `s` go to
  /// the sink (not copied into the string).
  Html& bulk(std::string_view s);
  /// With a sink: the string so far to the sink once it holds `at_least` bytes, then cleared.
  Html& flush(size_t at_least = 0);

  [[nodiscard]] std::string& out() { return out_; }

 private:
  static std::span<const Attr> span(Attrs a) { return {a.begin(), a.size()}; }
  void attributes(std::span<const Attr> attrs);
  std::string& out_;
  const Sink* sink_;
};

/// The value of an SVG `points` attribute: "x,y x,y …" with `decimals` places.
template <class Points>
std::string svgPoints(const Points& pts, int decimals) {
  std::string s;
  for (const auto& p : pts) {
    if (!s.empty()) s += ' ';
    s += num(p.x(), decimals);
    s += ',';
    s += num(p.y(), decimals);
  }
  return s;
}

}  // namespace roprec::report
