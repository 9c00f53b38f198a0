/// A drilling program written from a list of holes (postproc/drill_program.hpp, docs/programs.md
/// §14).
#include "postproc/drill_program.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/str_cat.hpp"
#include "postproc/dialects.hpp"
#include "postproc/lexer.hpp"

namespace roprec::postproc {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------- numbers (program.hpp formatLike)

/// `decimals` fixed decimals, no sign on zero (formatLike in the style of a plain "0").
std::string fixed(double v, int decimals) {
  NumberHints h;
  h.min_decimals = decimals;
  return formatLike("0", v, h);
}

std::string mm(double v_m) { return fixed(v_m * 1e3, 6); }

/// Informational millimetres (diameters, depths, distances in comments).
std::string mm3(double v_m) { return fixed(v_m * 1e3, 3); }

Vec3 abcDeg(const Mat3& R) { return zyxFromRotation(R) / kDeg; }

std::string krlFrame(const Pose& T) {
  const Vec3 abc = abcDeg(T.linear());
  const Vec3 x = T.translation();
  return "X " + mm(x.x()) + ",Y " + mm(x.y()) + ",Z " + mm(x.z()) + ",A " + fixed(abc[0], 9) +
         ",B " + fixed(abc[1], 9) + ",C " + fixed(abc[2], 9);
}

std::string quatText(const Mat3& R, const char* sep) {
  const Eigen::Quaterniond q = quaternionFromRotation(R);
  return fixed(q.w(), 12) + sep + fixed(q.x(), 12) + sep + fixed(q.y(), 12) + sep +
         fixed(q.z(), 12);
}

std::string xyzText(const Vec3& x, const char* sep) {
  return mm(x.x()) + sep + mm(x.y()) + sep + mm(x.z());
}

std::string rapidPose(const Pose& T) {
  return "[[" + xyzText(T.translation(), ",") + "],[" + quatText(T.linear(), ",") + "]]";
}

// ---------------------------------------------------------------- validation and names

[[noreturn]] void invalid(const std::string& what) {
  throw std::invalid_argument("drilling program: " + what);
}

bool finitePose(const Pose& T) { return T.matrix().allFinite(); }

bool rotationOk(const Mat3& R) {
  return (R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff() < 1e-9 && R.determinant() > 0;
}

bool printableId(const std::string& s) {
  if (s.empty() || s.front() == ' ' || s.back() == ' ') return false;
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f || c == '"') return false;
  }
  return true;
}

/// Comment text: one line, control characters replaced.
std::string commentText(const std::string& s, bool no_semicolon = false) {
  std::string r;
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    r += (u < 0x20 || u == 0x7f || (no_semicolon && c == ';')) ? '_' : c;
  }
  return r;
}

bool identifier(const std::string& s, std::size_t max_len) {
  if (s.empty() || s.size() > max_len || !std::isalpha(static_cast<unsigned char>(s[0])))
    return false;
  for (const char c : s) {
    if (!isIdentChar(c) || c == '$') return false;
  }
  return true;
}

bool keyword(const std::string& s) {
  static const std::set<std::string> kw = {
      // KRL
      "DEF", "DEFFCT", "DEFDAT", "END", "ENDFCT", "ENDDAT", "DECL", "GLOBAL", "CONST", "PUBLIC",
      "PTP", "LIN", "CIRC", "SPTP", "SLIN", "SCIRC", "SPL", "PTP_REL", "LIN_REL", "CIRC_REL", "IF",
      "THEN", "ELSE", "ENDIF", "FOR", "TO", "STEP", "ENDFOR", "WHILE", "ENDWHILE", "REPEAT",
      "UNTIL", "LOOP", "ENDLOOP", "SWITCH", "CASE", "DEFAULT", "ENDSWITCH", "WAIT", "SEC", "HALT",
      "GOTO", "EXIT", "RETURN", "RESUME", "INTERRUPT", "TRIGGER", "WHEN", "DISTANCE", "DELAY", "DO",
      "PRIO", "ON", "OFF", "AND", "OR", "NOT", "EXOR", "B_AND", "B_OR", "B_NOT", "B_EXOR", "TRUE",
      "FALSE", "INT", "REAL", "BOOL", "CHAR", "FRAME", "POS", "E6POS", "AXIS", "E6AXIS", "STRUC",
      "ENUM", "SIGNAL", "IN", "OUT", "C_DIS", "C_PTP", "C_VEL", "C_ORI", "C_SPL", "WITH", "CA",
      "BAS", "CONTINUE", "ANIN", "ANOUT", "BRAKE", "IMPORT", "IS", "MAXIMUM", "MINIMUM", "EXT",
      "EXTFCT",
      // RAPID
      "MODULE", "ENDMODULE", "PROC", "ENDPROC", "FUNC", "ENDFUNC", "TRAP", "ENDTRAP", "VAR", "PERS",
      "LOCAL", "TASK", "ELSEIF", "TEST", "ENDTEST", "BACKWARD", "ERROR", "UNDO", "RAISE", "RETRY",
      "TRYNEXT", "NOSTEPIN", "VIEWONLY", "READONLY", "SYSMODULE", "INOUT", "DIV", "MOD", "XOR",
      "MOVEJ", "MOVEL", "MOVEC", "MOVEABSJ", "CONFJ", "CONFL", "WAITTIME", "OFFS", "RELTOOL",
      "TOOL0", "WOBJ0", "LOAD0", "FINE", "MAIN", "NUM", "DNUM", "STRING", "ROBTARGET",
      "JOINTTARGET", "TOOLDATA", "WOBJDATA", "SPEEDDATA", "ZONEDATA", "LOADDATA", "CONFDATA",
      "POSE", "ORIENT", "EXTJOINT", "ROBJOINT", "VMAX"};
  return kw.count(upper(s)) != 0;
}

