#include "postproc/convert.hpp"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <thread>
#include <unordered_map>
#include <unordered_set>

#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/fixed_chars.hpp"
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

/// A frame's sanitised name ("" for none), made once per frame.
class FrameNames {
 public:
  explicit FrameNames(const char* fallback) : fallback_(fallback) {}
  const std::string& of(const Frame* f) {
    static const std::string kNone;
    if (f == nullptr) return kNone;
    auto it = names_.find(f);
    if (it == names_.end()) it = names_.emplace(f, sanitize(f->ref, fallback_)).first;
    return it->second;
  }

 private:
  const char* fallback_;
  std::map<const Frame*, std::string> names_;
};

/// A motion the new program carries. Its pose, its target's configuration and (circular)
/// auxiliary point are read from the program where a writer needs them (itemPose, auxPose,
/// itemJoints; the same arithmetic each time): an item holds what the motion itself decides.
struct Item {
  int motion{-1};
  int target{-1};
  /// output-name key: the target, or a unique key (−2 − motion) when an offset makes the pose
  /// differ
  int key{-1};
  int aux{-1};
  MotionType type{MotionType::kLinear};
  bool cartesian{true};
  bool fine{false};
  const Frame* base{nullptr};
  const Frame* tool{nullptr};
  const Configuration* config{nullptr};  ///< the target's
  std::array<double, 6> ext{};           ///< E1..E6, kUnusedExt where the target states none
  double speed{-1};
};

/// Hands a note to the report (ConversionReport::on_note, else `notes`).
void note(ConversionReport& rep, std::string s) {
  if (rep.on_note) {
    rep.on_note(s);
  } else {
    rep.notes.push_back(std::move(s));
  }
}

/// "FILE:LINE" of a motion ("FILE" without a line).
std::string motionWhere(const Program& p, const Motion& m) {
  const std::string& path = p.files[static_cast<std::size_t>(m.file)].path;
  return m.line > 0 ? path + ":" + std::to_string(m.line) : path;
}

