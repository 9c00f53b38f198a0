/// \file hole_maps.cpp
/// The hole report's deviation maps (hole_sections.hpp): per face group, one panel per quantity
/// (|δrobot|, e⊥ or the residual, U₉₅), markers shaped by IK branch and outlined by verdict.
///
/// Each face group (holes whose drilling axes agree within dot > 0.99, first-seen order) is drawn
/// as seen along its mean drilling direction a, with u × v = −a pointing at the viewer (a true
/// view, not mirrored), v = u × a. Walls (|a_z| < 0.9) are drawn upright: v = part +z projected
/// on the face, u = a × v. Top and bottom faces: u = the part X axis, else the principal
/// direction of the hole positions projected on the plane ⊥ a (PCA; its largest-magnitude
/// component made positive). Coordinates are p·u and p·v in mm (part frame), equal scale on
/// both axes.

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <span>

#include "plugin/report/hole_sections.hpp"
#include "plugin/report/palette.hpp"

namespace roprec::report {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMarginL = 58, kMarginR = 16, kMarginT = 12, kPanelW = 440;
constexpr size_t kMaxFailLabels = 24;  ///< per panel; the rest are in the table
constexpr double kBin = 7.0;           ///< px, the square bins of a large job's map

// ------------------------------------------------------------------ colour scales

struct ColourScale {
  bool valid{false};
  double data_min{0}, data_max{0};
  double lo{0}, hi{1}, step{1};
  [[nodiscard]] double t(double v) const { return hi > lo ? (v - lo) / (hi - lo) : 0.5; }
};

using Values = std::vector<std::optional<double>>;  ///< per hole, µm; empty: not shown

/// One scale over every value of the sets, its ends on multiples of a nice step.
ColourScale makeScale(const std::vector<const Values*>& sets) {
  ColourScale s;
  for (const Values* set : sets) {
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

// ------------------------------------------------------------------ face groups

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

  [[nodiscard]] double px(double x) const { return kMarginL + (x - x0) * s; }
  [[nodiscard]] double py(double y) const { return kMarginT + (y1 - y) * s; }
  /// Member k on the screen.
  [[nodiscard]] Eigen::Vector2d screen(size_t k) const { return {px(xy[k].x()), py(xy[k].y())}; }
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

/// The screen's right direction u of a face (see the file comment); sets f.axis to the mean
/// drilling direction.
Vec3 screenRight(FaceGroup& f, const std::vector<HoleView>& hv) {
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
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
  if (std::abs(f.axis.z()) > 0.9995) return Vec3::UnitX();  // top/bottom: the part's own X
  if (std::abs(f.axis.z()) < 0.9) return f.axis.cross((P * Vec3::UnitZ()).normalized());  // wall
  if (es.info() == Eigen::Success && es.eigenvalues()[2] > 1e-9 * std::max(1.0, C.trace())) {
    return P * es.eigenvectors().col(2);
  }
  // one hole (or coincident holes): the base axis least aligned with the drilling axis
  Eigen::Index k = 0;
  f.axis.cwiseAbs().minCoeff(&k);
  return P * Vec3::Unit(k);
}

/// u normalised; on a top or bottom face its largest-magnitude component made positive.
Vec3 signedRight(const FaceGroup& f, Vec3 u) {
  u.normalize();
  if (std::abs(f.axis.z()) < 0.9) return u;
  Eigen::Index big = 0;
  const double m = u.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < 3; ++i) {
    if (std::abs(u[i]) > m - 1e-9) {
      big = i;
      break;
    }
  }
  return u[big] < 0 ? Vec3(-u) : u;
}

/// The members' screen coordinates (mm) and the plot's size and scale around them.
void fitToPlot(FaceGroup& f, const std::vector<HoleView>& hv) {
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
}

/// Marker size from the median nearest-neighbour spacing on screen (px).
double markerRadius(const FaceGroup& f) {
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
  if (nn.empty()) return n > 4000 ? 3.0 : 6.0;
  std::nth_element(nn.begin(), nn.begin() + static_cast<long>(nn.size() / 2), nn.end());
  return std::clamp(0.4 * nn[nn.size() / 2], 3.0, 6.5);
}

void layoutFace(FaceGroup& f, const std::vector<HoleView>& hv) {
  f.u = signedRight(f, screenRight(f, hv));
  f.v = f.u.cross(f.axis).normalized();
  fitToPlot(f, hv);
  f.marker_r = markerRadius(f);
}

/// The face groups (tighter grouping first; coarser when that gives more than 8 faces), laid out.
std::vector<FaceGroup> faceGroups(const ReportInput& in, const std::vector<HoleView>& hv) {
  std::vector<FaceGroup> faces = groupFaces(hv, 0.99);
  if (faces.size() > 8) faces = groupFaces(hv, 0.9);
  for (FaceGroup& f : faces) {
    f.R_part_W = in.T_W_part.linear().transpose();
    layoutFace(f, hv);
  }
  return faces;
}

// ------------------------------------------------------------------ marker shapes

/// A regular polygon of n corners (the first at angle `rot`), radius rr, around (x, y).
std::string polygonPoints(double x, double y, int n, double rot, double rr) {
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < n; ++i) {
    const double a = rot + 2.0 * kPi * i / n;
    pts.emplace_back(x + rr * std::cos(a), y + rr * std::sin(a));
  }
  return svgPoints(pts, 2);
}

std::string starPoints(double x, double y, double r) {
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < 10; ++i) {
    const double a = -kPi / 2 + kPi * i / 5;
    const double rr = (i % 2 ? 0.5 : 1.35) * r;
    pts.emplace_back(x + rr * std::cos(a), y + rr * std::sin(a));
  }
  return svgPoints(pts, 2);
}