/// Unique-name allocator (case-insensitive for KRL/RAPID, exact for the tables).
class Names {
 public:
  Names(bool nocase, std::size_t max_len) : nocase_(nocase), max_(max_len) {}
  void reserve(const std::string& s) { used_.insert(key(s)); }
  [[nodiscard]] bool taken(const std::string& s) const { return used_.count(key(s)) != 0; }
  std::string take(const std::string& base, std::size_t max_len) {
    const std::size_t lim = std::min(max_len, max_);
    std::string c = base.substr(0, lim);
    for (int k = 2; taken(c) || (nocase_ && keyword(c)); ++k) {
      std::string s(1, '_');
      s += std::to_string(k);
      c = base.substr(0, lim > s.size() ? lim - s.size() : 0) + s;
    }
    reserve(c);
    return c;
  }

 private:
  bool nocase_;
  std::size_t max_;
  std::set<std::string> used_;
  [[nodiscard]] std::string key(const std::string& s) const { return nocase_ ? upper(s) : s; }
};

/// An identifier from free text: identifier characters kept, others '_', letter first.
std::string programIdent(const std::string& s, std::size_t max_len, const char* fallback) {
  std::string r;
  for (const char c : s) r += (isIdentChar(c) && c != '$') ? c : '_';
  if (r.empty() || !std::isalpha(static_cast<unsigned char>(r[0])))
    r = fallback + (r.empty() ? "" : "_" + r);
  if (r.size() > max_len) r.resize(max_len);
  return r;
}

// ---------------------------------------------------------------- the cycles

struct Cycle {
  const DrillHole* hole{nullptr};
  std::string bottom;  ///< point names (KRL/RAPID identifiers, table ids)
  std::string approach;
  std::string clear;
  std::string retract;  ///< tables only
  Pose T_app{Pose::Identity()};
  Pose T_clr{Pose::Identity()};
  Pose T_bot{Pose::Identity()};
  Configuration config;     ///< parsed (KRL/RAPID/TP)
  std::string config_text;  ///< as written into the program ("" = none)
  bool config_given{false};
};

Pose along(const Pose& T, double d) {
  Pose r = T;
  r.translation() = T.translation() + T.linear().col(2) * d;
  return r;
}

/// KRL S/T text as given: `S 2 T 35`, `S 'B010' T 'B100011'`, `S 6`, `T 3` → ",S 2,T 35".
std::optional<std::string> krlConfig(const std::string& text, Configuration& c) {
  std::string s;
  std::vector<std::string> w;
  for (std::size_t i = 0; i < text.size();) {
    while (i < text.size() && (text[i] == ' ' || text[i] == ',' || text[i] == '\t')) ++i;
    std::size_t j = i;
    while (j < text.size() && text[j] != ' ' && text[j] != ',' && text[j] != '\t') ++j;
    if (j > i) w.push_back(text.substr(i, j - i));
    i = j;
  }
  if (w.empty() || w.size() % 2 != 0 || w.size() > 4) return std::nullopt;
  c = Configuration{};
  c.vendor = Vendor::kKuka;
  for (std::size_t k = 0; k < w.size(); k += 2) {
    const std::string key = upper(w[k]);
    const std::string& v = w[k + 1];
    int value = 0;
    if (v.size() >= 3 && v.front() == '\'' && v.back() == '\'' && (v[1] == 'B' || v[1] == 'b')) {
      const std::string bits = v.substr(2, v.size() - 3);
      if (bits.empty() || bits.size() > 16 || bits.find_first_not_of("01") != std::string::npos)
        return std::nullopt;
      for (const char b : bits) value = 2 * value + (b - '0');
    } else {
      if (v.empty() || v.size() > 5 || v.find_first_not_of("0123456789") != std::string::npos)
        return std::nullopt;
      value = std::atoi(v.c_str());
    }
    if (key == "S" && c.status < 0) {
      c.status = value;
    } else if (key == "T" && c.turn < 0) {
      c.turn = value;
    } else {
      return std::nullopt;
    }
    strAppend(s, ",", key, " ", v);
  }
  return s;
}

