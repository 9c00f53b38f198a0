#include "compensator/support/xml_node.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "compensator/support/error.hpp"
#include "compensator/support/str_cat.hpp"

namespace roprec {

std::optional<double> parseNumber(const std::string& s) {
  size_t b = 0;
  size_t e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  if (b == e) return std::nullopt;
  // std::from_chars: the "C" format whatever the host process's locale (a host that set a
  // comma-decimal locale must not change a number). A leading '+' is accepted as strtod did.
  const char* first = s.data() + b;
  const char* last = s.data() + e;
  if (*first == '+' && last - first > 1 && first[1] != '-' && first[1] != '+') ++first;
  double v = 0.0;
  const auto r = std::from_chars(first, last, v, std::chars_format::general);
  if (r.ec != std::errc() || r.ptr != last || !std::isfinite(v)) return std::nullopt;
  return v;
}

bool XmlNode::has(const std::string& attr) const { return get(attr).has_value(); }

std::optional<std::string> XmlNode::get(const std::string& attr) const {
  for (const auto& [k, v] : attributes) {
    if (k == attr) return v;
  }
  return std::nullopt;
}

void XmlNode::fail(const std::string& message) const { throw InputError(file, line, message); }

std::string XmlNode::str(const std::string& attr) const {
  auto v = get(attr);
  if (!v) fail("<" + name + "> is missing the attribute '" + attr + "'");
  return *v;
}

std::string XmlNode::str(const std::string& attr, const std::string& fallback) const {
  auto v = get(attr);
  return v ? *v : fallback;
}

double XmlNode::number(const std::string& attr) const {
  const std::string s = str(attr);
  auto v = parseNumber(s);
  if (!v) fail("<" + name + "> attribute '" + attr + "' is not a finite number: '" + s + "'");
  return *v;
}

double XmlNode::number(const std::string& attr, double fallback) const {
  return has(attr) ? number(attr) : fallback;
}

Eigen::VectorXd XmlNode::numbers(const std::string& attr, int n) const {
  const std::string s = str(attr);
  std::istringstream in(s);
  std::vector<double> vals;
  std::string tok;
  while (in >> tok) {
    auto v = parseNumber(tok);
    if (!v)
      fail(strCat("<", name, "> attribute '", attr, "' has a value that is not a finite number: '",
                  tok, "'"));
    vals.push_back(*v);
  }
  if (static_cast<int>(vals.size()) != n) {
    fail("<" + name + "> attribute '" + attr + "' needs " + std::to_string(n) + " numbers, got " +
         std::to_string(vals.size()) + ": '" + s + "'");
  }
  Eigen::VectorXd out(n);
  for (int i = 0; i < n; ++i) out[i] = vals[static_cast<size_t>(i)];
  return out;
}

Eigen::Vector3d XmlNode::vec3(const std::string& attr, const Eigen::Vector3d& fallback) const {
  if (!has(attr)) return fallback;
  return numbers(attr, 3);
}

bool XmlNode::boolean(const std::string& attr, bool fallback) const {
  auto v = get(attr);
  if (!v) return fallback;
  if (*v == "true" || *v == "1" || *v == "yes") return true;
  if (*v == "false" || *v == "0" || *v == "no") return false;
  fail("<" + name + "> attribute '" + attr + "' must be true or false, got '" + *v + "'");
}

const XmlNode* XmlNode::child(const std::string& element) const {
  for (const auto& c : children) {
    if (c.name == element) return &c;
  }
  return nullptr;
}

std::vector<const XmlNode*> XmlNode::childrenNamed(const std::string& element) const {
  std::vector<const XmlNode*> out;
  for (const auto& c : children) {
    if (c.name == element) out.push_back(&c);
  }
  return out;
}

namespace {

std::string lowerAscii(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// Edit distance with adjacent transpositions (optimal string alignment): 'xzy' -> 'xyz' is 1.
/// Rolling rows (the transposition needs the one before the previous), one allocation.
std::size_t editDistance(const std::string& a, const std::string& b) {
  const std::size_t n = a.size();
  const std::size_t m = b.size();
  std::vector<std::size_t> rows(3 * (m + 1));
  std::size_t* prev2 = rows.data();
  std::size_t* prev = prev2 + (m + 1);
  std::size_t* cur = prev + (m + 1);
  for (std::size_t j = 0; j <= m; ++j) prev[j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        cur[j] = std::min(cur[j], prev2[j - 2] + 1);
    }
    std::swap(prev2, prev);  // rotate: prev2 <- prev, prev <- cur, cur <- old prev2
    std::swap(prev, cur);
  }
  return prev[m];
}

/// How near `name` is to `known` (lower is nearer); nullopt when it is not a near miss. A name
/// longer than `known` by more than the distance allowed is not compared at all (a 10 MB name
/// costs nothing), and the edit distance only runs when the lengths are within that distance.
std::optional<std::size_t> nearness(const std::string& name, const std::string& known) {
  const std::size_t limit = name.size() <= 2 ? 0 : name.size() <= 4 ? 1 : 2;
  if (name.size() > known.size() + limit) return std::nullopt;
  const std::string a = lowerAscii(name);
  const std::string b = lowerAscii(known);
  if (a == b) return 0;
  const std::size_t diff = a.size() > b.size() ? a.size() - b.size() : b.size() - a.size();
  if (diff <= limit) {
    if (const std::size_t d = editDistance(a, b); d <= limit) return d;
  }
  // an abbreviation: 'dia' for 'diameter'
  if (a.size() >= 3 && b.rfind(a, 0) == 0) return 3;
  return std::nullopt;
}

std::vector<std::string> toStrings(std::initializer_list<const char*> names) {
  std::vector<std::string> out;
  for (const char* n : names) out.emplace_back(n);
  return out;
}

bool contains(std::initializer_list<const char*> names, const std::string& s) {
  return std::any_of(names.begin(), names.end(), [&](const char* n) { return s == n; });
}

std::string knownList(const std::vector<std::string>& known, const std::string& open,
                      const std::string& close) {
  if (known.empty()) return " (it takes none)";
  std::string list;
  for (const std::string& k : known) strAppend(list, list.empty() ? "" : ", ", open, k, close);
  return " (known: " + list + ")";
}

}  // namespace

std::string didYouMean(const std::string& name, const std::vector<std::string>& known,
                       const std::string& quote_open, const std::string& quote_close) {
  const std::string* best = nullptr;
  std::size_t best_d = 0;
  for (const std::string& k : known) {
    const std::optional<std::size_t> d = nearness(name, k);
    if (d && (best == nullptr || *d < best_d)) {
      best = &k;
      best_d = *d;
    }
  }
  if (best == nullptr) return "";
  return " (did you mean " + quote_open + *best + quote_close + "?)";
}

void allowOnly(const XmlNode& e, std::initializer_list<const char*> names) {
  for (const auto& [k, v] : e.attributes) {
    if (contains(names, k)) continue;
    const std::vector<std::string> known = toStrings(names);
    std::string hint = didYouMean(k, known);
    if (hint.empty()) hint = knownList(known, "", "");
    e.fail(strCat("unknown attribute '", clipForMessage(k), "' on <", clipForMessage(e.name), ">",
                  hint));
  }
}

void allowChildren(const XmlNode& e, std::initializer_list<const char*> names) {
  for (const XmlNode& c : e.children) {
    if (contains(names, c.name)) continue;
    const std::vector<std::string> known = toStrings(names);
    std::string hint = didYouMean(c.name, known, "<", ">");
    if (hint.empty()) hint = knownList(known, "<", ">");
    c.fail("unknown element <" + clipForMessage(c.name) + "> in <" + clipForMessage(e.name) + ">" +
           hint);
  }
}

void allowAtMostOnce(const XmlNode& e, std::initializer_list<const char*> names) {
  for (const char* n : names) {
    const std::vector<const XmlNode*> all = e.childrenNamed(n);
    if (all.size() > 1) {
      all[1]->fail("<" + std::string(n) + "> is given twice in <" + e.name + "> (first at line " +
                   std::to_string(all[0]->line) + ")");
    }
  }
}

namespace {
XmlNode convert(const tinyxml2::XMLElement* e, const std::string& file) {
  XmlNode n;
  n.file = file;
  n.name = e->Name();
  n.line = e->GetLineNum();
  for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a != nullptr; a = a->Next()) {
    n.attributes.emplace_back(a->Name(), a->Value());
  }
  if (const char* t = e->GetText()) {
    std::string s = t;
    const auto b = s.find_first_not_of(" \t\r\n");
    const auto en = s.find_last_not_of(" \t\r\n");
    n.text = b == std::string::npos ? "" : s.substr(b, en - b + 1);
  }
  for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c != nullptr;
       c = c->NextSiblingElement()) {
    n.children.push_back(convert(c, file));
  }
  return n;
}
}  // namespace

XmlNode parseXmlText(const std::string& text, const std::string& file) {
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLError err = doc.Parse(text.c_str(), text.size());
  if (err != tinyxml2::XML_SUCCESS) {
    std::string detail = doc.ErrorStr() ? doc.ErrorStr() : "";
    // tinyxml2: "Error=XML_ERROR_X ErrorID=n (0xn) Line number=k: detail" -> keep the detail
    if (const auto p = detail.find(": "); p != std::string::npos) {
      detail = detail.substr(p + 2);
    } else if (detail.rfind("Error=", 0) == 0) {
      detail.clear();
    }
    std::string msg = std::string("malformed XML (") + doc.ErrorName() + ")";
    if (!detail.empty()) msg += ": " + detail;
    throw InputError(file, std::max(1, doc.ErrorLineNum()), msg);
  }
  const tinyxml2::XMLElement* root = doc.RootElement();
  if (root == nullptr) throw InputError(file, 1, "XML document has no root element");
  return convert(root, file);
}

XmlNode loadXmlFile(const std::string& path, InputKind kind) {
  return parseXmlText(readInputFile(path, kind), path);
}

}  // namespace roprec