std::vector<Item> collect(const Program& p, bool joints_ok, ConversionReport& rep) {
  std::vector<Item> items;
  items.reserve(p.motions.size());
  for (std::size_t i = 0; i < p.motions.size(); ++i) {
    const Motion& m = p.motions[i];
    if (m.target < 0) {
      rep.skipped.push_back(motionWhere(p, m) + ": " + p.text(m.instruction) + " " +
                            p.text(m.target_text) + " (target built at run time" +
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
    it.config = &t.config;
    it.speed = m.speed_mm_s;
    it.fine = m.fine;
    for (std::size_t k = 0; k < it.ext.size(); ++k)
      it.ext[k] = t.ext[k].present() ? t.ext[k].value : kUnusedExt;
    if (t.kind == TargetKind::kJoint) {
      if (!joints_ok) {
        rep.skipped.push_back(
            motionWhere(p, m) + ": joint target " +
            (t.name.empty() ? std::string("(inline)") : t.name) +
            " (joint conventions differ between vendors; re-teach it in the output)");
        continue;
      }
      it.cartesian = false;
      items.push_back(it);
      continue;
    }
    if (!motionPose(p, m)) {
      rep.skipped.push_back(motionWhere(p, m) + ": " + p.text(m.target_text) +
                            " (incomplete pose or unknown offset)");
      continue;
    }
    if (m.aux >= 0) {
      const Target& a = p.targets()[static_cast<std::size_t>(m.aux)];
      if (a.kind != TargetKind::kCartesian || !targetComplete(a)) {
        rep.skipped.push_back(motionWhere(p, m) +
                              ": circular motion with a non-Cartesian auxiliary point");
        continue;
      }
      it.aux = m.aux;
    } else if (m.type == MotionType::kCircular) {
      it.type = MotionType::kLinear;
      note(rep, motionWhere(p, m) + ": circular motion without auxiliary point written as linear");
    }
    items.push_back(it);
  }
  return items;
}

/// The pose a Cartesian item moves to (collect() checked that it has one).
Pose itemPose(const Program& p, const Item& it) {
  return *motionPose(p, p.motions[static_cast<std::size_t>(it.motion)]);
}

/// The joint values of a joint item (deg or mm), none for a Cartesian one.
std::vector<double> itemJoints(const Program& p, const Item& it) {
  if (it.cartesian) return {};
  return targetJointsDeg(p.targets()[static_cast<std::size_t>(it.target)]);
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
    note(rep, zero_axes +
                  " = 0 in every target of the KRL source: taken as unused external axes (RAPID "
                  "9E+09)");
}

bool hasExt(const Item& it, std::size_t k) {
  return k < it.ext.size() && std::fabs(it.ext[k]) < 8e9;
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
std::string_view lineAt(const SourceFile& f, std::size_t l) {
  const std::size_t a = f.line_starts[l];
  std::size_t b = l + 1 < f.line_starts.size() ? f.line_starts[l + 1] : f.bytes.size();
  while (b > a && (f.bytes[b - 1] == '\n' || f.bytes[b - 1] == '\r')) --b;
  return std::string_view(f.bytes).substr(a, b - a);
}

/// `s` up to its comment (`comment` outside double quotes), trimmed.
std::string_view codeOf(std::string_view s, char comment) {
  bool in_string = false;
  std::size_t end = s.size();
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '"') in_string = !in_string;
    if (!in_string && s[i] == comment) {
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
std::string_view firstWord(std::string_view u) {
  std::size_t n = 0;
  while (n < u.size() && isIdentChar(u[n])) ++n;
  return u.substr(0, n);
}

bool oneOf(std::string_view w, std::initializer_list<std::string_view> words) {
  for (const std::string_view x : words) {
    if (w == x) return true;
  }
  return false;
}

bool startsWith(std::string_view u, std::initializer_list<std::string_view> prefixes) {
  for (const std::string_view x : prefixes) {
    if (u.substr(0, x.size()) == x) return true;
  }
  return false;
}

/// KRL: the kind of a code line the minimal program does not carry; "" when it is carried or
/// structure (declarations, frames and speeds carried by value, inline-form motion parameters).
std::string_view krlKind(std::string_view u) {
  const std::string_view w = firstWord(u);
  if (u.empty() || u[0] == '&' ||
      oneOf(w, {"DEF",  "END",      "DEFDAT",   "ENDDAT",    "DEFFCT",    "ENDFCT",  "DECL",
                "EXT",  "EXTFCT",   "SIGNAL",   "STRUC",     "ENUM",      "PTP",     "LIN",
                "CIRC", "SPTP",     "SLIN",     "SCIRC",     "PTP_REL",   "LIN_REL", "BAS",
                "INI",  "PDAT_ACT", "LDAT_ACT", "FDAT_ACT",  "$BWDSTART", "$H_POS",  "$VEL",
                "$ACC", "$BASE",    "$TOOL",    "BASE_DATA", "TOOL_DATA"}))
    return "";
  if (w == "GLOBAL") return u.find("INTERRUPT") != std::string_view::npos ? "interrupt" : "";
  if (w == "WAIT") return "wait";
  if (w == "$APO") return "approximation parameter";
  if (oneOf(w, {"$OUT", "$ANOUT", "ANOUT", "PULSE", "$OUT_C"})) return "I/O";
  if (w == "INTERRUPT") return "interrupt";
  if (oneOf(w, {"IF",        "ELSE",    "ENDIF",  "FOR",   "ENDFOR", "WHILE",   "ENDWHILE",
                "LOOP",      "ENDLOOP", "REPEAT", "UNTIL", "SWITCH", "CASE",    "DEFAULT",
                "ENDSWITCH", "GOTO",    "EXIT",   "HALT",  "RETURN", "CONTINUE"}))
    return "control flow";
  if (!w.empty() && u.size() > w.size() &&
      u.find_first_not_of(" \t", w.size()) != std::string_view::npos &&
      u[u.find_first_not_of(" \t", w.size())] == '(')
    return "call";
  return u.find('=') != std::string_view::npos ? "assignment" : "other";
}

/// RAPID: as krlKind. ConfJ/ConfL are written \Off (the header says so).
std::string_view rapidKind(std::string_view u) {
  const std::string_view w = firstWord(u);
  if (oneOf(w,
            {"MODULE", "ENDMODULE", "PROC",  "ENDPROC", "FUNC",  "ENDFUNC", "TRAP",     "ENDTRAP",
             "LOCAL",  "TASK",      "PERS",  "VAR",     "CONST", "ERROR",   "BACKWARD", "UNDO",
             "CONFJ",  "CONFL",     "MOVEL", "MOVEJ",   "MOVEC", "MOVEABSJ"}))
    return "";
  if (w.substr(0, 4) == "WAIT") return "wait";
  if (oneOf(w, {"SETDO", "SET", "RESET", "PULSEDO", "SETAO", "SETGO", "INVERTDO", "SETDO"}))
    return "I/O";
  if (oneOf(w, {"IF",       "ELSEIF", "ELSE",  "ENDIF",   "FOR",     "ENDFOR", "WHILE",
                "ENDWHILE", "TEST",   "CASE",  "DEFAULT", "ENDTEST", "GOTO",   "RETURN",
                "EXIT",     "STOP",   "BREAK", "RAISE",   "RETRY",   "TRYNEXT"}))
    return "control flow";
  const std::size_t k = u.find_first_not_of(" \t", w.size());
  if (k != std::string_view::npos && (u.substr(k, 2) == ":=" || u[k] == '{' || u[k] == '.'))
    return "assignment";
  return w.empty() ? "other" : "call";
}

/// A RAPID line that opens or closes a block (no `;` ends it).
bool rapidBlockLine(std::string_view u) {
  return oneOf(firstWord(u),
               {"MODULE",   "ENDMODULE", "PROC",   "ENDPROC", "FUNC",    "ENDFUNC", "TRAP",
                "ENDTRAP",  "IF",        "ELSEIF", "ELSE",    "ENDIF",   "FOR",     "ENDFOR",
                "WHILE",    "ENDWHILE",  "TEST",   "CASE",    "DEFAULT", "ENDTEST", "ERROR",
                "BACKWARD", "UNDO",      "LOCAL",  "TASK"}) &&
         u.find(';') == std::string_view::npos;
}

/// FANUC TP (a /MN line without its number and `;`): as krlKind.
std::string_view tpKind(std::string_view u) {
  const std::string_view w = firstWord(u);
  if (u.empty() || u[0] == '!' || u.substr(0, 2) == "//" || u[0] == ':' ||
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
/// program does not carry (`kind` empty: carried, structure, comment or a motion). The code and
/// the kind are views (into the program's bytes and literals): no copy per line.
class LineScanner {
 public:
  explicit LineScanner(const Program& p) : p_(p) {
    for (const Frame& fr : p.frames) {
      if (fr.resolved) carried_vars_.insert(upper(fr.ref));
    }
    std::vector<bool> seen(p.texts.size(), false);  // a speed text is looked at once
    for (const Motion& m : p.motions) {
      if (m.speed_mm_s <= 0 || seen[m.speed_text.index]) continue;
      seen[m.speed_text.index] = true;
      carried_vars_.insert(upper(p.text(m.speed_text)));
    }
  }
  /// The code of `raw` (comment stripped) in `code` and its kind ("" when nothing is lost).
  std::string_view kind(std::string_view raw, std::string_view& code) {
    if (p_.dialect == Dialect::kTp) return tp(raw, code);
    if (p_.dialect == Dialect::kRapid) return rapid(raw, code);
    code = codeOf(raw, ';');
    return krlKind(upperView(code));
  }

 private:
  /// `s` in upper case, in the scanner's buffer (valid until the next call).
  std::string_view upperView(std::string_view s) {
    upper_.assign(s);
    for (char& c : upper_) c = asciiUpper(c);
    return upper_;
  }

  std::string_view tp(std::string_view raw, std::string_view& code) {
    if (!raw.empty() && raw[0] == '/') {  // a section: only /MN holds instructions
      in_mn_ = raw.substr(0, 3) == "/MN";
      return "";
    }
    const std::size_t first = raw.find_first_not_of(' ');
    if (!in_mn_ || first == std::string_view::npos || raw[first] == ':')
      return "";  // outside /MN, blank, or the second line of a C motion
    const std::size_t colon = raw.find(':');
    code = codeOf(colon == std::string_view::npos ? raw : raw.substr(colon + 1), '\x01');
    while (!code.empty() && (code.back() == ';' || code.back() == ' ' || code.back() == '\t'))
      code.remove_suffix(1);
    return tpKind(upperView(code));
  }

  std::string_view rapid(std::string_view raw, std::string_view& code) {
    code = codeOf(raw, '!');
    if (code == "%%%") in_header_ = !in_header_;  // the module header: VERSION, LANGUAGE
    if (code.empty() || code == "%%%" || in_header_) return "";
    const std::string_view u = upperView(code);
    const bool continued = open_;
    open_ = !rapidBlockLine(u) && code.back() != ';';
    if (continued) return "";
    const std::string_view k = rapidKind(u);
    // `rdkWObj.uframe := ...`, `rdkSpeed := ...`: frames and speeds the new program states by
    // value (the reader resolved them)
    return k == "assignment" && carried_vars_.count(firstWord(u)) ? "" : k;
  }

  const Program& p_;
  std::set<std::string, std::less<>> carried_vars_;  ///< upper case
  std::string upper_;                                ///< upperView's buffer
  bool in_mn_{false};                                ///< TP: inside /MN
  bool in_header_{false};                            ///< RAPID: inside the %%% header
  bool open_{false};  ///< RAPID: a statement continues on the next line
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
  std::vector<std::string> order;                              // "text (kind" in first-seen order
  std::map<std::string, std::vector<int>, std::less<>> lines;  // its lines
  LineScanner scan(p);
  std::string key;
  std::vector<int>* last = nullptr;  // the lines of the last key (a WAIT per hole: no look-up)
  std::string last_key;
  // a motion's line is carried; the scanner keeps no state across one in KRL and TP (RAPID: a
  // statement may continue over lines)
  const bool skip_motions = p.dialect != Dialect::kRapid;
  for (std::size_t l = 0; l < f.line_starts.size(); ++l) {
    if (skip_motions && motion_line[l + 1]) continue;
    std::string_view code;
    const std::string_view kind = scan.kind(lineAt(f, l), code);
    if (kind.empty() || motion_line[l + 1]) continue;
    key.clear();
    if (code.size() > 60) {
      strAppend(key, code.substr(0, 57), "...", " (", kind);
    } else {
      strAppend(key, code, " (", kind);
    }
    if (last == nullptr || key != last_key) {
      auto it = lines.find(key);
      if (it == lines.end()) {
        order.push_back(key);
        it = lines.emplace(key, std::vector<int>{}).first;
      }
      last = &it->second;
      last_key = key;
    }
    last->push_back(static_cast<int>(l + 1));
  }
  for (const std::string& k : order) {
    const std::vector<int>& at = lines.find(k)->second;
    std::string s = f.path + ":" + std::to_string(at[0]) + ": " + k;
    if (at.size() > 1) {
      s += "; " + std::to_string(at.size()) + " in all, lines ";
      s += lineList(at, all_lines, kNoticeBytes - std::min(kNoticeBytes / 2, s.size() + 1));
    }
    rep.not_carried.push_back(s + ")");
  }
}

/// The zone the writer of `to` gives a motion (fine: exact stop).
std::string_view writtenZone(Dialect to, const Item& it) {
  if (to == Dialect::kKrl)
    return it.fine ? "exact stop" : it.type == MotionType::kJoint ? "C_PTP" : "C_DIS";
  if (to == Dialect::kRapid) return it.fine ? "fine" : "z1";
  return it.fine ? "FINE" : "CNT100";
}

/// Whether every word of a zone text (`C_DIS C_DIS`: KRL may repeat it) is `into`.
bool sameZone(std::string_view from, std::string_view into) {
  bool same = true;
  for (std::size_t a = 0; a < from.size();) {
    const std::size_t b = std::min(from.find(' ', a), from.size());
    same = same && iequals(from.substr(a, b - a), into);
    a = b + 1;
  }
  return same;
}

/// One line per zone mapping that changes what the source says ("z10 -> C_DIS"), with the
/// source lines of the motions it concerns: "zone z10 -> C_DIS at FILE:12,14,20 (3 motions)"
/// (every line with `all_lines`, else a notice of at most kNoticeBytes). A motion's mapping
/// depends on its zone text and on whether it is a joint motion only: looked up once per pair.
void listZoneMappings(const Program& p, Dialect to, const std::vector<Item>& items, bool all_lines,
                      ConversionReport& rep) {
  struct Mapping {
    std::string key;  ///< "z10 -> C_DIS"
    std::string file;
    std::vector<int> lines;
  };
  std::vector<Mapping> order;
  std::map<std::string, std::size_t, std::less<>> by_key;
  std::unordered_map<std::uint64_t, int> by_zone;  // (zone text, joint motion) -> mapping, -1: same
  for (const Item& it : items) {
    const Motion& m = p.motions[static_cast<std::size_t>(it.motion)];
    if (it.fine) continue;  // exact stop in, exact stop out
    const std::uint64_t code =
        std::uint64_t{m.zone_text.index} * 2 + (it.type == MotionType::kJoint ? 1 : 0);
    auto z = by_zone.find(code);
    if (z == by_zone.end()) {
      const std::string_view from =
          m.zone_text.empty() ? std::string_view("approximated") : p.text(m.zone_text);
      const std::string_view into = writtenZone(to, it);
      int index = -1;
      if (!sameZone(from, into)) {
        const std::string key = strCat(from, " -> ", into);
        auto k = by_key.find(key);
        if (k == by_key.end()) {
          order.push_back({key, p.files[static_cast<std::size_t>(m.file)].path, {}});
          k = by_key.emplace(key, order.size() - 1).first;
        }
        index = static_cast<int>(k->second);
      }
      z = by_zone.emplace(code, index).first;
    }
    if (z->second >= 0) order[static_cast<std::size_t>(z->second)].lines.push_back(m.line);
  }
  for (const Mapping& g : order) {
    std::string s = strCat("zone ", g.key, " at ", g.file, ":");
    const std::string tail = " (" + std::to_string(g.lines.size()) +
                             (g.lines.size() == 1 ? " motion" : " motions") +
                             "; the approximation size is not carried)";
    s += lineList(g.lines, all_lines,
                  kNoticeBytes - std::min(kNoticeBytes / 2, s.size() + tail.size()));
    s += tail;
    rep.not_carried.push_back(s);
  }
}

// ---------------------------------------------------------------- output

/// A block of output bytes: a buffer of kBlockCapacity bytes and the count used.
struct Block {
  static constexpr std::size_t kCapacity = (std::size_t{1} << 20U) + (std::size_t{1} << 16U);
  std::unique_ptr<char[]> bytes{std::make_unique<char[]>(kCapacity)};
  std::size_t size{0};
};

/// Hands blocks of bytes to a ByteWriter on a thread of its own, in order: the write system
/// calls (copying into the page cache: a good part of a large conversion's time) overlap the
/// formatting. One block waits at most (two blocks in memory). An error of the writer is thrown
/// by the next write() or by finish().
class BackgroundWriter {
 public:
  explicit BackgroundWriter(const ByteWriter& w) : w_(w), thread_([this] { run(); }) {}
  BackgroundWriter(const BackgroundWriter&) = delete;
  BackgroundWriter& operator=(const BackgroundWriter&) = delete;
  ~BackgroundWriter() { stop(); }

  /// Queues `block` (waits while the last one is being written); `block` comes back empty (a
  /// block written before).
  void write(Block& block) {
    std::unique_lock<std::mutex> l(m_);
    idle_.wait(l, [this] { return !pending_; });
    if (error_) std::rethrow_exception(error_);
    std::swap(block_, block);
    block.size = 0;
    pending_ = true;
    work_.notify_one();
  }
  /// Waits for every block to be written; throws the writer's error.
  void finish() {
    stop();
    if (error_) std::rethrow_exception(error_);
  }

 private:
  void run() {
    std::unique_lock<std::mutex> l(m_);
    while (true) {
      work_.wait(l, [this] { return pending_ || stopping_; });
      if (!pending_) return;
      l.unlock();
      std::exception_ptr e;
      if (!error_) {
        try {
          w_(std::string_view(block_.bytes.get(), block_.size));
        } catch (...) {
          e = std::current_exception();
        }
      }
      l.lock();
      if (e) error_ = e;
      pending_ = false;
      idle_.notify_all();
    }
  }
  void stop() {
    {
      std::unique_lock<std::mutex> l(m_);
      idle_.wait(l, [this] { return !pending_; });
      stopping_ = true;
      work_.notify_one();
    }
    if (thread_.joinable()) thread_.join();
  }

  const ByteWriter& w_;
  std::mutex m_;
  std::condition_variable work_;  ///< a block is pending, or stopping
  std::condition_variable idle_;  ///< no block is pending
  Block block_;                   ///< the block being written (pending_)
  bool pending_{false};
  bool stopping_{false};
  std::exception_ptr error_;
  std::thread thread_;  ///< last: started once the members above exist
};

/// The bytes of one output file, appended piece by piece (a copy into a block, no call per
/// piece) and handed on in blocks of about kBlock bytes to a BackgroundWriter: the file is never
/// held whole. finish() hands on the rest and waits for the writes.
class Out {
 public:
  explicit Out(const ByteWriter& w) : writer_(w) {}
  Out(const Out&) = delete;
  Out& operator=(const Out&) = delete;
  ~Out() = default;

  template <class... Pieces>
  Out& add(const Pieces&... pieces) {
    (put(std::string_view(pieces)), ...);
    return *this;
  }
  /// fmt(v, decimals) appended: appendFixed's text written in place.
  Out& num(double v, int decimals) {
    if (!std::isfinite(v)) return add(fmt(v, decimals));
    room(kNumberRoom);
    char* const b = buf_.bytes.get() + buf_.size;
    const auto r = toFixedChars(b, b + kNumberRoom, v, std::clamp(decimals, 0, 60));
    std::size_t n = static_cast<std::size_t>(r.ptr - b);
    if (n > 0 && b[0] == '-' &&
        std::all_of(b + 1, r.ptr, [](char c) { return c == '0' || c == '.'; })) {
      std::memmove(b, b + 1, n - 1);  // a value that rounds to zero has no sign
      --n;
    }
    buf_.size += n;
    return *this;
  }
  void finish() {
    if (buf_.size > 0) writer_.write(buf_);
    writer_.finish();
  }

 private:
  static constexpr std::size_t kBlock = std::size_t{1} << 20U;
  static constexpr std::size_t kNumberRoom = 400;  ///< DBL_MAX with 60 places and a sign

  /// Room for `n` more bytes (n ≤ Block::kCapacity): the block handed on first when needed.
  void room(std::size_t n) {
    if (buf_.size + n > Block::kCapacity) writer_.write(buf_);
  }
  /// Inline: a literal's copy is a few moves.
  [[gnu::always_inline]] void put(std::string_view s) {
    if (s.size() > Block::kCapacity - buf_.size) {
      putLarge(s);
      return;
    }
    std::memcpy(buf_.bytes.get() + buf_.size, s.data(), s.size());
    buf_.size += s.size();
    if (buf_.size >= kBlock) writer_.write(buf_);
  }
  /// A piece larger than the room left.
  void putLarge(std::string_view s) {
    while (s.size() > Block::kCapacity - buf_.size) {
      const std::size_t k = Block::kCapacity - buf_.size;
      std::memcpy(buf_.bytes.get() + buf_.size, s.data(), k);
      buf_.size += k;
      writer_.write(buf_);
      s.remove_prefix(k);
    }
    std::memcpy(buf_.bytes.get() + buf_.size, s.data(), s.size());
    buf_.size += s.size();
    if (buf_.size >= kBlock) writer_.write(buf_);
  }

  Block buf_;
  BackgroundWriter writer_;
};

/// The number given to each output-name key (an item's target, or a motion with an offset: key
/// −2 − motion) in first-use order, 1, 2, ...: a table by target and one by motion, no map.
class KeyNumbers {
 public:
  explicit KeyNumbers(const Program& p)
      : by_target_(p.targets().size(), 0), by_motion_(p.motions.size(), 0) {}
  /// The key's number, 0 when it has none yet.
  [[nodiscard]] int find(int key) const { return slot(key); }
  /// Gives `key` the next number (it has none yet) and returns it.
  int give(int key) {
    slot(key) = ++count_;
    return count_;
  }
  [[nodiscard]] int count() const { return count_; }

 private:
  [[nodiscard]] int slot(int key) const {
    return key >= 0 ? by_target_[static_cast<std::size_t>(key)]
                    : by_motion_[static_cast<std::size_t>(-2 - key)];
  }
  int& slot(int key) {
    return key >= 0 ? by_target_[static_cast<std::size_t>(key)]
                    : by_motion_[static_cast<std::size_t>(-2 - key)];
  }
  std::vector<int> by_target_;
  std::vector<int> by_motion_;
  int count_{0};
};

/// The pose an item's auxiliary point names (MoveC, CIRC) and its configuration.
Pose auxPose(const Program& p, const Item& it) {
  return targetPose(p, p.targets()[static_cast<std::size_t>(it.aux)]);
}
const Configuration& auxConfig(const Program& p, const Item& it) {
  return p.targets()[static_cast<std::size_t>(it.aux)].config;
}

// ---------------------------------------------------------------- KRL

void abcText(Out& o, const Pose& T) {
  const Vec3 abc = zyxFromRotation(T.linear()) / kDeg;
  o.add("X ").num(T.translation().x() * 1e3, 6).add(",Y ").num(T.translation().y() * 1e3, 6);
  o.add(",Z ").num(T.translation().z() * 1e3, 6).add(",A ").num(abc[0], 9).add(",B ");
  o.num(abc[1], 9).add(",C ").num(abc[2], 9);
}

/// The .src: frames and speeds where they change, a motion line per item (the E6POS names
/// given in first-use order, as krlDat declares them).
void krlSrc(Out& o, const Program& p, const std::vector<Item>& items, const std::string& name,
            ConversionReport& rep) {
  const std::string src_name = fs::path(p.files[0].path).filename().string();
  o.add("&ACCESS RVP\n&REL 1\nDEF ", name, "( )\n");
  o.add("; generated by roprec convert from ", src_name, "\n");
  o.add(
      "; configuration carried at the branch level: S bits 0-2 (bit 1 = elbow up); T not "
      "carried\n");
  o.add("BAS(#INITMOV,0)\n");
  KeyNumbers names(p);
  auto decl = [&](int key) {
    const int n = names.find(key);
    return std::to_string(n ? n : names.give(key));
  };
  const Frame* cur_base = nullptr;
  const Frame* cur_tool = nullptr;
  bool first = true;
  double vel = -1;
  for (const Item& it : items) {
    if (first || it.base != cur_base) {
      if (it.base == nullptr) {
        o.add("BAS(#BASE,0)\n");
        note(rep, "no base frame in the source: poses written in $WORLD (BASE 0)");
      } else if (!it.base->resolved && tableIndex(it.base->ref, "BASE_DATA")) {
        o.add("$BASE=", it.base->ref, "\n");
      } else {
        requireResolved(it.base, p.files[0].path, "base frame");
        o.add("$BASE={FRAME: ");
        abcText(o, it.base->pose);
        o.add("} ; ", it.base->ref, "\n");
      }
      cur_base = it.base;
    }
    if (first || it.tool != cur_tool) {
      if (it.tool == nullptr) {
        o.add("BAS(#TOOL,0)\n");
        note(rep, "no tool in the source: TCP = flange (TOOL 0)");
      } else if (!it.tool->resolved && tableIndex(it.tool->ref, "TOOL_DATA")) {
        o.add("$TOOL=", it.tool->ref, "\n");
      } else {
        requireResolved(it.tool, p.files[0].path, "tool");
        o.add("$TOOL={FRAME: ");
        abcText(o, it.tool->pose);
        o.add("} ; ", it.tool->ref, "\n");
      }
      cur_tool = it.tool;
    }
    first = false;
    if (it.type != MotionType::kJoint && it.speed > 0 && it.speed != vel) {
      o.add("$VEL.CP=", fmtG(it.speed / 1000.0), "\n");
      vel = it.speed;
    }
    const std::string n = decl(it.key);
    if (it.type == MotionType::kJoint) {
      o.add("PTP XP", n, it.fine ? "" : " C_PTP", "\n");
    } else if (it.type == MotionType::kCircular) {
      const std::string a = decl(it.aux);
      o.add("CIRC XP", a, ", XP", n, it.fine ? "" : " C_DIS", "\n");
    } else {
      o.add("LIN XP", n, it.fine ? "" : " C_DIS", "\n");
    }
  }
  o.add("END\n");
}

/// The .dat: an E6POS declaration per name, in the order krlSrc gives them.
void krlDat(Out& o, const Program& p, const std::vector<Item>& items, const std::string& name) {
  o.add("&ACCESS RVP\n&REL 1\nDEFDAT ", name, "\n");
  KeyNumbers names(p);
  auto decl = [&](int key, const Pose& T, const Configuration& c, const Item& it) {
    if (names.find(key)) return;
    o.add("DECL E6POS XP", std::to_string(names.give(key)), "={");
    abcText(o, T);
    if (const auto b = c.branch())
      o.add(",S ", std::to_string(configurationFromBranch(Vendor::kKuka, *b).status));
    for (std::size_t k = 0; k < 6; ++k) {
      if (hasExt(it, k)) o.add(",E", std::to_string(k + 1), " ").num(it.ext[k], 6);
    }
    o.add("}\n");
  };
  for (const Item& it : items) {
    if (!names.find(it.key)) decl(it.key, itemPose(p, it), *it.config, it);
    if (it.type == MotionType::kCircular) decl(it.aux, auxPose(p, it), auxConfig(p, it), it);
  }
  o.add("ENDDAT\n");
}

void toKrl(const Program& p, const std::vector<Item>& items, const std::string& out,
           ConversionReport& rep, const ConvertedFileSink& sink) {
  const std::string name = programName(out, 24);
  fs::path o(out);
  const std::string dat_path = (o.parent_path() / (o.stem().string() + ".dat")).string();
  std::string src_path = out;
  if (!iequals(o.extension().string(), ".src"))
    src_path = (o.parent_path() / (o.stem().string() + ".src")).string();
  sink(src_path, [&](const ByteWriter& w) {
    Out s(w);
    krlSrc(s, p, items, name, rep);
    s.finish();
  });
  sink(dat_path, [&](const ByteWriter& w) {
    Out d(w);
    krlDat(d, p, items, name);
    d.finish();
  });
}

// ---------------------------------------------------------------- RAPID

void poseRapid(Out& o, const Pose& T) {
  const Eigen::Quaterniond q = quaternionFromRotation(T.linear());
  o.add("[[").num(T.translation().x() * 1e3, 6).add(",").num(T.translation().y() * 1e3, 6);
  o.add(",").num(T.translation().z() * 1e3, 6).add("],[").num(q.w(), 12).add(",");
  o.num(q.x(), 12).add(",").num(q.y(), 12).add(",").num(q.z(), 12).add("]]");
}

/// The RAPID module's names: robtargets p<n> by key, tools and work objects by frame, given in
/// the order the motions use them (declare() writes their declarations and notes).
class RapidNames {
 public:
  explicit RapidNames(const Program& p) : p_(p), targets_(p) {}

  /// Declares what `it` uses, in the order the motions name it: its target, tool, work object
  /// and (MoveC) auxiliary point.
  void declare(Out& o, const Item& it, ConversionReport& rep) {
    if (!targets_.find(it.key)) target(o, it.key, itemPose(p_, it), *it.config, it, rep);
    tool(o, it.tool, rep);
    wobj(o, it.base);
    if (it.type == MotionType::kCircular)
      target(o, it.aux, auxPose(p_, it), auxConfig(p_, it), it, rep);
  }
  [[nodiscard]] std::string target(int key) const {
    return "p" + std::to_string(targets_.find(key));
  }
  [[nodiscard]] std::string tool(const Frame* f) const {
    return f == nullptr ? std::string("tool0") : tools_.at(f);
  }
  [[nodiscard]] std::string wobj(const Frame* f) const {
    return f == nullptr ? std::string("wobj0") : wobjs_.at(f);
  }

 private:
  void target(Out& o, int key, const Pose& T, const Configuration& c, const Item& it,
              ConversionReport& rep) {
    if (targets_.find(key)) return;
    const std::string n = "p" + std::to_string(targets_.give(key));
    const int cfx = c.branch().value_or(0);
    if (!c.branch()) note(rep, n + ": no configuration in the source; cfx written 0");
    o.add("  CONST robtarget ", n, ":=[");
    const Eigen::Quaterniond q = quaternionFromRotation(T.linear());
    o.add("[").num(T.translation().x() * 1e3, 6).add(",").num(T.translation().y() * 1e3, 6);
    o.add(",").num(T.translation().z() * 1e3, 6).add("],[").num(q.w(), 12).add(",");
    o.num(q.x(), 12).add(",").num(q.y(), 12).add(",").num(q.z(), 12).add("]");
    o.add(",[0,0,0,", std::to_string(cfx), "],[");
    for (std::size_t k = 0; k < 6; ++k) {
      if (k) o.add(",");
      if (hasExt(it, k)) {
        o.num(it.ext[k], 6);
      } else {
        o.add("9E+09");
      }
    }
    o.add("]];\n");
  }
  void tool(Out& o, const Frame* f, ConversionReport& rep) {
    if (f == nullptr || tools_.count(f)) return;
    requireResolved(f, p_.files[0].path, "tool");
    std::string n = "tTool" + std::to_string(tools_.size() + 1);
    tools_[f] = n;
    o.add("  ! ", f->ref, "; tool load not carried: set ", n, ".tload\n");
    o.add("  PERS tooldata ", n, ":=[TRUE,");
    poseRapid(o, f->pose);
    o.add(",[1,[0,0,0.001],[1,0,0,0],0,0,0]];\n");
    note(rep, n + ": tool load data not carried (placeholder mass 1 kg); set it before running");
  }
  void wobj(Out& o, const Frame* f) {
    if (f == nullptr || wobjs_.count(f)) return;
    requireResolved(f, p_.files[0].path, "base frame");
    std::string n = "wObj" + std::to_string(wobjs_.size() + 1);
    wobjs_[f] = n;
    o.add("  ! ", f->ref, "\n");
    o.add("  PERS wobjdata ", n, ":=[FALSE,TRUE,\"\",");
    poseRapid(o, f->pose);
    o.add(",[[0,0,0],[1,0,0,0]]];\n");
  }

  const Program& p_;
  KeyNumbers targets_;
  std::map<const Frame*, std::string> tools_;
  std::map<const Frame*, std::string> wobjs_;
};

/// The module: header, every declaration (first pass over the motions), then the procedure.
void rapidModule(Out& o, const Program& p, const std::vector<Item>& items, const std::string& name,
                 ConversionReport& rep) {
  o.add("MODULE ", name, "\n");
  o.add("  ! generated by roprec convert from ", fs::path(p.files[0].path).filename().string(),
        "\n");
  o.add(
      "  ! configuration carried at the branch level (cfx); cf1, cf4, cf6 unknown: ConfJ/ConfL "
      "off\n");
  RapidNames names(p);
  for (const Item& it : items) names.declare(o, it, rep);
  o.add("  PROC ", name, "()\n    ConfJ \\Off;\n    ConfL \\Off;\n");
  for (const Item& it : items) {
    const std::string n = names.target(it.key);
    const std::string tool = names.tool(it.tool);
    const std::string wobj = names.wobj(it.base);
    const char* zone = it.fine ? "fine" : "z1";
    const std::string speed = it.speed > 0 ? "[" + fmtG(it.speed) + ",500,5000,1000]" : "v1000";
    if (it.type == MotionType::kJoint) {
      o.add("    MoveJ ", n, ",", speed, ",", zone, ",", tool, "\\WObj:=", wobj, ";\n");
    } else if (it.type == MotionType::kCircular) {
      o.add("    MoveC ", names.target(it.aux), ",", n, ",", speed, ",", zone, ",", tool,
            "\\WObj:=", wobj, ";\n");
    } else {
      o.add("    MoveL ", n, ",", speed, ",", zone, ",", tool, "\\WObj:=", wobj, ";\n");
    }
  }
  o.add("  ENDPROC\nENDMODULE\n");
}

void toRapid(const Program& p, const std::vector<Item>& items, const std::string& out,
             ConversionReport& rep, const ConvertedFileSink& sink) {
  std::string path = out;
  if (fs::path(out).extension().empty()) path += ".mod";
  sink(path, [&](const ByteWriter& w) {
    Out o(w);
    rapidModule(o, p, items, programName(out, 32), rep);
    o.finish();
  });
}

// ---------------------------------------------------------------- TP

/// The TP program's numbers: UFRAME/UTOOL by frame, P[n] by key in first-use order, and the
/// count of numbered /MN lines (LINE_COUNT); plan() gives them and the notes in motion order.
class TpPlan {
 public:
  explicit TpPlan(const Program& p) : p_(p), pnum_(p) {}

  void plan(const std::vector<Item>& items, ConversionReport& rep) {
    int cur_uf = -1;
    int cur_ut = -1;
    bool turn_note = false;
    // a frame selection line when frame n is not the current one (and its two remark lines
    // with a note when its values are known)
    auto select = [&](const char* kind, int n, const auto* frame, int& current) {
      if (n == current) return;
      if (frame != nullptr && frame->resolved) {
        lines_ += 2;
        note(rep, std::string("set ") + kind + "[" + std::to_string(n) +
                      "] on the controller (values in the remarks)");
      }
      ++lines_;
      current = n;
    };
    for (const Item& it : items) {
      select("UFRAME", number(uf_, it.base, "UFRAME"), it.base, cur_uf);
      select("UTOOL", number(ut_, it.tool, "UTOOL"), it.tool, cur_ut);
      if (!turn_note) {
        note(rep,
             "FANUC turn digits written 0 (turns are not carried across vendors); check J4/J6 "
             "turns");
        turn_note = true;
      }
      record(it.key, *it.config, rep);
      if (it.type == MotionType::kCircular) record(it.aux, auxConfig(p_, it), rep);
      ++lines_;  // a C motion's second line is not numbered
    }
  }
  [[nodiscard]] int uframe(const Frame* f) const { return f == nullptr ? 0 : uf_.at(f); }
  [[nodiscard]] int utool(const Frame* f) const { return f == nullptr ? 0 : ut_.at(f); }
  [[nodiscard]] int position(int key) const { return pnum_.find(key); }
  [[nodiscard]] int lineCount() const { return lines_; }

 private:
  static int number(std::map<const Frame*, int>& table, const Frame* f, const char* kind) {
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
  }
  void record(int key, const Configuration& c, ConversionReport& rep) {
    if (pnum_.find(key)) return;
    const int n = pnum_.give(key);
    if (!c.branch())
      note(rep,
           "P[" + std::to_string(n) + "]: no configuration in the source; CONFIG written 'F U T'");
  }

  const Program& p_;
  std::map<const Frame*, int> uf_;
  std::map<const Frame*, int> ut_;
  KeyNumbers pnum_;
  int lines_{0};
};

/// A frame's values as /MN remarks ("! UF1 REF ;", "! = x,y,z,w,p,r ;").
void tpFrameRemarks(Out& o, int& line, const char* kind, int number, const Frame& f) {
  const Vec3 abc = zyxFromRotation(f.pose.linear()) / kDeg;
  const Vec3 x = f.pose.translation() * 1e3;
  char buf[16];
  std::snprintf(buf, sizeof buf, "%4d:", ++line);
  o.add(buf, "  ! ", kind, std::to_string(number), " ", f.ref, " ;\n");
  std::snprintf(buf, sizeof buf, "%4d:", ++line);
  o.add(buf, "  ! = ").num(x.x(), 3).add(",").num(x.y(), 3).add(",").num(x.z(), 3).add(",");
  o.num(abc[2], 6).add(",").num(abc[1], 6).add(",").num(abc[0], 6).add(" ;\n");
}

/// The /MN section: frame selections where they change, a numbered line per motion.
void tpMain(Out& o, const std::vector<Item>& items, const TpPlan& plan) {
  int cur_uf = -1;
  int cur_ut = -1;
  int line = 0;
  char buf[16];
  auto numbered = [&]() {
    std::snprintf(buf, sizeof buf, "%4d:", ++line);
    return std::string_view(buf);
  };
  for (const Item& it : items) {
    const int ufn = plan.uframe(it.base);
    const int utn = plan.utool(it.tool);
    if (ufn != cur_uf) {
      if (it.base != nullptr && it.base->resolved) tpFrameRemarks(o, line, "UF", ufn, *it.base);
      o.add(numbered(), "  UFRAME_NUM=", std::to_string(ufn), " ;\n");
      cur_uf = ufn;
    }
    if (utn != cur_ut) {
      if (it.tool != nullptr && it.tool->resolved) tpFrameRemarks(o, line, "UT", utn, *it.tool);
      o.add(numbered(), "  UTOOL_NUM=", std::to_string(utn), " ;\n");
      cur_ut = utn;
    }
    const std::string n = std::to_string(plan.position(it.key));
    const char* term = it.fine ? "FINE" : "CNT100";
    const std::string speed =
        it.type == MotionType::kJoint ? "100%" : (it.speed > 0 ? fmtG(it.speed) : "250") + "mm/sec";
    if (it.type == MotionType::kJoint) {
      o.add(numbered(), "J P[", n, "] ", speed, " ", term, " ;\n");
    } else if (it.type == MotionType::kCircular) {
      o.add(numbered(), "C P[", std::to_string(plan.position(it.aux)), "] \n");
      o.add("    :  P[", n, "] ", speed, " ", term, " ;\n");
    } else {
      o.add(numbered(), "L P[", n, "] ", speed, " ", term, " ;\n");
    }
  }
}

/// The /POS section: each P[n] once, in number order (first use), with the frames of the motion
/// that first uses it.
void tpPositions(Out& o, const Program& p, const std::vector<Item>& items, const TpPlan& plan) {
  int written = 0;
  auto record = [&](int key, const Pose& T, const Configuration& c, const Item& it) {
    const int n = plan.position(key);
    if (n <= written) return;
    written = n;
    const Configuration fc = configurationFromBranch(Vendor::kFanuc, c.branch().value_or(0));
    const Vec3 abc = zyxFromRotation(T.linear()) / kDeg;
    o.add("P[", std::to_string(n), "]{\n   GP1:\n\tUF : ", std::to_string(plan.uframe(it.base)),
          ", UT : ", std::to_string(plan.utool(it.tool)), ",\t\tCONFIG : '", fc.text(), "',\n");
    o.add("\tX = ").num(T.translation().x() * 1e3, 6).add("  mm,\tY = ");
    o.num(T.translation().y() * 1e3, 6).add("  mm,\tZ = ").num(T.translation().z() * 1e3, 6);
    o.add("  mm,\n\tW = ").num(abc[2], 9).add(" deg,\tP = ").num(abc[1], 9).add(" deg,\tR = ");
    o.num(abc[0], 9).add(" deg");
    for (std::size_t k = 0; k < 3; ++k) {
      if (hasExt(it, k)) o.add(",\n\tE", std::to_string(k + 1), "= ").num(it.ext[k], 6).add("  mm");
    }
    o.add("\n};\n");
  };
  for (const Item& it : items) {
    if (plan.position(it.key) > written) record(it.key, itemPose(p, it), *it.config, it);
    if (it.type == MotionType::kCircular) record(it.aux, auxPose(p, it), auxConfig(p, it), it);
  }
}

void toTp(const Program& p, const std::vector<Item>& items, const std::string& out,
          ConversionReport& rep, const ConvertedFileSink& sink) {
  const std::string name = upper(programName(out, 36));
  TpPlan plan(p);
  plan.plan(items, rep);
  std::string path = out;
  if (fs::path(out).extension().empty()) path += ".ls";
  sink(path, [&](const ByteWriter& w) {
    Out o(w);
    o.add("/PROG  ", name,
          "\n/ATTR\nOWNER\t\t= MNEDITOR;\nCOMMENT\t\t= \"roprec convert\";\nPROG_SIZE\t= 0;\n");
    o.add(
        "CREATE\t\t= DATE 00-01-01  TIME 00:00:00;\nMODIFIED\t= DATE 00-01-01  TIME "
        "00:00:00;\nFILE_NAME\t= ;\n");
    o.add("VERSION\t\t= 0;\nLINE_COUNT\t= ", std::to_string(plan.lineCount()),
          ";\nMEMORY_SIZE\t= 0;\n");
    o.add(
        "PROTECT\t\t= READ_WRITE;\nTCD:  STACK_SIZE\t= 0,\n      TASK_PRIORITY\t= 50,\n      "
        "TIME_SLICE\t= 0,\n");
    o.add("      BUSY_LAMP_OFF\t= 0,\n      ABORT_REQUEST\t= 0,\n      PAUSE_REQUEST\t= 0;\n");
    o.add("DEFAULT_GROUP\t= 1,*,*,*,*;\nCONTROL_CODE\t= 00000000 00000000;\n/MN\n");
    tpMain(o, items, plan);
    o.add("/POS\n");
    tpPositions(o, p, items, plan);
    o.add("/END\n");
    o.finish();
  });
}

// ---------------------------------------------------------------- CSV / JSON

void quat(Out& o, const Pose& T, const char* sep) {
  const Eigen::Quaterniond q = quaternionFromRotation(T.linear());
  o.num(q.w(), 12).add(sep).num(q.x(), 12).add(sep).num(q.y(), 12).add(sep).num(q.z(), 12);
}

void xyz(Out& o, const Pose& T, const char* sep) {
  o.num(T.translation().x() * 1e3, 6).add(sep).num(T.translation().y() * 1e3, 6).add(sep);
  o.num(T.translation().z() * 1e3, 6);
}

const char* motionName(const Item& it) {
  return it.type == MotionType::kJoint ? "J" : it.type == MotionType::kCircular ? "C" : "L";
}

/// The ids of the targets of a target list: an item's target name (sanitised) the first time
/// that name is given, else "T<n>" (n = the count of targets named so far + 1); the same id for
/// the same key again. The "T<n>" ids are numbers, not strings, and a look-up per new target.
class TargetIds {
 public:
  explicit TargetIds(const Program& p) : p_(p), keys_(p) {}

  /// The id of an item's target.
  std::string_view of(const Item& it) {
    const int order = keys_.find(it.key);
    const int id = order != 0 ? ids_[static_cast<std::size_t>(order)] : give(it);
    if (id > 0) {
      id_.assign("T");
      id_ += std::to_string(id);
      return id_;
    }
    return names_[static_cast<std::size_t>(-id - 1)];
  }

 private:
  /// A new id: > 0 for "T<id>", < 0 for names_[-id - 1] (KeyNumbers holds ids as numbers).
  int give(const Item& it) {
    std::string n = it.key == it.target
                        ? sanitize(p_.targets()[static_cast<std::size_t>(it.target)].name, "")
                        : "";
    if (taken(n)) n.clear();
    const int count = keys_.count() + 1;  // the ids given so far + 1
    int id = 0;
    if (n.empty()) {
      id = count;
      if (generated_.size() <= static_cast<std::size_t>(id)) generated_.resize(2 * id + 1, false);
      generated_[static_cast<std::size_t>(id)] = true;
    } else {
      given_.insert(n);
      names_.push_back(std::move(n));
      id = -static_cast<int>(names_.size());
    }
    keys_.give(it.key);  // counts the ids given
    ids_.resize(std::max<std::size_t>(ids_.size(), static_cast<std::size_t>(count) + 1), 0);
    ids_[static_cast<std::size_t>(count)] = id;
    return id;
  }
  /// Whether `n` was given as an id already (a name, or a "T<n>").
  [[nodiscard]] bool taken(const std::string& n) const {
    if (n.empty()) return false;
    if (given_.count(n)) return true;
    if (n.size() < 2 || n.size() > 11 || n[0] != 'T' || n[1] == '0') return false;
    std::size_t k = 0;
    for (std::size_t i = 1; i < n.size(); ++i) {
      if (!isDigit(n[i])) return false;
      k = k * 10 + static_cast<std::size_t>(n[i] - '0');
    }
    return k < generated_.size() && generated_[k];
  }

  const Program& p_;
  KeyNumbers keys_;                        ///< key -> the order its id was given in (1, 2, ...)
  std::vector<int> ids_;                   ///< by that order: the id (see give())
  std::vector<std::string> names_;         ///< the names given as ids
  std::unordered_set<std::string> given_;  ///< the same, for the look-up
  std::vector<bool> generated_;            ///< "T<k>" given
  std::string id_;                         ///< of()'s buffer for a "T<n>"
};

void csvTargets(Out& o, const Program& p, const std::vector<Item>& items) {
  o.add("# roprec target list converted from ", fs::path(p.files[0].path).filename().string(),
        "\n");
  o.add(
      "# units: mm, deg; orientation: quaternion qw,qx,qy,qz; poses are TCP poses in the named "
      "frame\n");
  std::map<std::string, const Frame*> frames;
  std::map<std::string, const Frame*> tools;
  for (const Item& it : items) {
    if (it.base != nullptr && it.base->resolved) frames[sanitize(it.base->ref, "frame")] = it.base;
    if (it.tool != nullptr && it.tool->resolved) tools[sanitize(it.tool->ref, "tool")] = it.tool;
  }
  for (const auto& [n, f] : frames) {
    o.add("# frame ", n, ": ");
    xyz(o, f->pose, " ");
    o.add(" ");
    quat(o, f->pose, " ");
    o.add("\n");
  }
  for (const auto& [n, f] : tools) {
    o.add("# tool ", n, ": ");
    xyz(o, f->pose, " ");
    o.add(" ");
    quat(o, f->pose, " ");
    o.add("\n");
  }
  o.add("id,motion,x,y,z,qw,qx,qy,qz,frame,tool,conf,speed,j1,j2,j3,j4,j5,j6\n");
  TargetIds ids(p);
  FrameNames frame_names("frame");
  FrameNames tool_names("tool");
  for (const Item& it : items) {
    o.add(ids.of(it), ",", motionName(it), ",");
    if (it.cartesian) {
      const Pose T = itemPose(p, it);
      xyz(o, T, ",");
      o.add(",");
      quat(o, T, ",");
    } else {
      o.add(",,,,,,");
    }
    o.add(",", frame_names.of(it.base), ",", tool_names.of(it.tool));
    const std::string conf = it.config->text();
    if (conf.find(',') != std::string::npos) {
      o.add(",\"", conf, "\"");
    } else {
      o.add(",", conf);
    }
    o.add(",", it.speed > 0 ? fmtG(it.speed) : "");
    const std::vector<double> joints = itemJoints(p, it);
    for (std::size_t k = 0; k < 6; ++k) {
      o.add(",");
      if (k < joints.size()) o.num(joints[k], 9);
    }
    o.add("\n");
  }
}

void jsonTargets(Out& o, const Program& p, const std::vector<Item>& items) {
  o.add("{\n  \"format\": \"roprec-targets\",\n  \"source\": ",
        jsonStr(fs::path(p.files[0].path).filename().string()),
        ",\n  \"units\": {\"length\": \"mm\", \"angle\": \"deg\"},\n  \"frames\": [");
  std::map<std::string, const Frame*> frames;
  for (const Item& it : items) {
    for (const Frame* f : {it.base, it.tool}) {
      if (f != nullptr && f->resolved) frames[sanitize(f->ref, "frame")] = f;
    }
  }
  bool first = true;
  for (const auto& [n, f] : frames) {
    o.add(first ? "\n" : ",\n", "    {\"name\": ", jsonStr(n), ", \"position_mm\": [");
    xyz(o, f->pose, ", ");
    o.add("], \"quaternion_wxyz\": [");
    quat(o, f->pose, ", ");
    o.add("]}");
    first = false;
  }
  o.add(first ? "" : "\n  ", "],\n  \"targets\": [");
  TargetIds ids(p);
  FrameNames frame_names("frame");
  FrameNames tool_names("tool");
  first = true;
  for (const Item& it : items) {
    o.add(first ? "\n" : ",\n", "    {\"id\": ", jsonStr(std::string(ids.of(it))),
          ", \"motion\": \"", motionName(it), "\"");
    if (it.cartesian) {
      o.add(", \"position_mm\": [");
      const Pose T = itemPose(p, it);
      xyz(o, T, ", ");
      o.add("], \"quaternion_wxyz\": [");
      quat(o, T, ", ");
      o.add("]");
    }
    const std::vector<double> joints = itemJoints(p, it);
    if (!joints.empty()) {
      o.add(", \"joints_deg\": [");
      for (std::size_t k = 0; k < joints.size(); ++k) {
        if (k) o.add(", ");
        o.num(joints[k], 9);
      }
      o.add("]");
    }
    if (it.base != nullptr) o.add(", \"frame\": ", jsonStr(frame_names.of(it.base)));
    if (it.tool != nullptr) o.add(", \"tool\": ", jsonStr(tool_names.of(it.tool)));
    if (it.config->present()) o.add(", \"config\": ", jsonStr(it.config->text()));
    if (it.speed > 0) o.add(", \"speed_mm_s\": ", fmtG(it.speed));
    o.add(", \"fine\": ", it.fine ? "true" : "false", "}");
    first = false;
  }
  o.add(first ? "" : "\n  ", "]\n}\n");
}

void toTable(const Program& p, const std::vector<Item>& items, const std::string& out, bool json,
             const ConvertedFileSink& sink) {
  const std::string path =
      fs::path(out).extension().empty() ? out + (json ? ".json" : ".csv") : out;
  sink(path, [&](const ByteWriter& w) {
    Out o(w);
    if (json) {
      jsonTargets(o, p, items);
    } else {
      csvTargets(o, p, items);
    }
    o.finish();
  });
}

void writeConverted(const Program& p, const std::vector<Item>& items, Dialect to,
                    const std::string& out_path, ConversionReport& report,
                    const ConvertedFileSink& sink) {
  switch (to) {
    case Dialect::kKrl:
      toKrl(p, items, out_path, report, sink);
      return;
    case Dialect::kRapid:
      toRapid(p, items, out_path, report, sink);
      return;
    case Dialect::kTp:
      toTp(p, items, out_path, report, sink);
      return;
    case Dialect::kCsv:
    case Dialect::kHoleCsv:
      toTable(p, items, out_path, false, sink);
      return;
    case Dialect::kJson:
      toTable(p, items, out_path, true, sink);
      return;
  }
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

void convertProgram(const Program& p, Dialect to, const std::string& out_path,
                    ConversionReport& report, bool all_lines, const ConvertedFileSink& sink) {
  const bool table = to == Dialect::kCsv || to == Dialect::kJson;
  std::vector<Item> items = collect(p, table, report);
  std::future<std::vector<std::string>> lost;
  if (!table) {  // a program: say what of the source it does not carry
    markUnusedKrlExternalAxes(p, items, report);
    // listed on a thread of its own while the files are written (it reads the program and the
    // items only); its notices follow the ones collect() gave, in the same order
    lost = std::async(std::launch::async, [&p, &items, to, all_lines] {
      ConversionReport r;
      listNotCarried(p, all_lines, r);
      listZoneMappings(p, to, items, all_lines, r);
      return std::move(r.not_carried);
    });
  }
  writeConverted(p, items, to, out_path, report, sink);
  if (lost.valid()) {
    for (std::string& s : lost.get()) report.not_carried.push_back(std::move(s));
  }
}

std::vector<std::pair<std::string, std::string>> convertProgram(const Program& p, Dialect to,
                                                                const std::string& out_path,
                                                                ConversionReport& report,
                                                                bool all_lines) {
  std::vector<std::pair<std::string, std::string>> files;
  convertProgram(
      p, to, out_path, report, all_lines,
      [&](const std::string& path, const std::function<void(const ByteWriter&)>& produce) {
        std::string bytes;
        produce([&](std::string_view s) { bytes.append(s); });
        files.emplace_back(path, std::move(bytes));
      });
  return files;
}

}  // namespace roprec::postproc