std::vector<Cycle> buildCycles(const std::vector<DrillHole>& holes, const DrillProgramOptions& o,
                               Names& names, std::size_t id_len) {
  std::vector<Cycle> cycles(holes.size());
  const bool idents = o.dialect == Dialect::kKrl || o.dialect == Dialect::kRapid;
  std::set<std::string> ids;
  for (std::size_t i = 0; i < holes.size(); ++i) {
    const DrillHole& h = holes[i];
    const std::string where = "hole " + std::to_string(i + 1) + " '" + commentText(h.id) + "'";
    if (!printableId(h.id))
      invalid(where + ": the id must be non-empty printable text without '\"' or outer blanks");
    if (!ids.insert(h.id).second) invalid(where + ": duplicate id");
    if (!finitePose(h.T_frame_tcp) || !rotationOk(h.T_frame_tcp.linear()))
      invalid(where + ": pose is not a finite rigid transform");
    if (!std::isfinite(h.depth) || h.depth <= 0) invalid(where + ": depth must be > 0");
    if (!std::isfinite(h.diameter) || h.diameter < 0) invalid(where + ": diameter must be >= 0");
    Cycle& c = cycles[i];
    c.hole = &h;
    c.T_app = along(h.T_frame_tcp, -o.approach);
    c.T_clr = along(h.T_frame_tcp, -o.clearance);
    c.T_bot = along(h.T_frame_tcp, h.depth);
    if (!h.config) continue;
    std::string text = *h.config;
    text.erase(0, std::min(text.size(), text.find_first_not_of(" \t")));
    text.erase(text.find_last_not_of(" \t") + 1);
    if (text.empty()) continue;
    if (!printableId(text))
      invalid(where + ": configuration must be one line of printable text without '\"'");
    c.config_given = true;
    switch (o.dialect) {
      case Dialect::kKrl: {
        const auto s = krlConfig(text, c.config);
        if (!s)
          invalid(strCat(where,
                         ": KUKA configuration expected ('S 2 T 35' or \"S 'B010' T 'B100011'\"), "
                         "got '",
                         text, "'"));
        c.config_text = *s;
        break;
      }
      case Dialect::kRapid:
        c.config = parseConfigurationText(text);
        if (c.config.vendor != Vendor::kAbb)
          invalid(strCat(where, ": ABB configuration expected ('[0,-1,0,0]'), got '", text, "'"));
        c.config_text = c.config.text();
        break;
      case Dialect::kTp:
        c.config = parseConfigurationText(text);
        if (c.config.vendor != Vendor::kFanuc)
          invalid(
              strCat(where, ": FANUC configuration expected ('N U T, 0, 0, 0'), got '", text, "'"));
        c.config_text = c.config.text();
        break;
      case Dialect::kCsv:
      case Dialect::kJson:
        c.config = parseConfigurationText(text);
        c.config_text = text;
        break;
      case Dialect::kHoleCsv:
        c.config_given = false;
        break;
    }
  }
  // names: ids that are valid names first, then the fallbacks, then the cycle points
  std::vector<bool> named(holes.size(), false);
  for (std::size_t i = 0; i < holes.size(); ++i) {
    const std::string& id = holes[i].id;
    if (idents && (!identifier(id, id_len) || keyword(id) || names.taken(id))) continue;
    if (!idents && names.taken(id)) continue;
    cycles[i].bottom = id;
    names.reserve(id);
    named[i] = true;
  }
  for (std::size_t i = 0; i < holes.size(); ++i) {
    if (!named[i])
      cycles[i].bottom = names.take(idents ? "H" + std::to_string(i + 1) : holes[i].id, id_len);
  }
  for (Cycle& c : cycles) {
    c.approach = names.take(c.bottom + "_APP", id_len + 4);
    c.clear = names.take(c.bottom + "_CLR", id_len + 4);
    if (!idents) c.retract = names.take(c.bottom + "_RET", id_len + 4);
  }
  return cycles;
}

struct Point {
  const std::string* name;
  const Pose* T;
};

/// approach, clearance, bottom
std::array<Point, 3> points(const Cycle& c) {
  return {Point{&c.approach, &c.T_app}, Point{&c.clear, &c.T_clr}, Point{&c.bottom, &c.T_bot}};
}

std::string cycleComment(const Cycle& c) {
  std::string s = commentText(c.hole->id) + " drill";
  if (c.hole->diameter > 0) s += " D" + mm3(c.hole->diameter);
  return s + " depth " + mm3(c.hole->depth);
}