/// The marker of IK branch `branch` (mod 8: circle, square, diamond, four triangles, star) at
/// (x, y), radius r, followed by the `extra` attributes.
void marker(Html& h, int branch, double x, double y, double r, Attrs extra) {
  std::vector<Attr> a;
  const char* tag = "polygon";
  switch (((branch % 8) + 8) % 8) {
    case 0:
      tag = "circle";
      a = {{"cx", fixed(x, 2)}, {"cy", fixed(y, 2)}, {"r", fixed(r, 2)}};
      break;
    case 1:
      tag = "rect";
      a = {{"x", fixed(x - 0.9 * r, 2)},
           {"y", fixed(y - 0.9 * r, 2)},
           {"width", fixed(2 * (0.9 * r), 2)},
           {"height", fixed(2 * (0.9 * r), 2)}};
      break;
    case 2:
      a = {Attr::markup("points", polygonPoints(x, y, 4, 0.0, 1.2 * r))};
      break;
    case 3:
      a = {Attr::markup("points", polygonPoints(x, y, 3, -kPi / 2, 1.25 * r))};
      break;
    case 4:
      a = {Attr::markup("points", polygonPoints(x, y, 3, kPi / 2, 1.25 * r))};
      break;
    case 5:
      a = {Attr::markup("points", polygonPoints(x, y, 3, 0.0, 1.25 * r))};
      break;
    case 6:
      a = {Attr::markup("points", polygonPoints(x, y, 3, kPi, 1.25 * r))};
      break;
    default:
      a = {Attr::markup("points", starPoints(x, y, r))};
  }
  a.insert(a.end(), extra.begin(), extra.end());
  h.leaf(tag, a);
}

/// The cross of a hole that was not predicted.
void cross(Html& h, double x, double y, double r, const char* colour) {
  const double e = 0.95 * r;
  h.leaf("path",
         {Attr::markup("d", "M" + num(x - e, 2) + " " + num(y - e, 2) + "L" + num(x + e, 2) + " " +
                                num(y + e, 2) + "M" + num(x - e, 2) + " " + num(y + e, 2) + "L" +
                                num(x + e, 2) + " " + num(y - e, 2)),
          {"stroke", colour},
          {"stroke-width", "2.2"},
          {"stroke-linecap", "round"},
          {"fill", "none"}});
}

// ------------------------------------------------------------------ panels

enum class ArrowOf { kNone, kRobot, kWork };

struct Panel {
  std::string title;     ///< markup
  std::string quantity;  ///< colour-bar label
  const Values* values{nullptr};
  const ColourScale* scale{nullptr};
  ArrowOf arrows{ArrowOf::kNone};
  bool after{false};     ///< outline by the verdict after compensation
  bool tol_mark{false};  ///< mark t/2 on the colour bar
};

/// One face in one panel: what every stage of drawing it reads.
struct PanelView {
  const FaceGroup& f;
  const std::vector<HoleView>& hv;
  const Panel& pn;
  [[nodiscard]] const HoleView& hole(size_t k) const { return hv[f.members[k]]; }
  [[nodiscard]] std::optional<double> value(size_t k) const { return (*pn.values)[f.members[k]]; }
  /// The verdict a marker shows: after compensation on an "after" panel when compensated.
  [[nodiscard]] Verdict verdict(size_t k) const {
    const HoleView& h = hole(k);
    if (pn.after && h.after != nullptr) return h.after->verdict;
    return h.f->verdict;
  }
};

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

