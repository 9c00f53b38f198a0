/// \file report.cpp
/// The self-contained HTML report (see report.hpp). Layout, in order: header and plain-language
/// summary; deviation maps per face group; verdict counts and capability; uncertainty budget;
/// per-hole table; footer with the conventions.
///
/// Deterministic bytes: numbers are written with std::to_chars (locale-independent, fixed
/// decimals, "-0" printed as "0"), holes and budget terms are visited in input order, there is no
/// time stamp and no script. Every string that comes from the inputs is HTML-escaped.
///
/// Maps: each face group (holes whose drilling axes agree within dot > 0.99, first-seen order) is
/// drawn as seen along its mean drilling direction a, with u × v = −a pointing at the viewer (a
/// true view, not mirrored), v = u × a. Walls (|a_z| < 0.9) are drawn upright: v = base +z
/// projected on the face, u = a × v. Top and bottom faces: u = the principal direction of the hole
/// positions projected on the plane ⊥ a (PCA; its largest-magnitude component made positive).
/// Coordinates are p·u and p·v in mm (base frame), equal scale on both axes. Colour scale: viridis
/// (matplotlib's perceptually uniform sequential map, van der Walt & Smith 2015), 11 anchors
/// interpolated linearly in sRGB.

#include "plugin/api/report.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string_view>

#include "compensator/robot/robot_card.hpp"
#include "compensator/support/fixed_chars.hpp"
#include "compensator/support/str_cat.hpp"
#include "compensator/support/xml_escape.hpp"
#include "plugin/api/prediction_setup.hpp"

namespace roprec::api {
namespace {

std::string esc(std::string_view s) { return escapeXml(s); }

// ------------------------------------------------------------------ formatting

constexpr const char* kDash = "\u2014";
constexpr double kPi = std::numbers::pi;

/// Fixed decimals, locale-independent; "-0.0" → "0.0"; non-finite → an em dash.
std::string num(double v, int decimals) {
  if (!std::isfinite(v)) return kDash;
  std::string s;
  appendFixed(s, v, decimals);
  return s;
}

std::string plural(long n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

double pct(double part, double whole) { return whole > 0 ? 100.0 * part / whole : 0.0; }

// ------------------------------------------------------------------ colours

struct Rgb {
  double r, g, b;
};

/// viridis at t ∈ [0, 1] (matplotlib `_viridis_data` sampled at 0, 0.1, …, 1).
Rgb viridis(double t) {
  static constexpr std::array<std::array<int, 3>, 11> kV{{{68, 1, 84},
                                                          {72, 36, 117},
                                                          {65, 68, 135},
                                                          {53, 95, 141},
                                                          {42, 120, 142},
                                                          {33, 145, 140},
                                                          {34, 168, 132},
                                                          {68, 191, 112},
                                                          {122, 209, 81},
                                                          {189, 223, 38},
                                                          {253, 231, 37}}};
  if (!std::isfinite(t)) t = 0;
  t = std::clamp(t, 0.0, 1.0) * 10.0;
  const int i = std::min(9, static_cast<int>(std::floor(t)));
  const double f = t - i;
  return {kV[i][0] + f * (kV[i + 1][0] - kV[i][0]), kV[i][1] + f * (kV[i + 1][1] - kV[i][1]),
          kV[i][2] + f * (kV[i + 1][2] - kV[i][2])};
}

std::string hex(const Rgb& c) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string s = "#";
  for (const double x : {c.r, c.g, c.b}) {
    const int v = std::clamp(static_cast<int>(std::lround(x)), 0, 255);
    s += kHex[v >> 4];
    s += kHex[v & 15];
  }
  return s;
}

struct VerdictStyle {
  Verdict verdict;
  const char* label;  ///< human-readable
  const char* cls;    ///< CSS class suffix
  const char* badge;  ///< short badge text (the table; the full key is its tooltip)
  const char* bar;    ///< bar / cross colour
};

constexpr std::array<VerdictStyle, 6> kVerdicts{{
    {Verdict::kConforms, "conforms", "ok", "conforms", "#2da44e"},
    {Verdict::kConformsAfterCompensation, "conforms after compensation", "comp", "after comp.",
     "#d4a72c"},
    {Verdict::kNotCapable, "not capable", "nc", "not capable", "#cf222e"},
    {Verdict::kUnreachable, "unreachable", "unr", "unreachable", "#57606a"},
    {Verdict::kSingular, "singular", "sing", "singular", "#8250df"},
    {Verdict::kNotConverged, "not converged", "nconv", "not converged", "#bc4c00"},
}};

const VerdictStyle& styleOf(Verdict v) {
  for (const VerdictStyle& s : kVerdicts) {
    if (s.verdict == v) return s;
  }
  return kVerdicts[0];
}

// ------------------------------------------------------------------ scales and ticks

double niceStep(double raw) {
  if (!(raw > 0) || !std::isfinite(raw)) return 1.0;
  const double e = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / e;
  const double m = f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0;
  return m * e;
}

int decimalsFor(double step) {
  if (!(step > 0)) return 0;
  return std::clamp(static_cast<int>(-std::floor(std::log10(step) + 1e-9)), 0, 6);
}

/// Multiples of `step` within [lo, hi] (inclusive, with a small tolerance).
std::vector<double> ticksIn(double lo, double hi, double step) {
  std::vector<double> t;
  const double eps = 1e-6 * step;
  for (double k = std::ceil((lo - eps) / step); k * step <= hi + eps && t.size() < 64; k += 1.0) {
    t.push_back(k * step);
  }
  return t;
}

struct ColourScale {
  bool valid{false};
  double data_min{0}, data_max{0};
  double lo{0}, hi{1}, step{1};
  [[nodiscard]] double t(double v) const { return hi > lo ? (v - lo) / (hi - lo) : 0.5; }
};

ColourScale makeScale(const std::vector<const std::vector<std::optional<double>>*>& sets) {
  ColourScale s;
  for (const auto* set : sets) {
    for (const auto& v : *set) {
      if (!v || !std::isfinite(*v)) continue;
      if (!s.valid) {
        s.data_min = s.data_max = *v;
        s.valid = true;
      }
      s.data_min = std::min(s.data_min, *v);
      s.data_max = std::max(s.data_max, *v);
    }
  }
  if (!s.valid) return s;
  const double range =
      std::max(s.data_max - s.data_min, std::max(1e-3, 0.02 * std::abs(s.data_max)));
  s.step = niceStep(range / 5.0);
  s.lo = std::floor(s.data_min / s.step + 1e-9) * s.step;
  s.hi = std::ceil(s.data_max / s.step - 1e-9) * s.step;
  if (s.hi <= s.lo) s.hi = s.lo + s.step;
  return s;
}

// ------------------------------------------------------------------ hole views and face groups

struct HoleView {
  const ReportHole* rh{nullptr};
  const HolePrediction* p{nullptr};
  Vec3 pos_mm{Vec3::Zero()};  ///< part frame
  Vec3 axis{Vec3::UnitZ()};   ///< part frame
  bool ok{false};
  bool config_change{false};
  int prev_branch{-1};
};

std::vector<HoleView> holeViews(const ReportInput& in) {
  std::vector<HoleView> hv;
  hv.reserve(in.holes.size());
  int prev_branch = -1;
  const Pose T_part_W = in.T_W_part.inverse();
  for (const ReportHole& rh : in.holes) {
    if (rh.prediction == nullptr)
      throw std::invalid_argument("renderReport: a hole without a prediction");
    HoleView h;
    h.rh = &rh;
    h.p = rh.prediction;
    h.pos_mm = (T_part_W * rh.T_W_tcp.translation()) * 1e3;
    const Vec3 a = T_part_W.linear() * rh.T_W_tcp.linear().col(2);
    h.axis = a.norm() > 0 ? Vec3(a.normalized()) : Vec3(Vec3::UnitZ());
    h.ok = h.p->status == HoleStatus::kOk;
    if (h.ok) {
      h.config_change = prev_branch >= 0 && h.p->branch != prev_branch;
      h.prev_branch = prev_branch;
      prev_branch = h.p->branch;
    }
    hv.push_back(h);
  }
  return hv;
}

std::string dirLabel(const Vec3& d) {
  static constexpr std::array<const char*, 3> kAxis{"X", "Y", "Z"};
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) > 0.9995)
      return std::string(d[i] > 0 ? "+" : "\u2212") + kAxis[static_cast<size_t>(i)];
  }
  return "(" + num(d.x(), 3) + ", " + num(d.y(), 3) + ", " + num(d.z(), 3) + ")";
}

/// Screen-axis labelling: a direction along ±X/±Y/±Z of the part frame is labelled with that
/// part coordinate (tick values then read part mm: sign = the direction's sign); otherwise
/// "u = (…)" in part coordinates.
struct AxisLabel {
  std::string text;
  double sign{1};
};

AxisLabel axisLabel(const char* name, const Vec3& d) {
  static constexpr std::array<const char*, 3> kAxis{"X", "Y", "Z"};
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) > 0.9995) {
      return {std::string("part ") + kAxis[static_cast<size_t>(i)] + " [mm]",
              d[i] > 0 ? 1.0 : -1.0};
    }
  }
  return {std::string(name) + " = " + dirLabel(d) + " (part) [mm]", 1.0};
}

struct FaceGroup {
  Vec3 axis{Vec3::UnitZ()};
  Vec3 u{Vec3::UnitX()}, v{Vec3::UnitY()};
  std::vector<size_t> members;
  std::vector<Eigen::Vector2d> xy;  ///< mm, per member
  // screen mapping
  double x0{0}, y1{0}, s{1};  ///< visible left, visible top (mm), px per mm
  double plot_w{368}, plot_h{260};
  double marker_r{5};
  Mat3 R_part_W{Mat3::Identity()};  ///< base-frame vectors (δ) into the part frame
};

std::vector<FaceGroup> groupFaces(const std::vector<HoleView>& hv, double dot_min) {
  std::vector<FaceGroup> g;
  std::vector<Vec3> rep;
  for (size_t i = 0; i < hv.size(); ++i) {
    size_t k = 0;
    while (k < rep.size() && rep[k].dot(hv[i].axis) <= dot_min) ++k;
    if (k == rep.size()) {
      rep.push_back(hv[i].axis);
      g.emplace_back();
    }
    g[k].members.push_back(i);
  }
  return g;
}

constexpr double kMarginL = 58, kMarginR = 16, kMarginT = 12, kPanelW = 440;