std::string summary(const DrillProgramOptions& o, std::size_t n) {
  return std::to_string(n) + " holes; cycle: approach " + mm3(o.approach) +
         " mm above the entry, rapid to " + mm3(o.clearance) + " mm, feed " +
         fixed(o.feed * 1e3, 3) + " mm/s to the bottom, dwell " + fixed(o.dwell, 3) +
         " s, retract at " + fixed(o.rapid * 1e3, 3) + " mm/s; TCP +Z = drilling direction";
}

// ---------------------------------------------------------------- KRL

DrillProgramText krl(const std::vector<DrillHole>& holes, const DrillProgramOptions& o) {
  DrillProgramText t;
  t.name = programIdent(o.name, 24, "P");
  Names names(true, 24);
  names.reserve(t.name);
  const std::vector<Cycle> cycles = buildCycles(holes, o, names, 20);
  std::string src = "&ACCESS RVP\n&REL 1\n";
  if (!o.comment.empty()) src += "&COMMENT " + commentText(o.comment) + "\n";
  src += "DEF " + t.name + "( )\n;FOLD INI\nBAS(#INITMOV,0)\n;ENDFOLD (INI)\n";
  src += "; written by roprec: " + summary(o, holes.size()) + "\n";
  src += "; frame " + commentText(o.frame_name) + " (program frame in the robot base), tool " +
         commentText(o.tool_name) + "\n";
  src += "$BASE={FRAME: " + krlFrame(o.T_base_frame) + "}\n";
  src += "$TOOL={FRAME: " + krlFrame(o.T_flange_tcp) + "}\n";
  std::string dat = "&ACCESS RVP\n&REL 1\nDEFDAT " + t.name + "\n";
  const std::string vrapid = "$VEL.CP=" + fixed(o.rapid, 6) + "\n";
  const std::string vfeed = "$VEL.CP=" + fixed(o.feed, 6) + "\n";
  bool any_config = false;
  for (const Cycle& c : cycles) {
    const std::string cm = cycleComment(c);
    src += "; " + cm + "\n";
    src += vrapid + "PTP " + c.approach + " C_PTP\n";
    src += "LIN " + c.clear + " C_DIS\n";
    src += vfeed + "LIN " + c.bottom + "\n";
    if (o.dwell > 0) src += "WAIT SEC " + fixed(o.dwell, 3) + "\n";
    src += vrapid + "LIN " + c.approach + " C_DIS\n";
    dat += "; " + cm + "\n";
    for (const Point& q : points(c))
      dat += "DECL E6POS " + *q.name + "={" + krlFrame(*q.T) + c.config_text + "}\n";
    any_config = any_config || c.config_given;
  }
  src += "END\n";
  dat += "ENDDAT\n";
  if (!cycles.empty() && !any_config)
    t.notes.push_back("no configuration given: S and T omitted (the PTP keeps the current one)");
  t.files = {{".src", src}, {".dat", dat}};
  return t;
}

// ---------------------------------------------------------------- RAPID