/// The svg element, the plot frame, the square grid, the ticks and the axis labels.
void renderPlotFrame(Html& h, const FaceGroup& f, const Panel& pn, double height) {
  const double plot_bottom = kMarginT + f.plot_h;
  const double x_lo = f.x0, x_hi = f.x0 + f.plot_w / f.s;
  const double y_hi = f.y1, y_lo = f.y1 - f.plot_h / f.s;
  const double step = niceStep(std::max(x_hi - x_lo, y_hi - y_lo) / 6.0);  // equal on both axes
  const int dec = decimalsFor(step);
  const AxisLabel lx = axisLabel("u", f.u), ly = axisLabel("v", f.v);
  const std::vector<double> xt = ticksIn(x_lo, x_hi, step), yt = ticksIn(y_lo, y_hi, step);
  h.open("svg", {{"xmlns", "http://www.w3.org/2000/svg"},
                 Attr::markup("viewBox", "0 0 " + num(kPanelW, 0) + " " + num(height, 0)),
                 {"role", "img"},
                 {"aria-label", pn.quantity}});
  h.leaf("rect", {{"class", "plot"},
                  {"x", fixed(kMarginL, 1)},
                  {"y", fixed(kMarginT, 1)},
                  {"width", fixed(f.plot_w, 1)},
                  {"height", fixed(f.plot_h, 1)}});
  h.open("g", {{"class", "grid"}});
  for (const double t : xt) {
    h.leaf("line", {{"x1", fixed(f.px(t), 1)},
                    {"y1", fixed(kMarginT, 1)},
                    {"x2", fixed(f.px(t), 1)},
                    {"y2", fixed(plot_bottom, 1)}});
  }
  for (const double t : yt) {
    h.leaf("line", {{"x1", fixed(kMarginL, 1)},
                    {"y1", fixed(f.py(t), 1)},
                    {"x2", fixed(kMarginL + f.plot_w, 1)},
                    {"y2", fixed(f.py(t), 1)}});
  }
  h.close("g").open("g", {{"class", "tick"}});
  for (const double t : xt) {
    h.element(
        "text",
        {{"x", fixed(f.px(t), 1)}, {"y", fixed(plot_bottom + 15, 1)}, {"text-anchor", "middle"}},
        num(lx.sign * t, dec));
  }
  for (const double t : yt) {
    h.element("text",
              {{"x", fixed(kMarginL - 6, 1)}, {"y", fixed(f.py(t) + 4, 1)}, {"text-anchor", "end"}},
              num(ly.sign * t, dec));
  }
  h.close("g");
  h.element("text",
            {{"class", "axis"},
             {"x", fixed(kMarginL + 0.5 * f.plot_w, 1)},
             {"y", fixed(plot_bottom + 33, 1)},
             {"text-anchor", "middle"}},
            lx.text);
  h.element("text",
            {{"class", "axis"},
             Attr::markup("transform",
                          "translate(14 " + num(kMarginT + 0.5 * f.plot_h, 1) + ") rotate(-90)"),
             {"text-anchor", "middle"}},
            ly.text);
}

/// The program order as a dashed path.
void renderProgramPath(Html& h, const FaceGroup& f) {
  if (f.members.size() <= 1) return;
  std::vector<Eigen::Vector2d> pts;
  for (size_t k = 0; k < f.members.size(); ++k) pts.push_back(f.screen(k));
  h.leaf("polyline", {{"class", "path"}, Attr::markup("points", svgPoints(pts, 1))});
}

/// One marker with its tooltip: the hole's shape filled by its value, or a cross.
void renderMarker(Html& h, const PanelView& pv, size_t k) {
  const HoleView& hole = pv.hole(k);
  const api::ReportPrediction& p = *hole.p;
  const Eigen::Vector2d c = pv.f.screen(k);
  const double r = pv.f.marker_r;
  const std::optional<double> v = pv.value(k);
  std::string tip = p.id;
  h.open("g");
  if (!hole.ok) {
    tip += std::string(" \u00b7 ") + verdictName(p.verdict);
    if (!p.reason.empty()) tip += ": " + p.reason;
    cross(h, c.x(), c.y(), r, styleOf(p.verdict).bar);
  } else {
    const Verdict verdict = pv.verdict(k);
    tip += " \u00b7 " + (v ? num(*v, 1) + " \u00b5m" : std::string("n/a")) + " \u00b7 " +
           verdictName(verdict) + " \u00b7 branch " + std::to_string(p.branch);
    if (!p.config.empty()) tip += " (" + p.config + ")";
    const std::string fill = v ? viridisHex(pv.pn.scale->t(*v)) : std::string("#ffffff");
    marker(h, p.branch, c.x(), c.y(), r,
           {{"fill", fill}, {"class", std::string("mk v-") + styleOf(verdict).cls}});
    if (hole.config_change) {
      tip += " \u00b7 configuration change from branch " + std::to_string(hole.prev_branch);
      h.leaf("circle", {{"class", "chg"},
                        {"cx", fixed(c.x(), 2)},
                        {"cy", fixed(c.y(), 2)},
                        {"r", fixed(r + 3.2, 2)}});
    }
  }
  h.element("title", {}, tip).close("g");
}