void layoutFace(FaceGroup& f, const std::vector<HoleView>& hv) {
  Vec3 asum = Vec3::Zero();
  Vec3 mean = Vec3::Zero();
  for (const size_t i : f.members) {
    asum += hv[i].axis;
    mean += hv[i].pos_mm;
  }
  f.axis = asum.norm() > 1e-12 ? Vec3(asum.normalized()) : hv[f.members.front()].axis;
  mean /= static_cast<double>(f.members.size());
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - f.axis * f.axis.transpose();
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (const size_t i : f.members) {
    const Vec3 d = P * (hv[i].pos_mm - mean);
    C += d * d.transpose();
  }
  Vec3 u;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
  if (std::abs(f.axis.z()) > 0.9995) {
    // a top or bottom face of the part: its own X axis to the right (never a rotated view)
    u = Vec3::UnitX();
  } else if (std::abs(f.axis.z()) < 0.9) {
    // a wall (not a top or bottom face): drawn upright, base +z up, v = +z projected on the face
    const Vec3 up = (P * Vec3::UnitZ()).normalized();
    u = f.axis.cross(up);
  } else if (es.info() == Eigen::Success && es.eigenvalues()[2] > 1e-9 * std::max(1.0, C.trace())) {
    u = P * es.eigenvectors().col(2);
  } else {
    // one hole (or coincident holes): the base axis least aligned with the drilling axis
    Eigen::Index k = 0;
    f.axis.cwiseAbs().minCoeff(&k);
    u = P * Vec3::Unit(k);
  }
  u.normalize();
  if (std::abs(f.axis.z()) >= 0.9) {
    Eigen::Index big = 0;
    const double m = u.cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < 3; ++i) {
      if (std::abs(u[i]) > m - 1e-9) {
        big = i;
        break;
      }
    }
    if (u[big] < 0) u = -u;
  }
  f.u = u;
  f.v = u.cross(f.axis).normalized();

  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (const size_t i : f.members) {
    const Eigen::Vector2d q(hv[i].pos_mm.dot(f.u), hv[i].pos_mm.dot(f.v));
    f.xy.push_back(q);
    xmin = std::min(xmin, q.x());
    xmax = std::max(xmax, q.x());
    ymin = std::min(ymin, q.y());
    ymax = std::max(ymax, q.y());
  }
  const double span = std::max({xmax - xmin, ymax - ymin, 1.0});
  const double dx = xmax - xmin + 0.12 * span;
  const double dy = ymax - ymin + 0.12 * span;
  f.plot_w = kPanelW - kMarginL - kMarginR;
  f.plot_h = std::clamp(f.plot_w * dy / dx, 170.0, 360.0);
  f.s = std::min(f.plot_w / dx, f.plot_h / dy);
  f.x0 = 0.5 * (xmin + xmax) - 0.5 * f.plot_w / f.s;
  f.y1 = 0.5 * (ymin + ymax) + 0.5 * f.plot_h / f.s;

  // marker size from the median nearest-neighbour spacing on screen
  std::vector<double> nn;
  const size_t n = f.xy.size();
  if (n <= 4000) {
    for (size_t i = 0; i < n; ++i) {
      double best = 1e300;
      for (size_t j = 0; j < n; ++j) {
        if (j != i) best = std::min(best, (f.xy[i] - f.xy[j]).norm());
      }
      if (best < 1e299 && best > 1e-9) nn.push_back(best * f.s);
    }
  }
  if (nn.empty()) {
    f.marker_r = n > 4000 ? 3.0 : 6.0;
  } else {
    std::nth_element(nn.begin(), nn.begin() + static_cast<long>(nn.size() / 2), nn.end());
    f.marker_r = std::clamp(0.4 * nn[nn.size() / 2], 3.0, 6.5);
  }
}

// ------------------------------------------------------------------ SVG pieces

std::string shapePath(int branch, double x, double y, double r) {
  auto poly = [&](int n, double rot, double rr) {
    std::string s = "<polygon points=\"";
    for (int i = 0; i < n; ++i) {
      const double a = rot + 2.0 * kPi * i / n;
      if (i) s += ' ';
      s += num(x + rr * std::cos(a), 2) + "," + num(y + rr * std::sin(a), 2);
    }
    return s + "\"";
  };
  switch (((branch % 8) + 8) % 8) {
    case 0:
      return "<circle cx=\"" + num(x, 2) + "\" cy=\"" + num(y, 2) + "\" r=\"" + num(r, 2) + "\"";
    case 1: {
      const double h = 0.9 * r;
      return "<rect x=\"" + num(x - h, 2) + "\" y=\"" + num(y - h, 2) + "\" width=\"" +
             num(2 * h, 2) + "\" height=\"" + num(2 * h, 2) + "\"";
    }
    case 2:
      return poly(4, 0.0, 1.2 * r);
    case 3:
      return poly(3, -kPi / 2, 1.25 * r);
    case 4:
      return poly(3, kPi / 2, 1.25 * r);
    case 5:
      return poly(3, 0.0, 1.25 * r);
    case 6:
      return poly(3, kPi, 1.25 * r);
    default: {
      std::string s = "<polygon points=\"";
      for (int i = 0; i < 10; ++i) {
        const double a = -kPi / 2 + kPi * i / 5;
        const double rr = (i % 2 ? 0.5 : 1.35) * r;
        if (i) s += ' ';
        s += num(x + rr * std::cos(a), 2) + "," + num(y + rr * std::sin(a), 2);
      }
      return s + "\"";
    }
  }
}

std::string crossPath(double x, double y, double r, const char* colour) {
  const double h = 0.95 * r;
  return "<path d=\"M" + num(x - h, 2) + " " + num(y - h, 2) + "L" + num(x + h, 2) + " " +
         num(y + h, 2) + "M" + num(x - h, 2) + " " + num(y + h, 2) + "L" + num(x + h, 2) + " " +
         num(y - h, 2) + "\" stroke=\"" + colour +
         "\" stroke-width=\"2.2\" stroke-linecap=\"round\" fill=\"none\"";
}

enum class ArrowOf { kNone, kRobot, kWork };

struct Panel {
  std::string title;
  std::string quantity;  ///< colour-bar label
  const std::vector<std::optional<double>>* values{nullptr};
  const ColourScale* scale{nullptr};
  ArrowOf arrows{ArrowOf::kNone};
  bool after{false};     ///< outline by the verdict after compensation
  bool tol_mark{false};  ///< mark t/2 on the colour bar
};

/// The verdict a marker shows: before, or after compensation when the panel is an "after" one
/// and the hole was compensated.
Verdict verdictOf(const HoleView& h, bool after) {
  if (after && h.rh->after != nullptr) return h.rh->after->verdict;
  return h.p->verdict;
}

/// Severity for aggregation and label priority (higher = worse).
int severity(Verdict v) {
  switch (v) {
    case Verdict::kConforms:
      return 0;
    case Verdict::kConformsAfterCompensation:
      return 1;
    case Verdict::kNotCapable:
      return 3;
    default:
      return 2;
  }
}

constexpr size_t kMaxFailLabels = 24;  ///< per panel; the rest are in the table

/// The tolerance t/2 (µm) of the face's holes on a colour bar: a red mark and label where it lies
/// on the scale, an arrow at the end when the scale ends below it (all values are then below t/2).
void renderToleranceMarks(std::string& o, const FaceGroup& f, const std::vector<HoleView>& hv,
                          const ColourScale& sc, double bx, double bw, double bar_y) {
  std::vector<double> halves;
  for (const size_t i : f.members) {
    const double t2 = 0.5 * hv[i].p->tolerance * 1e6;
    if (t2 > 0 && std::find(halves.begin(), halves.end(), t2) == halves.end()) halves.push_back(t2);
  }
  std::sort(halves.begin(), halves.end());
  if (halves.size() > 3) halves.erase(halves.begin() + 1, halves.end() - 1);
  for (size_t n = 0; n < halves.size(); ++n) {
    const double t2 = halves[n];
    const std::string label = "t/2 = " + num(t2, 0);
    if (t2 <= sc.hi && t2 >= sc.lo) {
      const double x = bx + bw * sc.t(t2);
      o += "<g class=\"tol\"><line x1=\"" + num(x, 1) + "\" y1=\"" + num(bar_y - 4, 1) +
           "\" x2=\"" + num(x, 1) + "\" y2=\"" + num(bar_y + 16, 1) + "\"/><text x=\"" + num(x, 1) +
           "\" y=\"" + num(bar_y + 39 + 10.0 * static_cast<double>(n), 1) +
           "\" text-anchor=\"middle\">" + label + "</text></g>";
    } else if (t2 > sc.hi) {
      o += "<g class=\"tol\"><text x=\"" + num(bx + bw, 1) + "\" y=\"" +
           num(bar_y + 39 + 10.0 * static_cast<double>(n), 1) + "\" text-anchor=\"end\">" + label +
           " \u00b5m \u25b6 (above the scale: every value is below t/2)</text></g>";
    } else {
      o += "<g class=\"tol\"><text x=\"" + num(bx, 1) + "\" y=\"" +
           num(bar_y + 39 + 10.0 * static_cast<double>(n), 1) + "\" text-anchor=\"start\">\u25c0 " +
           label + " \u00b5m (below the scale: every value exceeds t/2)</text></g>";
    }
  }
}

/// Large jobs: holes binned on a square screen grid (7 px); each bin is filled with its largest
/// value and outlined by its worst verdict, its tooltip gives the count, the maximum and up to
/// three ids of its worst holes.
template <class Px, class Py>
void renderBins(std::string& o, const FaceGroup& f, const std::vector<HoleView>& hv,
                const Panel& pn, const Px& px, const Py& py) {
  constexpr double kBin = 7.0;
  const int nx = std::max(1, static_cast<int>(std::ceil(f.plot_w / kBin)));
  const int ny = std::max(1, static_cast<int>(std::ceil(f.plot_h / kBin)));
  struct Bin {
    int count{0}, worst{-1};
    std::optional<double> max;
    std::vector<size_t> ids;  ///< members, worst verdict first (≤ 3)
  };
  std::vector<Bin> bins(static_cast<size_t>(nx) * static_cast<size_t>(ny));
  for (size_t k = 0; k < f.members.size(); ++k) {
    const HoleView& h = hv[f.members[k]];
    const int bx = std::clamp(static_cast<int>((px(f.xy[k].x()) - kMarginL) / kBin), 0, nx - 1);
    const int by = std::clamp(static_cast<int>((py(f.xy[k].y()) - kMarginT) / kBin), 0, ny - 1);
    Bin& b = bins[static_cast<size_t>(by) * static_cast<size_t>(nx) + static_cast<size_t>(bx)];
    ++b.count;
    const int sev = severity(verdictOf(h, pn.after));
    if (sev > b.worst) {
      b.worst = sev;
      b.ids.clear();
    }
    if (sev == b.worst && b.ids.size() < 3) b.ids.push_back(k);
    const std::optional<double> v = (*pn.values)[f.members[k]];
    if (h.ok && v && (!b.max || *v > *b.max)) b.max = v;
  }
  const ColourScale& sc = *pn.scale;
  for (int by = 0; by < ny; ++by) {
    for (int bx = 0; bx < nx; ++bx) {
      const Bin& b =
          bins[static_cast<size_t>(by) * static_cast<size_t>(nx) + static_cast<size_t>(bx)];
      if (b.count == 0) continue;
      const Verdict v = verdictOf(hv[f.members[b.ids.front()]], pn.after);
      o += "<rect class=\"bin v-" + std::string(styleOf(v).cls) + "\" x=\"" +
           num(kMarginL + bx * kBin, 1) + "\" y=\"" + num(kMarginT + by * kBin, 1) +
           "\" width=\"7\" height=\"7\" fill=\"" +
           (b.max ? hex(viridis(sc.t(*b.max))) : std::string("#d0d7de")) + "\"><title>" +
           plural(b.count, "hole", "holes") + " \u00b7 max " +
           (b.max ? num(*b.max, 1) + " \u00b5m" : std::string("n/a")) + " \u00b7 worst " +
           verdictName(v);
      for (const size_t k : b.ids) o += " \u00b7 " + esc(hv[f.members[k]].p->id);
      o += "</title></rect>";
    }
  }
}

