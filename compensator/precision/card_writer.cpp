#include "compensator/precision/card_writer.hpp"

#include <algorithm>
#include <cmath>

#include "compensator/support/error.hpp"
#include "compensator/support/xml_escape.hpp"

namespace roprec {

std::vector<CardStiffnessUpdate> cardUpdates(const IdentificationResult& r) {
  std::vector<CardStiffnessUpdate> u;
  for (int j = 0; j < 6; ++j) {
    if (r.joint_identified[static_cast<size_t>(j)])
      u.push_back({j, r.compliance.k[j], r.k_sigma[j]});
  }
  return u;
}

std::string identifiedSource(int holes, const std::string& measured_file, double sigma) {
  return "identified: " + std::to_string(holes) + " holes from " + measured_file +
         " by roprec verify (σ = " + formatCardNumber(sigma, 2) + " N·m/rad)";
}

namespace {

/// An attribute inside a tag: the span of its value (between the quotes) and the quote.
struct Attribute {
  std::string name;
  std::size_t value_begin{0};
  std::size_t value_end{0};
};

struct JointTag {
  std::size_t begin{0};  ///< '<'
  std::size_t end{0};    ///< one past the attributes (the position of '/>' or '>')
  int line{0};
  char quote{'"'};  ///< the quote the tag's attributes use (for appended ones)
  std::vector<Attribute> attributes;
};

int lineAt(const std::string& s, std::size_t pos) {
  return 1 + static_cast<int>(
                 std::count(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
}

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

/// Parses the attributes of the tag starting at `begin` ('<joint').
JointTag parseTag(const std::string& s, std::size_t begin, const std::string& path) {
  JointTag t;
  t.begin = begin;
  t.line = lineAt(s, begin);
  std::size_t i = begin + 6;
  bool quote_seen = false;
  while (true) {
    while (i < s.size() && isSpace(s[i])) ++i;
    if (i >= s.size()) throw InputError(path, t.line, "unterminated <joint> tag");
    if (s[i] == '>' || s[i] == '/') {
      t.end = i;
      return t;
    }
    const std::size_t name_begin = i;
    while (i < s.size() && s[i] != '=' && !isSpace(s[i]) && s[i] != '>') ++i;
    Attribute a;
    a.name = s.substr(name_begin, i - name_begin);
    while (i < s.size() && isSpace(s[i])) ++i;
    if (i >= s.size() || s[i] != '=')
      throw InputError(path, lineAt(s, i), "malformed attribute '" + a.name + "'");
    ++i;
    while (i < s.size() && isSpace(s[i])) ++i;
    if (i >= s.size() || (s[i] != '"' && s[i] != '\'')) {
      throw InputError(path, lineAt(s, i), "attribute '" + a.name + "' needs a quoted value");
    }
    const char q = s[i];
    if (!quote_seen) t.quote = q;
    quote_seen = true;
    a.value_begin = ++i;
    while (i < s.size() && s[i] != q) ++i;
    if (i >= s.size()) throw InputError(path, t.line, "unterminated attribute '" + a.name + "'");
    a.value_end = i++;
    t.attributes.push_back(a);
  }
}

/// Position of the first `<name` tag (followed by space, '/' or '>') at or after `from` outside
/// comments, or npos.
std::size_t findTag(const std::string& s, const std::string& name, const std::string& path,
                    std::size_t from = 0) {
  std::size_t i = from;
  while ((i = s.find('<', i)) != std::string::npos) {
    if (s.compare(i, 4, "<!--") == 0) {
      const std::size_t e = s.find("-->", i + 4);
      if (e == std::string::npos) throw InputError(path, lineAt(s, i), "unterminated comment");
      i = e + 3;
      continue;
    }
    const std::size_t after = i + 1 + name.size();
    if (s.compare(i + 1, name.size(), name) == 0 && after < s.size() &&
        (isSpace(s[after]) || s[after] == '/' || s[after] == '>'))
      return i;
    ++i;
  }
  return std::string::npos;
}

/// The <joint> tags of the card in document order, comments and processing instructions skipped.
std::vector<JointTag> jointTags(const std::string& s, const std::string& path) {
  std::vector<JointTag> tags;
  for (std::size_t i = findTag(s, "joint", path); i != std::string::npos;
       i = findTag(s, "joint", path, tags.back().end))
    tags.push_back(parseTag(s, i, path));
  if (tags.size() != 6) {
    throw InputError(path, 0,
                     "a robot card needs 6 <joint> elements, found " + std::to_string(tags.size()));
  }
  return tags;
}

/// The provenance kept after "; before: " (raw attribute text, already escaped).
std::string previousSource(const std::string& old_raw) {
  if (old_raw.rfind("identified:", 0) != 0) return old_raw;
  const std::size_t b = old_raw.find("; before: ");
  return b == std::string::npos ? std::string() : old_raw.substr(b + 10);
}

/// One pending replacement of bytes [begin, end) by `text`.
struct Edit {
  std::size_t begin{0};
  std::size_t end{0};
  std::string text;
};

const Attribute* findAttribute(const JointTag& t, const std::string& name) {
  for (const Attribute& a : t.attributes) {
    if (a.name == name) return &a;
  }
  return nullptr;
}

/// Replaces the value of `name`, or appends the attribute at the end of the tag.
Edit setAttribute(const JointTag& t, const std::string& name, const std::string& escaped_value) {
  if (const Attribute* a = findAttribute(t, name))
    return {a->value_begin, a->value_end, escaped_value};
  return {t.end, t.end, " " + name + "=" + t.quote + escaped_value + t.quote};
}

void checkUpdate(const CardStiffnessUpdate& u, const std::string& path) {
  if (u.joint < 0 || u.joint > 5)
    throw InputError(path, 0, "joint index " + std::to_string(u.joint) + " is not 0..5");
  if (!(u.stiffness > 0) || !std::isfinite(u.stiffness)) {
    throw InputError(
        path, 0, "joint " + std::to_string(u.joint + 1) + ": the identified stiffness must be > 0");
  }
}

}  // namespace

std::string updateCardStiffness(const std::string& card_text, const std::string& card_path,
                                const std::vector<CardStiffnessUpdate>& updates, int holes,
                                const std::string& measured_file) {
  const std::vector<JointTag> tags = jointTags(card_text, card_path);
  std::vector<Edit> edits;
  for (const CardStiffnessUpdate& u : updates) {
    checkUpdate(u, card_path);
    const JointTag& t = tags[static_cast<size_t>(u.joint)];
    edits.push_back(setAttribute(t, "stiffness", formatCardNumber(u.stiffness)));
    const Attribute* old = findAttribute(t, "source");
    const std::string before =
        old ? previousSource(card_text.substr(old->value_begin, old->value_end - old->value_begin))
            : std::string();
    const std::string source = escapeXml(identifiedSource(holes, measured_file, u.sigma), t.quote) +
                               (before.empty() ? std::string() : "; before: " + before);
    edits.push_back(setAttribute(t, "source", source));
  }
  // apply from the back so earlier offsets stay valid (appended attributes keep document order)
  std::stable_sort(edits.begin(), edits.end(),
                   [](const Edit& a, const Edit& b) { return a.begin > b.begin; });
  std::string out = card_text;
  for (const Edit& e : edits) out.replace(e.begin, e.end - e.begin, e.text);
  return out;
}

namespace {

std::size_t lineStart(const std::string& s, std::size_t pos) {
  const std::size_t nl = s.rfind('\n', pos == 0 ? 0 : pos - 1);
  return nl == std::string::npos || pos == 0 ? 0 : nl + 1;
}

std::size_t afterLineEnd(const std::string& s, std::size_t pos) {
  const std::size_t nl = s.find('\n', pos);
  return nl == std::string::npos ? s.size() : nl + 1;
}

/// One past the end of the <calibration> element starting at `begin`.
std::size_t calibrationEnd(const std::string& s, std::size_t begin, const std::string& path) {
  const std::size_t gt = s.find('>', begin);
  if (gt == std::string::npos)
    throw InputError(path, lineAt(s, begin), "unterminated <calibration> tag");
  if (s[gt - 1] == '/') return gt + 1;
  const std::size_t close = s.find("</calibration>", gt);
  if (close == std::string::npos)
    throw InputError(path, lineAt(s, begin), "<calibration> has no </calibration>");
  return close + 14;
}

}  // namespace

std::string replaceCardCalibration(const std::string& card_text, const std::string& card_path,
                                   const std::string& block) {
  std::string out = card_text;
  const std::size_t at = findTag(card_text, "calibration", card_path);
  if (at != std::string::npos) {
    const std::size_t begin = lineStart(card_text, at);
    const std::size_t end = afterLineEnd(card_text, calibrationEnd(card_text, at, card_path));
    return out.replace(begin, end - begin, block);
  }
  const std::size_t close = card_text.rfind("</robot>");
  if (close == std::string::npos)
    throw InputError(card_path, 0, "the card has no </robot> to put the <calibration> before");
  return out.insert(lineStart(card_text, close), block);
}

}  // namespace roprec
