#include "postproc/convert.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/str_cat.hpp"
#include "postproc/dialects.hpp"
#include "postproc/lexer.hpp"

namespace roprec::postproc {
namespace {

namespace fs = std::filesystem;

std::string fmt(double v, int decimals) {
  std::string s = cFixed(v, decimals);  // "C" format whatever the locale
  bool zero = true;
  for (const char c : s) zero = zero && (c == '-' || c == '0' || c == '.');
  if (zero && !s.empty() && s[0] == '-') s.erase(0, 1);
  return s;
}

std::string fmtG(double v) { return cGeneral(v, 10); }

std::string sanitize(const std::string& s, const std::string& fallback) {
  std::string r;
  for (const char c : s) r += (isIdentChar(c) || c == '[' || c == ']') ? c : '_';
  return r.empty() ? fallback : r;
}

std::string programName(const std::string& out_path, std::size_t max_len) {
  std::string stem = fs::path(out_path).stem().string();
  std::string r;
  for (const char c : stem) r += isIdentChar(c) && c != '$' ? c : '_';
  if (r.empty() || isDigit(r[0])) r = "P" + r;
  if (r.size() > max_len) r.resize(max_len);
  return r;
}

constexpr double kUnusedExt = 9e9;  ///< RAPID's "no external axis" value (9E+09)

struct Item {
  int motion{-1};
  MotionType type{MotionType::kLinear};
  bool cartesian{true};
  Pose T{Pose::Identity()};
  int target{-1};
  int key{
      -1};  ///< output-name key: the target, or a unique key when an offset makes the pose differ
  int aux{-1};
  Pose Taux{Pose::Identity()};
  const Frame* base{nullptr};
  const Frame* tool{nullptr};
  Configuration config;
  std::vector<double> ext;
  std::vector<double> joints;
  double speed{-1};
  bool fine{false};
};

std::vector<Item> collect(const Program& p, bool joints_ok, ConversionReport& rep) {
  std::vector<Item> items;
  for (std::size_t i = 0; i < p.motions.size(); ++i) {
    const Motion& m = p.motions[i];
    const std::string& path = p.files[static_cast<std::size_t>(m.file)].path;
    const std::string where = m.line > 0 ? path + ":" + std::to_string(m.line) : path;
    if (m.target < 0) {
      rep.skipped.push_back(where + ": " + p.text(m.instruction) + " " + p.text(m.target_text) +
                            " (target built at run time" +
                            (m.derivation.empty() ? "" : ": " + p.text(m.derivation)) + ")");
      continue;
    }
    const Target& t = p.targets()[static_cast<std::size_t>(m.target)];
    Item it;
    it.motion = static_cast<int>(i);
    it.type = m.type;
    it.target = m.target;
    it.key = m.has_offset ? -static_cast<int>(i) - 2 : m.target;
    it.base = m.base >= 0 ? &p.frames[static_cast<std::size_t>(m.base)] : nullptr;
    it.tool = m.tool >= 0 ? &p.frames[static_cast<std::size_t>(m.tool)] : nullptr;
    it.config = t.config;
    it.speed = m.speed_mm_s;
    it.fine = m.fine;
    for (const NumberField& e : t.ext) it.ext.push_back(e.present() ? e.value : kUnusedExt);
    if (t.kind == TargetKind::kJoint) {
      if (!joints_ok) {
        rep.skipped.push_back(
            where + ": joint target " + (t.name.empty() ? std::string("(inline)") : t.name) +
            " (joint conventions differ between vendors; re-teach it in the output)");
        continue;
      }
      it.cartesian = false;
      it.joints = targetJointsDeg(t);
      items.push_back(std::move(it));
      continue;
    }
    const std::optional<Pose> T = motionPose(p, m);
    if (!T) {
      rep.skipped.push_back(where + ": " + p.text(m.target_text) +
                            " (incomplete pose or unknown offset)");
      continue;
    }
    it.T = *T;
    if (m.aux >= 0) {
      const Target& a = p.targets()[static_cast<std::size_t>(m.aux)];
      if (a.kind != TargetKind::kCartesian || !targetComplete(a)) {
        rep.skipped.push_back(where + ": circular motion with a non-Cartesian auxiliary point");
        continue;
      }
      it.aux = m.aux;
      it.Taux = targetPose(p, a);
    } else if (m.type == MotionType::kCircular) {
      it.type = MotionType::kLinear;
      rep.notes.push_back(where + ": circular motion without auxiliary point written as linear");
    }
    items.push_back(std::move(it));
  }
  return items;
}

/// KRL states E1..E6 in every E6POS, 0 for axes the cell does not have: an external axis that is
/// 0 in every Cartesian target of a KRL source is taken as unused (RAPID 9E+09, not written in
/// KRL/TP), and said in a note. Other dialects state only the axes they have.
void markUnusedKrlExternalAxes(const Program& p, std::vector<Item>& items, ConversionReport& rep) {
  if (p.dialect != Dialect::kKrl) return;
  std::string zero_axes;
  for (std::size_t k = 0; k < 6; ++k) {
    bool seen = false;
    bool zero = true;
    for (const Item& it : items) {
      if (!it.cartesian || k >= it.ext.size() || std::fabs(it.ext[k]) >= 8e9) continue;
      seen = true;
      zero = zero && it.ext[k] == 0.0;
    }
    if (!seen || !zero) continue;
    for (Item& it : items) {
      if (k < it.ext.size()) it.ext[k] = kUnusedExt;
    }
    zero_axes += (zero_axes.empty() ? "E" : ", E") + std::to_string(k + 1);
  }
  if (!zero_axes.empty())
    rep.notes.push_back(zero_axes +
                        " = 0 in every target of the KRL source: taken as unused "
                        "external axes (RAPID 9E+09)");
}

bool hasExt(const Item& it, std::size_t k) {
  return k < it.ext.size() && std::fabs(it.ext[k]) < 8e9;
}

std::string abcText(const Pose& T) {
  const Vec3 abc = zyxFromRotation(T.linear()) / kDeg;
  return "X " + fmt(T.translation().x() * 1e3, 6) + ",Y " + fmt(T.translation().y() * 1e3, 6) +
         ",Z " + fmt(T.translation().z() * 1e3, 6) + ",A " + fmt(abc[0], 9) + ",B " +
         fmt(abc[1], 9) + ",C " + fmt(abc[2], 9);
}

std::optional<int> tableIndex(const std::string& ref, const char* table) {
  const std::string u = upper(ref);
  const std::string t(table);
  if (u.rfind(t + "[", 0) != 0 || u.back() != ']') return std::nullopt;
  const std::string n = u.substr(t.size() + 1, u.size() - t.size() - 2);
  if (n.empty() || n.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  if (n.size() > 9) return std::nullopt;
  return std::atoi(n.c_str());
}

void requireResolved(const Frame* f, const std::string& path, const char* what) {
  if (f != nullptr && !f->resolved) {
    throw InputError(path, 0,
                     std::string(what) + " '" + f->ref +
                         "' is not defined in the program; give its value with --frame '" + f->ref +
                         "=x y z a b c'");
  }
}

// ---------------------------------------------------------------- what the new program drops

/// Line `l` (0-based) of `f` without its terminator.
std::string lineAt(const SourceFile& f, std::size_t l) {
  const std::size_t a = f.line_starts[l];
  std::size_t b = l + 1 < f.line_starts.size() ? f.line_starts[l + 1] : f.bytes.size();
  while (b > a && (f.bytes[b - 1] == '\n' || f.bytes[b - 1] == '\r')) --b;
  return f.bytes.substr(a, b - a);
}

/// `s` up to its comment (`comment` outside double quotes), trimmed.
std::string codeOf(const std::string& s, const char* comment) {
  bool in_string = false;
  std::size_t end = s.size();
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '"') in_string = !in_string;
    if (!in_string && s.compare(i, std::strlen(comment), comment) == 0) {
      end = i;
      break;
    }
  }
  std::size_t a = 0;
  while (a < end && (s[a] == ' ' || s[a] == '\t')) ++a;
  while (end > a && (s[end - 1] == ' ' || s[end - 1] == '\t')) --end;
  return s.substr(a, end - a);
}

/// The first word of `u` (upper case): identifier characters up to the first other character.
std::string firstWord(const std::string& u) {
  std::size_t n = 0;
  while (n < u.size() && isIdentChar(u[n])) ++n;
  return u.substr(0, n);
}

bool oneOf(const std::string& w, std::initializer_list<const char*> words) {
  for (const char* x : words) {
    if (w == x) return true;
  }
  return false;
}

bool startsWith(const std::string& u, std::initializer_list<const char*> prefixes) {
  for (const char* x : prefixes) {
    if (u.rfind(x, 0) == 0) return true;
  }
  return false;
}

/// KRL: the kind of a code line the minimal program does not carry; "" when it is carried or
/// structure (declarations, frames and speeds carried by value, inline-form motion parameters).
std::string krlKind(const std::string& u) {
  const std::string w = firstWord(u);
  if (u.empty() || u[0] == '&' ||
      oneOf(w, {"DEF",  "END",      "DEFDAT",   "ENDDAT",    "DEFFCT",    "ENDFCT",  "DECL",
                "EXT",  "EXTFCT",   "SIGNAL",   "STRUC",     "ENUM",      "PTP",     "LIN",
                "CIRC", "SPTP",     "SLIN",     "SCIRC",     "PTP_REL",   "LIN_REL", "BAS",
                "INI",  "PDAT_ACT", "LDAT_ACT", "FDAT_ACT",  "$BWDSTART", "$H_POS",  "$VEL",
                "$ACC", "$BASE",    "$TOOL",    "BASE_DATA", "TOOL_DATA"}))
    return "";
  if (w == "GLOBAL") return u.find("INTERRUPT") != std::string::npos ? "interrupt" : "";
  if (w == "WAIT") return "wait";
  if (w == "$APO") return "approximation parameter";
  if (oneOf(w, {"$OUT", "$ANOUT", "ANOUT", "PULSE", "$OUT_C"})) return "I/O";
  if (w == "INTERRUPT") return "interrupt";
  if (oneOf(w, {"IF",        "ELSE",    "ENDIF",  "FOR",   "ENDFOR", "WHILE",   "ENDWHILE",
                "LOOP",      "ENDLOOP", "REPEAT", "UNTIL", "SWITCH", "CASE",    "DEFAULT",
                "ENDSWITCH", "GOTO",    "EXIT",   "HALT",  "RETURN", "CONTINUE"}))
    return "control flow";
  if (!w.empty() && u.size() > w.size() &&
      u.find_first_not_of(" \t", w.size()) != std::string::npos &&
      u[u.find_first_not_of(" \t", w.size())] == '(')
    return "call";
  return u.find('=') != std::string::npos ? "assignment" : "other";
}

/// RAPID: as krlKind. ConfJ/ConfL are written \Off (the header says so).
std::string rapidKind(const std::string& u) {
  const std::string w = firstWord(u);
  if (oneOf(w,
            {"MODULE", "ENDMODULE", "PROC",  "ENDPROC", "FUNC",  "ENDFUNC", "TRAP",     "ENDTRAP",
             "LOCAL",  "TASK",      "PERS",  "VAR",     "CONST", "ERROR",   "BACKWARD", "UNDO",
             "CONFJ",  "CONFL",     "MOVEL", "MOVEJ",   "MOVEC", "MOVEABSJ"}))
    return "";
  if (w.rfind("WAIT", 0) == 0) return "wait";
  if (oneOf(w, {"SETDO", "SET", "RESET", "PULSEDO", "SETAO", "SETGO", "INVERTDO", "SETDO"}))
    return "I/O";
  if (oneOf(w, {"IF",       "ELSEIF", "ELSE",  "ENDIF",   "FOR",     "ENDFOR", "WHILE",
                "ENDWHILE", "TEST",   "CASE",  "DEFAULT", "ENDTEST", "GOTO",   "RETURN",
                "EXIT",     "STOP",   "BREAK", "RAISE",   "RETRY",   "TRYNEXT"}))
    return "control flow";
  const std::size_t k = u.find_first_not_of(" \t", w.size());
  if (k != std::string::npos && (u.compare(k, 2, ":=") == 0 || u[k] == '{' || u[k] == '.'))
    return "assignment";
  return w.empty() ? "other" : "call";
}

/// A RAPID line that opens or closes a block (no `;` ends it).
bool rapidBlockLine(const std::string& u) {
  return oneOf(firstWord(u),
               {"MODULE",   "ENDMODULE", "PROC",   "ENDPROC", "FUNC",    "ENDFUNC", "TRAP",
                "ENDTRAP",  "IF",        "ELSEIF", "ELSE",    "ENDIF",   "FOR",     "ENDFOR",
                "WHILE",    "ENDWHILE",  "TEST",   "CASE",    "DEFAULT", "ENDTEST", "ERROR",
                "BACKWARD", "UNDO",      "LOCAL",  "TASK"}) &&
         u.find(';') == std::string::npos;
}

/// FANUC TP (a /MN line without its number and `;`): as krlKind.
std::string tpKind(const std::string& u) {
  const std::string w = firstWord(u);
  if (u.empty() || u[0] == '!' || u.rfind("//", 0) == 0 || u[0] == ':' ||
      oneOf(w, {"J", "L", "C", "A", "UFRAME_NUM", "UTOOL_NUM", "OFFSET", "TOOL_OFFSET"}))
    return "";
  if (w == "WAIT") return "wait";
  if (startsWith(u, {"DO[", "RO[", "AO[", "GO[", "SDO[", "F[", "PULSE"})) return "I/O";
  if (oneOf(w, {"CALL", "RUN"})) return "call";
  if (oneOf(w, {"LBL", "JMP", "IF", "SELECT", "ELSE", "ENDIF", "FOR", "ENDFOR", "END", "ABORT",
                "PAUSE"}))
    return "control flow";
  if (startsWith(u, {"R[", "PR[", "AR["})) return "register";
  return "other";
}

/// Reads a program's main file line by line and names the kind of each instruction the new
/// program does not carry (`kind` empty: carried, structure, comment or a motion).
class LineScanner {
 public:
  explicit LineScanner(const Program& p) : p_(p) {
    for (const Frame& fr : p.frames) {
      if (fr.resolved) carried_vars_.insert(upper(fr.ref));
    }
    for (const Motion& m : p.motions) {
      if (m.speed_mm_s > 0) carried_vars_.insert(upper(p.text(m.speed_text)));
    }
  }
  /// The code of `raw` (comment stripped) in `code` and its kind ("" when nothing is lost).
  std::string kind(const std::string& raw, std::string& code) {
    if (p_.dialect == Dialect::kTp) return tp(raw, code);
    if (p_.dialect == Dialect::kRapid) return rapid(raw, code);
    code = codeOf(raw, ";");
    return krlKind(upper(code));
  }