/// Large jobs: holes binned on a square screen grid (kBin px); each bin is filled with its
/// largest value and outlined by its worst verdict, its tooltip gives the count, the maximum and
/// up to three ids of its worst holes.
struct Bin {
  int count{0}, worst{-1};
  std::optional<double> max;
  std::vector<size_t> ids;  ///< members, worst verdict first (≤ 3)
};

std::vector<Bin> binHoles(const PanelView& pv, int nx, int ny) {
  std::vector<Bin> bins(static_cast<size_t>(nx) * static_cast<size_t>(ny));
  for (size_t k = 0; k < pv.f.members.size(); ++k) {
    const Eigen::Vector2d c = pv.f.screen(k);
    const int bx = std::clamp(static_cast<int>((c.x() - kMarginL) / kBin), 0, nx - 1);
    const int by = std::clamp(static_cast<int>((c.y() - kMarginT) / kBin), 0, ny - 1);
    Bin& b = bins[static_cast<size_t>(by) * static_cast<size_t>(nx) + static_cast<size_t>(bx)];
    ++b.count;
    const int sev = severity(pv.verdict(k));
    if (sev > b.worst) {
      b.worst = sev;
      b.ids.clear();
    }
    if (sev == b.worst && b.ids.size() < 3) b.ids.push_back(k);
    const std::optional<double> v = pv.value(k);
    if (pv.hole(k).ok && v && (!b.max || *v > *b.max)) b.max = v;
  }
  return bins;
}

void renderBins(Html& h, const PanelView& pv) {
  const int nx = std::max(1, static_cast<int>(std::ceil(pv.f.plot_w / kBin)));
  const int ny = std::max(1, static_cast<int>(std::ceil(pv.f.plot_h / kBin)));
  const std::vector<Bin> bins = binHoles(pv, nx, ny);
  for (int by = 0; by < ny; ++by) {
    for (int bx = 0; bx < nx; ++bx) {
      const Bin& b =
          bins[static_cast<size_t>(by) * static_cast<size_t>(nx) + static_cast<size_t>(bx)];
      if (b.count == 0) continue;
      const Verdict v = pv.verdict(b.ids.front());
      std::string tip = plural(b.count, "hole", "holes") + " \u00b7 max " +
                        (b.max ? num(*b.max, 1) + " \u00b5m" : std::string("n/a")) +
                        " \u00b7 worst " + verdictName(v);
      for (const size_t k : b.ids) tip += " \u00b7 " + pv.hole(k).f->id;
      h.open("rect", {{"class", std::string("bin v-") + styleOf(v).cls},
                      {"x", fixed(kMarginL + bx * kBin, 1)},
                      {"y", fixed(kMarginT + by * kBin, 1)},
                      {"width", "7"},
                      {"height", "7"},
                      {"fill", b.max ? viridisHex(pv.pn.scale->t(*b.max)) : "#d0d7de"}})
          .element("title", {}, tip)
          .close("rect");
    }
  }
}

/// The members that do not conform (their count), the first `limit` of them in order: worst
/// verdict first, then the largest value, ties in program order.
struct Failing {
  std::vector<size_t> first;
  size_t count{0};
};

Failing failingMembers(const PanelView& pv, size_t limit) {
  struct Key {
    int severity;
    double shown;
    size_t k;
  };
  // by the value as the tooltip prints it (0.1 µm), ties in program order: the order does not
  // hang on a value's last bits (another platform's libm)
  const auto shown = [](std::optional<double> v) { return v ? std::round(*v * 10.0) : -1.0; };
  const auto before = [](const Key& a, const Key& b) {
    if (a.severity != b.severity) return a.severity > b.severity;
    if (a.shown != b.shown) return a.shown > b.shown;
    return a.k < b.k;
  };
  Failing out;
  std::vector<Key> first;  // the first `limit` keys so far, in order (keys are distinct: k)
  first.reserve(limit + 1);
  for (size_t k = 0; k < pv.f.members.size(); ++k) {
    const int s = severity(pv.verdict(k));
    if (s <= 0) continue;
    ++out.count;
    const Key key{s, shown(pv.value(k)), k};
    if (first.size() == limit && (limit == 0 || !before(key, first.back()))) continue;
    first.insert(std::upper_bound(first.begin(), first.end(), key, before), key);
    if (first.size() > limit) first.pop_back();
  }
  for (const Key& key : first) out.first.push_back(key.k);
  return out;
}