void renderPanel(std::string& o, const FaceGroup& f, const std::vector<HoleView>& hv,
                 const Panel& pn) {
  const double W = kPanelW;
  const double plot_bottom = kMarginT + f.plot_h;
  const double bar_y = plot_bottom + 58;
  const double H = bar_y + (pn.tol_mark ? 66 : 40);
  const ColourScale& sc = *pn.scale;
  auto px = [&](double x) { return kMarginL + (x - f.x0) * f.s; };
  auto py = [&](double y) { return kMarginT + (f.y1 - y) * f.s; };

  o += "<figure class=\"panel\"><figcaption>" + pn.title + "</figcaption>";
  o += "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " + num(W, 0) + " " + num(H, 0) +
       "\" role=\"img\" aria-label=\"" + esc(pn.quantity) + "\">";
  // plot frame, grid and ticks (equal step on both axes: the grid is square)
  const double x_lo = f.x0, x_hi = f.x0 + f.plot_w / f.s;
  const double y_hi = f.y1, y_lo = f.y1 - f.plot_h / f.s;
  const double step = niceStep(std::max(x_hi - x_lo, y_hi - y_lo) / 6.0);
  const int dec = decimalsFor(step);
  const AxisLabel lx = axisLabel("u", f.u), ly = axisLabel("v", f.v);
  o += "<rect class=\"plot\" x=\"" + num(kMarginL, 1) + "\" y=\"" + num(kMarginT, 1) +
       "\" width=\"" + num(f.plot_w, 1) + "\" height=\"" + num(f.plot_h, 1) + "\"/>";
  o += "<g class=\"grid\">";
  for (const double t : ticksIn(x_lo, x_hi, step)) {
    o += "<line x1=\"" + num(px(t), 1) + "\" y1=\"" + num(kMarginT, 1) + "\" x2=\"" +
         num(px(t), 1) + "\" y2=\"" + num(plot_bottom, 1) + "\"/>";
  }
  for (const double t : ticksIn(y_lo, y_hi, step)) {
    o += "<line x1=\"" + num(kMarginL, 1) + "\" y1=\"" + num(py(t), 1) + "\" x2=\"" +
         num(kMarginL + f.plot_w, 1) + "\" y2=\"" + num(py(t), 1) + "\"/>";
  }
  o += "</g><g class=\"tick\">";
  for (const double t : ticksIn(x_lo, x_hi, step)) {
    o += "<text x=\"" + num(px(t), 1) + "\" y=\"" + num(plot_bottom + 15, 1) +
         "\" text-anchor=\"middle\">" + num(lx.sign * t, dec) + "</text>";
  }
  for (const double t : ticksIn(y_lo, y_hi, step)) {
    o += "<text x=\"" + num(kMarginL - 6, 1) + "\" y=\"" + num(py(t) + 4, 1) +
         "\" text-anchor=\"end\">" + num(ly.sign * t, dec) + "</text>";
  }
  o += "</g>";
  o += "<text class=\"axis\" x=\"" + num(kMarginL + 0.5 * f.plot_w, 1) + "\" y=\"" +
       num(plot_bottom + 33, 1) + "\" text-anchor=\"middle\">" + esc(lx.text) + "</text>";
  o += "<text class=\"axis\" transform=\"translate(14 " + num(kMarginT + 0.5 * f.plot_h, 1) +
       ") rotate(-90)\" text-anchor=\"middle\">" + esc(ly.text) + "</text>";

  const bool aggregate = hv.size() > kReportAggregateAbove;
  // program order path (not when aggregated: it would only be a smear)
  if (!aggregate && f.members.size() > 1) {
    o += "<polyline class=\"path\" points=\"";
    for (size_t k = 0; k < f.members.size(); ++k) {
      if (k) o += ' ';
      o += num(px(f.xy[k].x()), 1) + "," + num(py(f.xy[k].y()), 1);
    }
    o += "\"/>";
  }

  const double r = f.marker_r;
  size_t worst = f.members.size();
  for (size_t k = 0; k < f.members.size(); ++k) {
    const HoleView& h = hv[f.members[k]];
    const std::optional<double> v = (*pn.values)[f.members[k]];
    if (h.ok && v && (worst == f.members.size() || *v > *(*pn.values)[f.members[worst]])) worst = k;
  }
  if (aggregate) {
    renderBins(o, f, hv, pn, px, py);
  } else {
    for (size_t k = 0; k < f.members.size(); ++k) {
      const HoleView& h = hv[f.members[k]];
      const double x = px(f.xy[k].x()), y = py(f.xy[k].y());
      const std::optional<double> v = (*pn.values)[f.members[k]];
      const Verdict verdict = verdictOf(h, pn.after);
      std::string tip = esc(h.p->id);
      o += "<g>";
      if (!h.ok) {
        tip += " \u00b7 " + std::string(verdictName(h.p->verdict));
        if (!h.p->reason.empty()) tip += ": " + esc(h.p->reason);
        o += crossPath(x, y, r, styleOf(h.p->verdict).bar) + "/>";
      } else {
        tip += " \u00b7 " + (v ? num(*v, 1) + " \u00b5m" : std::string("n/a")) + " \u00b7 " +
               verdictName(verdict) + " \u00b7 branch " + std::to_string(h.p->branch);
        if (!h.p->config.empty()) tip += " (" + esc(h.p->config) + ")";
        const std::string fill = v ? hex(viridis(sc.t(*v))) : std::string("#ffffff");
        o += shapePath(h.p->branch, x, y, r) + " fill=\"" + fill + "\" class=\"mk v-" +
             styleOf(verdict).cls + "\"/>";
        if (h.config_change) {
          tip += " \u00b7 configuration change from branch " + std::to_string(h.prev_branch);
          o += "<circle class=\"chg\" cx=\"" + num(x, 2) + "\" cy=\"" + num(y, 2) + "\" r=\"" +
               num(r + 3.2, 2) + "\"/>";
        }
      }
      o += "<title>" + tip + "</title></g>";
    }
  }

  // ids of the holes that do not conform, visible without hovering (worst first, capped)
  std::vector<size_t> failing;
  for (size_t k = 0; k < f.members.size(); ++k) {
    if (severity(verdictOf(hv[f.members[k]], pn.after)) > 0) failing.push_back(k);
  }
  std::stable_sort(failing.begin(), failing.end(), [&](size_t a, size_t b) {
    const int sa = severity(verdictOf(hv[f.members[a]], pn.after));
    const int sb = severity(verdictOf(hv[f.members[b]], pn.after));
    if (sa != sb) return sa > sb;
    // by the value as the tooltip prints it (0.1 µm), ties in program order: the order does not
    // hang on a value's last bits (another platform's libm)
    const auto shown = [](std::optional<double> v) { return v ? std::round(*v * 10.0) : -1.0; };
    return shown((*pn.values)[f.members[a]]) > shown((*pn.values)[f.members[b]]);
  });
  for (size_t n = 0; n < failing.size() && n < kMaxFailLabels; ++n) {
    const size_t k = failing[n];
    const HoleView& h = hv[f.members[k]];
    const double x = px(f.xy[k].x()), y = py(f.xy[k].y());
    const bool right = x + r + 4 + 6.2 * static_cast<double>(h.p->id.size()) < kMarginL + f.plot_w;
    o += "<text class=\"flabel f-" + std::string(styleOf(verdictOf(h, pn.after)).cls) + "\" x=\"" +
         num(right ? x + r + 3 : x - r - 3, 1) + "\" y=\"" + num(y + 3.5, 1) + "\" text-anchor=\"" +
         (right ? "start" : "end") + "\">" + esc(h.p->id) + "</text>";
  }
  if (failing.size() > kMaxFailLabels) {
    o += "<text class=\"tick\" x=\"" + num(kMarginL + 4, 1) + "\" y=\"" +
         num(kMarginT + f.plot_h - 5, 1) + "\">+" +
         std::to_string(failing.size() - kMaxFailLabels) +
         " more not conforming: see the table</text>";
  }

  // δ direction of the three largest values (direction only, not to scale)
  if (pn.arrows != ArrowOf::kNone) {
    std::vector<size_t> order;
    for (size_t k = 0; k < f.members.size(); ++k) {
      if (hv[f.members[k]].ok && (*pn.values)[f.members[k]]) order.push_back(k);
    }
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
      return *(*pn.values)[f.members[a]] > *(*pn.values)[f.members[b]];
    });
    if (order.size() > 3) order.resize(3);
    for (const size_t k : order) {
      const HolePrediction& p = *hv[f.members[k]].p;
      const Vec3 d = f.R_part_W * (pn.arrows == ArrowOf::kRobot ? p.d_robot : p.d_work);
      const Eigen::Vector2d q(d.dot(f.u), -d.dot(f.v));
      if (q.norm() < 1e-3 * std::max(d.norm(), 1e-15) || q.norm() <= 0) continue;
      const Eigen::Vector2d e = q.normalized();
      const Eigen::Vector2d c(px(f.xy[k].x()), py(f.xy[k].y()));
      const Eigen::Vector2d a0 = c + (r + 3.5) * e, a1 = c + (r + 24) * e;
      const Eigen::Vector2d n(-e.y(), e.x());
      const Eigen::Vector2d b = a1 - 7 * e;
      o += "<g class=\"arrow\"><line x1=\"" + num(a0.x(), 1) + "\" y1=\"" + num(a0.y(), 1) +
           "\" x2=\"" + num(b.x(), 1) + "\" y2=\"" + num(b.y(), 1) + "\"/><polygon points=\"" +
           num(a1.x(), 1) + "," + num(a1.y(), 1) + " " + num(b.x() + 3.5 * n.x(), 1) + "," +
           num(b.y() + 3.5 * n.y(), 1) + " " + num(b.x() - 3.5 * n.x(), 1) + "," +
           num(b.y() - 3.5 * n.y(), 1) + "\"/></g>";
    }
  }

  // label of the largest value
  if (worst < f.members.size()) {
    const HoleView& h = hv[f.members[worst]];
    const double x = px(f.xy[worst].x()), y = py(f.xy[worst].y());
    const std::string label =
        esc(h.p->id) + " \u00b7 " + num(*(*pn.values)[f.members[worst]], 1) + " \u00b5m";
    const double est_w = 6.2 * static_cast<double>(h.p->id.size() + 10);
    const bool right = x + r + 5 + est_w < kMarginL + f.plot_w;
    const double label_y = std::max(kMarginT + 12, y - r - 4);
    o += "<text class=\"maxlabel\" x=\"" + num(right ? x + r + 4 : x - r - 4, 1) + "\" y=\"" +
         num(label_y, 1) + "\" text-anchor=\"" + (right ? "start" : "end") + "\">max " + label +
         "</text>";
  }

  // colour bar
  const double bx = kMarginL, bw = f.plot_w;
  o += "<text class=\"axis\" x=\"" + num(bx, 1) + "\" y=\"" + num(bar_y - 6, 1) + "\">" +
       esc(pn.quantity) + " [\u00b5m]</text>";
  if (sc.valid) {
    o += "<text class=\"tick\" x=\"" + num(bx + bw, 1) + "\" y=\"" + num(bar_y - 6, 1) +
         "\" text-anchor=\"end\">min " + num(sc.data_min, 1) + " \u00b7 max " +
         num(sc.data_max, 1) + "</text>";
    constexpr int kSeg = 48;
    for (int i = 0; i < kSeg; ++i) {
      o += "<rect x=\"" + num(bx + bw * i / kSeg, 2) + "\" y=\"" + num(bar_y, 1) + "\" width=\"" +
           num(bw / kSeg + (i + 1 < kSeg ? 1.0 : 0.0), 2) +
           "\" height=\"12\" shape-rendering=\"crispEdges\" fill=\"" +
           hex(viridis((i + 0.5) / kSeg)) + "\"/>";
    }
    o += "<rect class=\"barframe\" x=\"" + num(bx, 1) + "\" y=\"" + num(bar_y, 1) + "\" width=\"" +
         num(bw, 1) + "\" height=\"12\"/>";
    const int bdec = decimalsFor(sc.step);
    for (const double t : ticksIn(sc.lo, sc.hi, sc.step)) {
      const double x = bx + bw * sc.t(t);
      o += "<line class=\"barTick\" x1=\"" + num(x, 1) + "\" y1=\"" + num(bar_y + 12, 1) +
           "\" x2=\"" + num(x, 1) + "\" y2=\"" + num(bar_y + 16, 1) +
           "\"/><text class=\"tick\" x=\"" + num(x, 1) + "\" y=\"" + num(bar_y + 28, 1) +
           "\" text-anchor=\"middle\">" + num(t, bdec) + "</text>";
    }
    if (pn.tol_mark) renderToleranceMarks(o, f, hv, sc, bx, bw, bar_y);
  } else {
    o += "<text class=\"tick\" x=\"" + num(bx, 1) + "\" y=\"" + num(bar_y + 12, 1) +
         "\">no value to show</text>";
  }
  o += "</svg></figure>";
}