 private:
  std::string tp(const std::string& raw, std::string& code) {
    if (!raw.empty() && raw[0] == '/') {  // a section: only /MN holds instructions
      in_mn_ = raw.rfind("/MN", 0) == 0;
      return "";
    }
    const std::size_t first = raw.find_first_not_of(' ');
    if (!in_mn_ || first == std::string::npos || raw[first] == ':')
      return "";  // outside /MN, blank, or the second line of a C motion
    const std::size_t colon = raw.find(':');
    code = codeOf(colon == std::string::npos ? raw : raw.substr(colon + 1), "\x01");
    while (!code.empty() && (code.back() == ';' || code.back() == ' ' || code.back() == '\t'))
      code.pop_back();
    return tpKind(upper(code));
  }

  std::string rapid(const std::string& raw, std::string& code) {
    code = codeOf(raw, "!");
    if (code == "%%%") in_header_ = !in_header_;  // the module header: VERSION, LANGUAGE
    if (code.empty() || code == "%%%" || in_header_) return "";
    const std::string u = upper(code);
    const bool continued = open_;
    open_ = !rapidBlockLine(u) && code.back() != ';';
    if (continued) return "";
    const std::string k = rapidKind(u);
    // `rdkWObj.uframe := ...`, `rdkSpeed := ...`: frames and speeds the new program states by
    // value (the reader resolved them)
    return k == "assignment" && carried_vars_.count(firstWord(u)) ? "" : k;
  }