/// Ids of the holes that do not conform, visible without hovering (worst first, capped).
void renderFailLabels(Html& h, const PanelView& pv) {
  const Failing failing = failingMembers(pv, kMaxFailLabels);
  const FaceGroup& f = pv.f;
  const double r = f.marker_r;
  for (const size_t k : failing.first) {
    const std::string& id = pv.hole(k).f->id;
    const Eigen::Vector2d c = f.screen(k);
    const bool right = c.x() + r + 4 + 6.2 * static_cast<double>(id.size()) < kMarginL + f.plot_w;
    h.element("text",
              {{"class", std::string("flabel f-") + styleOf(pv.verdict(k)).cls},
               {"x", fixed(right ? c.x() + r + 3 : c.x() - r - 3, 1)},
               {"y", fixed(c.y() + 3.5, 1)},
               {"text-anchor", right ? "start" : "end"}},
              id);
  }
  if (failing.count > kMaxFailLabels) {
    h.element("text",
              {{"class", "tick"},
               {"x", fixed(kMarginL + 4, 1)},
               {"y", fixed(kMarginT + f.plot_h - 5, 1)}},
              "+" + std::to_string(failing.count - kMaxFailLabels) +
                  " more not conforming: see the table");
  }
}

/// δ direction of the three largest values (direction only, not to scale).
void renderArrows(Html& h, const PanelView& pv) {
  if (pv.pn.arrows == ArrowOf::kNone) return;
  const FaceGroup& f = pv.f;
  // the three largest values, ties in member order (a stable sort's first three)
  const auto before = [&](size_t a, size_t b) {
    const double va = *pv.value(a), vb = *pv.value(b);
    return va > vb || (!(vb > va) && a < b);
  };
  std::vector<size_t> order;  // the first three so far, in order
  order.reserve(4);
  for (size_t k = 0; k < f.members.size(); ++k) {
    if (!pv.hole(k).ok || !pv.value(k)) continue;
    if (order.size() == 3 && !before(k, order.back())) continue;
    order.insert(std::upper_bound(order.begin(), order.end(), k, before), k);
    if (order.size() > 3) order.pop_back();
  }
  for (const size_t k : order) {
    const api::MapFacts& p = *pv.hole(k).f;
    const Vec3 d = f.R_part_W * (pv.pn.arrows == ArrowOf::kRobot ? p.d_robot : p.d_work);
    const Eigen::Vector2d q(d.dot(f.u), -d.dot(f.v));
    if (q.norm() < 1e-3 * std::max(d.norm(), 1e-15) || q.norm() <= 0) continue;
    const Eigen::Vector2d e = q.normalized();
    const Eigen::Vector2d c = f.screen(k);
    const Eigen::Vector2d a0 = c + (f.marker_r + 3.5) * e, a1 = c + (f.marker_r + 24) * e;
    const Eigen::Vector2d n(-e.y(), e.x());
    const Eigen::Vector2d b = a1 - 7 * e;
    const std::array<Eigen::Vector2d, 3> head{a1, b + 3.5 * n, b - 3.5 * n};
    h.open("g", {{"class", "arrow"}})
        .leaf("line", {{"x1", fixed(a0.x(), 1)},
                       {"y1", fixed(a0.y(), 1)},
                       {"x2", fixed(b.x(), 1)},
                       {"y2", fixed(b.y(), 1)}})
        .leaf("polygon", {Attr::markup("points", svgPoints(head, 1))})
        .close("g");
  }
}

/// The member with the largest value among the predicted holes (size() when none).
size_t worstMember(const PanelView& pv) {
  const size_t none = pv.f.members.size();
  size_t worst = none;
  for (size_t k = 0; k < pv.f.members.size(); ++k) {
    const std::optional<double> v = pv.value(k);
    if (pv.hole(k).ok && v && (worst == none || *v > *pv.value(worst))) worst = k;
  }
  return worst;
}

/// "max ID · v µm" next to the largest value.
void renderMaxLabel(Html& h, const PanelView& pv, size_t worst) {
  if (worst >= pv.f.members.size()) return;
  const FaceGroup& f = pv.f;
  const double r = f.marker_r;
  const std::string& id = pv.hole(worst).f->id;
  const Eigen::Vector2d c = f.screen(worst);
  const double est_w = 6.2 * static_cast<double>(id.size() + 10);
  const bool right = c.x() + r + 5 + est_w < kMarginL + f.plot_w;
  h.element("text",
            {{"class", "maxlabel"},
             {"x", fixed(right ? c.x() + r + 4 : c.x() - r - 4, 1)},
             {"y", fixed(std::max(kMarginT + 12, c.y() - r - 4), 1)},
             {"text-anchor", right ? "start" : "end"}},
            "max " + id + " \u00b7 " + num(*pv.value(worst), 1) + " \u00b5m");
}

