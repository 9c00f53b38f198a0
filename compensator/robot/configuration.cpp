#include "compensator/robot/configuration.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "compensator/support/error.hpp"
#include "compensator/support/fixed_chars.hpp"

namespace roprec {

namespace {

constexpr double kQuadrantSnap = 1e-9;  // in quadrant units (90°): boundary rule, see header

std::string trim(const std::string& s) {
  size_t a = 0;
  size_t b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

bool parseInt(const std::string& s, int& out) {
  const std::string t = trim(s);
  if (t.empty()) return false;
  size_t i = (t[0] == '-' || t[0] == '+') ? 1 : 0;
  if (i >= t.size()) return false;
  for (size_t k = i; k < t.size(); ++k) {
    if (!std::isdigit(static_cast<unsigned char>(t[k]))) return false;
  }
  if (t.size() > 9) return false;
  out = std::atoi(t.c_str());
  return true;
}

/// KRL integer: decimal or a binary literal 'B0101'.
bool parseKrlInt(const std::string& s, int& out) {
  const std::string t = trim(s);
  if (t.size() >= 4 && t.front() == '\'' && t.back() == '\'' && (t[1] == 'B' || t[1] == 'b')) {
    int v = 0;
    if (t.size() - 3 > 30) return false;
    for (size_t k = 2; k + 1 < t.size(); ++k) {
      if (t[k] != '0' && t[k] != '1') return false;
      v = 2 * v + (t[k] - '0');
    }
    out = v;
    return true;
  }
  return parseInt(t, out);
}

}  // namespace

int fanucTurn(double theta) {
  const double deg = theta / kDeg;
  if (deg >= 0.0) return static_cast<int>(std::floor((deg + 180.0) / 360.0));
  return -static_cast<int>(std::floor((-deg + 180.0) / 360.0));
}

int abbQuadrant(double theta) {
  const double q = theta / (0.5 * kPi);
  return static_cast<int>(std::floor(q + kQuadrantSnap));
}

KukaConfig kukaConfig(const IkModel& model, const RobotCard& card, const Vec6& q_urdf,
                      const ConfigurationOptions& options) {
  const IkBranch b = ikBranch(model, q_urdf);
  const Vec6 c = toControllerJoints(card, q_urdf);
  KukaConfig k;
  k.status = (options.kuka_status_high_bits & ~7) | b.shoulder | ((b.elbow == 0 ? 1 : 0) << 1) |
             (b.wrist << 2);
  int t = 0;
  for (int n = 0; n < 6; ++n) t |= (c[n] < 0.0 ? 1 : 0) << n;
  k.turn = t;
  return k;
}

AbbConfig abbConfig(const IkModel& model, const RobotCard& card, const Vec6& q_urdf) {
  const Vec6 c = toControllerJoints(card, q_urdf);
  AbbConfig a;
  a.cf1 = abbQuadrant(c[0]);
  a.cf4 = abbQuadrant(c[3]);
  a.cf6 = abbQuadrant(c[5]);
  a.cfx = ikBranch(model, q_urdf).index();
  return a;
}

FanucConfig fanucConfig(const IkModel& model, const RobotCard& card, const Vec6& q_urdf,
                        const ConfigurationOptions& options) {
  const IkBranch b = ikBranch(model, q_urdf);
  const Vec6 c = toControllerJoints(card, q_urdf);
  FanucConfig f;
  f.flip = b.wrist == 0;
  f.up = b.elbow == 0;
  f.top = b.shoulder == 0;
  for (size_t i = 0; i < 3; ++i) f.turns[i] = fanucTurn(c[options.fanuc_turn_axes[i] - 1]);
  return f;
}

VendorConfig configurationOf(const IkModel& model, const RobotCard& card, const Vec6& q_urdf,
                             const ConfigurationOptions& options) {
  VendorConfig v;
  v.vendor = card.vendor;
  v.branch = ikBranch(model, q_urdf).index();
  switch (card.vendor) {
    case Vendor::kKuka:
      v.kuka = kukaConfig(model, card, q_urdf, options);
      break;
    case Vendor::kAbb:
      v.abb = abbConfig(model, card, q_urdf);
      break;
    case Vendor::kFanuc:
      v.fanuc = fanucConfig(model, card, q_urdf, options);
      break;
    case Vendor::kGeneric:
      break;
  }
  return v;
}

std::optional<int> branchOfConfig(const VendorConfig& c) {
  switch (c.vendor) {
    case Vendor::kKuka: {
      if (!c.kuka.status) return std::nullopt;
      const int s = *c.kuka.status;
      const int shoulder = s & 1;
      const int elbow = ((s >> 1) & 1) ? 0 : 1;
      const int wrist = (s >> 2) & 1;
      return 4 * shoulder + 2 * elbow + wrist;
    }
    case Vendor::kAbb:
      return c.abb.cfx;
    case Vendor::kFanuc:
      return 4 * (c.fanuc.top ? 0 : 1) + 2 * (c.fanuc.up ? 0 : 1) + (c.fanuc.flip ? 0 : 1);
    case Vendor::kGeneric:
      return c.branch;
  }
  return std::nullopt;
}

std::string formatKuka(const KukaConfig& c) {
  std::string s;
  if (c.status) s += "S " + std::to_string(*c.status);
  if (c.turn) s += (s.empty() ? "" : " ") + std::string("T ") + std::to_string(*c.turn);
  return s;
}

std::string formatAbb(const AbbConfig& c) {
  return "[" + std::to_string(c.cf1) + "," + std::to_string(c.cf4) + "," + std::to_string(c.cf6) +
         "," + std::to_string(c.cfx) + "]";
}

std::string formatFanuc(const FanucConfig& c) {
  std::string s;
  s += c.flip ? 'F' : 'N';
  s += ' ';
  s += c.up ? 'U' : 'D';
  s += ' ';
  s += c.top ? 'T' : 'B';
  for (int t : c.turns) s += ", " + std::to_string(t);
  return s;
}

std::string formatConfig(const VendorConfig& c) {
  switch (c.vendor) {
    case Vendor::kKuka:
      return formatKuka(c.kuka);
    case Vendor::kAbb:
      return formatAbb(c.abb);
    case Vendor::kFanuc:
      return formatFanuc(c.fanuc);
    case Vendor::kGeneric:
      break;
  }
  return "branch " + std::to_string(c.branch);
}

KukaConfig parseKuka(const std::string& text, const std::string& file, int line) {
  std::string t = text;
  for (char& ch : t) {
    if (ch == '{' || ch == '}' || ch == ',') ch = ' ';
  }
  std::istringstream in(t);
  std::vector<std::string> tok;
  for (std::string w; in >> w;) tok.push_back(w);
  KukaConfig k;
  auto bad = [&](const std::string& why) {
    throw InputError(file, line,
                     "KUKA configuration '" + text + "': " + why +
                         " (expected e.g. \"S 2 T 34\" or \"S 'B010' T 'B100010'\")");
  };
  if (tok.empty()) bad("empty");
  for (size_t i = 0; i < tok.size(); i += 2) {
    const std::string key = tok[i];
    if (i + 1 >= tok.size()) bad("'" + key + "' has no value");
    int v = 0;
    if (!parseKrlInt(tok[i + 1], v) || v < 0)
      bad("'" + tok[i + 1] + "' is not a non-negative integer");
    if (key == "S" || key == "s") {
      if (k.status) bad("S given twice");
      k.status = v;
    } else if (key == "T" || key == "t") {
      if (k.turn) bad("T given twice");
      if (v > 63) bad("T " + std::to_string(v) + " has bits beyond axis 6");
      k.turn = v;
    } else {
      bad("unknown field '" + key + "'");
    }
  }
  return k;
}

AbbConfig parseAbb(const std::string& text, const std::string& file, int line) {
  std::string t = trim(text);
  if (!t.empty() && t.front() == '[') {
    if (t.back() != ']') {
      throw InputError(file, line,
                       "ABB confdata '" + text + "': missing ']' (expected e.g. \"[0,-1,2,1]\")");
    }
    t = t.substr(1, t.size() - 2);
  }
  for (char& ch : t) {
    if (ch == ',') ch = ' ';
  }
  std::istringstream in(t);
  std::vector<std::string> tok;
  for (std::string w; in >> w;) tok.push_back(w);
  std::array<int, 4> v{};
  if (tok.size() != 4) {
    throw InputError(file, line,
                     "ABB confdata '" + text + "': needs 4 integers [cf1,cf4,cf6,cfx], got " +
                         std::to_string(tok.size()));
  }
  for (size_t i = 0; i < 4; ++i) {
    if (!parseInt(tok[i], v[i])) {
      throw InputError(file, line,
                       "ABB confdata '" + text + "': '" + tok[i] + "' is not an integer");
    }
  }
  if (v[3] < 0 || v[3] > 7) {
    throw InputError(file, line,
                     "ABB confdata '" + text + "': cfx must be 0..7, got " + std::to_string(v[3]));
  }
  return {v[0], v[1], v[2], v[3]};
}

FanucConfig parseFanuc(const std::string& text, const std::string& file, int line) {
  std::string t = trim(text);
  if (t.size() >= 2 && t.front() == '\'' && t.back() == '\'') t = t.substr(1, t.size() - 2);
  auto bad = [&](const std::string& why) {
    throw InputError(file, line,
                     "FANUC CONFIG '" + text + "': " + why + " (expected e.g. \"N U T, 0, 0, 0\")");
  };
  std::vector<std::string> parts;
  {
    std::string cur;
    for (char ch : t) {
      if (ch == ',') {
        parts.push_back(cur);
        cur.clear();
      } else {
        cur += ch;
      }
    }
    parts.push_back(cur);
  }
  if (parts.size() != 4) bad("needs the letters and three turn numbers separated by commas");
  std::string letters;
  for (char ch : parts[0]) {
    if (!std::isspace(static_cast<unsigned char>(ch)))
      letters += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  }
  if (letters.size() != 3) bad("needs three letters F|N U|D T|B");
  FanucConfig f;
  if (letters[0] == 'F')
    f.flip = true;
  else if (letters[0] == 'N')
    f.flip = false;
  else
    bad(std::string("first letter must be F or N, got '") + letters[0] + "'");
  if (letters[1] == 'U')
    f.up = true;
  else if (letters[1] == 'D')
    f.up = false;
  else
    bad(std::string("second letter must be U or D, got '") + letters[1] + "'");
  if (letters[2] == 'T')
    f.top = true;
  else if (letters[2] == 'B')
    f.top = false;
  else
    bad(std::string("third letter must be T or B, got '") + letters[2] + "'");
  for (size_t i = 0; i < 3; ++i) {
    if (!parseInt(parts[i + 1], f.turns[i]))
      bad("'" + trim(parts[i + 1]) + "' is not an integer turn number");
  }
  return f;
}

VendorConfig parseConfig(Vendor vendor, const std::string& text, const std::string& file,
                         int line) {
  VendorConfig v;
  v.vendor = vendor;
  switch (vendor) {
    case Vendor::kKuka:
      v.kuka = parseKuka(text, file, line);
      break;
    case Vendor::kAbb:
      v.abb = parseAbb(text, file, line);
      break;
    case Vendor::kFanuc:
      v.fanuc = parseFanuc(text, file, line);
      break;
    case Vendor::kGeneric: {
      std::string t = trim(text);
      if (t.rfind("branch", 0) == 0) t = t.substr(6);
      if (!parseInt(t, v.branch) || v.branch < 0 || v.branch > 7) {
        throw InputError(file, line,
                         "configuration '" + text + "': expected \"branch N\" with N = 0..7");
      }
      break;
    }
  }
  if (auto b = branchOfConfig(v)) v.branch = *b;
  return v;
}

namespace {

std::string degText(double rad) {
  std::string s;
  appendFixed(s, rad / kDeg, 1);  // "C" format, "-0.0" written "0.0"
  return s;
}

/// ABB: does quadrant `have` of angle θ meet `want` (equal, or adjacent with θ within tol of the
/// shared boundary)?
bool quadrantMeets(double theta, int want, int have, double tol) {
  if (want == have) return true;
  if (std::abs(want - have) != 1) return false;
  const double boundary = 0.5 * kPi * std::max(want, have);
  return std::abs(theta - boundary) <= tol;
}

/// FANUC: turn `have` of θ meets `want` (equal, or adjacent with θ within tol of ±180° + k·360°).
bool turnMeets(double theta, int want, int have, double tol) {
  if (want == have) return true;
  if (std::abs(want - have) != 1) return false;
  const double boundary = want + have > 0 ? kPi + 2.0 * kPi * std::min(want, have)
                                          : -kPi + 2.0 * kPi * std::max(want, have);
  return std::abs(theta - boundary) <= tol;
}

/// Mismatch count (KUKA: T bits; ABB: Σ|Δcf|; FANUC: Σ|Δturn|) of q against the turn flags of
/// `config`, flags met within `tol` of their boundary counting as matched; `why` lists them.
int turnMismatch(const IkModel& model, const RobotCard& card, const Vec6& q,
                 const VendorConfig& config, const ConfigurationOptions& options, double tol,
                 std::string* why) {
  const Vec6 c = toControllerJoints(card, q);
  int d = 0;
  // the text is made only when asked for (the IK choice calls this per candidate, why = nullptr)
  auto note = [&](const auto& text) {
    if (why) *why += (why->empty() ? "" : ", ") + text();
  };
  switch (config.vendor) {
    case Vendor::kKuka: {
      if (!config.kuka.turn) return 0;
      for (int n = 0; n < 6; ++n) {
        const bool want_neg = ((*config.kuka.turn >> n) & 1) != 0;
        if (want_neg == (c[n] < 0.0) || std::abs(c[n]) <= tol) continue;
        ++d;
        note([&] {
          return "T bit " + std::to_string(n) + " (A" + std::to_string(n + 1) + " at " +
                 degText(c[n]) + " deg, the flag says " + (want_neg ? "< 0" : ">= 0") + ")";
        });
      }
      return d;
    }
    case Vendor::kAbb: {
      const AbbConfig a = abbConfig(model, card, q);
      const std::array<int, 3> want{config.abb.cf1, config.abb.cf4, config.abb.cf6};
      const std::array<int, 3> have{a.cf1, a.cf4, a.cf6};
      const std::array<int, 3> axis{1, 4, 6};
      for (size_t k = 0; k < 3; ++k) {
        const double th = c[axis[k] - 1];
        if (quadrantMeets(th, want[k], have[k], tol)) continue;
        d += std::abs(want[k] - have[k]);
        note([&] {
          return "cf" + std::to_string(axis[k]) + " " + std::to_string(want[k]) + " -> " +
                 std::to_string(have[k]) + " (axis " + std::to_string(axis[k]) + " at " +
                 degText(th) + " deg)";
        });
      }
      return d;
    }
    case Vendor::kFanuc: {
      const FanucConfig f = fanucConfig(model, card, q, options);
      for (size_t k = 0; k < 3; ++k) {
        const int ax = options.fanuc_turn_axes[k];
        const double th = c[ax - 1];
        if (turnMeets(th, config.fanuc.turns[k], f.turns[k], tol)) continue;
        d += std::abs(f.turns[k] - config.fanuc.turns[k]);
        note([&] {
          return "turn " + std::to_string(k + 1) + " " + std::to_string(config.fanuc.turns[k]) +
                 " -> " + std::to_string(f.turns[k]) + " (J" + std::to_string(ax) + " at " +
                 degText(th) + " deg)";
        });
      }
      return d;
    }
    case Vendor::kGeneric:
      break;
  }
  return 0;
}

}  // namespace

std::string turnFlagMismatch(const IkModel& model, const RobotCard& card, const Vec6& q,
                             const VendorConfig& config, const ConfigurationOptions& options,
                             double tolerance) {
  std::string why;
  turnMismatch(model, card, q, config, options, tolerance, &why);
  return why;
}

ConfiguredSolution solveIkWithConfiguration(const IkModel& model, const RobotCard& card,
                                            const Pose& target, const VendorConfig& config,
                                            const ConfigurationOptions& options) {
  return solveIkWithConfiguration(model, card, target, config, options, ConfigurationMatch{});
}

ConfiguredSolution solveIkWithConfiguration(const IkModel& model, const RobotCard& card,
                                            const Pose& target, const VendorConfig& config,
                                            const ConfigurationOptions& options,
                                            const ConfigurationMatch& match) {
  ConfiguredSolution out;
  // 128 solutions (~16 kB) set up once per thread, not per call: solveIk fills what it returns
  // (count, failure) and only solutions[0, count) are read
  thread_local IkResult all;
  IkOptions o;
  o.turns = IkTurns::kAll;
  o.seed = match.seed;
  const std::optional<int> want_branch = branchOfConfig(config);
  // A known branch needs one of the eight (ik.hpp, IkOptions::branch); when it gives nothing
  // usable, every branch is solved again so the reason names what the target allows.
  if (want_branch) {
    o.branch = *want_branch;
    solveIk(model, target, o, all);
    bool usable = false;
    for (int i = 0; i < all.count && !usable; ++i) {
      const IkSolution& s = all.solutions[static_cast<size_t>(i)];
      usable = s.converged && s.within_limits;
    }
    if (!usable) {
      o.branch = -1;
      solveIk(model, target, o, all);
    }
  } else {
    solveIk(model, target, o, all);
  }
  if (all.count == 0) {
    out.reason = describeIkFailure(all);
    return out;
  }
  const IkSolution* best = nullptr;
  int best_mismatch = 0;
  double best_norm = 0.0;
  bool branch_seen = false;
  for (int i = 0; i < all.count; ++i) {
    const IkSolution& s = all.solutions[static_cast<size_t>(i)];
    if (!s.converged || !s.within_limits) continue;
    if (want_branch && s.branch.index() != *want_branch) continue;
    branch_seen = true;
    const int mismatch =
        turnMismatch(model, card, s.q, config, options, match.boundary_tolerance, nullptr);
    // ties: nearest the seed, else the smallest Σ|θ| (deterministic)
    const double norm = match.seed ? (s.q - *match.seed).squaredNorm() : s.q.cwiseAbs().sum();
    if (!best || mismatch < best_mismatch ||
        (mismatch == best_mismatch && norm < best_norm - 1e-12)) {
      best = &s;
      best_mismatch = mismatch;
      best_norm = norm;
    }
  }
  if (!best) {
    out.reason = branch_seen
                     ? "no converged solution"
                     : "no solution within the joint limits has the configuration's branch " +
                           std::to_string(want_branch.value_or(-1)) + " (" + formatConfig(config) +
                           ")";
    return out;
  }
  out.found = true;
  out.solution = *best;
  out.mismatch = best_mismatch;
  out.exact = best_mismatch == 0;
  if (!out.exact && match.explain_inexact) {
    out.reason = "no solution matches the turn flags of " + formatConfig(config) +
                 "; nearest differs by " + std::to_string(best_mismatch);
  }
  return out;
}

}  // namespace roprec