  const Program& p_;
  std::set<std::string> carried_vars_;  ///< upper case
  bool in_mn_{false};                   ///< TP: inside /MN
  bool in_header_{false};               ///< RAPID: inside the %%% header
  bool open_{false};                    ///< RAPID: a statement continues on the next line
};

/// A notice's line numbers "19,28,37": as many as fit in `budget` characters, followed by ",..."
/// when some are left out (the notice states the count); with `all_lines` every one, as
/// "19, 28, 37" (the CLI cuts a word of over 1000 bytes on stderr: clipLongWords).
std::string lineList(const std::vector<int>& lines, bool all_lines, std::size_t budget) {
  std::string s;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string n = std::to_string(lines[i]);
    if (!all_lines && s.size() + n.size() + 5 > budget) return s + ",...";
    if (i) s += all_lines ? ", " : ",";
    s += n;
  }
  return s;
}

/// Every instruction of the source that the new program does not carry, as
/// "FILE:LINE: text (kind)", in source order; an instruction written several times (a WAIT per
/// hole) once, at its first line: "FILE:19: WAIT SEC 0.3 (wait; 204 in all, lines 19,28,...)"
/// (every line with `all_lines`, else a notice of at most kNoticeBytes).
void listNotCarried(const Program& p, bool all_lines, ConversionReport& rep) {
  if (p.files.empty() ||
      (p.dialect != Dialect::kKrl && p.dialect != Dialect::kRapid && p.dialect != Dialect::kTp))
    return;  // a target list has nothing but targets
  const SourceFile& f = p.files[0];
  std::vector<char> motion_line(f.line_starts.size() + 1, 0);  // by line number
  for (const Motion& m : p.motions) {
    if (m.file == 0 && m.line > 0 && static_cast<std::size_t>(m.line) < motion_line.size())
      motion_line[static_cast<std::size_t>(m.line)] = 1;
  }
  std::vector<std::string> order;                 // "text (kind" in first-seen order
  std::map<std::string, std::vector<int>> lines;  // its lines
  LineScanner scan(p);
  for (std::size_t l = 0; l < f.line_starts.size(); ++l) {
    std::string code;
    const std::string kind = scan.kind(lineAt(f, l), code);
    if (kind.empty() || motion_line[l + 1]) continue;
    if (code.size() > 60) code = code.substr(0, 57) + "...";
    const std::string key = strCat(code, " (", kind);
    if (!lines.count(key)) order.push_back(key);
    lines[key].push_back(static_cast<int>(l + 1));
  }
  for (const std::string& key : order) {
    const std::vector<int>& at = lines[key];
    std::string s = f.path + ":" + std::to_string(at[0]) + ": " + key;
    if (at.size() > 1) {
      s += "; " + std::to_string(at.size()) + " in all, lines ";
      s += lineList(at, all_lines, kNoticeBytes - std::min(kNoticeBytes / 2, s.size() + 1));
    }
    rep.not_carried.push_back(s + ")");
  }
}

