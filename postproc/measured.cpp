#include "postproc/measured.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string_view>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/fixed_chars.hpp"
#include "compensator/support/input_file.hpp"
#include "compensator/support/str_cat.hpp"
#include "postproc/text_lines.hpp"

namespace roprec::postproc {

const char* measuredFormatName(MeasuredFormat f) {
  switch (f) {
    case MeasuredFormat::kCsv:
      return "csv";
    case MeasuredFormat::kPcDmis:
      return "pc-dmis";
    case MeasuredFormat::kDmis:
      return "dmis";
  }
  return "?";
}

namespace {

// ---------------------------------------------------------------- text helpers

std::string upper(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return r;
}

std::string lowerAscii(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

/// CSV cells, trimmed; a cell in double quotes may hold commas ("" is a quote).
std::vector<std::string> csvCells(std::string_view line) {
  std::vector<std::string> cells;
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::string cell;
    if (i < line.size() && line[i] == '"') {
      ++i;
      while (i < line.size()) {
        if (line[i] == '"' && i + 1 < line.size() && line[i + 1] == '"') {
          cell += '"';
          i += 2;
        } else if (line[i] == '"') {
          ++i;
          break;
        } else {
          cell += line[i++];
        }
      }
      while (i < line.size() && line[i] != ',') ++i;
    } else {
      const std::size_t j = line.find(',', i);
      const std::size_t e = j == std::string_view::npos ? line.size() : j;
      cell = std::string(trimBlanks(line.substr(i, e - i)));
      i = e;
    }
    cells.push_back(cell);
    if (i >= line.size()) break;
    ++i;  // the comma
  }
  return cells;
}

/// A finite number (optional leading '+'), locale-independent; nullopt otherwise.
std::optional<double> parseFinite(std::string_view s) {
  s = trimBlanks(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty() || s.front() == '+') return std::nullopt;
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v, std::chars_format::general);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// ---------------------------------------------------------------- tabular formats (CSV, PC-DMIS)

/// Which header names a tabular format reads.
struct TableSpec {
  const char* format_label;
  const char* header_hint;
  bool lower_case_names;  ///< messages name the columns in lower case
  std::vector<std::string> id, x, y, z, i, j, k, u, d, type;  ///< accepted names (upper case)
};

const TableSpec& csvSpec() {
  static const TableSpec s{"roprec CSV",
                           "id,x,y,z[,i,j,k][,u]",
                           true,
                           {"ID"},
                           {"X"},
                           {"Y"},
                           {"Z"},
                           {"I"},
                           {"J"},
                           {"K"},
                           {"U"},
                           {},
                           {}};
  return s;
}

const TableSpec& pcDmisSpec() {
  static const TableSpec s{"PC-DMIS CSV",
                           "TYPE,NAME,X,Y,Z[,I,J,K]",
                           false,
                           {"NAME"},
                           {"X"},
                           {"Y"},
                           {"Z"},
                           {"I"},
                           {"J"},
                           {"K"},
                           {},
                           {"D", "DIAM", "DIAMETER"},
                           {"TYPE"}};
  return s;
}

/// Header name as compared: upper case, a unit suffix (_MM, _UM) dropped.
std::string headerKey(const std::string& cell) {
  std::string k = upper(cell);
  for (const char* suf : {"_MM", "_UM"}) {
    const std::string s(suf);
    if (k.size() > s.size() && k.compare(k.size() - s.size(), s.size(), s) == 0)
      k.erase(k.size() - s.size());
  }
  return k;
}

struct TableColumns {
  int id{-1}, x{-1}, y{-1}, z{-1}, i{-1}, j{-1}, k{-1}, u{-1}, d{-1}, type{-1};
};

int findColumn(const std::vector<std::string>& keys, const std::vector<std::string>& names) {
  for (std::size_t c = 0; c < keys.size(); ++c) {
    for (const std::string& n : names) {
      if (keys[c] == n) return static_cast<int>(c);
    }
  }
  return -1;
}

TableColumns tableColumns(const std::vector<std::string>& header, const TableSpec& spec,
                          const std::string& path, int line) {
  std::vector<std::string> keys;
  keys.reserve(header.size());
  for (const std::string& h : header) keys.push_back(headerKey(h));
  for (std::size_t a = 0; a < keys.size(); ++a) {
    for (std::size_t b = a + 1; b < keys.size(); ++b) {
      if (!keys[a].empty() && keys[a] == keys[b]) {
        throw InputError(path, line, "column '" + header[b] + "' appears twice in the header");
      }
    }
  }
  TableColumns c;
  c.id = findColumn(keys, spec.id);
  c.x = findColumn(keys, spec.x);
  c.y = findColumn(keys, spec.y);
  c.z = findColumn(keys, spec.z);
  c.i = findColumn(keys, spec.i);
  c.j = findColumn(keys, spec.j);
  c.k = findColumn(keys, spec.k);
  c.u = findColumn(keys, spec.u);
  c.d = findColumn(keys, spec.d);
  c.type = findColumn(keys, spec.type);
  const std::pair<int, const std::string*> required[] = {{c.id, &spec.id.front()},
                                                         {c.x, &spec.x.front()},
                                                         {c.y, &spec.y.front()},
                                                         {c.z, &spec.z.front()}};
  for (const auto& [col, name] : required) {
    if (col < 0) {
      const std::string shown = spec.lower_case_names ? lowerAscii(*name) : *name;
      throw InputError(path, line,
                       "missing column '" + shown + "' (a " + spec.format_label + " header names " +
                           spec.header_hint + ")");
    }
  }
  const int axis_given = (c.i >= 0) + (c.j >= 0) + (c.k >= 0);
  if (axis_given != 0 && axis_given != 3) {
    throw InputError(path, line, "the axis columns i, j, k must all be given, or none");
  }
  return c;
}

/// The value of an optional cell ("" when the row is shorter or the column absent).
std::string cellOf(const std::vector<std::string>& cells, int col) {
  return col >= 0 && static_cast<std::size_t>(col) < cells.size()
             ? cells[static_cast<std::size_t>(col)]
             : std::string();
}

double requiredNumber(const std::vector<std::string>& cells, int col, const char* name,
                      const std::string& path, int line) {
  const std::string s = cellOf(cells, col);
  if (s.empty())
    throw InputError(path, line, std::string("missing value in column '") + name + "'");
  const auto v = parseFinite(s);
  if (!v)
    throw InputError(path, line, "'" + s + "' in column '" + name + "' is not a finite number");
  return *v;
}

std::optional<double> optionalNumber(const std::vector<std::string>& cells, int col,
                                     const char* name, const std::string& path, int line) {
  if (cellOf(cells, col).empty()) return std::nullopt;
  return requiredNumber(cells, col, name, path, line);
}

Vec3 unitAxis(const Vec3& a, const std::string& path, int line) {
  const double n = a.norm();
  if (!(n > 1e-9)) throw InputError(path, line, "the measured axis (i, j, k) is zero");
  return a / n;
}

std::optional<Vec3> tableAxis(const std::vector<std::string>& cells, const TableColumns& c,
                              const std::string& path, int line) {
  const int empty =
      cellOf(cells, c.i).empty() + cellOf(cells, c.j).empty() + cellOf(cells, c.k).empty();
  if (empty == 3) return std::nullopt;
  if (empty != 0)
    throw InputError(path, line, "the axis cells i, j, k must all be given, or all be empty");
  const Vec3 a(requiredNumber(cells, c.i, "i", path, line),
               requiredNumber(cells, c.j, "j", path, line),
               requiredNumber(cells, c.k, "k", path, line));
  return unitAxis(a, path, line);
}

/// PC-DMIS rows whose TYPE names a hole-like feature (or is empty) are holes; datums are not.
bool holeType(const std::string& type) {
  const std::string t = upper(type);
  if (t.empty()) return true;
  for (const char* k : {"CIRC", "CYL", "HOLE", "POINT"}) {
    if (t.find(k) != std::string::npos) return true;
  }
  return false;
}

MeasuredHole tableRow(const std::vector<std::string>& cells, const TableColumns& c,
                      const std::string& path, int line) {
  MeasuredHole h;
  h.line = line;
  h.id = cellOf(cells, c.id);
  if (h.id.empty()) throw InputError(path, line, "empty hole id");
  h.p_mm =
      Vec3(requiredNumber(cells, c.x, "x", path, line), requiredNumber(cells, c.y, "y", path, line),
           requiredNumber(cells, c.z, "z", path, line));
  if (c.i >= 0) h.axis = tableAxis(cells, c, path, line);
  h.u_um = optionalNumber(cells, c.u, "u", path, line);
  if (h.u_um && *h.u_um < 0)
    throw InputError(path, line, "the measurement uncertainty u must be >= 0 µm");
  const auto d = optionalNumber(cells, c.d, "diameter", path, line);
  if (d && *d > 0) h.diameter_mm = d;
  return h;
}

/// Index of the header line: the first content line (roprec CSV), or the first line naming TYPE
/// and NAME (PC-DMIS, after a preamble).
std::size_t headerIndex(const std::vector<TextLine>& lines, MeasuredFormat f) {
  for (std::size_t n = 0; n < lines.size(); ++n) {
    if (isBlankOrComment(lines[n].text)) continue;
    if (f == MeasuredFormat::kCsv) return n;
    const std::vector<std::string> cells = csvCells(lines[n].text);
    std::vector<std::string> keys;
    keys.reserve(cells.size());
    for (const std::string& s : cells) keys.push_back(headerKey(s));
    if (findColumn(keys, {"TYPE"}) >= 0 && findColumn(keys, {"NAME"}) >= 0) return n;
  }
  return lines.size();
}

std::vector<MeasuredHole> readTable(const std::vector<TextLine>& lines, MeasuredFormat f,
                                    const std::string& path) {
  const TableSpec& spec = f == MeasuredFormat::kCsv ? csvSpec() : pcDmisSpec();
  const std::size_t h = headerIndex(lines, f);
  if (h >= lines.size())
    throw InputError(path, 1, std::string("no ") + spec.header_hint + " header");
  const std::size_t header_cells = csvCells(lines[h].text).size();
  const TableColumns c = tableColumns(csvCells(lines[h].text), spec, path, lines[h].number);
  std::vector<MeasuredHole> holes;
  for (std::size_t n = h + 1; n < lines.size(); ++n) {
    if (isBlankOrComment(lines[n].text)) continue;
    const std::vector<std::string> cells = csvCells(lines[n].text);
    // roprec CSV: a row longer than its header shifts the values (a decimal comma: "-200,28").
    std::size_t used = cells.size();  // trailing empty cells ("1,2,3,") are harmless
    while (used > header_cells && trimBlanks(cells[used - 1]).empty()) --used;
    if (f == MeasuredFormat::kCsv && used > header_cells)
      throw InputError(path, lines[n].number,
                       std::to_string(used) + " cells but the header has " +
                           std::to_string(header_cells) +
                           " (decimal commas? numbers use a point: -200.28)");
    if (c.type >= 0 && !holeType(cellOf(cells, c.type))) continue;
    holes.push_back(tableRow(cells, c, path, lines[n].number));
  }
  return holes;
}

// ---------------------------------------------------------------- DMIS

struct Statement {
  std::string text;  ///< joined, comment-free, trimmed
  int line{0};       ///< first physical line
};

/// DMIS statements: `$$` comments removed, `$`-continued lines joined.
std::vector<Statement> dmisStatements(const std::vector<TextLine>& lines) {
  std::vector<Statement> out;
  Statement cur;
  bool continuing = false;
  for (const TextLine& l : lines) {
    std::string_view t = l.text;
    if (const std::size_t c = t.find("$$"); c != std::string_view::npos) t = t.substr(0, c);
    t = trimBlanks(t);
    const bool cont = !t.empty() && t.back() == '$';
    if (cont) t = trimBlanks(t.substr(0, t.size() - 1));
    if (!continuing) cur = Statement{std::string(), l.number};
    cur.text += std::string(t);
    continuing = cont;
    if (!continuing && !cur.text.empty()) out.push_back(cur);
  }
  if (continuing && !cur.text.empty()) out.push_back(cur);
  return out;
}

/// A feature statement `F(label)=FEAT/...` or `FA(label)=FEAT/...`.
struct FeatureStatement {
  bool actual{false};
  std::string label;
  std::string body;  ///< after "FEAT/"
};

std::optional<FeatureStatement> featureStatement(const std::string& s) {
  const std::string u = upper(s);
  FeatureStatement f;
  std::size_t p = 0;
  if (u.rfind("FA(", 0) == 0) {
    f.actual = true;
    p = 3;
  } else if (u.rfind("F(", 0) == 0) {
    p = 2;
  } else {
    return std::nullopt;
  }
  const std::size_t close = s.find(')', p);
  if (close == std::string::npos) return std::nullopt;
  f.label = std::string(trimBlanks(std::string_view(s).substr(p, close - p)));
  std::size_t q = close + 1;
  while (q < s.size() && (s[q] == ' ' || s[q] == '\t')) ++q;
  if (q >= s.size() || s[q] != '=') return std::nullopt;
  ++q;
  while (q < s.size() && (s[q] == ' ' || s[q] == '\t')) ++q;
  if (u.compare(q, 5, "FEAT/") != 0) return std::nullopt;
  f.body = s.substr(q + 5);
  return f;
}

/// Length unit of a `UNITS/...` statement, in mm.
std::optional<double> dmisUnits(const std::string& s, const std::string& path, int line) {
  const std::string u = upper(s);
  if (u.rfind("UNITS/", 0) != 0) return std::nullopt;
  std::string_view rest = std::string_view(u).substr(6);
  rest = rest.substr(0, rest.find(','));
  const std::string unit(trimBlanks(rest));
  static const std::map<std::string, double> scale = {
      {"MM", 1.0}, {"CM", 10.0}, {"METER", 1000.0}, {"INCH", 25.4}, {"FEET", 304.8}};
  const auto it = scale.find(unit);
  if (it == scale.end()) throw InputError(path, line, "unknown DMIS length unit '" + unit + "'");
  return it->second;
}

/// A hole from a feature statement, or nullopt for a feature that is not a hole.
std::optional<MeasuredHole> dmisHole(const FeatureStatement& f, double unit_mm,
                                     const std::string& path, int line) {
  std::vector<std::string> a = csvCells(f.body);
  for (std::string& s : a) s = std::string(trimBlanks(s));
  const std::string type = a.empty() ? std::string() : upper(a[0]);
  if (type != "CIRCLE" && type != "CYLNDR") return std::nullopt;
  if (a.size() < 3 || upper(a[1]) == "OUTER") return std::nullopt;
  if (upper(a[1]) != "INNER")
    throw InputError(path, line, "F(" + f.label + "): expected INNER or OUTER, got '" + a[1] + "'");
  if (upper(a[2]) != "CART")
    throw InputError(path, line,
                     "F(" + f.label + "): only CART coordinates are read, got '" + a[2] + "'");
  static const char* names[] = {"x", "y", "z", "i", "j", "k", "diameter"};
  if (a.size() < 9)
    throw InputError(path, line, "F(" + f.label + "): a hole needs x,y,z,i,j,k after CART");
  double v[7] = {0, 0, 0, 0, 0, 0, 0};
  for (std::size_t n = 0; n < 7 && n + 3 < a.size(); ++n) {
    const auto x = parseFinite(a[n + 3]);
    if (!x)
      throw InputError(
          path, line,
          "F(" + f.label + "): '" + a[n + 3] + "' (" + names[n] + ") is not a finite number");
    v[n] = *x;
  }
  MeasuredHole h;
  h.id = f.label;
  h.line = line;
  if (h.id.empty()) throw InputError(path, line, "empty feature label");
  h.p_mm = Vec3(v[0], v[1], v[2]) * unit_mm;
  h.axis = unitAxis(Vec3(v[3], v[4], v[5]), path, line);
  if (v[6] > 0) h.diameter_mm = v[6] * unit_mm;
  return h;
}

std::vector<MeasuredHole> readDmis(const std::vector<TextLine>& lines, const std::string& path) {
  std::vector<MeasuredHole> nominal;
  std::vector<MeasuredHole> actual;
  double unit_mm = 1.0;
  for (const Statement& s : dmisStatements(lines)) {
    if (const auto u = dmisUnits(s.text, path, s.line)) {
      unit_mm = *u;
      continue;
    }
    const auto f = featureStatement(s.text);
    if (!f) continue;
    if (auto h = dmisHole(*f, unit_mm, path, s.line)) (f->actual ? actual : nominal).push_back(*h);
  }
  return actual.empty() ? nominal : actual;
}

void requireUniqueIds(const std::vector<MeasuredHole>& holes, const std::string& path) {
  std::map<std::string, int> first;
  for (const MeasuredHole& h : holes) {
    const auto [it, inserted] = first.emplace(h.id, h.line);
    if (!inserted) {
      throw InputError(
          path, h.line,
          "duplicate hole id '" + h.id + "' (first on line " + std::to_string(it->second) + ")");
    }
  }
}

/// Measured values a CMM can produce: every |coordinate| ≤ 100 m (1e5 mm) from the workobject
/// origin, u ≤ 10 mm (1e4 µm), a diameter ≤ 2 m. A value beyond is a corrupted or mis-scaled file
/// (1e300 would overflow the statistics). Throws InputError at the hole's line.
void requirePlausible(const std::vector<MeasuredHole>& holes, const std::string& path) {
  for (const MeasuredHole& h : holes) {
    if (h.p_mm.cwiseAbs().maxCoeff() > 1e5)
      throw InputError(path, h.line,
                       "hole '" + h.id +
                           "': a coordinate lies more than 100 m from the workobject origin "
                           "(positions are in mm, in the workobject frame)");
    if (h.u_um && *h.u_um > 1e4)
      throw InputError(path, h.line,
                       "hole '" + h.id +
                           "': the measurement uncertainty u is over 10 mm "
                           "(u is a standard uncertainty per axis in µm)");
    if (h.diameter_mm && *h.diameter_mm > 2000)
      throw InputError(path, h.line, "hole '" + h.id + "': the diameter is over 2 m (mm expected)");
  }
}

// ---------------------------------------------------------------- writers

/// Fixed notation, locale-independent; "-0.000" printed as "0.000".
std::string fixed(double v, int decimals) {
  std::string s;
  appendFixed(s, v, decimals);
  return s;
}

std::string csvId(const std::string& id) {
  if (id.find_first_of(",\"\n\r") == std::string::npos && trimBlanks(id) == id) return id;
  std::string q = "\"";
  for (const char c : id) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

bool anyAxis(const std::vector<MeasuredHole>& holes) {
  for (const MeasuredHole& h : holes) {
    if (h.axis) return true;
  }
  return false;
}

std::string axisCells(const MeasuredHole& h) {
  if (!h.axis) return ",,";
  return fixed(h.axis->x(), 9) + "," + fixed(h.axis->y(), 9) + "," + fixed(h.axis->z(), 9);
}

std::string positionCells(const MeasuredHole& h, int decimals) {
  return fixed(h.p_mm.x(), decimals) + "," + fixed(h.p_mm.y(), decimals) + "," +
         fixed(h.p_mm.z(), decimals);
}

}  // namespace

std::optional<MeasuredFormat> detectMeasuredFormat(const std::string& text) {
  const std::vector<TextLine> lines = splitTextLines(text);
  for (const Statement& s : dmisStatements(lines)) {
    if (featureStatement(s.text)) return MeasuredFormat::kDmis;
  }
  std::size_t first = lines.size();
  for (std::size_t n = 0; n < lines.size() && first == lines.size(); ++n) {
    if (!isBlankOrComment(lines[n].text)) first = n;
  }
  if (first == lines.size()) return std::nullopt;
  std::vector<std::string> keys;
  for (const std::string& s : csvCells(lines[first].text)) keys.push_back(headerKey(s));
  if (findColumn(keys, {"ID"}) >= 0) return MeasuredFormat::kCsv;
  if (headerIndex(lines, MeasuredFormat::kPcDmis) < lines.size()) return MeasuredFormat::kPcDmis;
  return std::nullopt;
}

MeasuredHoles parseMeasured(const std::string& text, const std::string& path) {
  const auto format = detectMeasuredFormat(text);
  const std::vector<TextLine> lines = splitTextLines(text);
  if (!format) {
    int line = 1;
    for (const TextLine& l : lines) {
      if (!isBlankOrComment(l.text)) {
        line = l.number;
        break;
      }
    }
    throw InputError(
        path, line,
        "not a measured-hole file: expected a CSV header id,x,y,z[,i,j,k][,u], a PC-DMIS CSV "
        "header "
        "TYPE,NAME,X,Y,Z,... or DMIS statements F(id)=FEAT/CIRCLE,INNER,CART,x,y,z,i,j,k,diam");
  }
  MeasuredHoles m;
  m.path = path;
  m.format = *format;
  m.holes =
      *format == MeasuredFormat::kDmis ? readDmis(lines, path) : readTable(lines, *format, path);
  requireUniqueIds(m.holes, path);
  requirePlausible(m.holes, path);
  return m;
}

MeasuredHoles readMeasured(const std::string& path) {
  return parseMeasured(readInputFile(path, InputKind::kMeasured), path);
}

std::string writeMeasuredCsv(const std::vector<MeasuredHole>& holes,
                             const MeasuredWriteOptions& o) {
  const bool axis = anyAxis(holes);
  bool u = false;
  for (const MeasuredHole& h : holes) u = u || h.u_um.has_value();
  std::string s = std::string("id,x,y,z") + (axis ? ",i,j,k" : "") + (u ? ",u" : "") + "\n";
  for (const MeasuredHole& h : holes) {
    s += csvId(h.id) + "," + positionCells(h, o.decimals);
    if (axis) {
      s += ',';
      s += axisCells(h);
    }
    if (u) {
      s += ',';
      if (h.u_um) s += fixed(*h.u_um, 3);
    }
    s += '\n';
  }
  return s;
}

std::string writeMeasuredPcDmis(const std::vector<MeasuredHole>& holes,
                                const MeasuredWriteOptions& o) {
  std::string s = "TYPE,NAME,X,Y,Z,I,J,K,D\n";
  for (const MeasuredHole& h : holes) {
    s += "CIRCLE," + csvId(h.id) + "," + positionCells(h, o.decimals) + "," + axisCells(h) + "," +
         (h.diameter_mm ? fixed(*h.diameter_mm, o.decimals) : std::string()) + "\n";
  }
  return s;
}

std::string writeMeasuredDmis(const std::vector<MeasuredHole>& holes,
                              const MeasuredWriteOptions& o) {
  std::string s = "DMISMN/'roprec measured holes',05.3\nUNITS/MM,ANGDEC\n";
  for (const MeasuredHole& h : holes) {
    if (!h.axis)
      throw std::invalid_argument("DMIS needs an axis for every hole: hole '" + h.id +
                                  "' has none");
    if (h.id.find_first_of(")\n\r") != std::string::npos) {
      throw std::invalid_argument("hole id '" + h.id + "' cannot be a DMIS label");
    }
    s += "FA(" + h.id + ")=FEAT/CIRCLE,INNER,CART," + positionCells(h, o.decimals) + "," +
         axisCells(h) + "," + fixed(h.diameter_mm.value_or(0.0), o.decimals) + "\n";
  }
  return s + "ENDFIL\n";
}

std::string writeMeasured(const std::vector<MeasuredHole>& holes, MeasuredFormat format,
                          const MeasuredWriteOptions& o) {
  switch (format) {
    case MeasuredFormat::kCsv:
      return writeMeasuredCsv(holes, o);
    case MeasuredFormat::kPcDmis:
      return writeMeasuredPcDmis(holes, o);
    case MeasuredFormat::kDmis:
      return writeMeasuredDmis(holes, o);
  }
  return {};
}

// ---------------------------------------------------------------- matching

namespace {

double maxProgramSpan(const std::vector<ProgramHoleRef>& program) {
  double span = 0;
  for (std::size_t a = 0; a < program.size(); ++a) {
    for (std::size_t b = a + 1; b < program.size(); ++b)
      span = std::max(span, (program[a].p_mm - program[b].p_mm).norm());
  }
  return span;
}

/// Every measured |coordinate| < 5 although the program spans ≥ 10 mm, and the matched holes read
/// as mm are not near their nominal positions: the file is in metres.
void refuseMetres(const MeasuredHoles& m, const std::vector<ProgramHoleRef>& program,
                  const MeasuredMatch& match) {
  for (const MeasuredHole& h : m.holes) {
    if (h.p_mm.cwiseAbs().maxCoeff() >= 5.0) return;
  }
  const double span = maxProgramSpan(program);
  if (span < 10.0) return;
  double sum2 = 0;
  for (std::size_t p = 0; p < program.size(); ++p) {
    const int k = match.measured_of_program[p];
    if (k >= 0) sum2 += (m.holes[static_cast<std::size_t>(k)].p_mm - program[p].p_mm).squaredNorm();
  }
  if (std::sqrt(sum2 / match.matched) <= 1.0) return;
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, span, std::chars_format::fixed, 1);
  throw InputError(m.path, m.holes.empty() ? 0 : m.holes.front().line,
                   "the measured positions look like metres (every |coordinate| < 5 while the "
                   "program's holes are up "
                   "to " +
                       std::string(buf, r.ptr) +
                       " mm apart): give them in mm, in the workobject frame");
}

}  // namespace

MeasuredMatch matchMeasured(const MeasuredHoles& measured,
                            const std::vector<ProgramHoleRef>& program) {
  MeasuredMatch r;
  r.measured_of_program.assign(program.size(), -1);
  std::map<std::string, int> program_index;
  for (std::size_t p = 0; p < program.size(); ++p)
    program_index.emplace(program[p].id, static_cast<int>(p));
  for (std::size_t k = 0; k < measured.holes.size(); ++k) {
    const auto it = program_index.find(measured.holes[k].id);
    if (it == program_index.end()) {
      r.unknown.push_back(static_cast<int>(k));
      continue;
    }
    r.measured_of_program[static_cast<std::size_t>(it->second)] = static_cast<int>(k);
    ++r.matched;
  }
  for (std::size_t p = 0; p < program.size(); ++p) {
    if (r.measured_of_program[p] < 0) r.unmeasured.push_back(static_cast<int>(p));
  }
  if (r.matched == 0) {
    throw InputError(measured.path, measured.holes.empty() ? 0 : measured.holes.front().line,
                     "no measured hole id matches a hole of the program");
  }
  refuseMetres(measured, program, r);
  return r;
}

}  // namespace roprec::postproc