DrillProgramText rapid(const std::vector<DrillHole>& holes, const DrillProgramOptions& o) {
  DrillProgramText t;
  t.name = programIdent(o.name, 32, "M");
  const std::string tool = o.tool_name;
  const std::string wobj = o.frame_name;
  Names names(true, 32);
  for (const std::string& n :
       {t.name, tool, wobj, std::string("vDrillRapid"), std::string("vDrillFeed")})
    names.reserve(n);
  const std::vector<Cycle> cycles = buildCycles(holes, o, names, 28);
  std::string s = "MODULE " + t.name + "\n";
  if (!o.comment.empty()) s += "  ! " + commentText(o.comment) + "\n";
  s += "  ! written by roprec: " + summary(o, holes.size()) + "\n";
  std::string load;
  if (o.tool_mass > 0) {
    load = "[" + fixed(o.tool_mass, 3) + ",[" + fixed(o.tool_cog.x() * 1e3, 3) + "," +
           fixed(o.tool_cog.y() * 1e3, 3) + "," + fixed(o.tool_cog.z() * 1e3, 3) +
           "],[1,0,0,0],0,0,0]";
  } else {
    load = "[1,[0,0,0.001],[1,0,0,0],0,0,0]";
    t.notes.push_back(tool + ": tool load not given (placeholder mass 1 kg); set " + tool +
                      ".tload before running");
  }
  s += "  PERS tooldata " + tool + ":=[TRUE," + rapidPose(o.T_flange_tcp) + "," + load + "];\n";
  s += "  PERS wobjdata " + wobj + ":=[FALSE,TRUE,\"\"," + rapidPose(o.T_base_frame) +
       ",[[0,0,0],[1,0,0,0]]];\n";
  s += "  CONST speeddata vDrillRapid:=[" + fixed(o.rapid * 1e3, 3) + ",500,5000,1000];\n";
  s += "  CONST speeddata vDrillFeed:=[" + fixed(o.feed * 1e3, 3) + ",500,5000,1000];\n";
  const std::string ext = ",[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];\n";
  std::string body = "  PROC " + t.name + "()\n    ConfL \\Off;\n";
  const std::string args = "," + tool + "\\WObj:=" + wobj + ";\n";
  int conf_j = -1;
  bool missing = false;
  for (const Cycle& c : cycles) {
    const std::string cm = cycleComment(c);
    s += "  ! " + cm + "\n";
    const std::string cf = c.config_given ? c.config_text : "[0,0,0,0]";
    for (const Point& q : points(c)) {
      const std::string pr = rapidPose(*q.T);
      strAppend(s, "  CONST robtarget ", *q.name, ":=[",
                std::string_view(pr).substr(1, pr.size() - 2), ",", cf, ext);
    }
    const int want = c.config_given ? 1 : 0;
    if (want != conf_j) body += want ? "    ConfJ \\On;\n" : "    ConfJ \\Off;\n";
    conf_j = want;
    missing = missing || !c.config_given;
    body += "    ! " + cm + "\n";
    body += "    MoveJ " + c.approach + ",vDrillRapid,z10" + args;
    body += "    MoveL " + c.clear + ",vDrillRapid,z1" + args;
    body += "    MoveL " + c.bottom + ",vDrillFeed,fine" + args;
    if (o.dwell > 0) body += "    WaitTime " + fixed(o.dwell, 3) + ";\n";
    body += "    MoveL " + c.approach + ",vDrillRapid,z10" + args;
  }
  if (missing)
    t.notes.push_back(
        "holes without configuration: robconf [0,0,0,0] under ConfJ \\Off (nearest configuration)");
  body += "  ENDPROC\nENDMODULE\n";
  t.files = {{".mod", s + body}};
  return t;
}

// ---------------------------------------------------------------- FANUC TP