/// The zone the writer of `to` gives a motion (fine: exact stop).
std::string writtenZone(Dialect to, const Item& it) {
  if (to == Dialect::kKrl)
    return it.fine ? "exact stop" : it.type == MotionType::kJoint ? "C_PTP" : "C_DIS";
  if (to == Dialect::kRapid) return it.fine ? "fine" : "z1";
  return it.fine ? "FINE" : "CNT100";
}

/// One line per zone mapping that changes what the source says ("z10 -> C_DIS"), with the
/// source lines of the motions it concerns: "zone z10 -> C_DIS at FILE:12,14,20 (3 motions)"
/// (every line with `all_lines`, else a notice of at most kNoticeBytes).
void listZoneMappings(const Program& p, Dialect to, const std::vector<Item>& items, bool all_lines,
                      ConversionReport& rep) {
  std::vector<std::string> order;
  std::map<std::string, std::pair<std::string, std::vector<int>>> seen;  // mapping -> file, lines
  for (const Item& it : items) {
    const Motion& m = p.motions[static_cast<std::size_t>(it.motion)];
    if (it.fine) continue;  // exact stop in, exact stop out
    const std::string from =
        m.zone_text.empty() ? std::string("approximated") : p.text(m.zone_text);
    const std::string into = writtenZone(to, it);
    bool same = true;  // KRL may repeat the word: `C_DIS C_DIS`
    for (std::size_t a = 0; a < from.size();) {
      const std::size_t b = std::min(from.find(' ', a), from.size());
      same = same && iequals(from.substr(a, b - a), into);
      a = b + 1;
    }
    if (same) continue;
    const std::string key = strCat(from, " -> ", into);
    if (!seen.count(key)) {
      order.push_back(key);
      seen[key].first = p.files[static_cast<std::size_t>(m.file)].path;
    }
    seen[key].second.push_back(m.line);
  }
  for (const std::string& key : order) {
    const auto& [file, lines] = seen[key];
    std::string s = strCat("zone ", key, " at ", file, ":");
    const std::string tail = " (" + std::to_string(lines.size()) +
                             (lines.size() == 1 ? " motion" : " motions") +
                             "; the approximation size is not carried)";
    s += lineList(lines, all_lines,
                  kNoticeBytes - std::min(kNoticeBytes / 2, s.size() + tail.size()));
    s += tail;
    rep.not_carried.push_back(s);
  }
}

// ---------------------------------------------------------------- KRL