/// The tolerance t/2 (µm) of the face's holes on a colour bar: a red mark and label where it lies
/// on the scale, an arrow at the end when the scale ends below it (all values are then below t/2).
void renderToleranceMarks(Html& h, const PanelView& pv, double bx, double bw, double bar_y) {
  const ColourScale& sc = *pv.pn.scale;
  std::vector<double> halves;
  for (const size_t i : pv.f.members) {
    const double t2 = 0.5 * pv.hv[i].f->tolerance * 1e6;
    if (t2 > 0 && std::find(halves.begin(), halves.end(), t2) == halves.end()) halves.push_back(t2);
  }
  std::sort(halves.begin(), halves.end());
  if (halves.size() > 3) halves.erase(halves.begin() + 1, halves.end() - 1);
  for (size_t n = 0; n < halves.size(); ++n) {
    const double t2 = halves[n];
    const std::string label = "t/2 = " + num(t2, 0);
    const Fixed y = fixed(bar_y + 39 + 10.0 * static_cast<double>(n), 1);
    h.open("g", {{"class", "tol"}});
    if (t2 <= sc.hi && t2 >= sc.lo) {
      const double x = bx + bw * sc.t(t2);
      h.leaf("line", {{"x1", fixed(x, 1)},
                      {"y1", fixed(bar_y - 4, 1)},
                      {"x2", fixed(x, 1)},
                      {"y2", fixed(bar_y + 16, 1)}})
          .element("text", {{"x", fixed(x, 1)}, {"y", y}, {"text-anchor", "middle"}}, label);
    } else if (t2 > sc.hi) {
      h.element("text", {{"x", fixed(bx + bw, 1)}, {"y", y}, {"text-anchor", "end"}},
                label + " \u00b5m \u25b6 (above the scale: every value is below t/2)");
    } else {
      h.element("text", {{"x", fixed(bx, 1)}, {"y", y}, {"text-anchor", "start"}},
                "\u25c0 " + label + " \u00b5m (below the scale: every value exceeds t/2)");
    }
    h.close("g");
  }
}

/// The colour bar under the plot: its label, range, 48 steps of viridis, ticks and t/2.
void renderColourBar(Html& h, const PanelView& pv, double bar_y) {
  const ColourScale& sc = *pv.pn.scale;
  const double bx = kMarginL, bw = pv.f.plot_w;
  h.element("text", {{"class", "axis"}, {"x", fixed(bx, 1)}, {"y", fixed(bar_y - 6, 1)}},
            pv.pn.quantity + " [\u00b5m]");
  if (!sc.valid) {
    h.element("text", {{"class", "tick"}, {"x", fixed(bx, 1)}, {"y", fixed(bar_y + 12, 1)}},
              "no value to show");
    return;
  }
  h.element("text",
            {{"class", "tick"},
             {"x", fixed(bx + bw, 1)},
             {"y", fixed(bar_y - 6, 1)},
             {"text-anchor", "end"}},
            "min " + num(sc.data_min, 1) + " \u00b7 max " + num(sc.data_max, 1));
  constexpr int kSeg = 48;
  for (int i = 0; i < kSeg; ++i) {
    h.leaf("rect", {{"x", fixed(bx + bw * i / kSeg, 2)},
                    {"y", fixed(bar_y, 1)},
                    {"width", fixed(bw / kSeg + (i + 1 < kSeg ? 1.0 : 0.0), 2)},
                    {"height", "12"},
                    {"shape-rendering", "crispEdges"},
                    {"fill", viridisHex((i + 0.5) / kSeg)}});
  }
  h.leaf("rect", {{"class", "barframe"},
                  {"x", fixed(bx, 1)},
                  {"y", fixed(bar_y, 1)},
                  {"width", fixed(bw, 1)},
                  {"height", "12"}});
  const int bdec = decimalsFor(sc.step);
  for (const double t : ticksIn(sc.lo, sc.hi, sc.step)) {
    const double x = bx + bw * sc.t(t);
    h.leaf("line", {{"class", "barTick"},
                    {"x1", fixed(x, 1)},
                    {"y1", fixed(bar_y + 12, 1)},
                    {"x2", fixed(x, 1)},
                    {"y2", fixed(bar_y + 16, 1)}})
        .element("text",
                 {{"class", "tick"},
                  {"x", fixed(x, 1)},
                  {"y", fixed(bar_y + 28, 1)},
                  {"text-anchor", "middle"}},
                 num(t, bdec));
  }
  if (pv.pn.tol_mark) renderToleranceMarks(h, pv, bx, bw, bar_y);
}

void renderPanel(Html& h, const FaceGroup& f, const std::vector<HoleView>& hv, const Panel& pn) {
  const PanelView pv{f, hv, pn};
  const double bar_y = kMarginT + f.plot_h + 58;
  const bool aggregate = hv.size() > api::kReportAggregateAbove;
  h.open("figure", {{"class", "panel"}}).markupElement("figcaption", {}, pn.title);
  renderPlotFrame(h, f, pn, bar_y + (pn.tol_mark ? 66 : 40));
  if (aggregate) {
    renderBins(h, pv);  // no program path: it would only be a smear
  } else {
    renderProgramPath(h, f);
    for (size_t k = 0; k < f.members.size(); ++k) renderMarker(h, pv, k);
  }
  renderFailLabels(h, pv);
  renderArrows(h, pv);
  renderMaxLabel(h, pv, worstMember(pv));
  renderColourBar(h, pv, bar_y);
  h.close("svg").close("figure");
}