DrillProgramText tp(const std::vector<DrillHole>& holes, const DrillProgramOptions& o) {
  DrillProgramText t;
  t.name = upper(programIdent(o.name, 36, "P"));
  if (o.uframe < 0 || o.uframe > 9) invalid("FANUC uframe must be 0..9");
  if (o.utool < 0 || o.utool > 10) invalid("FANUC utool must be 0..10");
  Names names(true, 36);
  const std::vector<Cycle> cycles = buildCycles(holes, o, names, 32);
  const long rapid_mm = std::max(1L, std::lround(o.rapid * 1e3));
  const long feed_mm = std::max(1L, std::lround(o.feed * 1e3));
  if (feed_mm >= rapid_mm)
    invalid("FANUC speeds are whole mm/sec: the feed rounds to " + std::to_string(feed_mm) +
            ", not below the rapid speed " + std::to_string(rapid_mm));
  if (std::fabs(rapid_mm - o.rapid * 1e3) > 1e-9 || std::fabs(feed_mm - o.feed * 1e3) > 1e-9) {
    t.notes.push_back("FANUC speeds rounded to whole mm/sec: rapid " + std::to_string(rapid_mm) +
                      ", feed " + std::to_string(feed_mm));
  }
  std::vector<std::string> mn;
  auto remark = [&](const std::string& r) { mn.push_back("! " + commentText(r, true) + " ;"); };
  auto frameRemark = [&](const char* kind, int n, const std::string& name, const Pose& T) {
    const Vec3 abc = abcDeg(T.linear());
    const Vec3 x = T.translation() * 1e3;
    remark(std::string(kind) + std::to_string(n) + " " + name);
    remark("= " + fixed(x.x(), 3) + "," + fixed(x.y(), 3) + "," + fixed(x.z(), 3) + "," +
           fixed(abc[2], 6) + "," + fixed(abc[1], 6) + "," + fixed(abc[0], 6));
  };
  if (!o.comment.empty()) remark(o.comment);
  frameRemark("UF", o.uframe, o.frame_name, o.T_base_frame);
  frameRemark("UT", o.utool, o.tool_name, o.T_flange_tcp);
  mn.push_back("UFRAME_NUM=" + std::to_string(o.uframe) + " ;");
  mn.push_back("UTOOL_NUM=" + std::to_string(o.utool) + " ;");
  t.notes.push_back("set UFRAME[" + std::to_string(o.uframe) + "] and UTOOL[" +
                    std::to_string(o.utool) +
                    "] on the controller (values in the program's remarks)");
  std::string pos;
  int n = 0;
  bool missing = false;
  auto field = [](double v) {
    std::string s = fixed(v, 6);
    return s.size() < 12 ? std::string(12 - s.size(), ' ') + s : s;
  };
  const std::string fallback = configurationFromBranch(Vendor::kFanuc, 0).text();
  NumberHints bare;
  bare.min_decimals = 2;
  for (const Cycle& c : cycles) {
    const std::string cf = c.config_given ? c.config_text : fallback;
    missing = missing || !c.config_given;
    std::array<int, 3> idx{};
    const std::array<Point, 3> pts = points(c);
    for (std::size_t k = 0; k < 3; ++k) {
      const Pose* T = pts[k].T;
      idx[k] = ++n;
      const Vec3 abc = abcDeg(T->linear());
      const Vec3 x = T->translation() * 1e3;
      pos += "P[" + std::to_string(n) + "]{\n   GP1:\n\tUF : " + std::to_string(o.uframe) +
             ", UT : " + std::to_string(o.utool) + ",\t\tCONFIG : '" + cf + "',\n";
      pos += "\tX = " + field(x.x()) + "  mm,\tY = " + field(x.y()) + "  mm,\tZ = " + field(x.z()) +
             "  mm,\n";
      pos += "\tW = " + field(abc[2]) + " deg,\tP = " + field(abc[1]) +
             " deg,\tR = " + field(abc[0]) + " deg\n};\n";
    }
    remark(cycleComment(c));
    mn.push_back("J P[" + std::to_string(idx[0]) + "] 50% CNT50 ;");
    mn.push_back("L P[" + std::to_string(idx[1]) + "] " + std::to_string(rapid_mm) +
                 "mm/sec CNT10 ;");
    mn.push_back("L P[" + std::to_string(idx[2]) + "] " + std::to_string(feed_mm) +
                 "mm/sec FINE ;");
    if (o.dwell > 0) mn.push_back("WAIT " + formatLike(".00", o.dwell, bare) + "(sec) ;");
    mn.push_back("L P[" + std::to_string(idx[0]) + "] " + std::to_string(rapid_mm) +
                 "mm/sec CNT50 ;");
  }
  if (missing)
    t.notes.push_back("holes without configuration: CONFIG '" + fallback + "' written; check it");
  const std::string title =
      commentText(o.comment.empty() ? std::string("roprec drill") : o.comment, true);
  std::string s = "/PROG  " + t.name + "\n/ATTR\nOWNER\t\t= MNEDITOR;\nCOMMENT\t\t= \"";
  for (const char ch : title.substr(0, 16)) s += ch == '"' ? '\'' : ch;
  s += "\";\nPROG_SIZE\t= 0;\nCREATE\t\t= DATE 00-01-01  TIME 00:00:00;\nMODIFIED\t= DATE 00-01-01 "
       " TIME 00:00:00;\n";
  s += "FILE_NAME\t= ;\nVERSION\t\t= 0;\nLINE_COUNT\t= " + std::to_string(mn.size()) +
       ";\nMEMORY_SIZE\t= 0;\n";
  s += "PROTECT\t\t= READ_WRITE;\nTCD:  STACK_SIZE\t= 0,\n      TASK_PRIORITY\t= 50,\n      "
       "TIME_SLICE\t= 0,\n";
  s += "      BUSY_LAMP_OFF\t= 0,\n      ABORT_REQUEST\t= 0,\n      PAUSE_REQUEST\t= 0;\n";
  s += "DEFAULT_GROUP\t= 1,*,*,*,*;\nCONTROL_CODE\t= 00000000 00000000;\n/MN\n";
  for (std::size_t i = 0; i < mn.size(); ++i) {
    char num[16];
    std::snprintf(num, sizeof num, "%4d:", static_cast<int>(i + 1));
    const bool motion = mn[i].size() > 1 && (mn[i][0] == 'J' || mn[i][0] == 'L') && mn[i][1] == ' ';
    s += num + std::string(motion ? "" : "  ") + mn[i] + "\n";
  }
  s += "/POS\n" + pos + "/END\n";
  t.files = {{".ls", s}};
  return t;
}

// ---------------------------------------------------------------- CSV / JSON target lists, hole
// list

std::string csvCell(const std::string& s) {
  return (s.find(',') != std::string::npos || (!s.empty() && s[0] == '#')) ? "\"" + s + "\"" : s;
}

struct Row {
  const std::string* id;
  const char* motion;
  const Pose* T;
  double speed;  // m/s
  bool fine;
  double dwell;
};

std::vector<Row> rows(const Cycle& c, const DrillProgramOptions& o) {
  return {{&c.approach, "J", &c.T_app, o.rapid, false, 0.0},
          {&c.clear, "L", &c.T_clr, o.rapid, false, 0.0},
          {&c.bottom, "L", &c.T_bot, o.feed, true, o.dwell},
          {&c.retract, "L", &c.T_app, o.rapid, false, 0.0}};
}