std::vector<std::pair<std::string, std::string>> toKrl(const Program& p,
                                                       const std::vector<Item>& items,
                                                       const std::string& out,
                                                       ConversionReport& rep) {
  const std::string name = programName(out, 24);
  const std::string src_name = fs::path(p.files[0].path).filename().string();
  std::string src = "&ACCESS RVP\n&REL 1\nDEF " + name + "( )\n";
  src += "; generated by roprec convert from " + src_name + "\n";
  src +=
      "; configuration carried at the branch level: S bits 0-2 (bit 1 = elbow up); T not carried\n";
  src += "BAS(#INITMOV,0)\n";
  std::string dat = "&ACCESS RVP\n&REL 1\nDEFDAT " + name + "\n";
  std::map<int, std::string> names;
  auto decl = [&](int target, const Pose& T, const Configuration& c, const Item& it) {
    const auto f = names.find(target);
    if (f != names.end()) return f->second;
    std::string n = "XP" + std::to_string(names.size() + 1);
    names[target] = n;
    std::string d = "DECL E6POS " + n + "={" + abcText(T);
    if (const auto b = c.branch())
      d += ",S " + std::to_string(configurationFromBranch(Vendor::kKuka, *b).status);
    for (std::size_t k = 0; k < 6; ++k) {
      if (hasExt(it, k)) d += ",E" + std::to_string(k + 1) + " " + fmt(it.ext[k], 6);
    }
    dat += d + "}\n";
    return n;
  };
  const Frame* cur_base = nullptr;
  const Frame* cur_tool = nullptr;
  bool first = true;
  double vel = -1;
  for (const Item& it : items) {
    if (first || it.base != cur_base) {
      if (it.base == nullptr) {
        src += "BAS(#BASE,0)\n";
        rep.notes.push_back("no base frame in the source: poses written in $WORLD (BASE 0)");
      } else if (!it.base->resolved && tableIndex(it.base->ref, "BASE_DATA")) {
        src += "$BASE=" + it.base->ref + "\n";
      } else {
        requireResolved(it.base, p.files[0].path, "base frame");
        src += "$BASE={FRAME: " + abcText(it.base->pose) + "} ; " + it.base->ref + "\n";
      }
      cur_base = it.base;
    }
    if (first || it.tool != cur_tool) {
      if (it.tool == nullptr) {
        src += "BAS(#TOOL,0)\n";
        rep.notes.push_back("no tool in the source: TCP = flange (TOOL 0)");
      } else if (!it.tool->resolved && tableIndex(it.tool->ref, "TOOL_DATA")) {
        src += "$TOOL=" + it.tool->ref + "\n";
      } else {
        requireResolved(it.tool, p.files[0].path, "tool");
        src += "$TOOL={FRAME: " + abcText(it.tool->pose) + "} ; " + it.tool->ref + "\n";
      }
      cur_tool = it.tool;
    }
    first = false;
    if (it.type != MotionType::kJoint && it.speed > 0 && it.speed != vel) {
      src += "$VEL.CP=" + fmtG(it.speed / 1000.0) + "\n";
      vel = it.speed;
    }
    const std::string n = decl(it.key, it.T, it.config, it);
    if (it.type == MotionType::kJoint) {
      src += "PTP " + n + (it.fine ? "" : " C_PTP") + "\n";
    } else if (it.type == MotionType::kCircular) {
      const std::string a =
          decl(it.aux, it.Taux, p.targets()[static_cast<std::size_t>(it.aux)].config, it);
      strAppend(src, "CIRC ", a, ", ", n, it.fine ? "" : " C_DIS", "\n");
    } else {
      src += "LIN " + n + (it.fine ? "" : " C_DIS") + "\n";
    }
  }
  src += "END\n";
  dat += "ENDDAT\n";
  fs::path o(out);
  const std::string dat_path = (o.parent_path() / (o.stem().string() + ".dat")).string();
  std::string src_path = out;
  if (!iequals(o.extension().string(), ".src"))
    src_path = (o.parent_path() / (o.stem().string() + ".src")).string();
  return {{src_path, src}, {dat_path, dat}};
}

// ---------------------------------------------------------------- RAPID

std::string poseRapid(const Pose& T) {
  const Eigen::Quaterniond q = quaternionFromRotation(T.linear());
  return "[[" + fmt(T.translation().x() * 1e3, 6) + "," + fmt(T.translation().y() * 1e3, 6) + "," +
         fmt(T.translation().z() * 1e3, 6) + "],[" + fmt(q.w(), 12) + "," + fmt(q.x(), 12) + "," +
         fmt(q.y(), 12) + "," + fmt(q.z(), 12) + "]]";
}

std::vector<std::pair<std::string, std::string>> toRapid(const Program& p,
                                                         const std::vector<Item>& items,
                                                         const std::string& out,
                                                         ConversionReport& rep) {
  const std::string name = programName(out, 32);
  std::string head = "MODULE " + name + "\n";
  head += "  ! generated by roprec convert from " + fs::path(p.files[0].path).filename().string() +
          "\n";
  head +=
      "  ! configuration carried at the branch level (cfx); cf1, cf4, cf6 unknown: ConfJ/ConfL "
      "off\n";
  std::string decls;
  std::string body = "  PROC " + name + "()\n    ConfJ \\Off;\n    ConfL \\Off;\n";
  std::map<const Frame*, std::string> tools;
  std::map<const Frame*, std::string> wobjs;
  std::map<int, std::string> names;
  auto toolName = [&](const Frame* f) -> std::string {
    if (f == nullptr) return "tool0";
    const auto it = tools.find(f);
    if (it != tools.end()) return it->second;
    requireResolved(f, p.files[0].path, "tool");
    std::string n = "tTool" + std::to_string(tools.size() + 1);
    tools[f] = n;
    decls += "  ! " + f->ref + "; tool load not carried: set " + n + ".tload\n";
    decls += "  PERS tooldata " + n + ":=[TRUE," + poseRapid(f->pose) +
             ",[1,[0,0,0.001],[1,0,0,0],0,0,0]];\n";
    rep.notes.push_back(
        n + ": tool load data not carried (placeholder mass 1 kg); set it before running");
    return n;
  };
  auto wobjName = [&](const Frame* f) -> std::string {
    if (f == nullptr) return "wobj0";
    const auto it = wobjs.find(f);
    if (it != wobjs.end()) return it->second;
    requireResolved(f, p.files[0].path, "base frame");
    std::string n = "wObj" + std::to_string(wobjs.size() + 1);
    wobjs[f] = n;
    decls += "  ! " + f->ref + "\n";
    decls += "  PERS wobjdata " + n + ":=[FALSE,TRUE,\"\"," + poseRapid(f->pose) +
             ",[[0,0,0],[1,0,0,0]]];\n";
    return n;
  };
  auto target = [&](int key, const Pose& T, const Configuration& c, const Item& it) {
    const auto f = names.find(key);
    if (f != names.end()) return f->second;
    std::string n = "p" + std::to_string(names.size() + 1);
    names[key] = n;
    const int cfx = c.branch().value_or(0);
    if (!c.branch()) rep.notes.push_back(n + ": no configuration in the source; cfx written 0");
    std::string ext = "[";
    for (std::size_t k = 0; k < 6; ++k)
      ext += (k ? "," : "") + (hasExt(it, k) ? fmt(it.ext[k], 6) : std::string("9E+09"));
    ext += "]";
    const std::string pr = poseRapid(T);
    decls += "  CONST robtarget " + n + ":=[" + pr.substr(1, pr.size() - 2) + ",[0,0,0," +
             std::to_string(cfx) + "]," + ext + "];\n";
    return n;
  };
  for (const Item& it : items) {
    const std::string n = target(it.key, it.T, it.config, it);
    const std::string tool = toolName(it.tool);
    const std::string wobj = wobjName(it.base);
    const std::string zone = it.fine ? "fine" : "z1";
    const std::string speed = it.speed > 0 ? "[" + fmtG(it.speed) + ",500,5000,1000]" : "v1000";
    if (it.type == MotionType::kJoint) {
      strAppend(body, "    MoveJ ", n, ",", speed, ",", zone, ",", tool, "\\WObj:=", wobj, ";\n");
    } else if (it.type == MotionType::kCircular) {
      const std::string a =
          target(it.aux, it.Taux, p.targets()[static_cast<std::size_t>(it.aux)].config, it);
      strAppend(body, "    MoveC ", a, ",", n, ",", speed, ",", zone, ",", tool, "\\WObj:=", wobj,
                ";\n");
    } else {
      strAppend(body, "    MoveL ", n, ",", speed, ",", zone, ",", tool, "\\WObj:=", wobj, ";\n");
    }
  }
  body += "  ENDPROC\nENDMODULE\n";
  std::string path = out;
  if (fs::path(out).extension().empty()) path += ".mod";
  return {{path, head + decls + body}};
}