// ------------------------------------------------------------------ the section

/// The values the panels show, µm per hole (empty where the hole was not predicted).
struct MapValues {
  Values robot, err, res, U;
};

MapValues mapValues(const std::vector<HoleView>& hv) {
  const size_t n = hv.size();
  MapValues q{Values(n), Values(n), Values(n), Values(n)};
  for (size_t i = 0; i < n; ++i) {
    if (!hv[i].ok) continue;
    const api::MapFacts& p = *hv[i].f;
    q.robot[i] = p.d_robot.norm() * 1e6;
    q.err[i] = p.position_error * 1e6;
    q.U[i] = p.U_work_exact * 1e6;
    if (hv[i].rh != nullptr && hv[i].rh->residual_um) {
      q.res[i] = *hv[i].rh->residual_um;
    } else if (hv[i].after != nullptr && hv[i].after->status == HoleStatus::kOk) {
      q.res[i] = hv[i].after->position_error * 1e6;
    }
  }
  return q;
}

struct MapScales {
  ColourScale robot, err, U;
};

/// Predict: |δrobot|, e⊥, U₉₅. Compensate: e⊥ before and the residual after on one scale,
/// |δrobot|, U₉₅.
std::vector<Panel> panelsOf(bool compensation, const MapValues& q, const MapScales& s) {
  const Panel robot{"|\u03b4robot| \u2014 robot deviation under load", "|\u03b4robot|", &q.robot,
                    &s.robot, ArrowOf::kRobot};
  const Panel U{"U<sub>95</sub> \u2014 95 % radius of the work deviation (anisotropic)",
                "U95",
                &q.U,
                &s.U,
                ArrowOf::kNone,
                false,
                true};
  if (!compensation) {
    return {robot,
            {"Position error \u22a5 axis |\u03b4work\u22a5|", "e\u22a5", &q.err, &s.err,
             ArrowOf::kWork, false, true},
            U};
  }
  return {{"Position error \u22a5 axis \u2014 before compensation", "e\u22a5 before", &q.err,
           &s.err, ArrowOf::kWork, false, true},
          {"Residual \u2014 after compensation", "residual after", &q.res, &s.err, ArrowOf::kNone,
           true, true},
          robot,
          U};
}

void renderMapsNote(Html& h, const ReportInput& in, size_t holes) {
  const bool aggregate = holes > api::kReportAggregateAbove;
  h.open("p", {{"class", "note"}})
      .markup(
          "Each face is drawn as seen along its drilling direction (into the material), walls "
          "upright (part +Z up), top and bottom faces with the part X axis to the right; "
          "holes at their nominal positions, coordinates in mm in the part frame (<b>")
      .text(in.part_frame)
      .markup("</b>). Colours share one scale per quantity across all faces")
      .markup(in.compensation ? " (before and after use the same scale)" : "")
      .markup("; the marker outline shows the verdict")
      .markup(in.compensation ? " (after compensation on the residual map)" : "")
      .markup(
          ", the ids of the holes that do not conform are written next to them, and t/2 is "
          "marked on the colour bars of e\u22a5 and U. ")
      .markup(aggregate ? "This job has " + std::to_string(holes) +
                              " holes: each square is a bin of holes, filled with its largest "
                              "value and outlined by its worst verdict (hover for the count and "
                              "the worst ids)."
                        : std::string("Hover a marker for the hole id and value."))
      .close("p");
}

/// A legend entry: a 22 px icon and its text (markup).
template <class DrawIcon>
void legendEntry(Html& h, const DrawIcon& icon, const std::string& text) {
  h.open("span").open("svg", {{"class", "icon"},
                              {"viewBox", "0 0 22 22"},
                              {"width", "22"},
                              {"height", "22"},
                              {"aria-hidden", "true"}});
  icon(h);
  h.close("svg").markup(text).close("span");
}