void checkTableNames(const DrillProgramOptions& o) {
  for (const std::string* n : {&o.frame_name, &o.tool_name}) {
    if (!identifier(*n, 64))
      invalid("frame/tool name '" + commentText(*n) + "' must be an identifier");
  }
}

DrillProgramText csv(const std::vector<DrillHole>& holes, const DrillProgramOptions& o) {
  DrillProgramText t;
  t.name = o.name;
  Names names(false, 1024);
  const std::vector<Cycle> cycles = buildCycles(holes, o, names, 1000);
  std::string s;
  if (!o.comment.empty()) s += "# " + commentText(o.comment) + "\n";
  s += "# roprec drilling program " + commentText(o.name) + ": " + summary(o, holes.size()) + "\n";
  s += "# units: mm, mm/s, s; orientation: quaternion qw,qx,qy,qz; poses are TCP poses in the "
       "named frame\n";
  s += "# frame " + o.frame_name + ": " + xyzText(o.T_base_frame.translation(), " ") + " " +
       quatText(o.T_base_frame.linear(), " ") + "\n";
  s += "# tool " + o.tool_name + ": " + xyzText(o.T_flange_tcp.translation(), " ") + " " +
       quatText(o.T_flange_tcp.linear(), " ") + "\n";
  s += "id,motion,x,y,z,qw,qx,qy,qz,frame,tool,conf,speed,dwell\n";
  for (const Cycle& c : cycles) {
    for (const Row& r : rows(c, o)) {
      s += csvCell(*r.id) + "," + r.motion + "," + xyzText(r.T->translation(), ",") + "," +
           quatText(r.T->linear(), ",") + "," + o.frame_name + "," + o.tool_name + "," +
           csvCell(c.config_text) + "," + fixed(r.speed * 1e3, 3) + "," +
           (r.dwell > 0 ? fixed(r.dwell, 3) : "") + "\n";
    }
  }
  t.files = {{".csv", s}};
  return t;
}

DrillProgramText json(const std::vector<DrillHole>& holes, const DrillProgramOptions& o) {
  DrillProgramText t;
  t.name = o.name;
  Names names(false, 1024);
  const std::vector<Cycle> cycles = buildCycles(holes, o, names, 1000);
  auto frame = [](const std::string& n, const Pose& T) {
    return "    {\"name\": " + jsonStr(n) + ", \"position_mm\": [" +
           xyzText(T.translation(), ", ") + "], \"quaternion_wxyz\": [" +
           quatText(T.linear(), ", ") + "]}";
  };
  std::string s = "{\n  \"format\": \"roprec-targets\",\n  \"source\": " +
                  jsonStr("roprec drilling program " + o.name) + ",\n";
  if (!o.comment.empty()) s += "  \"comment\": " + jsonStr(commentText(o.comment)) + ",\n";
  s += "  \"cycle\": " + jsonStr(summary(o, holes.size())) + ",\n";
  s += "  \"units\": {\"length\": \"mm\", \"angle\": \"deg\"},\n  \"frames\": [\n" +
       frame(o.frame_name, o.T_base_frame) + ",\n" + frame(o.tool_name, o.T_flange_tcp) +
       "\n  ],\n  \"targets\": [";
  bool first = true;
  for (const Cycle& c : cycles) {
    for (const Row& r : rows(c, o)) {
      s += std::string(first ? "\n" : ",\n") + "    {\"id\": " + jsonStr(*r.id) +
           ", \"motion\": \"" + r.motion + "\", \"position_mm\": [" +
           xyzText(r.T->translation(), ", ") + "], \"quaternion_wxyz\": [" +
           quatText(r.T->linear(), ", ") + "], \"frame\": " + jsonStr(o.frame_name) +
           ", \"tool\": " + jsonStr(o.tool_name);
      if (c.config_given) s += ", \"config\": " + jsonStr(c.config_text);
      s += ", \"speed_mm_s\": " + fixed(r.speed * 1e3, 3) +
           ", \"fine\": " + (r.fine ? "true" : "false");
      if (r.dwell > 0) s += ", \"dwell_s\": " + fixed(r.dwell, 3);
      s += ", \"hole\": " + jsonStr(c.hole->id) + "}";
      first = false;
    }
  }
  s += std::string(first ? "" : "\n  ") + "]\n}\n";
  t.files = {{".json", s}};
  return t;
}