// ---------------------------------------------------------------- TP

std::vector<std::pair<std::string, std::string>> toTp(const Program& p,
                                                      const std::vector<Item>& items,
                                                      const std::string& out,
                                                      ConversionReport& rep) {
  std::string name = upper(programName(out, 36));
  std::map<const Frame*, int> uf;
  std::map<const Frame*, int> ut;
  auto number = [&](std::map<const Frame*, int>& table, const Frame* f, const char* kind) {
    if (f == nullptr) return 0;
    const auto it = table.find(f);
    if (it != table.end()) return it->second;
    int n = 0;
    if (const auto k = tableIndex(f->ref, kind)) {
      n = *k;
    } else {
      n = static_cast<int>(table.size()) + 1;
      for (const auto& [g, m] : table) n = std::max(n, m + 1);
    }
    table[f] = n;
    return n;
  };
  std::vector<std::string> mn;
  std::string pos;
  std::map<int, int> pnum;
  int cur_uf = -1;
  int cur_ut = -1;
  auto remark = [&](const std::string& s) { mn.push_back("  ! " + s + " ;"); };
  auto record = [&](int key, const Pose& T, const Configuration& c, const Item& it, int ufn,
                    int utn) {
    const auto f = pnum.find(key);
    if (f != pnum.end()) return f->second;
    const int n = static_cast<int>(pnum.size()) + 1;
    pnum[key] = n;
    Configuration fc = configurationFromBranch(Vendor::kFanuc, c.branch().value_or(0));
    if (!c.branch())
      rep.notes.push_back("P[" + std::to_string(n) +
                          "]: no configuration in the source; CONFIG written 'F U T'");
    const Vec3 abc = zyxFromRotation(T.linear()) / kDeg;
    pos += "P[" + std::to_string(n) + "]{\n   GP1:\n\tUF : " + std::to_string(ufn) +
           ", UT : " + std::to_string(utn) + ",\t\tCONFIG : '" + fc.text() + "',\n";
    pos += "\tX = " + fmt(T.translation().x() * 1e3, 6) +
           "  mm,\tY = " + fmt(T.translation().y() * 1e3, 6) +
           "  mm,\tZ = " + fmt(T.translation().z() * 1e3, 6) + "  mm,\n";
    pos += "\tW = " + fmt(abc[2], 9) + " deg,\tP = " + fmt(abc[1], 9) +
           " deg,\tR = " + fmt(abc[0], 9) + " deg";
    for (std::size_t k = 0; k < 3; ++k) {
      if (hasExt(it, k))
        pos += ",\n\tE" + std::to_string(k + 1) + "= " + fmt(it.ext[k], 6) + "  mm";
    }
    pos += "\n};\n";
    return n;
  };
  bool turn_note = false;
  for (const Item& it : items) {
    const int ufn = number(uf, it.base, "UFRAME");
    const int utn = number(ut, it.tool, "UTOOL");
    if (ufn != cur_uf) {
      if (it.base != nullptr && it.base->resolved) {
        const Vec3 abc = zyxFromRotation(it.base->pose.linear()) / kDeg;
        const Vec3 x = it.base->pose.translation() * 1e3;
        remark("UF" + std::to_string(ufn) + " " + it.base->ref);
        remark("= " + fmt(x.x(), 3) + "," + fmt(x.y(), 3) + "," + fmt(x.z(), 3) + "," +
               fmt(abc[2], 6) + "," + fmt(abc[1], 6) + "," + fmt(abc[0], 6));
        rep.notes.push_back("set UFRAME[" + std::to_string(ufn) +
                            "] on the controller (values in the remarks)");
      }
      mn.push_back("  UFRAME_NUM=" + std::to_string(ufn) + " ;");
      cur_uf = ufn;
    }
    if (utn != cur_ut) {
      if (it.tool != nullptr && it.tool->resolved) {
        const Vec3 abc = zyxFromRotation(it.tool->pose.linear()) / kDeg;
        const Vec3 x = it.tool->pose.translation() * 1e3;
        remark("UT" + std::to_string(utn) + " " + it.tool->ref);
        remark("= " + fmt(x.x(), 3) + "," + fmt(x.y(), 3) + "," + fmt(x.z(), 3) + "," +
               fmt(abc[2], 6) + "," + fmt(abc[1], 6) + "," + fmt(abc[0], 6));
        rep.notes.push_back("set UTOOL[" + std::to_string(utn) +
                            "] on the controller (values in the remarks)");
      }
      mn.push_back("  UTOOL_NUM=" + std::to_string(utn) + " ;");
      cur_ut = utn;
    }
    if (!turn_note) {
      rep.notes.push_back(
          "FANUC turn digits written 0 (turns are not carried across vendors); check J4/J6 turns");
      turn_note = true;
    }
    const int n = record(it.key, it.T, it.config, it, ufn, utn);
    const std::string term = it.fine ? "FINE" : "CNT100";
    const std::string speed =
        it.type == MotionType::kJoint ? "100%" : (it.speed > 0 ? fmtG(it.speed) : "250") + "mm/sec";
    if (it.type == MotionType::kJoint) {
      mn.push_back(strCat("J P[", std::to_string(n), "] ", speed, " ", term, " ;"));
    } else if (it.type == MotionType::kCircular) {
      const int a = record(it.aux, it.Taux, p.targets()[static_cast<std::size_t>(it.aux)].config,
                           it, ufn, utn);
      mn.push_back("C P[" + std::to_string(a) + "] ");
      mn.push_back(strCat(":  P[", std::to_string(n), "] ", speed, " ", term, " ;"));
    } else {
      mn.push_back(strCat("L P[", std::to_string(n), "] ", speed, " ", term, " ;"));
    }
  }
  std::string s =
      "/PROG  " + name +
      "\n/ATTR\nOWNER\t\t= MNEDITOR;\nCOMMENT\t\t= \"roprec convert\";\nPROG_SIZE\t= 0;\n";
  s += "CREATE\t\t= DATE 00-01-01  TIME 00:00:00;\nMODIFIED\t= DATE 00-01-01  TIME "
       "00:00:00;\nFILE_NAME\t= ;\n";
  s += "VERSION\t\t= 0;\nLINE_COUNT\t= " +
       std::to_string(mn.size() -
                      static_cast<std::size_t>(std::count_if(
                          mn.begin(), mn.end(),
                          [](const std::string& l) { return l.rfind(":  P[", 0) == 0; }))) +
       ";\nMEMORY_SIZE\t= 0;\n";
  s += "PROTECT\t\t= READ_WRITE;\nTCD:  STACK_SIZE\t= 0,\n      TASK_PRIORITY\t= 50,\n      "
       "TIME_SLICE\t= 0,\n";
  s += "      BUSY_LAMP_OFF\t= 0,\n      ABORT_REQUEST\t= 0,\n      PAUSE_REQUEST\t= 0;\n";
  s += "DEFAULT_GROUP\t= 1,*,*,*,*;\nCONTROL_CODE\t= 00000000 00000000;\n/MN\n";
  int line = 0;
  for (const std::string& l : mn) {
    if (l.rfind(":  P[", 0) == 0) {
      s += "    " + l + "\n";
      continue;
    }
    char buf[16];
    std::snprintf(buf, sizeof buf, "%4d:", ++line);
    s += buf + l + "\n";
  }
  s += "/POS\n" + pos + "/END\n";
  std::string path = out;
  if (fs::path(out).extension().empty()) path += ".ls";
  return {{path, s}};
}

