/// \file html.cpp
/// The reports' element builder (see html.hpp).
#include "plugin/report/html.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "compensator/support/fixed_chars.hpp"
#include "compensator/support/xml_escape.hpp"

namespace roprec::report {

std::string esc(std::string_view s) { return escapeXml(s); }

std::string num(double v, int decimals) {
  if (!std::isfinite(v)) return kDash;
  std::string s;
  appendFixed(s, v, decimals);
  return s;
}

Attr::Attr(std::string_view name, std::string_view text) : name_(name), value_(esc(text)) {}
Attr::Attr(std::string_view name, Fixed n) : name_(name), value_(num(n.v, n.decimals)) {}
Attr::Attr(std::string_view name, long long n) : name_(name), value_(std::to_string(n)) {}

Attr Attr::markup(std::string_view name, std::string value) {
  Attr a;
  a.name_ = name;
  a.value_ = std::move(value);
  return a;
}

void Html::attributes(std::span<const Attr> attrs) {
  for (const Attr& a : attrs) {
    out_ += ' ';
    out_ += a.name();
    out_ += "=\"";
    out_ += a.value();
    out_ += '"';
  }
}

Html& Html::open(std::string_view tag, std::span<const Attr> attrs) {
  out_ += '<';
  out_ += tag;
  attributes(attrs);
  out_ += '>';
  return *this;
}

Html& Html::close(std::string_view tag) {
  out_ += "</";
  out_ += tag;
  out_ += '>';
  return *this;
}

Html& Html::leaf(std::string_view tag, std::span<const Attr> attrs) {
  out_ += '<';
  out_ += tag;
  attributes(attrs);
  out_ += "/>";
  return *this;
}

Html& Html::element(std::string_view tag, Attrs attrs, std::string_view text) {
  return open(tag, attrs).text(text).close(tag);
}

Html& Html::markupElement(std::string_view tag, Attrs attrs, std::string_view markup) {
  return open(tag, attrs).markup(markup).close(tag);
}

namespace {

/// `s` is its own escapeXml: printable ASCII, tabs and line ends, none of & < > " '.
bool plainText(std::string_view s) {
  return std::all_of(s.begin(), s.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u < 0x80 && (u >= 0x20 || c == '\n' || c == '\t') && c != '&' && c != '<' && c != '>' &&
           c != '"' && c != '\'';
  });
}

}  // namespace

Html& Html::text(std::string_view s) {
  if (plainText(s)) {
    out_ += s;
  } else {
    out_ += esc(s);
  }
  return *this;
}

Html& Html::markup(std::string_view s) {
  out_ += s;
  return *this;
}

Html& Html::number(double v, int decimals) {
  if (std::isfinite(v)) {
    appendFixed(out_, v, decimals);
  } else {
    out_ += kDash;
  }
  return *this;
}

Html& Html::bulk(std::string_view s) {
  if (sink_ == nullptr) return markup(s);
  flush();
  (*sink_)(s);
  return *this;
}

Html& Html::flush(size_t at_least) {
  if (sink_ != nullptr && !out_.empty() && out_.size() >= at_least) {
    (*sink_)(out_);
    out_.clear();
  }
  return *this;
}

}  // namespace roprec::report