DrillProgramText holeList(const std::vector<DrillHole>& holes, const DrillProgramOptions& o) {
  DrillProgramText t;
  t.name = o.name;
  Names names(false, 1024);
  const std::vector<Cycle> cycles = buildCycles(holes, o, names, 1000);  // validation
  std::string s;
  if (!o.comment.empty()) s += "# " + commentText(o.comment) + "\n";
  s += "# roprec hole list " + commentText(o.name) +
       ": entry points (surface) in the program frame, mm; i,j,k = drilling "
       "direction into the material\n";
  s += "id,x,y,z,i,j,k,diameter,depth\n";
  for (const Cycle& c : cycles) {
    const DrillHole& h = *c.hole;
    const Vec3 d = h.T_frame_tcp.linear().col(2);
    s += csvCell(h.id) + "," + xyzText(h.T_frame_tcp.translation(), ",") + "," + fixed(d.x(), 9) +
         "," + fixed(d.y(), 9) + "," + fixed(d.z(), 9) + "," +
         (h.diameter > 0 ? mm(h.diameter) : "") + "," + mm(h.depth) + "\n";
  }
  t.notes.push_back(
      "a hole list carries neither the frame, the tool, the configuration nor the rotation about "
      "the drilling axis");
  t.files = {{".csv", s}};
  return t;
}

std::string withCrLf(const std::string& s) {
  std::string r;
  r.reserve(s.size() + s.size() / 32);
  for (const char c : s) {
    if (c == '\n') r += '\r';
    r += c;
  }
  return r;
}

}  // namespace

DrillProgramText writeDrillProgram(const std::vector<DrillHole>& holes,
                                   const DrillProgramOptions& o) {
  const auto finite = [](double v) { return std::isfinite(v); };
  if (!finite(o.approach) || !finite(o.clearance) || o.clearance < 0 || o.approach <= o.clearance) {
    invalid("approach must exceed clearance, and clearance must be >= 0");
  }
  if (!finite(o.feed) || !finite(o.rapid) || o.feed <= 0 || o.rapid <= o.feed)
    invalid("need 0 < feed < rapid");
  if (!finite(o.dwell) || o.dwell < 0) invalid("dwell must be >= 0");
  if (!finitePose(o.T_base_frame) || !rotationOk(o.T_base_frame.linear()))
    invalid("T_base_frame is not a finite rigid transform");
  if (!finitePose(o.T_flange_tcp) || !rotationOk(o.T_flange_tcp.linear()))
    invalid("T_flange_tcp is not a finite rigid transform");
  if (!finite(o.tool_mass) || !o.tool_cog.allFinite()) invalid("tool load must be finite");
  if (o.dialect == Dialect::kRapid || o.dialect == Dialect::kCsv || o.dialect == Dialect::kJson)
    checkTableNames(o);
  if (iequals(o.frame_name, o.tool_name)) invalid("frame and tool names must differ");
  DrillProgramText t;
  switch (o.dialect) {
    case Dialect::kKrl:
      t = krl(holes, o);
      break;
    case Dialect::kRapid:
      t = rapid(holes, o);
      break;
    case Dialect::kTp:
      t = tp(holes, o);
      break;
    case Dialect::kCsv:
      t = csv(holes, o);
      break;
    case Dialect::kJson:
      t = json(holes, o);
      break;
    case Dialect::kHoleCsv:
      t = holeList(holes, o);
      break;
  }
  t.dialect = o.dialect;
  if (o.crlf) {
    for (DrillProgramFile& f : t.files) f.text = withCrLf(f.text);
  }
  return t;
}

std::vector<std::string> drillProgramPaths(const DrillProgramText& t, const std::string& out_path) {
  std::vector<std::string> paths;
  if (t.files.empty()) return paths;
  const fs::path o(out_path);
  const std::string main = o.extension().empty() ? out_path + t.files[0].suffix : out_path;
  paths.push_back(main);
  const fs::path m(main);
  for (std::size_t i = 1; i < t.files.size(); ++i) {
    paths.push_back((m.parent_path() / (m.stem().string() + t.files[i].suffix)).string());
  }
  return paths;
}

std::vector<std::string> saveDrillProgram(const DrillProgramText& t, const std::string& out_path) {
  std::vector<std::string> paths = drillProgramPaths(t, out_path);
  if (t.dialect == Dialect::kKrl && !paths.empty() &&
      !iequals(fs::path(paths[0]).stem().string(), t.name)) {
    invalid("a KRL program must be saved as " + t.name + ".src (the DEF name), not " +
            fs::path(paths[0]).filename().string());
  }
  for (std::size_t i = 0; i < paths.size(); ++i) writeFileAtomic(paths[i], t.files[i].text);
  return paths;
}

Program parseDrillProgram(const DrillProgramText& t, const std::string& dir) {
  if (t.files.empty()) invalid("no files to read");
  const fs::path d(dir);
  const std::string main = (d / (t.name + t.files[0].suffix)).string();
  if (t.dialect == Dialect::kKrl && t.files.size() > 1) {
    return parseProgram(t.dialect, main, t.files[0].text, t.files[1].text,
                        (d / (t.name + t.files[1].suffix)).string());
  }
  return parseProgram(t.dialect, main, t.files[0].text);
}

}  // namespace roprec::postproc