// ---------------------------------------------------------------- CSV / JSON

std::string quat(const Pose& T, const char* sep) {
  const Eigen::Quaterniond q = quaternionFromRotation(T.linear());
  return fmt(q.w(), 12) + sep + fmt(q.x(), 12) + sep + fmt(q.y(), 12) + sep + fmt(q.z(), 12);
}

std::string xyz(const Pose& T, const char* sep) {
  return fmt(T.translation().x() * 1e3, 6) + sep + fmt(T.translation().y() * 1e3, 6) + sep +
         fmt(T.translation().z() * 1e3, 6);
}

std::string motionName(const Item& it) {
  return it.type == MotionType::kJoint ? "J" : it.type == MotionType::kCircular ? "C" : "L";
}

/// The ids given so far: by item key, and the set of names taken (a look-up per new target).
struct TargetIds {
  std::unordered_map<int, std::string> by_key;
  std::unordered_set<std::string> taken;
};

/// The id of an item's target: its name (sanitised) the first time that name is given, else
/// "T<n>" (n = the count of targets named so far + 1); the same id for the same key again.
const std::string& targetId(const Program& p, const Item& it, TargetIds& ids) {
  const auto f = ids.by_key.find(it.key);
  if (f != ids.by_key.end()) return f->second;
  std::string n = it.key == it.target
                      ? sanitize(p.targets()[static_cast<std::size_t>(it.target)].name, "")
                      : "";
  if (ids.taken.count(n)) n.clear();
  if (n.empty()) n = "T" + std::to_string(ids.by_key.size() + 1);
  ids.taken.insert(n);
  return ids.by_key.emplace(it.key, std::move(n)).first->second;
}