std::string legendIcon(const std::string& body) {
  return "<svg class=\"icon\" viewBox=\"0 0 22 22\" width=\"22\" height=\"22\" "
         "aria-hidden=\"true\">" +
         body + "</svg>";
}

// ------------------------------------------------------------------ budget labels

struct TermInfo {
  const char* name;
  const char* label;
  const char* basis;
};

constexpr std::array<TermInfo, 7> kTerms{{
    {"robot_repeatability", "Robot repeatability", "ISO 9283 RP, normal: \u03c3 = RP / 3.616"},
    {"robot_absolute_accuracy", "Robot absolute accuracy",
     "uncalibrated: AP / 2.7955 (card <accuracy>); calibrated: the calibration \u03c3 through the "
     "FK Jacobian; the controller option: its AP; + the registration \u03c3"},
    {"robot_deflection_model", "Deflection model",
     "joint stiffness and servo gain uncertainty propagated through the deflection"},
    {"robot_deflection_process_force", "Deflection under process-force scatter",
     "force scale rectangular, a/\u221a3, through the robot compliance"},
    {"mach_axis", "Drill axis deviation", "\u03b4axis = La tan \u03b8a, rectangular a/\u221a3"},
    {"mach_runout", "Spindle runout", "\u03b4\u03c1, arcsine a/\u221a2"},
    {"mach_tool_deflection", "Tool deflection",
     "\u03b4deftool under the rotating force Fr, arcsine a/\u221a2"},
}};

const TermInfo* termInfo(const std::string& name) {
  for (const TermInfo& ti : kTerms) {
    if (name == ti.name) return &ti;
  }
  return nullptr;
}

constexpr std::array<const char*, 4> kRobotColours{"#1f4e79", "#3a7dbf", "#8fbbe6", "#c9def5"};
constexpr std::array<const char*, 5> kProcessColours{"#b45309", "#e8892b", "#f5b971", "#fbd9a6",
                                                     "#fdebd0"};

struct TermStats {
  std::string name;
  bool process{false};
  double sum_u{0}, max_u{0}, sum_share{0};
  int n{0};
};

// ------------------------------------------------------------------ CSS