/// The IK branches present (ascending) with the configuration of their first hole.
std::vector<std::pair<int, std::string>> branchesPresent(const ReportInput& in,
                                                         const std::vector<HoleView>& hv) {
  std::vector<std::pair<int, std::string>> b;
  if (!in.mapped.empty()) b = in.totals.branches;  // counted as the holes went past
  for (const HoleView& v : hv) {
    if (!v.ok || v.p == nullptr) continue;
    addBranch(b, v.p->branch, v.p->config);
  }
  std::stable_sort(b.begin(), b.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  return b;
}

/// Shapes by branch (those present), configuration change, verdict outlines, crosses, arrows and
/// the program path.
void renderLegend(Html& h, const ReportInput& in, const std::vector<HoleView>& hv) {
  h.open("div", {{"class", "legend"}}).markup("<strong>Marker shape = IK branch:</strong>");
  for (const auto& b : branchesPresent(in, hv)) {
    const int branch = b.first;
    const std::string& config = b.second;
    legendEntry(
        h,
        [&](Html& g) {
          marker(g, branch, 11, 11, 6, {{"fill", "#8fbbe6"}, {"stroke", "#24292f"}});
        },
        "branch " + std::to_string(branch) +
            (config.empty() ? "" : " <span class=\"note\">(" + esc(config) + ")</span>"));
  }
  legendEntry(
      h,
      [](Html& g) {
        g.markup(
            "<circle cx=\"11\" cy=\"11\" r=\"5\" fill=\"#8fbbe6\" stroke=\"#24292f\"/>"
            "<circle cx=\"11\" cy=\"11\" r=\"8.5\" fill=\"none\" stroke=\"#e3120b\" "
            "stroke-width=\"2\"/>");
      },
      "configuration change from the previous hole");
  for (const VerdictStyle& vs : kVerdicts) {
    if (vs.verdict == Verdict::kUnreachable || vs.verdict == Verdict::kSingular ||
        vs.verdict == Verdict::kNotConverged)
      continue;
    legendEntry(
        h,
        [&](Html& g) {
          g.leaf("circle", {{"cx", "11"},
                            {"cy", "11"},
                            {"r", "6"},
                            {"fill", "#8fbbe6"},
                            {"class", std::string("lg v-") + vs.cls}});
        },
        std::string("outline: ") + vs.label);
  }
  legendEntry(
      h, [](Html& g) { cross(g, 11, 11, 6, "#57606a"); }, "unreachable / singular / not converged");
  legendEntry(
      h,
      [](Html& g) {
        g.markup(
            "<line x1=\"3\" y1=\"11\" x2=\"14\" y2=\"11\" stroke=\"#1f2328\" "
            "stroke-width=\"1.5\"/><polygon points=\"20,11 13,7.5 13,14.5\" "
            "fill=\"#1f2328\"/>");
      },
      "direction of \u03b4 at the 3 largest values (not to scale)");
  legendEntry(
      h,
      [](Html& g) {
        g.markup(
            "<line x1=\"2\" y1=\"11\" x2=\"20\" y2=\"11\" stroke=\"#afb8c1\" "
            "stroke-dasharray=\"3 2\"/>");
      },
      "program order");
  h.close("div");
}

/// "Face A · drilling direction −Z (part frame) · 12 holes, 12 reachable" and its panels (each
/// panel's markup in `drawn`, in order).
void renderFace(Html& h, const FaceGroup& f, const std::string& name,
                const std::vector<HoleView>& hv, std::span<const std::string> drawn) {
  const long reach =
      std::count_if(f.members.begin(), f.members.end(), [&](size_t i) { return hv[i].ok; });
  h.open("h3", {{"class", "face"}})
      .markup("Face " + name + " ")
      .open("small")
      .text("\u00b7 drilling direction " + dirLabel(f.axis) + " (part frame) \u00b7 " +
            plural(static_cast<long>(f.members.size()), "hole", "holes") + ", " +
            std::to_string(reach) + " reachable")
      .close("small")
      .close("h3");
  h.open("div", {{"class", drawn.size() == 4 ? "maps four" : "maps"}});
  for (const std::string& d : drawn) h.markup(d);
  h.close("div");
}

}  // namespace

void renderMaps(Html& h, const ReportInput& in, const std::vector<HoleView>& hv) {
  const MapValues q = mapValues(hv);
  const MapScales scales{makeScale({&q.robot}),
                         in.compensation ? makeScale({&q.err, &q.res}) : makeScale({&q.err}),
                         makeScale({&q.U})};
  const std::vector<Panel> panels = panelsOf(in.compensation, q, scales);
  const std::vector<FaceGroup> faces = faceGroups(in, hv);
  h.open("section", {{"id", "maps"}}).element("h2", {}, "Deviation maps over the work area");
  renderMapsNote(h, in, hv.size());
  renderLegend(h, in, hv);
  // every face's panels drawn on the workers (each panel on its own), written in order
  std::vector<std::string> drawn(faces.size() * panels.size());
  eachOnThreads(drawn.size(), in.threads, [&](size_t k) {
    Html d(drawn[k]);
    renderPanel(d, faces[k / panels.size()], hv, panels[k % panels.size()]);
  });
  for (size_t g = 0; g < faces.size(); ++g) {
    const std::string name =
        faces.size() <= 26 ? std::string(1, static_cast<char>('A' + g)) : std::to_string(g + 1);
    renderFace(h, faces[g], name, hv,
               std::span<const std::string>(drawn).subspan(g * panels.size(), panels.size()));
  }
  h.close("section");
}

}  // namespace roprec::report