std::vector<std::pair<std::string, std::string>> toCsv(const Program& p,
                                                       const std::vector<Item>& items,
                                                       const std::string& out) {
  std::string s =
      "# roprec target list converted from " + fs::path(p.files[0].path).filename().string() + "\n";
  s += "# units: mm, deg; orientation: quaternion qw,qx,qy,qz; poses are TCP poses in the named "
       "frame\n";
  std::map<std::string, const Frame*> frames;
  std::map<std::string, const Frame*> tools;
  for (const Item& it : items) {
    if (it.base != nullptr && it.base->resolved) frames[sanitize(it.base->ref, "frame")] = it.base;
    if (it.tool != nullptr && it.tool->resolved) tools[sanitize(it.tool->ref, "tool")] = it.tool;
  }
  for (const auto& [n, f] : frames)
    s += "# frame " + n + ": " + xyz(f->pose, " ") + " " + quat(f->pose, " ") + "\n";
  for (const auto& [n, f] : tools)
    s += "# tool " + n + ": " + xyz(f->pose, " ") + " " + quat(f->pose, " ") + "\n";
  s += "id,motion,x,y,z,qw,qx,qy,qz,frame,tool,conf,speed,j1,j2,j3,j4,j5,j6\n";
  TargetIds ids;
  for (const Item& it : items) {
    s += targetId(p, it, ids) + "," + motionName(it) + ",";
    s += it.cartesian ? xyz(it.T, ",") + "," + quat(it.T, ",") : std::string(",,,,,,");
    s += "," + (it.base ? sanitize(it.base->ref, "frame") : "") + "," +
         (it.tool ? sanitize(it.tool->ref, "tool") : "");
    const std::string conf = it.config.text();
    s += "," + (conf.find(',') != std::string::npos ? "\"" + conf + "\"" : conf);
    s += "," + (it.speed > 0 ? fmtG(it.speed) : "");
    for (std::size_t k = 0; k < 6; ++k)
      s += "," + (k < it.joints.size() ? fmt(it.joints[k], 9) : "");
    s += "\n";
  }
  return {{fs::path(out).extension().empty() ? out + ".csv" : out, s}};
}

std::vector<std::pair<std::string, std::string>> toJson(const Program& p,
                                                        const std::vector<Item>& items,
                                                        const std::string& out) {
  std::string s = "{\n  \"format\": \"roprec-targets\",\n  \"source\": " +
                  jsonStr(fs::path(p.files[0].path).filename().string()) +
                  ",\n  \"units\": {\"length\": \"mm\", \"angle\": \"deg\"},\n  \"frames\": [";
  std::map<std::string, const Frame*> frames;
  for (const Item& it : items) {
    for (const Frame* f : {it.base, it.tool}) {
      if (f != nullptr && f->resolved) frames[sanitize(f->ref, "frame")] = f;
    }
  }
  bool first = true;
  for (const auto& [n, f] : frames) {
    s += std::string(first ? "\n" : ",\n") + "    {\"name\": " + jsonStr(n) +
         ", \"position_mm\": [" + xyz(f->pose, ", ") + "], \"quaternion_wxyz\": [" +
         quat(f->pose, ", ") + "]}";
    first = false;
  }
  s += std::string(first ? "" : "\n  ") + "],\n  \"targets\": [";
  TargetIds ids;
  first = true;
  for (const Item& it : items) {
    s += std::string(first ? "\n" : ",\n") + "    {\"id\": " + jsonStr(targetId(p, it, ids)) +
         ", \"motion\": \"" + motionName(it) + "\"";
    if (it.cartesian)
      s += ", \"position_mm\": [" + xyz(it.T, ", ") + "], \"quaternion_wxyz\": [" +
           quat(it.T, ", ") + "]";
    if (!it.joints.empty()) {
      s += ", \"joints_deg\": [";
      for (std::size_t k = 0; k < it.joints.size(); ++k)
        s += (k ? ", " : "") + fmt(it.joints[k], 9);
      s += "]";
    }
    if (it.base != nullptr) s += ", \"frame\": " + jsonStr(sanitize(it.base->ref, "frame"));
    if (it.tool != nullptr) s += ", \"tool\": " + jsonStr(sanitize(it.tool->ref, "tool"));
    if (it.config.present()) s += ", \"config\": " + jsonStr(it.config.text());
    if (it.speed > 0) s += ", \"speed_mm_s\": " + fmtG(it.speed);
    s += std::string(", \"fine\": ") + (it.fine ? "true" : "false") + "}";
    first = false;
  }
  s += std::string(first ? "" : "\n  ") + "]\n}\n";
  return {{fs::path(out).extension().empty() ? out + ".json" : out, s}};
}

}  // namespace

Dialect dialectFromName(const std::string& name) {
  const std::string n = upper(name);
  if (n == "KRL" || n == "KUKA") return Dialect::kKrl;
  if (n == "RAPID" || n == "ABB") return Dialect::kRapid;
  if (n == "TP" || n == "LS" || n == "FANUC") return Dialect::kTp;
  if (n == "CSV") return Dialect::kCsv;
  if (n == "JSON") return Dialect::kJson;
  throw UsageError("--to must be krl, rapid, tp, csv or json (got '" + name + "')");
}

std::vector<std::pair<std::string, std::string>> convertProgram(const Program& p, Dialect to,
                                                                const std::string& out_path,
                                                                ConversionReport& report,
                                                                bool all_lines) {
  const bool table = to == Dialect::kCsv || to == Dialect::kJson;
  std::vector<Item> items = collect(p, table, report);
  if (!table) {  // a program: say what of the source it does not carry
    markUnusedKrlExternalAxes(p, items, report);
    listNotCarried(p, all_lines, report);
    listZoneMappings(p, to, items, all_lines, report);
  }
  switch (to) {
    case Dialect::kKrl:
      return toKrl(p, items, out_path, report);
    case Dialect::kRapid:
      return toRapid(p, items, out_path, report);
    case Dialect::kTp:
      return toTp(p, items, out_path, report);
    case Dialect::kCsv:
    case Dialect::kHoleCsv:
      return toCsv(p, items, out_path);
    case Dialect::kJson:
      return toJson(p, items, out_path);
  }
  return {};
}

}  // namespace roprec::postproc