constexpr const char* kCss = R"CSS(
:root{--fg:#1f2328;--muted:#59636e;--line:#d1d9e0;--soft:#f6f8fa;--accent:#0b5cad}
*{box-sizing:border-box}
html{-webkit-text-size-adjust:100%}
body{margin:0;color:var(--fg);background:#fff;font:14px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,"Helvetica Neue",Arial,"Noto Sans","Liberation Sans",sans-serif;font-variant-numeric:tabular-nums}
main{max-width:1480px;margin:0 auto;padding:24px 32px 40px}
h1{font-size:24px;line-height:1.25;margin:0 0 4px;font-weight:650;letter-spacing:-.01em}
h2{font-size:18px;margin:34px 0 10px;padding-bottom:6px;border-bottom:1px solid var(--line);font-weight:620}
h3{font-size:14px;margin:18px 0 8px;font-weight:620}
p{margin:6px 0 10px}
.sub{color:var(--muted);margin:0 0 16px}
.meta{display:grid;grid-template-columns:repeat(3,minmax(0,1fr));gap:8px 24px;margin:0 0 16px;padding:12px 16px;background:var(--soft);border:1px solid var(--line);border-radius:8px}
.meta div{min-width:0}
.meta dt{font-size:11px;text-transform:uppercase;letter-spacing:.05em;color:var(--muted)}
.meta dd{margin:0;overflow-wrap:anywhere}
.meta .wide{grid-column:1/-1}
.meta .src{color:var(--muted);font-size:12px}
.summary{font-size:15.5px;max-width:1100px;margin:14px 0 16px}
.kpis{display:grid;grid-template-columns:repeat(6,minmax(0,1fr));gap:10px;margin:8px 0 4px}
.kpi{border:1px solid var(--line);border-radius:8px;padding:10px 12px;border-top:4px solid var(--c,#8c959f)}
.kpi b{display:block;font-size:22px;font-weight:650;line-height:1.2}
.kpi span{color:var(--muted);font-size:12px}
.kpi b small{font-size:14px;font-weight:500;color:var(--muted)}
.face{margin:10px 0 6px;color:var(--fg)}
.face small{color:var(--muted);font-weight:400}
.maps{display:grid;grid-template-columns:repeat(3,minmax(0,1fr));gap:14px}
.maps.four{grid-template-columns:repeat(2,minmax(0,1fr))}
.panel{margin:0;border:1px solid var(--line);border-radius:8px;padding:8px 8px 2px;break-inside:avoid}
.panel figcaption{font-weight:600;font-size:13px;padding:0 4px 2px}
.panel svg{display:block;width:100%;height:auto}
.maps.four .panel svg{max-width:600px;margin:0 auto}
svg text{font-family:inherit;font-size:11px;fill:#424a53}
svg .axis{font-size:11.5px;fill:#1f2328}
svg .plot{fill:#fcfcfd;stroke:#afb8c1;stroke-width:1}
svg .grid line{stroke:#eaeef2;stroke-width:1}
svg .path{fill:none;stroke:#afb8c1;stroke-width:.8;stroke-dasharray:3 2}
svg .mk{stroke:#24292f;stroke-width:.7}
svg .chg{fill:none;stroke:#e3120b;stroke-width:1.9}
svg .v-ok{stroke:#24292f;stroke-width:.7}
svg .v-comp{stroke:#b07d00;stroke-width:2.4}
svg .v-nc{stroke:#cf222e;stroke-width:2.8}
svg .v-unr,svg .v-sing,svg .v-nconv{stroke:#57606a;stroke-width:2.4}
svg .bin{stroke-width:0}
svg .bin.v-comp{stroke-width:1.2}
svg .bin.v-nc{stroke-width:1.6}
svg .flabel{font-size:10.5px;font-weight:650;paint-order:stroke;stroke:#fff;stroke-width:3px;stroke-linejoin:round}
svg .f-nc{fill:#a40e26}
svg .f-comp{fill:#7d4e00}
svg .f-unr,svg .f-sing,svg .f-nconv{fill:#424a53}
svg .tol line{stroke:#cf222e;stroke-width:2}
svg .tol text{fill:#a40e26;font-size:10.5px;font-weight:600}
svg .arrow line{stroke:#1f2328;stroke-width:1.5}
svg .arrow polygon{fill:#1f2328}
svg .maxlabel{font-size:11px;font-weight:600;fill:#1f2328;paint-order:stroke;stroke:#fff;stroke-width:3px;stroke-linejoin:round}
svg .barframe{fill:none;stroke:#8c959f;stroke-width:.8}
svg .barTick{stroke:#57606a;stroke-width:1}
.legend{display:flex;flex-wrap:wrap;gap:6px 18px;align-items:center;margin:10px 0 4px;padding:8px 12px;border:1px solid var(--line);border-radius:8px;background:var(--soft);font-size:12.5px}
.legend span{display:inline-flex;align-items:center;gap:4px}
.legend .icon{flex:none}
.note{color:var(--muted);font-size:12.5px}
.two{display:grid;grid-template-columns:minmax(0,1fr) minmax(0,1fr);gap:24px;align-items:start}
.card{border:1px solid var(--line);border-radius:8px;padding:12px 16px}
.card h3{margin-top:0}
.vbars svg{width:100%;height:auto;display:block}
.big{font-size:28px;font-weight:650;line-height:1.15}
.big small{font-size:14px;color:var(--muted);font-weight:400}
.meter{height:12px;border-radius:6px;background:#eaeef2;overflow:hidden;margin:6px 0 12px}
.meter i{display:block;height:100%;background:#2da44e}
table{border-collapse:separate;border-spacing:0;font-size:12.5px}
th,td{padding:4px 8px;text-align:right;white-space:nowrap;border-bottom:1px solid #eaeef2}
th{background:#f0f3f6;font-weight:600;text-align:center;color:#1f2328;vertical-align:bottom}
th small{font-weight:400;color:var(--muted)}
td.l,th.l{text-align:left}
tbody tr:nth-child(even) td{background:#f8fafc}
tbody tr:hover td{background:#eef5ff}
.budget{width:100%}
.budget td,.budget th{padding:5px 10px}
.budget tr.sum td{border-top:1px solid var(--line);background:#fff}
.budget tr.sum td:first-child,.budget tr.sum td.n{font-weight:600}
.sw{display:inline-block;width:10px;height:10px;border-radius:2px;margin-right:6px;vertical-align:-1px}
.share{display:inline-block;height:8px;background:#8fbbe6;border-radius:2px;vertical-align:middle;margin-left:6px}
.stack{display:flex;height:22px;border-radius:5px;overflow:hidden;border:1px solid var(--line);margin:10px 0 4px}
.stack span{display:block;height:100%;overflow:hidden;white-space:nowrap;font-size:11px;line-height:22px;padding-left:5px;color:#fff}
.stack span.lt{color:#1f2328}
.scroll{max-height:78vh;overflow:auto;border:1px solid var(--line);border-radius:8px}
.holes{font-size:12px}
.holes th,.holes td{padding:3px 5px}
.holes th{white-space:normal;line-height:1.25}
.holes thead th{position:sticky;top:0;z-index:2;box-shadow:inset 0 -1px 0 var(--line)}
.holes .c0,.holes .c1{position:sticky;z-index:1;background:#fff}
.holes .c0{left:0;min-width:34px}
.holes .c1{left:34px;box-shadow:inset -1px 0 0 var(--line)}
.holes thead .c0,.holes thead .c1{z-index:3;background:#f0f3f6}
.holes td.id{font-weight:600;text-align:left}
.holes thead th{cursor:pointer;user-select:none}
.holes th[aria-sort=ascending]::after{content:" \25b2"}
.holes th[aria-sort=descending]::after{content:" \25bc"}
.holes.fonly tr.pass{display:none}
.holes td.cfgchg{color:#a40e26;font-weight:600}
.filter{display:inline-block;margin:4px 0 8px;font-size:13px}
.pager{margin:8px 0;font-size:13px}
.holes td.v span{display:inline-block;min-width:3em}
.holes td.j span{display:inline-block;min-width:3.1em}
.holes td.reason{text-align:left;color:#57606a;font-style:italic}
.holes td.why{min-width:14em;max-width:26em;white-space:normal;font-size:12px;color:#57606a}
.holes td.chg b{display:inline-block;min-width:1.7em;border:2px solid #e3120b;border-radius:999px;text-align:center;line-height:1.2}
.badge{display:inline-block;padding:0 7px;border-radius:999px;font-size:11px;font-weight:600;border:1px solid}
.b-ok{color:#116329;background:#dafbe1;border-color:#aceebb}
.b-comp{color:#7d4e00;background:#fff8c5;border-color:#eac54f}
.b-nc{color:#a40e26;background:#ffebe9;border-color:#ffcecb}
.b-unr{color:#424a53;background:#eaeef2;border-color:#d1d9e0}
.b-sing{color:#6639ba;background:#fbefff;border-color:#e6ccff}
.b-nconv{color:#953800;background:#fff1e5;border-color:#ffd8b5}
footer{margin-top:36px;padding-top:12px;border-top:1px solid var(--line);color:var(--muted);font-size:12px}
footer p{margin:4px 0}
@media (max-width:1100px){.maps,.maps.four{grid-template-columns:minmax(0,1fr)}.kpis{grid-template-columns:repeat(3,minmax(0,1fr))}.two,.meta{grid-template-columns:minmax(0,1fr)}}
@media print{@page{size:A4 landscape;margin:10mm}body{font-size:10pt}main{max-width:none;padding:0}.scroll{max-height:none;overflow:visible;border:0}.holes thead th{position:static}table{font-size:8pt}.holes{font-size:6.4pt}th,td,.holes th,.holes td{padding:1px 3px}.holes .c0,.holes .c1{position:static}h2{break-after:avoid}.card,.panel,.kpi{break-inside:avoid}tbody tr:hover td{background:inherit}}
)CSS";

// ------------------------------------------------------------------ table script

/// Sorting (click a head; again to reverse; numbers numerically, an em dash last) and the
/// "not conforming only" filter. Inline, no network; the page reads fully without it.
constexpr const char* kTableScript = R"JS(
(function(){
var t=document.getElementById('holetable');if(!t)return;
var cb=document.getElementById('failonly');
cb.addEventListener('change',function(){t.classList.toggle('fonly',cb.checked);});
var ths=t.tHead.rows[0].cells,dir={};
function key(r,i,txt){var c=r.cells[i];if(!c)return txt?'':Infinity;var s=c.textContent;
 if(txt)return s;var v=parseFloat(s);return isNaN(v)?Infinity:v;}
for(var i=0;i<ths.length;i++)(function(i){ths[i].addEventListener('click',function(){
 var txt=ths[i].getAttribute('data-t')==='1',b=t.tBodies[0],rows=Array.prototype.slice.call(b.rows);
 var d=dir[i]=-(dir[i]||-1);
 var k=rows.map(function(r,n){return [key(r,i,txt),n,r];});
 k.sort(function(a,c){if(a[0]<c[0])return -d;if(a[0]>c[0])return d;return a[1]-c[1];});
 var f=document.createDocumentFragment();k.forEach(function(x){f.appendChild(x[2]);});b.appendChild(f);
 for(var j=0;j<ths.length;j++)ths[j].removeAttribute('aria-sort');
 ths[i].setAttribute('aria-sort',d>0?'ascending':'descending');});})(i);
})();
)JS";

/// Large jobs: the rows live in ROPREC_ROWS (one "<tr>…</tr>" string each); the DOM holds one
/// page. Sorting (by the clicked column's text, numbers numerically) and the filter act on all.
constexpr const char* kPagedTableScript = R"JS(
(function(){
var R=window.ROPREC_ROWS,t=document.getElementById('holetable');if(!t||!R)return;
var b=t.tBodies[0],cb=document.getElementById('failonly'),pg=document.getElementById('pager');
var P=200,page=0,order=R.map(function(_,i){return i;}),dir={},keys={};
function cell(s,i){var p=s.split('\x1f')[i]||'';if(i>0)p=p.slice(p.indexOf('>')+1);return p.replace(/<[^>]*>/g,'');}
function rows(){return cb.checked?order.filter(function(i){return R[i].lastIndexOf('<tr class="pass"',0)!==0;}):order;}
function draw(){var r=rows(),n=Math.max(1,Math.ceil(r.length/P));if(page>=n)page=n-1;if(page<0)page=0;
 b.innerHTML=r.slice(page*P,page*P+P).map(function(i){return R[i].split('\x1f').join('</td><td');}).join('');
 pg.querySelector('span').textContent='rows '+(r.length?page*P+1:0)+'\u2013'+Math.min(r.length,page*P+P)+' of '+r.length;}
pg.querySelector('.prev').addEventListener('click',function(){page--;draw();});
pg.querySelector('.next').addEventListener('click',function(){page++;draw();});
cb.addEventListener('change',function(){page=0;draw();});
var ths=t.tHead.rows[0].cells;
for(var i=0;i<ths.length;i++)(function(i){ths[i].addEventListener('click',function(){
 var txt=ths[i].getAttribute('data-t')==='1';
 if(!keys[i])keys[i]=R.map(function(s){var c=cell(s,i);if(txt)return c;var v=parseFloat(c);return isNaN(v)?Infinity:v;});
 var k=keys[i],d=dir[i]=-(dir[i]||-1);
 order=R.map(function(_,n){return n;});
 order.sort(function(a,c){if(k[a]<k[c])return -d;if(k[a]>k[c])return d;return a-c;});
 for(var j=0;j<ths.length;j++)ths[j].removeAttribute('aria-sort');
 ths[i].setAttribute('aria-sort',d>0?'ascending':'descending');page=0;draw();});})(i);
draw();
})();
)JS";

// ------------------------------------------------------------------ sections

void renderHeader(std::string& o, const ReportInput& in, const std::vector<HoleView>& hv) {
  const CapabilitySummary& s = in.summary;
  o += "<header><h1>" + esc(in.title) + "</h1>";
  o += "<p class=\"sub\">Per-hole deviation, uncertainty and ISO 14253-1 tolerance verdict of a "
       "robotic drilling "
       "program" +
       std::string(in.compensation ? ", before and after compensation" : "") + ".</p>";
  auto item = [&](const char* k, const std::string& v, bool wide = false) {
    o += std::string("<div") + (wide ? " class=\"wide\"" : "") + "><dt>" + k + "</dt><dd>" +
         (v.empty() ? std::string(kDash) : v) + "</dd></div>";
  };
  o += "<dl class=\"meta\">";
  item("Robot", esc(in.robot));
  item("Cell", esc(in.cell));
  item("Program", esc(in.program));
  item("Process", esc(in.process));
  for (const std::string& res : in.resolutions) item("Frame/tool resolution", esc(res), true);
  if (!in.card_estimates.empty()) {
    std::string e;
    for (const std::string& x : in.card_estimates) e += (e.empty() ? "" : "<br>") + esc(x);
    item("Robot card estimates", "<span class=\"src\">" + e + "</span>", true);
  }
  item("Default position tolerance", "\u2300 " + num(in.default_tolerance_mm, 3) + " mm");
  item("Uncertainty method", esc(in.uncertainty_method));
  if (!in.uncertainty_source.empty()) {
    item("Uncertainty inputs and sources",
         "<span class=\"src\">" + esc(in.uncertainty_source) + "</span>", true);
  }
  o += "</dl>";

  // plain-language summary
  const int m = s.holes;
  std::string sum = "<p class=\"summary\"><strong>" + std::to_string(s.robot_can_take) + " of " +
                    plural(m, "hole", "holes") + " can be taken by the robot</strong> (" +
                    std::to_string(s.conforms) + " conform as programmed, " +
                    std::to_string(s.conforms_after_compensation) +
                    " after compensation), representing <strong>" + num(s.mc_time_taken, 1) +
                    " s</strong> of machining-center time (" +
                    num(pct(s.mc_time_taken, s.mc_time_total), 1) + " % of the " +
                    num(s.mc_time_total, 1) + " s these holes take on the machining center).";
  std::vector<std::string> rest;
  if (s.not_capable) {
    rest.push_back(plural(s.not_capable, "hole is", "holes are") +
                   " not capable: even after compensation the scatter alone exceeds the tolerance");
  }
  if (s.unreachable) rest.push_back(plural(s.unreachable, "hole is", "holes are") + " unreachable");
  if (s.singular) rest.push_back(plural(s.singular, "hole is", "holes are") + " at a singularity");
  if (s.not_converged)
    rest.push_back(plural(s.not_converged, "hole", "holes") + " did not converge");
  if (!rest.empty()) {
    sum += " ";
    for (size_t i = 0; i < rest.size(); ++i) {
      std::string t = rest[i];
      if (i == 0) t[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(t[0])));
      sum += t + (i + 1 == rest.size() ? "." : i + 2 == rest.size() ? " and " : ", ");
    }
  }
  int changes = 0;
  for (const HoleView& h : hv) changes += h.config_change ? 1 : 0;
  sum += " The robot changes its arm/wrist configuration " + plural(changes, "time", "times") +
         " along the program.";
  o += sum + "</p>";

  auto kpi = [&](const std::string& big, const std::string& label, const char* colour) {
    o += std::string("<div class=\"kpi\" style=\"--c:") + colour + "\"><b>" + big + "</b><span>" +
         label + "</span></div>";
  };
  o += "<div class=\"kpis\">";
  kpi(std::to_string(m), "holes in the program", "#8c959f");
  kpi(std::to_string(s.robot_can_take) + " <small>(" + num(pct(s.robot_can_take, m), 0) +
          " %)</small>",
      "robot can take", "#0b5cad");
  kpi(std::to_string(s.conforms), "conform", styleOf(Verdict::kConforms).bar);
  kpi(std::to_string(s.conforms_after_compensation), "conform after compensation",
      styleOf(Verdict::kConformsAfterCompensation).bar);
  kpi(std::to_string(s.not_capable + s.unreachable + s.singular + s.not_converged),
      "stay on the machining center", styleOf(Verdict::kNotCapable).bar);
  kpi(num(s.mc_time_taken, 1) + " s", "machining-center time the robot takes", "#0b5cad");
  o += "</div></header>";
}

void renderMaps(std::string& o, const ReportInput& in, const std::vector<HoleView>& hv) {
  const size_t n = hv.size();
  std::vector<std::optional<double>> q_robot(n), q_err(n), q_res(n), q_U(n);
  for (size_t i = 0; i < n; ++i) {
    if (!hv[i].ok) continue;
    const HolePrediction& p = *hv[i].p;
    q_robot[i] = p.d_robot.norm() * 1e6;
    q_err[i] = p.position_error * 1e6;
    q_U[i] = p.U_work_exact * 1e6;
    if (hv[i].rh->residual_um) {
      q_res[i] = *hv[i].rh->residual_um;
    } else if (hv[i].rh->after != nullptr && hv[i].rh->after->status == HoleStatus::kOk) {
      q_res[i] = hv[i].rh->after->position_error * 1e6;
    }
  }
  const ColourScale s_robot = makeScale({&q_robot});
  const ColourScale s_err = in.compensation ? makeScale({&q_err, &q_res}) : makeScale({&q_err});
  const ColourScale s_U = makeScale({&q_U});

  std::vector<Panel> panels;
  const Panel robot{"|\u03b4robot| \u2014 robot deviation under load", "|\u03b4robot|", &q_robot,
                    &s_robot, ArrowOf::kRobot};
  const Panel U{"U<sub>95</sub> \u2014 95 % radius of the work deviation (anisotropic)",
                "U95",
                &q_U,
                &s_U,
                ArrowOf::kNone,
                false,
                true};
  if (in.compensation) {
    panels.push_back({"Position error \u22a5 axis \u2014 before compensation", "e\u22a5 before",
                      &q_err, &s_err, ArrowOf::kWork, false, true});
    panels.push_back({"Residual \u2014 after compensation", "residual after", &q_res, &s_err,
                      ArrowOf::kNone, true, true});
    panels.push_back(robot);
    panels.push_back(U);
  } else {
    panels.push_back(robot);
    panels.push_back({"Position error \u22a5 axis |\u03b4work\u22a5|", "e\u22a5", &q_err, &s_err,
                      ArrowOf::kWork, false, true});
    panels.push_back(U);
  }

  o += "<section id=\"maps\"><h2>Deviation maps over the work area</h2>";
  o += "<p class=\"note\">Each face is drawn as seen along its drilling direction (into the "
       "material), walls upright (part +Z up), top and bottom faces with the part X axis to the "
       "right; holes at their nominal positions, coordinates in mm in the part frame (<b>" +
       esc(in.part_frame) + "</b>). Colours share one scale per quantity across all faces" +
       std::string(in.compensation ? " (before and after use the same scale)" : "") +
       "; the marker outline shows the verdict" +
       std::string(in.compensation ? " (after compensation on the residual map)" : "") +
       ", the ids of the holes that do not conform are written next to them, and t/2 is "
       "marked on the colour bars of e\u22a5 and U. " +
       (hv.size() > kReportAggregateAbove
            ? "This job has " + std::to_string(hv.size()) +
                  " holes: each square is a bin of holes, filled with its largest value and "
                  "outlined by its worst verdict (hover for the count and the worst ids)."
            : std::string("Hover a marker for the hole id and value.")) +
       "</p>";

  // legend: shapes by branch (those present), configuration change, non-reachable
  std::vector<int> branches;
  std::vector<std::string> branch_config;
  for (const HoleView& h : hv) {
    if (!h.ok) continue;
    if (std::find(branches.begin(), branches.end(), h.p->branch) == branches.end()) {
      branches.push_back(h.p->branch);
      branch_config.push_back(h.p->config);
    }
  }
  std::vector<size_t> idx(branches.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](size_t a, size_t b) { return branches[a] < branches[b]; });
  o += "<div class=\"legend\"><strong>Marker shape = IK branch:</strong>";
  for (const size_t i : idx) {
    o += "<span>" +
         legendIcon(shapePath(branches[i], 11, 11, 6) + " fill=\"#8fbbe6\" stroke=\"#24292f\"/>") +
         "branch " + std::to_string(branches[i]);
    if (!branch_config[i].empty())
      o += " <span class=\"note\">(" + esc(branch_config[i]) + ")</span>";
    o += "</span>";
  }
  o += "<span>" +
       legendIcon(
           "<circle cx=\"11\" cy=\"11\" r=\"5\" fill=\"#8fbbe6\" stroke=\"#24292f\"/><circle "
           "cx=\"11\" "
           "cy=\"11\" r=\"8.5\" fill=\"none\" stroke=\"#e3120b\" stroke-width=\"2\"/>") +
       "configuration change from the previous hole</span>";
  for (const VerdictStyle& vs : kVerdicts) {
    if (vs.verdict == Verdict::kUnreachable || vs.verdict == Verdict::kSingular ||
        vs.verdict == Verdict::kNotConverged)
      continue;
    o += "<span>" +
         legendIcon("<circle cx=\"11\" cy=\"11\" r=\"6\" fill=\"#8fbbe6\" class=\"lg v-" +
                    std::string(vs.cls) + "\"/>") +
         "outline: " + vs.label + "</span>";
  }
  o += "<span>" + legendIcon(crossPath(11, 11, 6, "#57606a") + "/>") +
       "unreachable / singular / not converged</span>";
  o += "<span>" +
       legendIcon(
           "<line x1=\"3\" y1=\"11\" x2=\"14\" y2=\"11\" stroke=\"#1f2328\" "
           "stroke-width=\"1.5\"/><polygon "
           "points=\"20,11 13,7.5 13,14.5\" fill=\"#1f2328\"/>") +
       "direction of \u03b4 at the 3 largest values (not to scale)</span>";
  o += "<span>" +
       legendIcon(
           "<line x1=\"2\" y1=\"11\" x2=\"20\" y2=\"11\" stroke=\"#afb8c1\" stroke-dasharray=\"3 "
           "2\"/>") +
       "program order</span></div>";

  std::vector<FaceGroup> faces = groupFaces(hv, 0.99);
  if (faces.size() > 8) faces = groupFaces(hv, 0.9);
  for (FaceGroup& f : faces) {
    f.R_part_W = in.T_W_part.linear().transpose();
    layoutFace(f, hv);
  }
  for (size_t g = 0; g < faces.size(); ++g) {
    const FaceGroup& f = faces[g];
    int reach = 0;
    for (const size_t i : f.members) reach += hv[i].ok ? 1 : 0;
    const std::string name =
        faces.size() <= 26 ? std::string(1, static_cast<char>('A' + g)) : std::to_string(g + 1);
    o += "<h3 class=\"face\">Face " + name + " <small>\u00b7 drilling direction " +
         esc(dirLabel(f.axis)) + " (part frame) \u00b7 " +
         plural(static_cast<long>(f.members.size()), "hole", "holes") + ", " +
         std::to_string(reach) + " reachable</small></h3>";
    o += std::string("<div class=\"maps") + (panels.size() == 4 ? " four" : "") + "\">";
    for (const Panel& p : panels) renderPanel(o, f, hv, p);
    o += "</div>";
  }
  o += "</section>";
}

void renderVerdicts(std::string& o, const ReportInput& in) {
  const CapabilitySummary& s = in.summary;
  const std::array<int, 6> counts{s.conforms,    s.conforms_after_compensation,
                                  s.not_capable, s.unreachable,
                                  s.singular,    s.not_converged};
  const int cmax = std::max(1, *std::max_element(counts.begin(), counts.end()));
  o += "<section id=\"verdicts\"><h2>Verdicts and capability</h2><div class=\"two\">";
  o += "<div class=\"card vbars\"><h3>Verdict per hole (ISO 14253-1 guard band)</h3>";
  constexpr double kRow = 30, kLabel = 200, kBar = 330;
  o += "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 640 " + num(kRow * 6 + 8, 0) +
       "\" role=\"img\" aria-label=\"verdict counts\">";
  for (size_t i = 0; i < kVerdicts.size(); ++i) {
    const double y = 4 + kRow * static_cast<double>(i);
    const double w = kBar * counts[i] / cmax;
    o += "<text x=\"" + num(kLabel - 10, 0) + "\" y=\"" + num(y + 19, 1) +
         "\" text-anchor=\"end\" class=\"axis\">" + kVerdicts[i].label + "</text>";
    o += "<rect x=\"" + num(kLabel, 0) + "\" y=\"" + num(y + 5, 1) + "\" width=\"" + num(kBar, 1) +
         "\" height=\"20\" rx=\"3\" fill=\"#f0f3f6\"/>";
    if (counts[i] > 0) {
      o += "<rect x=\"" + num(kLabel, 0) + "\" y=\"" + num(y + 5, 1) + "\" width=\"" +
           num(std::max(w, 2.0), 1) + "\" height=\"20\" rx=\"3\" fill=\"" + kVerdicts[i].bar +
           "\"/>";
    }
    o += "<text x=\"" + num(kLabel + kBar + 10, 0) + "\" y=\"" + num(y + 19, 1) +
         "\" class=\"axis\"><tspan font-weight=\"600\">" + std::to_string(counts[i]) +
         "</tspan> (" + num(pct(counts[i], s.holes), 1) + " %)</text>";
  }
  o += "</svg>";
  o += "<p class=\"note\">t = position tolerance \u2300, e\u22a5 = predicted position error \u22a5 "
       "the hole axis, "
       "U = U<sub>95</sub>, the 95 % radius of the anisotropic in-plane distribution (\u2265 "
       "U<sub>work</sub>). "
       "<b>conforms</b>: e\u22a5 + U \u2264 t/2; <b>conforms after "
       "compensation</b>: "
       "U \u2264 t/2 &lt; e\u22a5 + U (the systematic part is too large but can be compensated); "
       "<b>not capable</b>: U &gt; t/2 (the scatter alone is too large).</p></div>";

  const double share_taken = pct(s.mc_time_taken, s.mc_time_total);
  o += "<div class=\"card\"><h3>Capability \u2014 what the robot can take from the machining "
       "center</h3>";
  o += "<div class=\"big\">" + std::to_string(s.robot_can_take) + " <small>of " +
       plural(s.holes, "hole", "holes") + " (" + num(pct(s.robot_can_take, s.holes), 1) +
       " %)</small></div>";
  o += "<div class=\"meter\"><i style=\"width:" + num(pct(s.robot_can_take, s.holes), 2) +
       "%\"></i></div>";
  o += "<div class=\"big\">" + num(s.mc_time_taken, 1) + " s <small>of " + num(s.mc_time_total, 1) +
       " s machining-center time (" + num(share_taken, 1) + " %)</small></div>";
  o += "<div class=\"meter\"><i style=\"width:" + num(share_taken, 2) +
       "%;background:#0b5cad\"></i></div>";
  o += "<p>Drilling these holes on the robot instead of the machining center frees <strong>" +
       num(s.mc_time_taken, 1) + " s</strong> of machining-center time per part (" +
       num(share_taken, 1) + " % of its drilling time); " +
       plural(s.holes - s.robot_can_take, "hole", "holes") + " (" +
       num(s.mc_time_total - s.mc_time_taken, 1) + " s) stay on the machining center.</p>";
  o += "<p class=\"note\">Machining-center time per hole = depth / feed rate + positioning and "
       "approach. Process "
       "share of the total uncertainty (variance share): mean " +
       num(100 * s.mean_process_share, 1) + " %, max " + num(100 * s.max_process_share, 1) +
       " %.</p></div>";
  o += "</div></section>";
}

void renderBudget(std::string& o, const std::vector<HoleView>& hv) {
  std::vector<TermStats> terms;
  double k = 0;
  int n_ok = 0;
  struct Agg {
    double sum{0}, max{0};
  };
  std::array<Agg, 6> agg{};  // u_robot u_mach u_work U_robot U_mach U_work
  double share_sum = 0, share_max = 0;
  for (const HoleView& h : hv) {
    if (!h.ok) continue;
    const HolePrediction& p = *h.p;
    ++n_ok;
    if (k == 0) k = p.k;
    const double uw2 = p.u_work * p.u_work;
    for (const BudgetTerm& b : p.budget) {
      const std::string name = b.name ? b.name : "";
      auto it = std::find_if(terms.begin(), terms.end(),
                             [&](const TermStats& t) { return t.name == name; });
      if (it == terms.end()) {
        terms.push_back({name, b.process});
        it = terms.end() - 1;
      }
      it->sum_u += b.u;
      it->max_u = std::max(it->max_u, b.u);
      it->sum_share += uw2 > 0 ? b.u * b.u / uw2 : 0.0;
      ++it->n;
    }
    const std::array<double, 6> v{p.u_robot, p.u_mach, p.u_work, p.U_robot, p.U_mach, p.U_work};
    for (size_t i = 0; i < 6; ++i) {
      agg[i].sum += v[i];
      agg[i].max = std::max(agg[i].max, v[i]);
    }
    share_sum += p.process_share;
    share_max = std::max(share_max, p.process_share);
  }
  o += "<section id=\"budget\"><h2>Uncertainty budget</h2>";
  if (n_ok == 0) {
    o += "<p>No hole could be predicted, so there is no budget to show.</p></section>";
    return;
  }
  // colours: robot terms blue, process terms orange, in order of appearance
  std::vector<std::string> colours;
  colours.reserve(terms.size());
  size_t nr = 0, np = 0;
  for (const TermStats& t : terms) {
    colours.emplace_back(t.process ? kProcessColours[np++ % kProcessColours.size()]
                                   : kRobotColours[nr++ % kRobotColours.size()]);
  }
  o += "<p class=\"note\">Per-axis standard uncertainties in the plane \u22a5 the hole axis, "
       "independent terms "
       "combined by root-sum-square (GUM, JCGM 100:2008): u<sub>robot</sub>\u00b2 = "
       "u<sub>repeatability</sub>\u00b2 "
       "+ u<sub>deflection</sub>\u00b2, u<sub>mach</sub>\u00b2 = \u03a3 process terms, "
       "u<sub>work</sub>\u00b2 = "
       "u<sub>robot</sub>\u00b2 + u<sub>mach</sub>\u00b2. Statistics over the " +
       plural(n_ok, "predicted hole", "predicted holes") + ".</p>";
  o += "<div class=\"stack\">";
  size_t nr_seen = 0, np_seen = 0;
  for (size_t i = 0; i < terms.size(); ++i) {
    const double sh = 100.0 * terms[i].sum_share / n_ok;
    const TermInfo* info = termInfo(terms[i].name);
    const std::string label = info ? std::string(info->label) : esc(terms[i].name);
    const bool light = (terms[i].process ? np_seen : nr_seen) >= 2;
    (terms[i].process ? np_seen : nr_seen)++;
    o += "<span" + std::string(light ? " class=\"lt\"" : "") + " style=\"width:" + num(sh, 3) +
         "%;background:" + colours[i] + "\" title=\"" + label + ": " + num(sh, 1) + " %\">" +
         (sh >= 7.0 ? label + " " + num(sh, 0) + " %" : "") + "</span>";
  }
  o += "</div>";
  o += "<table class=\"budget\"><thead><tr><th class=\"l\">Term</th><th "
       "class=\"l\">Basis</th><th>Part of</th>"
       "<th>mean u [\u00b5m]</th><th>max u [\u00b5m]</th><th class=\"l\">mean variance "
       "share</th></tr></thead><tbody>";
  for (size_t i = 0; i < terms.size(); ++i) {
    const TermStats& t = terms[i];
    const TermInfo* info = termInfo(t.name);
    const double sh = 100.0 * t.sum_share / n_ok;
    o += "<tr><td class=\"l\"><span class=\"sw\" style=\"background:" + colours[i] + "\"></span>" +
         (info ? std::string(info->label) : esc(t.name)) + "</td><td class=\"l note\">" +
         (info ? std::string(info->basis) : esc(t.name)) + "</td><td>" +
         (t.process ? "process" : "robot") + "</td><td>" + num(t.sum_u / t.n * 1e6, 2) +
         "</td><td>" + num(t.max_u * 1e6, 2) + "</td><td class=\"l\">" + num(sh, 1) +
         " %<span class=\"share\" style=\"width:" + num(1.6 * sh, 1) +
         "px;background:" + colours[i] + "\"></span></td></tr>";
  }
  const std::array<const char*, 6> names{"u<sub>robot</sub>", "u<sub>mach</sub>",
                                         "u<sub>work</sub>",  "U<sub>robot</sub>",
                                         "U<sub>mach</sub>",  "U<sub>work</sub>"};
  const std::array<const char*, 6> basis{
      "combined standard, per axis", "combined standard, per axis", "combined standard, per axis",
      "expanded radial, k \u00b7 u", "expanded radial, k \u00b7 u", "expanded radial, k \u00b7 u"};
  for (size_t i = 0; i < 6; ++i) {
    o += std::string("<tr class=\"sum\"><td class=\"l\">") + names[i] +
         "</td><td class=\"l note\">" + basis[i] + "</td><td></td><td class=\"n\">" +
         num(agg[i].sum / n_ok * 1e6, 2) + "</td><td class=\"n\">" + num(agg[i].max * 1e6, 2) +
         "</td><td class=\"l\">" + (i == 2 ? "100 %" : "") + "</td></tr>";
  }
  o += "</tbody></table>";
  o += "<p>Coverage factor <strong>k = " + num(k, 3) +
       "</strong>: the position error is a 2-D radius; for an isotropic normal scatter with u per "
       "axis the radius is "
       "Rayleigh-distributed and P(r \u2264 k u) = 95 % needs k = \u221a(\u22122 ln 0.05) = 2.448 "
       "(k = 2 would "
       "cover only 86 % of the radius; docs/process.md \u00a75.1). U<sub>work</sub> = "
       "\u221a(U<sub>robot</sub>\u00b2 + "
       "U<sub>mach</sub>\u00b2) = k \u00b7 u<sub>work</sub> is the isotropic equivalent; the "
       "verdict uses "
       "U<sub>95</sub>, the exact 95 % radius of the anisotropic in-plane distribution (\u2265 "
       "U<sub>work</sub>).</p>";
  o += "<p>Process share of the total uncertainty (variance share of the process terms in "
       "u<sub>work</sub>\u00b2): "
       "<strong>mean " +
       num(100.0 * share_sum / n_ok, 1) + " %</strong>, max " + num(100.0 * share_max, 1) +
       " % (as a linear share of u<sub>work</sub>: mean " +
       num(100.0 * std::sqrt(share_sum / n_ok), 1) + " %).</p>";
  o += "</section>";
}

/// One numeric cell; non-finite / absent → an em dash (sorts last).
std::string numCell(double v, int decimals) { return "<td>" + num(v, decimals) + "</td>"; }
std::string dashCells(int n) {
  std::string s;
  for (int i = 0; i < n; ++i) s += "<td>" + std::string(kDash) + "</td>";
  return s;
}

struct Column {
  std::string head;  ///< HTML
  std::string unit;  ///< shown under the head
  bool text{false};  ///< sorts as text, left-aligned
};

/// The budget terms in first-seen order over the predicted holes.
std::vector<std::string> budgetNames(const std::vector<HoleView>& hv) {
  std::vector<std::string> names;
  for (const HoleView& h : hv) {
    if (!h.ok) continue;
    for (const BudgetTerm& b : h.p->budget) {
      const std::string n = b.name ? b.name : "";
      if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
    }
  }
  return names;
}

const char* shortTerm(const std::string& name) {
  static constexpr std::array<std::array<const char*, 2>, 7> kShort{{
      {"robot_repeatability", "u repeat."},
      {"robot_absolute_accuracy", "u abs. acc."},
      {"robot_deflection_model", "u defl. model"},
      {"robot_deflection_process_force", "u defl. force"},
      {"mach_axis", "u axis"},
      {"mach_runout", "u runout"},
      {"mach_tool_deflection", "u tool defl."},
  }};
  for (const auto& s : kShort) {
    if (name == s[0]) return s[1];
  }
  return nullptr;
}

/// Offset applied to a target: programmed − original position (mm, base frame) and the angle of
/// the rotation between them (deg).
struct Offset {
  Vec3 dp_mm{Vec3::Zero()};
  double angle_deg{0};
};
Offset offsetOf(const ReportHole& rh) {
  Offset off;
  if (!rh.T_W_programmed) return off;
  off.dp_mm = (rh.T_W_programmed->translation() - rh.T_W_tcp.translation()) * 1e3;
  const Eigen::AngleAxisd aa(rh.T_W_tcp.linear().transpose() * rh.T_W_programmed->linear());
  off.angle_deg = std::abs(aa.angle()) * 180.0 / kPi;
  return off;
}

bool passes(const HoleView& h) {
  const Verdict v = h.rh->after != nullptr ? h.rh->after->verdict : h.p->verdict;
  return v == Verdict::kConforms;
}

constexpr size_t kTableRowsPerPage = 200;  ///< rows a page of a large job's table

/// A string as a JavaScript string literal (no "</" so it cannot end the script element).
std::string jsString(std::string_view v) {
  std::string s = "\"";
  for (size_t i = 0; i < v.size(); ++i) {
    const char c = v[i];
    if (c == '\\' || c == '"') s += '\\';
    if (c == '/' && i > 0 && v[i - 1] == '<') s += '\\';
    if (c == '\n') {
      s += "\\n";
      continue;
    }
    if (c == '\x1f') {
      s += "\\x1f";
      continue;
    }
    s += c;
  }
  return s + "\"";
}

/// The joints as the table shows them: the controller's convention when the card is known.
Vec6 shownJoints(const ReportInput& in, const Vec6& q_urdf) {
  return in.card != nullptr ? toControllerJoints(*in.card, q_urdf) : q_urdf;
}

/// The table note on the joint convention (the J columns' unit line says "ctrl" or "URDF").
std::string jointConventionText(const ReportInput& in) {
  if (in.card == nullptr) return "Joints J1\u2013J6: motor-side command, URDF convention.";
  std::string s = "Joints J1\u2013J6: motor-side command as the " +
                  esc(vendorName(in.card->vendor)) +
                  " controller shows it (\u03b8<sub>ctrl</sub> = sign\u00b7\u03b8<sub>URDF</sub> "
                  "+ offset";
  if (in.card->j23_coupling != 0.0) {
    s += "; J3<sub>ctrl</sub> = J3<sub>URDF</sub> " +
         std::string(in.card->j23_coupling < 0 ? "\u2212 " : "+ ") +
         (std::fabs(in.card->j23_coupling) == 1.0
              ? ""
              : num(std::fabs(in.card->j23_coupling), 3) + "\u00b7") +
         "J2<sub>URDF</sub>";
  }
  return s + ").";
}

/// A text cell with a reason (dash when there is none).
std::string reasonCell(const std::string& reason) {
  return "<td class=\"l why\">" + (reason.empty() ? std::string(kDash) : esc(reason)) + "</td>";
}

void renderTable(std::string& o, const ReportInput& in, const std::vector<HoleView>& hv) {
  const std::vector<std::string> terms = budgetNames(hv);
  const bool has_split =
      std::any_of(hv.begin(), hv.end(), [](const HoleView& h) { return h.rh->split.has_value(); });
  std::vector<Column> cols{{"#", "", false},
                           {"Hole", "", true},
                           {in.compensation ? "Verdict before" : "Verdict", "", true},
                           {"e\u22a5", "\u00b5m"},
                           {"U<sub>95</sub>", "\u00b5m"},
                           {"e\u22a5 + U", "\u00b5m"},
                           {"t/2", "\u00b5m"},
                           {"|\u03b4robot|", "\u00b5m"}};
  if (has_split) {
    for (const char* part : {"gravity", "tool weight", "process", "controller"})
      cols.push_back({std::string("\u2192 ") + part, "\u00b5m"});
  }
  for (const char* c : {"\u03b4robot x", "\u03b4robot y", "\u03b4robot z", "\u03b4mach x",
                        "\u03b4mach y", "\u03b4mach z"})
    cols.push_back({c, "\u00b5m"});
  cols.push_back({"tilt", "\u00b5rad"});
  for (const std::string& t : terms) {
    const char* sh = shortTerm(t);
    cols.push_back({sh ? std::string(sh) : esc(t), "\u00b5m"});
  }
  cols.push_back({"U<sub>robot</sub>", "\u00b5m"});
  cols.push_back({"U<sub>mach</sub>", "\u00b5m"});
  cols.push_back({"\u2300", "mm"});
  cols.push_back({"Config", "", true});
  cols.push_back({"Br.", ""});
  const std::string jconv = in.card != nullptr ? "deg, ctrl" : "deg, URDF";
  for (int j = 1; j <= 6; ++j) cols.push_back({"J" + std::to_string(j), jconv});
  cols.push_back({"MC", "s"});
  if (in.compensation) {
    for (const char* c : {"\u0394x", "\u0394y", "\u0394z", "|\u0394p|"}) cols.push_back({c, "mm"});
    cols.push_back({"\u0394rot", "deg"});
    cols.push_back({"rot. about axis", "deg"});
    cols.push_back({"Why rotated", "", true});
    cols.push_back({"Config before \u2192 after", "", true});
    cols.push_back({"Why config changed", "", true});
    cols.push_back({"Verdict after", "", true});
    cols.push_back({"Residual", "\u00b5m"});
  }

  const bool large = hv.size() > kReportAggregateAbove;
  size_t n_fail = 0;
  for (const HoleView& h : hv) n_fail += passes(h) ? 0 : 1;
  o += "<section id=\"holes\"><h2>Per-hole results</h2>";
  o += "<p class=\"note\">In program order; click a column head to sort, tick \u201cnot "
       "conforming only\u201d to filter. e\u22a5 = |\u03b4work \u22a5 hole axis|, U = "
       "U<sub>95</sub> "
       "(k as above): the hole conforms when e\u22a5 + U \u2264 t/2. Deviations in the robot base "
       "frame. ";
  if (has_split) {
    o += "Why: the \u2192 columns split |\u03b4robot| into the parts caused by the arm's own "
         "weight, the tool weight, the process load and the controller reference (its gravity "
         "compensation or mastering offset), each part's component along \u03b4robot, so the four "
         "add up to |\u03b4robot| (hover for the part's vector; docs/reports.md \u00a73). ";
  }
  o += "u = per-axis standard uncertainty of each budget term. " + jointConventionText(in) +
       " A ringed branch marks a configuration change from the previous hole.";
  if (in.compensation) {
    o += " \u0394 = the offset applied to the target (programmed \u2212 original, base frame).";
  }
  o += "</p>";
  if (large) {
    o += "<p><strong>" + std::to_string(hv.size()) + " holes: the table shows " +
         std::to_string(kTableRowsPerPage) +
         " rows a page (sorting and filtering act on every hole).</strong></p>";
  }
  o += "<label class=\"filter\"><input type=\"checkbox\" id=\"failonly\"> not conforming only (" +
       std::to_string(n_fail) + ")</label>";
  o += "<div class=\"scroll\"><table class=\"holes\" id=\"holetable\"><thead><tr>";
  for (size_t c = 0; c < cols.size(); ++c) {
    o += "<th" +
         std::string(c == 0         ? " class=\"c0\""
                     : c == 1       ? " class=\"l c1\""
                     : cols[c].text ? " class=\"l\""
                                    : "") +
         (cols[c].text ? " data-t=\"1\"" : "") + ">" + cols[c].head;
    if (!cols[c].unit.empty()) o += "<br><small>" + cols[c].unit + "</small>";
    o += "</th>";
  }
  o += "</tr></thead><tbody>";
  std::string rows_js;  // large jobs: the rows as a script array, a page at a time in the DOM
  for (size_t i = 0; i < hv.size(); ++i) {
    const HoleView& h = hv[i];
    const HolePrediction& p = *h.p;
    const bool pass = passes(h);
    const size_t row_start = o.size();
    const VerdictStyle& vs = styleOf(p.verdict);
    o += std::string("<tr") + (pass ? " class=\"pass\"" : "") + "><td class=\"c0\">" +
         std::to_string(i + 1) + "</td><td class=\"id c1\">" + esc(p.id) +
         "</td><td class=\"l\"><span class=\"badge b-" + vs.cls + "\" title=\"" +
         verdictName(p.verdict) + "\">" + vs.badge + "</span></td>";
    const double t2 = 0.5 * p.tolerance * 1e6;
    if (h.ok) {
      const double e = p.position_error * 1e6, U = p.U_work_exact * 1e6;
      o += "<td><strong>" + num(e, 1) + "</strong></td>" + numCell(U, 1) + numCell(e + U, 1) +
           numCell(t2, 1) + numCell(p.d_robot.norm() * 1e6, 1);
      if (has_split) {
        if (h.rh->split) {
          const DeviationSplit& s = *h.rh->split;
          const double n = p.d_robot.norm();
          const Vec3 u = n > 0 ? Vec3(p.d_robot / n) : Vec3::Zero();
          for (const Vec3* part : {&s.gravity, &s.tool, &s.process, &s.controller}) {
            const Vec3 um = *part * 1e6;
            if (large) {  // the vectors only where the table is small (bytes, load time)
              o += numCell(part->dot(u) * 1e6, 1);
            } else {
              o += "<td title=\"(" + num(um.x(), 1) + ", " + num(um.y(), 1) + ", " +
                   num(um.z(), 1) + ") \u00b5m\">" + num(part->dot(u) * 1e6, 1) + "</td>";
            }
          }
        } else {
          o += dashCells(4);
        }
      }
      for (int k = 0; k < 3; ++k) o += numCell(p.d_robot[k] * 1e6, 1);
      for (int k = 0; k < 3; ++k) o += numCell(p.d_mach[k] * 1e6, 1);
      o += numCell(p.axis_tilt * 1e6, 1);
      for (const std::string& t : terms) {
        auto it = std::find_if(p.budget.begin(), p.budget.end(),
                               [&](const BudgetTerm& b) { return t == (b.name ? b.name : ""); });
        o += it == p.budget.end() ? dashCells(1) : numCell(it->u * 1e6, 2);
      }
      o += numCell(p.U_robot * 1e6, 1) + numCell(p.U_mach * 1e6, 1);
    } else {
      const int span = 14 + (has_split ? 4 : 0) + static_cast<int>(terms.size());
      o += "<td class=\"reason\" colspan=\"" + std::to_string(span) + "\">" +
           (p.reason.empty() ? std::string(verdictName(p.verdict)) : esc(p.reason)) + "</td>";
    }
    o += numCell(p.diameter * 1e3, 2) + "<td class=\"l\">" +
         (p.config.empty() ? kDash : esc(p.config)) + "</td>";
    const bool has_joints = h.ok || !p.config.empty();
    if (h.config_change) {
      o += "<td class=\"chg\" title=\"configuration change: branch " +
           std::to_string(h.prev_branch) + " \u2192 " + std::to_string(p.branch) + "\"><b>" +
           std::to_string(p.branch) + "</b></td>";
    } else {
      o += "<td>" + (has_joints ? std::to_string(p.branch) : std::string(kDash)) + "</td>";
    }
    const Vec6 q = shownJoints(in, p.joints);
    for (int j = 0; j < 6; ++j) o += has_joints ? numCell(q[j] * 180.0 / kPi, 1) : dashCells(1);
    o += numCell(p.mc_time, 2);
    if (in.compensation) {
      const ReportHole& rh = *h.rh;
      if (rh.T_W_programmed) {
        const Offset off = offsetOf(rh);
        for (int k = 0; k < 3; ++k) o += numCell(off.dp_mm[k], 3);
        o += numCell(off.dp_mm.norm(), 3) + numCell(off.angle_deg, 3);
        const std::string& cb = rh.config_before.empty() ? p.config : rh.config_before;
        const std::string before = cb.empty() ? std::string(kDash) : esc(cb);
        const std::string after = rh.config_after ? esc(*rh.config_after) : before;
        o += rh.rotation_about_axis_deg ? numCell(*rh.rotation_about_axis_deg, 2) : dashCells(1);
        o += reasonCell(rh.rotation_reason);
        strAppend(o, "<td class=\"l", after != before ? " cfgchg" : "", "\">", before, " \u2192 ",
                  after, "</td>");
        o += reasonCell(rh.config_reason);
      } else {
        o += dashCells(5);
        o += rh.rotation_about_axis_deg ? numCell(*rh.rotation_about_axis_deg, 2) : dashCells(1);
        o += reasonCell(rh.rotation_reason) + "<td class=\"l\">" + std::string(kDash) + "</td>" +
             reasonCell(rh.config_reason);
      }
      const Verdict va = rh.after != nullptr ? rh.after->verdict : p.verdict;
      const VerdictStyle& vsa = styleOf(va);
      o += "<td class=\"l\"><span class=\"badge b-" + std::string(vsa.cls) + "\" title=\"" +
           verdictName(va) + "\">" + vsa.badge + "</span></td>" +
           (rh.residual_um ? numCell(*rh.residual_um, 1) : dashCells(1));
    }
    o += "</tr>";
    if (large) {
      // "</td><td" → the unit separator (JS "\x1f"): the rows are half the bytes; the script
      // joins them back for the page it shows
      std::string row = o.substr(row_start);
      std::string packed;
      packed.reserve(row.size());
      for (size_t k = 0; k < row.size();) {
        if (row.compare(k, 8, "</td><td") == 0) {
          packed += '\x1f';
          k += 8;
        } else {
          packed += row[k++];
        }
      }
      rows_js += (rows_js.empty() ? "" : ",\n") + jsString(packed);
      o.resize(row_start);
    }
  }
  o += "</tbody></table></div>";
  if (large) {
    o += "<div class=\"pager\" id=\"pager\"><button class=\"prev\">\u25c0 previous</button> "
         "<span></span> <button class=\"next\">next \u25b6</button></div>";
  }
  o += "</section>";
  o += "<script>";
  if (large) {
    o += "var ROPREC_ROWS=[" + rows_js + "];";
    o += kPagedTableScript;
  } else {
    o += kTableScript;
  }
  o += "</script>";
}

void renderFooter(std::string& o, const ReportInput& in) {
  o += "<footer><p>Generated by " + esc(in.generator) +
       ". Self-contained document: no network resources; one inline script sorts and filters the "
       "table.</p>"
       "<p>Conventions: SI inside; positions in mm and joints in degrees; deviations and "
       "uncertainties in "
       "\u00b5m, tilts in \u00b5rad; the robot base frame (URDF root link) for all vectors; TCP = "
       "flange \u00d7 "
       "tool frame, tool +z = drilling direction. \u03b4work = \u03b4robot + \u03b4mach; the "
       "position error "
       "e\u22a5 is the part of \u03b4work \u22a5 the hole axis. Position tolerance \u2300t per ISO "
       "1101 (the axis "
       "must lie in a cylinder of diameter t, i.e. e\u22a5 \u2264 t/2).</p>"
       "<p>Decision rule ISO 14253-1 (guard band g = U): conformance is proven only when e\u22a5 + "
       "U<sub>work</sub> "
       "\u2264 t/2. U<sub>work</sub> is the expanded 2-D radial uncertainty with the Rayleigh "
       "coverage factor "
       "(95 %). Ferreras-Higuero et al., Robotics and Computer-Integrated Manufacturing (2020), "
       "give the method "
       "this report follows.</p></footer>";
}

}  // namespace

std::string viridisHex(double t) { return hex(viridis(t)); }

const char* reportTableScript() { return kTableScript; }

void addPartFrameAndSplit(ReportInput& in, const PredictionContext& c) {
  const JobHoles& job = c.job;
  if (in.holes.size() != job.requests.size())
    throw std::invalid_argument("addPartFrameAndSplit: one report hole per request expected");
  // the part frame: the frame all holes' targets are given in, if they share one
  in.T_W_part = c.cell.T_base_wobj;
  in.part_frame = "cell workobject";
  if (!job.sources.empty()) {
    const HoleSource& s0 = job.sources.front();
    const bool shared =
        std::all_of(job.sources.begin(), job.sources.end(), [&](const HoleSource& s) {
          return s.frame_ref == s0.frame_ref && s.T_W_frame.isApprox(s0.T_W_frame, 1e-12);
        });
    if (shared) {
      in.T_W_part = s0.T_W_frame;
      if (!s0.frame_ref.empty()) in.part_frame = s0.frame_ref;
    }
  }
  std::vector<const HolePrediction*> preds;
  preds.reserve(in.holes.size());
  for (const ReportHole& h : in.holes) preds.push_back(h.prediction);
  const auto splits = splitRobotDeviations(c.model, c.tool, job.requests, preds);
  for (size_t i = 0; i < in.holes.size(); ++i) in.holes[i].split = splits[i];
}

std::string renderReport(const ReportInput& in) {
  const std::vector<HoleView> hv = holeViews(in);
  std::string o;
  o.reserve(65536 + 4096 * hv.size());
  o += "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
       "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
       "<meta name=\"generator\" content=\"" +
       esc(in.generator) + "\"><title>" + esc(in.title) + "</title><style>" + kCss +
       "</style></head><body><main>\n";
  renderHeader(o, in, hv);
  o += "\n";
  renderMaps(o, in, hv);
  o += "\n";
  renderVerdicts(o, in);
  o += "\n";
  renderBudget(o, hv);
  o += "\n";
  renderTable(o, in, hv);
  o += "\n";
  renderFooter(o, in);
  o += "\n</main></body></html>\n";
  return o;
}

}  // namespace roprec::api
