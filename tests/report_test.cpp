// The HTML report of `roprec predict` / `roprec compensate` (plugin/report/hole_report.hpp):
// structure, determinism, escaping, self-containedness, and a real headless-Chromium render whose
// screenshot is decoded (own PNG + inflate reader, checked by the PNG CRC-32 and zlib Adler-32 of
// every stream) and checked for a drawn map.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <regex>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "compensator/precision/prediction.hpp"
#include "compensator/robot/robot_card.hpp"
#include "plugin/api/deviation_split.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/robots.hpp"
#include "plugin/report/exports.hpp"
#include "plugin/report/hole_report.hpp"
#include "support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

// ------------------------------------------------------------------ synthetic input

/// Rotation whose third column (tool +z, the drilling direction) is `a`.
Pose toolPose(const Vec3& p, const Vec3& a) {
  const Vec3 z = a.normalized();
  const Vec3 helper = std::abs(z.z()) < 0.9 ? Vec3::UnitZ() : Vec3::UnitX();
  const Vec3 x = helper.cross(z).normalized();
  const Vec3 y = z.cross(x);
  Pose T = Pose::Identity();
  T.linear().col(0) = x;
  T.linear().col(1) = y;
  T.linear().col(2) = z;
  T.translation() = p;
  return T;
}

struct Synthetic {
  std::vector<HolePrediction> preds;
  std::vector<Pose> poses;
  int branch_changes{0};
  int not_ok{0};
};

/// 60 holes on two faces (30 on a vertical face drilled along +X, 30 on a top face drilled along
/// −Z), deviations growing with reach, a wrist-configuration change (branch 0 → 4 → 0) in the
/// middle of face A, one unreachable and one singular hole, a few holes with a large model
/// uncertainty (does not conform), tolerances ⌀0.2 / ⌀0.3 mm, verdicts by the ISO 14253-1 rule.
Synthetic makeSynthetic(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U01(0.0, 1.0);
  Synthetic s;
  const double k = 2.4477;
  int prev_branch = -1;
  for (int face = 0; face < 2; ++face) {
    for (int r = 0; r < 5; ++r) {
      for (int c = 0; c < 6; ++c) {
        HolePrediction p;
        const int n = face * 30 + r * 6 + c;
        p.id = "H" + std::to_string(100 + n);
        if (n == 7) p.id = "<script>&\"";
        Vec3 pos, axis;
        if (face == 0) {
          pos = Vec3(1.35, -0.25 + 0.1 * c, 0.45 + 0.07 * r);
          axis = Vec3::UnitX();
        } else {
          pos = Vec3(1.0 + 0.08 * r, -0.3 + 0.12 * c, 0.8);
          axis = -Vec3::UnitZ();
        }
        s.poses.push_back(toolPose(pos, axis));
        p.diameter = (c % 3 == 0) ? 12e-3 : 8e-3;
        p.depth = 2.0 * p.diameter;
        p.tolerance = (r == 4) ? 0.3e-3 : 0.2e-3;
        p.mc_time = p.depth / (0.2e-3 * 3000.0 / 60.0) + 2.0;
        p.branch = face == 0 ? ((r == 2 && c >= 2 && c <= 3) ? 4 : 0) : 2;
        p.config = p.branch == 0   ? "S 110 T 000010"
                   : p.branch == 4 ? "S 010 T 000010"
                                   : "S 110 T 000011";
        for (int j = 0; j < 6; ++j)
          p.joints[j] = (0.3 * j - 0.7 + 0.05 * c - 0.03 * r) * (face ? -1 : 1);
        if (n == 40) {
          p.status = HoleStatus::kUnreachable;
          p.verdict = Verdict::kUnreachable;
          p.reason = "no IK solution within the joint limits";
          p.config.clear();
          ++s.not_ok;
          s.preds.push_back(p);
          continue;
        }
        if (n == 53) {
          p.status = HoleStatus::kSingular;
          p.verdict = Verdict::kSingular;
          p.reason = "wrist singular (|sin θ5| = 0.004)";
          ++s.not_ok;
          s.preds.push_back(p);
          continue;
        }
        if (prev_branch >= 0 && p.branch != prev_branch) ++s.branch_changes;
        prev_branch = p.branch;
        const double reach = pos.head<2>().norm();
        const double mag = (25e-6 + 60e-6 * (reach - 1.0)) * (1.0 + 0.15 * U01(rng)) +
                           (p.branch == 4 ? 45e-6 : 0.0);
        const Vec3 dir = Vec3(-0.3 + 0.2 * U01(rng), 0.4 * U01(rng) - 0.2, -1.0).normalized();
        p.d_robot = mag * dir;
        p.d_mach = Vec3(2e-6 * U01(rng), -1.5e-6 * U01(rng), 0.0);
        p.d_work = p.d_robot + p.d_mach;
        p.d_rot = Vec3(1e-5 * U01(rng), -2e-5 * U01(rng), 3e-6);
        p.position_error = (p.d_work - p.d_work.dot(axis) * axis).norm();
        p.axis_tilt = (p.d_rot - p.d_rot.dot(axis) * axis).norm();
        const double scale_mach = p.diameter / 8e-3;
        p.budget = {
            {"robot_repeatability", 16.6e-6, false},
            {"robot_deflection_model", (n % 11 == 5 ? 45e-6 : 0.12 * mag), false},
            {"robot_deflection_process_force", 0.05 * mag, true},
            {"mach_axis", 2.4e-6 * scale_mach, true},
            {"mach_runout", 4.2e-6 * scale_mach, true},
            {"mach_tool_deflection", (3.0e-6 + 6e-6 * U01(rng)) * scale_mach * scale_mach, true}};
        double u_r2 = 0, u_m2 = 0, proc2 = 0;
        for (const BudgetTerm& b : p.budget) {
          (std::string(b.name).rfind("robot", 0) == 0 ? u_r2 : u_m2) += b.u * b.u;
          if (b.process) proc2 += b.u * b.u;
        }
        p.u_robot = std::sqrt(u_r2);
        p.u_mach = std::sqrt(u_m2);
        p.u_work = std::sqrt(u_r2 + u_m2);
        p.k = k;
        p.U_robot = k * p.u_robot;
        p.U_mach = k * p.u_mach;
        p.U_work = k * p.u_work;
        p.U_work_exact = p.U_work;
        p.process_share = proc2 / (p.u_work * p.u_work);
        const double half = 0.5 * p.tolerance;
        p.verdict = p.U_work > half                      ? Verdict::kNotCapable
                    : p.position_error + p.U_work > half ? Verdict::kConformsAfterCompensation
                                                         : Verdict::kConforms;
        s.preds.push_back(p);
      }
    }
  }
  return s;
}

api::ReportInput makeInput(const Synthetic& s, bool compensation) {
  api::ReportInput in;
  in.title = "roprec prediction \u2014 housing_<B>.src";
  in.robot = "kuka-kr120-r2500-pro (KUKA KR 120 R2500 pro)";
  in.cell = "e-motor housing cell (cells/housing.xml)";
  in.program = "programs/housing_<B>.src";
  in.process = "drilling, Al 6061-T6, Dc 8/12 mm, f 0.2 mm/rev, 3000 rpm";
  in.uncertainty_method = "linearised";
  in.uncertainty_source =
      "stiffness 10 % per joint; servo 20 % (estimate); process force \u00b115 %";
  in.default_tolerance_mm = 0.2;
  in.compensation = compensation;
  for (size_t i = 0; i < s.preds.size(); ++i) {
    api::ReportHole& h = in.holes.emplace_back();  // filled in place (no copy of its optionals)
    h.prediction = &s.preds[i];
    h.T_W_tcp = s.poses[i];
    if (compensation && s.preds[i].status == HoleStatus::kOk) {
      h.residual_um = 0.02 * s.preds[i].position_error * 1e6 + 0.3;
      h.rotation_about_axis_deg = (i % 5 == 0) ? 12.5 : 0.0;
    }
  }
  in.summary = summarize(s.preds);
  return in;
}

size_t countOf(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + what.size()))
    ++n;
  return n;
}

TEST(Report, DeterministicAndSelfContained) {
  const Synthetic s = makeSynthetic(20201);
  const std::string a = api::renderReport(makeInput(s, false));
  const Synthetic s2 = makeSynthetic(20201);  // rebuilt from scratch: other addresses, same values
  const std::string b = api::renderReport(makeInput(s2, false));
  EXPECT_EQ(a, b);
  EXPECT_EQ(a.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(a.find("</html>"), std::string::npos);

  // no network: the only URL is the SVG namespace
  std::string stripped = a;
  const std::string ns = "xmlns=\"http://www.w3.org/2000/svg\"";
  for (size_t p = stripped.find(ns); p != std::string::npos; p = stripped.find(ns))
    stripped.erase(p, ns.size());
  EXPECT_EQ(stripped.find("http://"), std::string::npos);
  EXPECT_EQ(stripped.find("https://"), std::string::npos);
  EXPECT_EQ(stripped.find("//www."), std::string::npos);
  EXPECT_EQ(stripped.find("url("), std::string::npos);
  EXPECT_EQ(stripped.find("@import"), std::string::npos);
  EXPECT_EQ(stripped.find(" src="), std::string::npos);
  // one inline script (table sorting and filtering), nothing loaded
  EXPECT_EQ(countOf(stripped, "<script"), 1u);
  EXPECT_EQ(countOf(stripped, "<script>"), 1u);
  EXPECT_EQ(stripped.find("<link"), std::string::npos);
}

TEST(Report, EscapesEveryInputString) {
  const Synthetic s = makeSynthetic(20201);
  const std::string html = api::renderReport(makeInput(s, false));
  EXPECT_EQ(html.find("<script>&"), std::string::npos);
  EXPECT_EQ(html.find("<B>"), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;&amp;&quot;"), std::string::npos);
  EXPECT_NE(html.find("housing_&lt;B&gt;.src"), std::string::npos);
  // the hostile id in the table row and in the map tooltips (3 panels)
  EXPECT_EQ(countOf(html, "<td class=\"id c1\">&lt;script&gt;&amp;&quot;</td>"), 1u);
  EXPECT_GE(countOf(html, "<title>&lt;script&gt;&amp;&quot;"), 3u);
}

TEST(Report, MapsTablesBudgetAndVerdicts) {
  const Synthetic s = makeSynthetic(20201);
  const api::ReportInput in = makeInput(s, false);
  const std::string html = api::renderReport(in);
  // two faces (+X and −Z drilling) × three maps
  EXPECT_EQ(countOf(html, "<h3 class=\"face\">"), 2u);
  EXPECT_EQ(countOf(html, "<figure class=\"panel\">"), 6u);
  EXPECT_EQ(countOf(html, "drilling direction +X"), 1u);
  EXPECT_EQ(countOf(html, "drilling direction \u2212Z"), 1u);
  EXPECT_EQ(countOf(html, "<figcaption>|\u03b4robot|"), 2u);
  EXPECT_EQ(countOf(html, "<figcaption>Position error"), 2u);
  EXPECT_EQ(countOf(html, "<figcaption>U<sub>95</sub>"), 2u);
  // every predicted hole is one marker per map; rings mark each configuration change in each map
  const size_t ok = s.preds.size() - static_cast<size_t>(s.not_ok);
  EXPECT_EQ(countOf(html, "class=\"mk v-"), 3 * ok);
  // the verdict outline of every marker matches the hole's verdict
  const CapabilitySummary& vs = in.summary;
  EXPECT_EQ(countOf(html, "class=\"mk v-ok\""), 3u * static_cast<size_t>(vs.conforms));
  EXPECT_EQ(countOf(html, "class=\"mk v-comp\""),
            3u * static_cast<size_t>(vs.conforms_after_compensation));
  EXPECT_EQ(countOf(html, "class=\"mk v-nc\""), 3u * static_cast<size_t>(vs.not_capable));
  EXPECT_EQ(s.branch_changes, 3);  // 0 → 4 → 0 on face A, 0 → 2 at face B
  EXPECT_EQ(countOf(html, "<circle class=\"chg\""), 3u * static_cast<size_t>(s.branch_changes));
  EXPECT_EQ(countOf(html, "<td class=\"chg\""), static_cast<size_t>(s.branch_changes));
  // unreachable and singular holes: crosses in each map (+1 legend icon), reason in the table
  EXPECT_EQ(countOf(html, "stroke-linecap=\"round\""), 3u * static_cast<size_t>(s.not_ok) + 1u);
  EXPECT_NE(html.find("no IK solution within the joint limits"), std::string::npos);
  // table: one row per hole, ids in order
  size_t last = 0;
  for (const HolePrediction& p : s.preds) {
    if (p.id.find('<') != std::string::npos) continue;
    const size_t at = html.find("<td class=\"id c1\">" + p.id + "</td>");
    ASSERT_NE(at, std::string::npos) << p.id;
    EXPECT_GT(at, last) << p.id;
    last = at;
  }
  const size_t tbody = html.find("<table class=\"holes\"");
  ASSERT_NE(tbody, std::string::npos);
  EXPECT_EQ(countOf(html.substr(tbody), "<td class=\"c0\">"), s.preds.size());
  EXPECT_EQ(countOf(html.substr(tbody), "<tr class=\"pass\"><td class=\"c0\">"),
            static_cast<size_t>(in.summary.conforms));
  // verdict badges match the predictions
  const CapabilitySummary& sum = in.summary;
  EXPECT_EQ(countOf(html, "class=\"badge b-ok\" title=\"conforms\">conforms<"),
            static_cast<size_t>(sum.conforms));
  EXPECT_EQ(countOf(html, "class=\"badge b-comp\""),
            static_cast<size_t>(sum.conforms_after_compensation));
  EXPECT_EQ(countOf(html, "class=\"badge b-nc\""), static_cast<size_t>(sum.not_capable));
  EXPECT_EQ(countOf(html, "class=\"badge b-unr\""), 1u);
  EXPECT_EQ(countOf(html, "class=\"badge b-sing\""), 1u);
  EXPECT_GT(sum.conforms, 0);
  EXPECT_GT(sum.conforms_after_compensation, 0);
  EXPECT_GT(sum.not_capable, 0);
  // the summary sentence and the budget (six terms, k explained)
  EXPECT_NE(html.find("<strong>" + std::to_string(sum.robot_can_take) +
                      " of 60 holes can be taken by the robot"),
            std::string::npos);
  EXPECT_NE(html.find("Robot repeatability"), std::string::npos);
  EXPECT_NE(html.find("Tool deflection"), std::string::npos);
  EXPECT_NE(html.find("k = 2.448"), std::string::npos);
  EXPECT_EQ(countOf(html, "<span class=\"sw\""), 6u);
}

TEST(Report, BudgetStatisticsAreTheMeansOverPredictedHoles) {
  const Synthetic s = makeSynthetic(7);
  const std::string html = api::renderReport(makeInput(s, false));
  // robot repeatability is 16.6 µm at every hole: mean = max = 16.60
  const size_t at = html.find("Robot repeatability</td>");
  ASSERT_NE(at, std::string::npos);
  const std::string row = html.substr(at, html.find("</tr>", at) - at);
  EXPECT_EQ(countOf(row, "<td>16.60</td>"), 2u) << row;
  // mean U_work by hand
  double sum = 0, mx = 0;
  int n = 0;
  for (const HolePrediction& p : s.preds) {
    if (p.status != HoleStatus::kOk) continue;
    sum += p.U_work * 1e6;
    mx = std::max(mx, p.U_work * 1e6);
    ++n;
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "<td class=\"n\">%.2f</td><td class=\"n\">%.2f</td>", sum / n, mx);
  const size_t uw = html.find("<td class=\"l\">U<sub>work</sub>");
  ASSERT_NE(uw, std::string::npos);
  EXPECT_NE(html.substr(uw, 300).find(buf), std::string::npos) << html.substr(uw, 300);
}

TEST(Report, CompensationAddsBeforeAfterMapsAndColumns) {
  const Synthetic s = makeSynthetic(20201);
  const std::string html = api::renderReport(makeInput(s, true));
  EXPECT_EQ(countOf(html, "<figure class=\"panel\">"), 8u);
  EXPECT_EQ(countOf(html, "before compensation</figcaption>"), 2u);
  EXPECT_EQ(countOf(html, "<figcaption>Residual"), 2u);
  EXPECT_NE(html.find("<th>Residual<br><small>\u00b5m</small></th>"), std::string::npos);
  EXPECT_NE(html.find("<td>12.50</td>"), std::string::npos);
}

TEST(Report, EmptyProgramStillRenders) {
  api::ReportInput in;
  in.title = "empty";
  const std::string html = api::renderReport(in);
  EXPECT_NE(html.find("</html>"), std::string::npos);
  EXPECT_NE(html.find("0 of 0 holes"), std::string::npos);
  EXPECT_EQ(countOf(html, "<figure class=\"panel\">"), 0u);
}

// ------------------------------------------------------------------ PNG decoding (RFC 1950/1951,
// PNG spec)

std::uint32_t crc32(const std::uint8_t* p, size_t n) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xFFFFFFFFu;
  for (size_t i = 0; i < n; ++i) c = table[(c ^ p[i]) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

/// Inflate (RFC 1951) after the canonical-Huffman decoder of zlib's puff.c (M. Adler).
class Inflate {
 public:
  Inflate(const std::vector<std::uint8_t>& in, size_t pos) : in_(in), pos_(pos) {}

  std::vector<std::uint8_t> run() {
    int last = 0;
    do {
      last = bits(1);
      const int type = bits(2);
      if (type == 0) {
        stored();
      } else if (type == 1) {
        fixed();
      } else if (type == 2) {
        dynamic();
      } else {
        throw std::runtime_error("inflate: invalid block type");
      }
    } while (!last);
    return std::move(out_);
  }
  [[nodiscard]] size_t bytePos() const { return pos_; }

 private:
  struct Huffman {
    std::array<short, 16> count{};
    std::vector<short> symbol;
  };

  int bits(int need) {
    long val = bitbuf_;
    while (bitcnt_ < need) {
      if (pos_ >= in_.size()) throw std::runtime_error("inflate: out of input");
      val |= static_cast<long>(in_[pos_++]) << bitcnt_;
      bitcnt_ += 8;
    }
    bitbuf_ = static_cast<int>(val >> need);
    bitcnt_ -= need;
    return static_cast<int>(val & ((1L << need) - 1));
  }

  void stored() {
    bitbuf_ = 0;
    bitcnt_ = 0;
    if (pos_ + 4 > in_.size()) throw std::runtime_error("inflate: truncated stored block");
    const unsigned len = in_[pos_] | (in_[pos_ + 1] << 8);
    const unsigned nlen = in_[pos_ + 2] | (in_[pos_ + 3] << 8);
    pos_ += 4;
    if (len != (~nlen & 0xFFFFu)) throw std::runtime_error("inflate: stored length mismatch");
    if (pos_ + len > in_.size()) throw std::runtime_error("inflate: truncated stored block");
    out_.insert(out_.end(), in_.begin() + static_cast<long>(pos_),
                in_.begin() + static_cast<long>(pos_ + len));
    pos_ += len;
  }

  int decode(const Huffman& h) {
    int code = 0, first = 0, index = 0;
    for (int len = 1; len <= 15; ++len) {
      code |= bits(1);
      const int count = h.count[static_cast<size_t>(len)];
      if (code - count < first) {
        const int at = index + (code - first);
        return h.symbol[static_cast<size_t>(at)];
      }
      index += count;
      first += count;
      first <<= 1;
      code <<= 1;
    }
    throw std::runtime_error("inflate: bad Huffman code");
  }

  static Huffman build(const short* length, int n) {
    Huffman h;
    h.symbol.assign(static_cast<size_t>(n), 0);
    for (int s = 0; s < n; ++s) h.count[static_cast<size_t>(length[s])]++;
    std::array<short, 16> offs{};
    for (int len = 1; len < 15; ++len) {
      offs[static_cast<size_t>(len) + 1] =
          static_cast<short>(offs[static_cast<size_t>(len)] + h.count[static_cast<size_t>(len)]);
    }
    for (int s = 0; s < n; ++s) {
      if (length[s] != 0)
        h.symbol[static_cast<size_t>(offs[static_cast<size_t>(length[s])]++)] =
            static_cast<short>(s);
    }
    return h;
  }

  void codes(const Huffman& lencode, const Huffman& distcode) {
    static constexpr std::array<short, 29> kLBase{3,  4,  5,  6,   7,   8,   9,   10,  11, 13,
                                                  15, 17, 19, 23,  27,  31,  35,  43,  51, 59,
                                                  67, 83, 99, 115, 131, 163, 195, 227, 258};
    static constexpr std::array<short, 29> kLExt{0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                                 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
    static constexpr std::array<int, 30> kDBase{
        1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
        193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
    static constexpr std::array<short, 30> kDExt{0, 0, 0,  0,  1,  1,  2,  2,  3,  3,
                                                 4, 4, 5,  5,  6,  6,  7,  7,  8,  8,
                                                 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
    for (;;) {
      int sym = decode(lencode);
      if (sym < 256) {
        out_.push_back(static_cast<std::uint8_t>(sym));
      } else if (sym == 256) {
        return;
      } else {
        sym -= 257;
        if (sym >= 29) throw std::runtime_error("inflate: bad length symbol");
        const size_t len = static_cast<size_t>(kLBase[static_cast<size_t>(sym)]) +
                           static_cast<size_t>(bits(kLExt[static_cast<size_t>(sym)]));
        const int dsym = decode(distcode);
        if (dsym >= 30) throw std::runtime_error("inflate: bad distance symbol");
        const size_t dist = static_cast<size_t>(kDBase[static_cast<size_t>(dsym)]) +
                            static_cast<size_t>(bits(kDExt[static_cast<size_t>(dsym)]));
        if (dist > out_.size()) throw std::runtime_error("inflate: distance too far back");
        for (size_t i = 0; i < len; ++i) out_.push_back(out_[out_.size() - dist]);
      }
    }
  }

  void fixed() {
    std::array<short, 288> l{};
    for (int s = 0; s < 288; ++s)
      l[static_cast<size_t>(s)] = s < 144 ? 8 : s < 256 ? 9 : s < 280 ? 7 : 8;
    std::array<short, 30> d{};
    d.fill(5);
    codes(build(l.data(), 288), build(d.data(), 30));
  }

  void dynamic() {
    static constexpr std::array<short, 19> kOrder{16, 17, 18, 0, 8,  7, 9,  6, 10, 5,
                                                  11, 4,  12, 3, 13, 2, 14, 1, 15};
    const int nlen = bits(5) + 257, ndist = bits(5) + 1, ncode = bits(4) + 4;
    if (nlen > 286 || ndist > 30) throw std::runtime_error("inflate: bad counts");
    std::array<short, 320> lengths{};
    for (int i = 0; i < ncode; ++i)
      lengths[static_cast<size_t>(kOrder[static_cast<size_t>(i)])] = static_cast<short>(bits(3));
    const Huffman lencode0 = build(lengths.data(), 19);
    int index = 0;
    while (index < nlen + ndist) {
      int sym = decode(lencode0);
      if (sym < 16) {
        lengths[static_cast<size_t>(index++)] = static_cast<short>(sym);
      } else {
        short len = 0;
        if (sym == 16) {
          if (index == 0) throw std::runtime_error("inflate: repeat with no first length");
          len = lengths[static_cast<size_t>(index - 1)];
          sym = 3 + bits(2);
        } else if (sym == 17) {
          sym = 3 + bits(3);
        } else {
          sym = 11 + bits(7);
        }
        if (index + sym > nlen + ndist) throw std::runtime_error("inflate: too many lengths");
        while (sym--) lengths[static_cast<size_t>(index++)] = len;
      }
    }
    codes(build(lengths.data(), nlen), build(lengths.data() + nlen, ndist));
  }

  const std::vector<std::uint8_t>& in_;
  size_t pos_;
  int bitbuf_{0}, bitcnt_{0};
  std::vector<std::uint8_t> out_;
};

struct Image {
  int w{0}, h{0};
  std::vector<std::uint8_t> rgb;  ///< 3 bytes a pixel
};

std::uint32_t be32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
         p[3];
}

/// 8-bit RGB/RGBA, non-interlaced PNG → RGB (alpha composited on white). Throws on any CRC/Adler
/// error.
Image decodePng(const std::vector<std::uint8_t>& f) {
  static constexpr std::array<std::uint8_t, 8> kSig{137, 80, 78, 71, 13, 10, 26, 10};
  if (f.size() < 8 || !std::equal(kSig.begin(), kSig.end(), f.begin()))
    throw std::runtime_error("png: signature");
  size_t p = 8;
  int w = 0, h = 0, ctype = -1;
  std::vector<std::uint8_t> idat;
  bool end = false;
  while (!end) {
    if (p + 12 > f.size()) throw std::runtime_error("png: truncated chunk");
    const std::uint32_t len = be32(&f[p]);
    if (p + 12 + len > f.size()) throw std::runtime_error("png: truncated chunk data");
    const std::string type(reinterpret_cast<const char*>(&f[p + 4]), 4);
    if (crc32(&f[p + 4], len + 4) != be32(&f[p + 8 + len]))
      throw std::runtime_error("png: CRC of " + type);
    const std::uint8_t* d = &f[p + 8];
    if (type == "IHDR") {
      w = static_cast<int>(be32(d));
      h = static_cast<int>(be32(d + 4));
      if (d[8] != 8 || (d[9] != 2 && d[9] != 6) || d[12] != 0)
        throw std::runtime_error("png: unsupported format");
      ctype = d[9];
    } else if (type == "IDAT") {
      idat.insert(idat.end(), d, d + len);
    } else if (type == "IEND") {
      end = true;
    }
    p += 12 + len;
  }
  if (w <= 0 || h <= 0 || idat.size() < 6) throw std::runtime_error("png: no image");
  if ((idat[0] & 0x0F) != 8 || ((idat[0] << 8) | idat[1]) % 31 != 0 || (idat[1] & 0x20)) {
    throw std::runtime_error("png: bad zlib header");
  }
  Inflate inf(idat, 2);
  const std::vector<std::uint8_t> raw = inf.run();
  std::uint32_t a = 1, b = 0;
  for (const std::uint8_t c : raw) {
    a = (a + c) % 65521u;
    b = (b + a) % 65521u;
  }
  if (inf.bytePos() + 4 > idat.size() || be32(&idat[inf.bytePos()]) != ((b << 16) | a)) {
    throw std::runtime_error("png: Adler-32 mismatch");
  }
  const size_t bpp = ctype == 6 ? 4 : 3;
  const size_t stride = bpp * static_cast<size_t>(w);
  if (raw.size() != (stride + 1) * static_cast<size_t>(h))
    throw std::runtime_error("png: size mismatch");
  std::vector<std::uint8_t> cur(stride), prev(stride, 0);
  Image img;
  img.w = w;
  img.h = h;
  img.rgb.resize(3 * static_cast<size_t>(w) * static_cast<size_t>(h));
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* row = &raw[static_cast<size_t>(y) * (stride + 1)];
    const int filter = row[0];
    for (size_t i = 0; i < stride; ++i) {
      const int x = row[1 + i];
      const int left = i >= bpp ? cur[i - bpp] : 0;
      const int up = prev[i];
      const int ul = i >= bpp ? prev[i - bpp] : 0;
      int v = 0;
      switch (filter) {
        case 0:
          v = x;
          break;
        case 1:
          v = x + left;
          break;
        case 2:
          v = x + up;
          break;
        case 3:
          v = x + (left + up) / 2;
          break;
        case 4: {
          const int pp = left + up - ul, pa = std::abs(pp - left), pb = std::abs(pp - up),
                    pc = std::abs(pp - ul);
          v = x + ((pa <= pb && pa <= pc) ? left : pb <= pc ? up : ul);
          break;
        }
        default:
          throw std::runtime_error("png: bad filter");
      }
      cur[i] = static_cast<std::uint8_t>(v & 0xFF);
    }
    for (int xx = 0; xx < w; ++xx) {
      const std::uint8_t* px = &cur[static_cast<size_t>(xx) * bpp];
      const double alpha = bpp == 4 ? px[3] / 255.0 : 1.0;
      for (int c = 0; c < 3; ++c) {
        img.rgb[3 * (static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(xx)) +
                static_cast<size_t>(c)] =
            static_cast<std::uint8_t>(std::lround(alpha * px[c] + (1.0 - alpha) * 255.0));
      }
    }
    std::swap(cur, prev);
  }
  return img;
}

std::vector<std::uint8_t> readBytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

TEST(ReportPng, DecoderRejectsCorruption) {
  // a 2×1 RGB PNG (stored deflate block), hand-assembled from the PNG and zlib specifications
  auto chunk = [](std::vector<std::uint8_t>& out, const char* type,
                  const std::vector<std::uint8_t>& data) {
    const std::uint32_t n = static_cast<std::uint32_t>(data.size());
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(n >> s));
    std::vector<std::uint8_t> td(type, type + 4);
    td.insert(td.end(), data.begin(), data.end());
    out.insert(out.end(), td.begin(), td.end());
    const std::uint32_t c = crc32(td.data(), td.size());
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(c >> s));
  };
  const std::vector<std::uint8_t> raw{0, 255, 0, 0, 10, 20, 30};  // filter 0, red, dark blue-ish
  std::uint32_t a = 1, b = 0;
  for (const std::uint8_t c : raw) {
    a = (a + c) % 65521u;
    b = (b + a) % 65521u;
  }
  const std::uint32_t adler = (b << 16) | a;
  std::vector<std::uint8_t> z{0x78, 0x01, 0x01, 7, 0, static_cast<std::uint8_t>(~7), 0xFF};
  z.insert(z.end(), raw.begin(), raw.end());
  for (int s = 24; s >= 0; s -= 8) z.push_back(static_cast<std::uint8_t>(adler >> s));
  std::vector<std::uint8_t> png{137, 80, 78, 71, 13, 10, 26, 10};
  chunk(png, "IHDR", {0, 0, 0, 2, 0, 0, 0, 1, 8, 2, 0, 0, 0});
  chunk(png, "IDAT", z);
  chunk(png, "IEND", {});
  const Image img = decodePng(png);
  ASSERT_EQ(img.w, 2);
  ASSERT_EQ(img.h, 1);
  EXPECT_EQ(img.rgb, (std::vector<std::uint8_t>{255, 0, 0, 10, 20, 30}));
  std::vector<std::uint8_t> bad = png;
  bad[8 + 12 + 13 + 8 + 8] ^= 1;  // a byte of the IDAT payload: CRC fails
  EXPECT_THROW(decodePng(bad), std::runtime_error);
}

/// Distance of a colour from the viridis curve (same anchors as the report), for saturated colours.
double viridisDistance(int r, int g, int b) {
  static const std::vector<std::array<double, 3>> curve = [] {
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
    std::vector<std::array<double, 3>> c;
    for (int i = 0; i < 10; ++i) {
      for (int s = 0; s < 24; ++s) {
        const double f = s / 24.0;
        c.push_back({kV[i][0] + f * (kV[i + 1][0] - kV[i][0]),
                     kV[i][1] + f * (kV[i + 1][1] - kV[i][1]),
                     kV[i][2] + f * (kV[i + 1][2] - kV[i][2])});
      }
    }
    c.push_back({253, 231, 37});
    return c;
  }();
  double best = 1e9;
  for (const auto& c : curve) {
    best = std::min(best, std::hypot(r - c[0], g - c[1], b - c[2]));
  }
  return best;
}

TEST(ReportChromium, HeadlessScreenshotShowsTheMaps) {
  const std::string chromium = "/usr/bin/chromium";
  if (!fs::exists(chromium)) {
    const char* ci = std::getenv("CI");
    if (ci != nullptr && std::string(ci) == "true")
      FAIL() << "no " << chromium << " (scripts/setup.sh installs it)";
    GTEST_SKIP() << "no " << chromium << " (scripts/setup.sh installs it)";
  }
  const Synthetic s = makeSynthetic(20201);
  const std::string html = api::renderReport(makeInput(s, false));
  const std::string dir = test::tempDir("report-chromium");
  const std::string page = dir + "/report.html", png = dir + "/report.png",
                    log = dir + "/chromium.log";
  test::writeFile(page, html);
  const std::string cmd =
      "timeout 60 '" + chromium +
      "' --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync "
      "--hide-scrollbars --user-data-dir='" +
      dir + "/profile' --window-size=1400,2000 --screenshot='" + png + "' 'file://" + page +
      "' >'" + log + "' 2>&1 </dev/null";
  const int rc = std::system(cmd.c_str());
  ASSERT_TRUE(fs::exists(png)) << "chromium exit " << rc << "\n" << test::readFile(log);
  if (const char* keep = std::getenv("ROPREC_REPORT_SCREENSHOT")) {  // for a look by a human
    fs::copy_file(png, keep, fs::copy_options::overwrite_existing);
    fs::copy_file(page, std::string(keep) + ".html", fs::copy_options::overwrite_existing);
  }

  const Image img = decodePng(readBytes(png));
  ASSERT_EQ(img.w, 1400);
  ASSERT_EQ(img.h, 2000);
  const size_t n = static_cast<size_t>(img.w) * static_cast<size_t>(img.h);
  size_t non_white = 0;
  std::vector<std::uint32_t> colours;
  // viridis pixels in short horizontal runs (markers, not the colour bars), per third of the width
  std::array<size_t, 3> marker_px{};
  size_t bar_px = 0, ring_px = 0;
  for (int y = 0; y < img.h; ++y) {
    int run = 0;
    for (int x = 0; x <= img.w; ++x) {
      bool vir = false;
      if (x < img.w) {
        const std::uint8_t* p = &img.rgb[3 * (static_cast<size_t>(y) * static_cast<size_t>(img.w) +
                                              static_cast<size_t>(x))];
        const int r = p[0], g = p[1], b = p[2];
        if (r < 245 || g < 245 || b < 245) ++non_white;
        colours.push_back((std::uint32_t(r) << 16) | (std::uint32_t(g) << 8) | std::uint32_t(b));
        const int sat = std::max({r, g, b}) - std::min({r, g, b});
        vir = sat > 40 && viridisDistance(r, g, b) < 8.0;
        if (std::hypot(r - 227, g - 18, b - 11) < 20)
          ++ring_px;  // configuration-change rings (#e3120b)
      }
      if (vir) {
        ++run;
      } else if (run > 0) {
        if (run <= 30) {
          marker_px[static_cast<size_t>(std::min(2, (x - run / 2) * 3 / img.w))] +=
              static_cast<size_t>(run);
        } else {
          bar_px += static_cast<size_t>(run);
        }
        run = 0;
      }
    }
  }
  std::sort(colours.begin(), colours.end());
  const size_t distinct =
      static_cast<size_t>(std::unique(colours.begin(), colours.end()) - colours.begin());
  const double non_white_fraction = static_cast<double>(non_white) / static_cast<double>(n);
  RecordProperty("screenshot", png);
  EXPECT_GT(non_white_fraction, 0.08) << png;
  EXPECT_GT(distinct, 500u) << png;
  // three maps side by side, each with markers (≥ ~20 px a hole for 58 holes)
  for (size_t third = 0; third < 3; ++third)
    EXPECT_GT(marker_px[third], 1000u) << "third " << third << " " << png;
  EXPECT_GT(bar_px, 3000u) << png;  // colour bars
  EXPECT_GT(ring_px, 40u) << png;   // configuration-change rings
  if (!HasFailure()) fs::remove_all(dir);
}

// ------------------------------------------------------------------ the sample job

std::string sample(const std::string& rel) { return test::sourceDir() + "/samples/" + rel; }

/// The fields of one CSV line (RFC 4180: quoted fields, "" inside quotes).
std::vector<std::string> csvFields(const std::string& line) {
  std::vector<std::string> f(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (quoted && ch == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      f.back() += '"';
      ++i;
    } else if (ch == '"') {
      quoted = !quoted;
    } else if (ch == ',' && !quoted) {
      f.emplace_back();
    } else {
      f.back() += ch;
    }
  }
  return f;
}

/// The cells of the per-hole table's body rows, tags stripped (one vector per row).
std::vector<std::vector<std::string>> tableRows(const std::string& html) {
  const size_t t0 = html.find("<table class=\"holes\"");
  const size_t b0 = html.find("<tbody>", t0), b1 = html.find("</tbody>", b0);
  std::vector<std::vector<std::string>> rows;
  const std::string body = html.substr(b0, b1 - b0);
  const std::regex tag("<[^>]*>");
  for (size_t r = body.find("<tr"); r != std::string::npos; r = body.find("<tr", r + 3)) {
    const size_t e = body.find("</tr>", r);
    std::vector<std::string> cells;
    for (size_t c = body.find("<td", r); c != std::string::npos && c < e;
         c = body.find("<td", c + 3)) {
      const size_t ce = body.find("</td>", c);
      const std::string open = body.substr(c, body.find('>', c) - c);
      std::string text = std::regex_replace(body.substr(c, ce - c), tag, "");
      cells.push_back(text);
      const size_t cs = open.find("colspan=\"");
      if (cs != std::string::npos) {
        for (int k = 1; k < std::stoi(open.substr(cs + 9)); ++k) cells.emplace_back("");
      }
    }
    rows.push_back(cells);
  }
  return rows;
}

std::vector<std::string> tableHeads(const std::string& html) {
  const size_t t0 = html.find("<table class=\"holes\"");
  const size_t h0 = html.find("<thead>", t0), h1 = html.find("</thead>", h0);
  std::vector<std::string> heads;
  const std::string head = html.substr(h0, h1 - h0);
  for (size_t c = head.find("<th"); c != std::string::npos; c = head.find("<th", c + 3)) {
    if (head[c + 3] != '>' && head[c + 3] != ' ') continue;  // <thead>
    heads.push_back(head.substr(c, head.find("</th>", c) - c));
  }
  return heads;
}

size_t columnOf(const std::vector<std::string>& heads, const std::string& what) {
  for (size_t i = 0; i < heads.size(); ++i) {
    if (heads[i].find(what) != std::string::npos) return i;
  }
  ADD_FAILURE() << "no column " << what;
  return 0;
}

TEST(ReportSample, VerdictsPartFrameAlignedTableAndTheWhy) {
  const api::PredictionResult r = api::predictJob(sample("cells/housing-kr120.xml"),
                                                  sample("emotor-housing/housing_kr120.src"));
  const std::string html = api::predictionReport(r);
  const CapabilitySummary& sum = r.summary;
  ASSERT_EQ(sum.holes, 204);
  // every marker carries its verdict (3 maps per face)
  EXPECT_EQ(countOf(html, "class=\"mk v-"), 3u * 204u);
  EXPECT_EQ(countOf(html, "class=\"mk v-comp\""),
            3u * static_cast<size_t>(sum.conforms_after_compensation));
  // failing ids written on the maps without hovering (capped per map), t/2 on the bars
  if (sum.conforms < sum.holes) {
    EXPECT_GT(countOf(html, "<text class=\"flabel f-"), 0u);
  }
  EXPECT_GE(countOf(html, "<g class=\"tol\">"), 2u * 4u);  // e⊥ and U of four faces
  EXPECT_NE(html.find("t/2 = 100"), std::string::npos);
  // maps in the part frame: the top face on part X/Y, the walls with part Z up; no rotated axes
  EXPECT_NE(html.find(">part X [mm]</text>"), std::string::npos);
  EXPECT_NE(html.find(">part Y [mm]</text>"), std::string::npos);
  EXPECT_NE(html.find(">part Z [mm]</text>"), std::string::npos);
  EXPECT_EQ(html.find("(0.707, 0.707, 0.000)"), std::string::npos);
  EXPECT_EQ(html.find("base X [mm]"), std::string::npos);

  // the table: one cell per column in every row, units in the heads, one number per cell
  const std::vector<std::string> heads = tableHeads(html);
  const auto rows = tableRows(html);
  ASSERT_EQ(rows.size(), 204u);
  for (const auto& row : rows) ASSERT_EQ(row.size(), heads.size());
  std::string all_heads;
  for (const std::string& h : heads) all_heads += h;
  for (const char* unit :
       {"<small>\u00b5m</small>", "<small>mm</small>", "<small>deg, ctrl</small>",
        "<small>\u00b5rad</small>", "<small>s</small>"}) {
    EXPECT_NE(all_heads.find(unit), std::string::npos) << unit;
  }
  const std::regex number("^-?[0-9]+(\\.[0-9]+)?$");
  const size_t c_e = columnOf(heads, ">e\u22a5<br>");
  const size_t c_d = columnOf(heads, "|\u03b4robot|");
  const size_t c_g = columnOf(heads, "\u2192 gravity"), c_t = columnOf(heads, "\u2192 tool weight");
  const size_t c_p = columnOf(heads, "\u2192 process"), c_c = columnOf(heads, "\u2192 controller");
  const size_t c_j1 = columnOf(heads, ">J1<");
  EXPECT_NE(heads[c_e].find("<small>\u00b5m</small>"), std::string::npos);
  EXPECT_NE(heads[c_j1].find("<small>deg, ctrl</small>"), std::string::npos);
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& row = rows[i];
    for (const size_t c : {c_e, c_d, c_g, c_t, c_p, c_c, c_j1})
      ASSERT_TRUE(std::regex_match(row[c], number))
          << "row " << i << " col " << c << " '" << row[c] << "'";
    // the why: the four parts along δrobot add up to |δrobot| (each printed to 0.1 µm)
    const double parts =
        std::stod(row[c_g]) + std::stod(row[c_t]) + std::stod(row[c_p]) + std::stod(row[c_c]);
    EXPECT_NEAR(parts, std::stod(row[c_d]), 0.26) << "row " << i;
    // the printed |δrobot| is the prediction's
    EXPECT_NEAR(std::stod(row[c_d]), r.holes[i].d_robot.norm() * 1e6, 0.051) << "row " << i;
  }
}

TEST(ReportSample, SplitIsNearlyAdditiveAndIndependentOfTheProgram) {
  const api::PredictionResult r = api::predictJob(sample("cells/housing-kr120.xml"),
                                                  sample("emotor-housing/housing_kr120.src"));
  std::vector<const HolePrediction*> preds;
  for (const HolePrediction& p : r.holes) preds.push_back(&p);
  const auto split =
      api::splitRobotDeviations(r.context.model, r.context.tool, r.context.job.requests, preds);
  ASSERT_EQ(split.size(), r.holes.size());
  double worst = 0;
  for (size_t i = 0; i < split.size(); ++i) {
    ASSERT_TRUE(split[i].has_value()) << r.holes[i].id;
    const api::DeviationSplit& s = *split[i];
    // exact by construction: the parts sum to δrobot
    EXPECT_LT((s.gravity + s.tool + s.process + s.controller - r.holes[i].d_robot).norm(), 1e-12);
    // the deflection is nonlinear: the process part on the loaded arm vs the process load on the
    // unloaded arm differs by the second-order coupling only (< 2 % of the part + 0.05 µm)
    const double diff = (s.process - s.process_alone).norm();
    EXPECT_LT(diff, 0.02 * s.process.norm() + 0.05e-6) << r.holes[i].id;
    worst = std::max(worst, diff / std::max(1e-12, s.process.norm()));
    // the KR 120 cell's controller compensates gravity with this tool: weight + reference ≈ 0
    // within the compensation's own linearisation (≤ 5 µm), so δrobot is mostly the process part
    EXPECT_LT((s.gravity + s.tool + s.controller).norm(), 5e-6) << r.holes[i].id;
  }
  RecordProperty("worst_relative_non_additivity", std::to_string(worst));
}

/// The reports' split leaves out the process load alone (not shown): one re-evaluation less, the
/// four parts shown the very same numbers.
TEST(ReportSample, SplitWithoutTheProcessAloneHasTheSameParts) {
  const api::PredictionResult r = api::predictJob(sample("cells/housing-kr120.xml"),
                                                  sample("emotor-housing/housing_kr120.src"));
  std::vector<const HolePrediction*> preds;
  for (const HolePrediction& p : r.holes) preds.push_back(&p);
  const auto& req = r.context.job.requests;
  const auto full = api::splitRobotDeviations(r.context.model, r.context.tool, req, preds, 2);
  const auto shown =
      api::splitRobotDeviations(r.context.model, r.context.tool, req, preds, 2, false);
  ASSERT_EQ(full.size(), shown.size());
  for (size_t i = 0; i < full.size(); ++i) {
    ASSERT_EQ(full[i].has_value(), shown[i].has_value()) << i;
    if (!full[i]) continue;
    EXPECT_TRUE(full[i]->gravity == shown[i]->gravity) << i;
    EXPECT_TRUE(full[i]->tool == shown[i]->tool) << i;
    EXPECT_TRUE(full[i]->process == shown[i]->process) << i;
    EXPECT_TRUE(full[i]->controller == shown[i]->controller) << i;
    EXPECT_GT(full[i]->process_alone.norm(), 0) << i;
    EXPECT_TRUE(shown[i]->process_alone.isZero(0)) << i;
  }
}

TEST(ReportSample, StreamedReportHasTheBytesOfTheWholeJobsReport) {
  // one drill, and a tool table whose drills have TCPs of their own (a split model per drill)
  for (const auto& [cell, program] :
       {std::pair<std::string, std::string>{"cells/housing-kr120.xml",
                                            "emotor-housing/housing_kr120.src"},
        {"cells/housing-kr120-tools.xml", "emotor-housing/housing_kr120_tools.src"}}) {
    const api::PredictionResult whole = api::predictJob(sample(cell), sample(program));
    const std::string expected = api::predictionReport(whole);
    api::JobOptions o;
    o.threads = 2;
    std::optional<api::PredictionReportStream> report;
    size_t seen = 0;
    const api::PredictionResult r = api::predictJobStreaming(
        sample(cell), sample(program), o,
        [&](size_t first, std::span<const HolePrediction> holes,
            std::span<const HoleRequest> requests, int threads) {
          EXPECT_EQ(first, seen);
          seen += holes.size();
          report->holes(holes, requests, threads);
        },
        [&](const api::PredictionContext& c) { report.emplace(c, 2); });
    EXPECT_EQ(seen, whole.holes.size());
    EXPECT_TRUE(r.holes.empty());  // nothing kept but the report's compact records
    EXPECT_EQ(report->finish(r), expected) << cell;
  }
}

/// A generated KRL drilling job of `n` holes on the housing's top face (KR 120 sample cell), like
/// scripts/gen-drill-job.py: approach, feed, dwell, retract on a 1.2 mm grid.
std::string writeDrillJob(const std::string& path, int n) {
  const int cols = static_cast<int>(std::ceil(std::sqrt(n * 1.2)));
  const double x0 = -0.6 * (cols - 1), y0 = -0.6 * ((n + cols - 1) / cols - 1);
  std::ostringstream f;
  f << "&ACCESS RVP\n&REL 1\nDEF drill_job ( )\n;FOLD INI\nBAS (#INITMOV,0 )\n;ENDFOLD (INI)\n"
    << "$BASE = {FRAME: X 1350.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C 0.000}\n"
    << "$TOOL = {FRAME: X 0.000,Y 0.000,Z 320.000,A 0.000,B 0.000,C 0.000}\n";
  char p[160];
  for (int k = 0; k < n; ++k) {
    const double x = x0 + 1.2 * (k % cols), y = y0 + 1.2 * (k / cols);
    f << "; B" << k + 1 << " drill D6.8 depth 16.0\n$VEL.CP = 0.25000\n";
    for (const auto& [move, z] : {std::pair<const char*, double>{"PTP", 300.0},
                                  {"LIN", 252.0},
                                  {"LIN", 234.0},
                                  {"LIN", 300.0}}) {
      std::snprintf(p, sizeof p, "%s {X %.3f,Y %.3f,Z %.3f,A 0.000,B 0.000,C 180.000}\n", move, x,
                    y, z);
      f << p;
      if (z == 234.0) f << "WAIT SEC 0.3\n";
    }
  }
  f << "END\n";
  test::writeFile(path, f.str());
  return path;
}

/// A large job (more than kReportAggregateAbove holes, several blocks) streamed on 1 and 2
/// threads: its rows rendered ahead as the holes go past, the document written piece by piece or
/// as one string, the bytes of the whole job's report.
TEST(ReportSample, StreamedLargeReportHasTheBytesOfTheWholeJobsReport) {
  const std::string dir = test::tempDir("report-stream-large");
  const std::string cell = sample("cells/housing-kr120.xml");
  const std::string program =
      writeDrillJob(dir + "/job.src", static_cast<int>(api::kReportAggregateAbove) + 333);
  const api::PredictionResult whole = api::predictJob(cell, program);
  ASSERT_GT(whole.holes.size(), api::kReportAggregateAbove);
  const std::string expected = api::predictionReport(whole);
  for (const int threads : {1, 2}) {
    api::JobOptions o;
    o.threads = threads;
    std::optional<api::PredictionReportStream> report;
    int blocks = 0;
    const api::PredictionResult r = api::predictJobStreaming(
        cell, program, o,
        [&](size_t, std::span<const HolePrediction> holes, std::span<const HoleRequest> requests,
            int t) {
          ++blocks;
          report->holes(holes, requests, t);
        },
        [&](const api::PredictionContext& c) { report.emplace(c, threads); });
    EXPECT_GT(blocks, 1);
    std::string pieces;
    size_t n_pieces = 0;
    report->finish(r, [&](std::string_view b) {
      pieces += b;
      ++n_pieces;
    });
    EXPECT_GT(n_pieces, 2u) << "written piece by piece";
    EXPECT_TRUE(pieces == expected) << threads << " threads";
  }
  fs::remove_all(dir);
}

Synthetic makeLarge(size_t n);

/// The streamed holes of a synthetic job as a streamed report keeps them.
std::vector<api::PredictedHole> predictedHoles(const Synthetic& s) {
  std::vector<api::PredictedHole> out;
  for (size_t i = 0; i < s.preds.size(); ++i) {
    api::PredictedHole& h = out.emplace_back();
    h.prediction = api::reportPrediction(s.preds[i]);
    h.position = s.poses[i].translation();
    h.axis = s.poses[i].linear().col(2);
  }
  return out;
}

/// The predicted holes of s with more columns late in the job: from hole 1500 on a second budget
/// term, from hole 2400 the δrobot split `split`.
std::vector<api::PredictedHole> holesWithLateColumns(const Synthetic& s,
                                                     const api::DeviationSplit& split) {
  std::vector<api::PredictedHole> holes = predictedHoles(s);
  for (size_t i = 1500; i < holes.size(); ++i) {
    if (holes[i].prediction.status != HoleStatus::kOk) continue;
    holes[i].prediction.budget.push_back({"mach_runout", 3.5e-6, true});
    if (i >= 2400) holes[i].split = split;
  }
  return holes;
}

/// The report input of the large job s with its holes `holes` on 2 threads (card: an empty card
/// that outlives the input).
api::ReportInput largeReportInput(const Synthetic& s, const std::vector<api::PredictedHole>& holes,
                                  const RobotCard& card) {
  api::ReportInput in = makeInput(Synthetic{}, false);
  in.summary = summarize(s.preds);
  in.card = &card;
  in.predicted = holes;
  in.threads = 2;
  return in;
}

/// Rows rendered ahead before a later hole brought another budget term or the first δrobot split
/// (the table then has more columns) are rendered again: the bytes of the report rendered with no
/// row ahead, whatever the runs and their worker count.
TEST(Report, RowsRenderedAheadWithOtherColumnsAreRenderedAgain) {
  const size_t n = api::kReportAggregateAbove + 900;
  const Synthetic s = makeLarge(n);
  const std::vector<api::PredictedHole> holes = holesWithLateColumns(s, api::DeviationSplit{});
  const RobotCard card{};
  api::ReportInput in = largeReportInput(s, holes, card);
  const std::string expected = api::renderReport(in);
  ASSERT_NE(expected.find("u runout"), std::string::npos);
  ASSERT_NE(expected.find("\u2192 gravity"), std::string::npos);
  for (const int threads : {1, 3}) {
    api::RowsAheadRenderer ahead(&card);
    std::vector<api::RenderedRows> rows;
    for (size_t b = 0; b < n - 100; b += 700) {  // the last 100 rows are left to renderReport
      const size_t e = std::min(n - 100, b + 700);
      ahead.render(std::span(holes).subspan(b, e - b), b, threads, rows);
    }
    ASSERT_GE(rows.size(), 4u);
    EXPECT_EQ(rows.front().terms, 1u);
    EXPECT_FALSE(rows.front().split_columns);
    EXPECT_TRUE(rows.back().split_columns);
    in.rows_ahead = rows;
    EXPECT_TRUE(api::renderReport(in) == expected) << threads;
    std::string pieces;
    api::renderReport(in, [&](std::string_view b) { pieces += b; });
    EXPECT_TRUE(pieces == expected) << threads;
    // runs that do not start where the one before ended are refused
    in.rows_ahead.erase(in.rows_ahead.begin() + 1);
    EXPECT_THROW(api::renderReport(in), std::invalid_argument);
  }
}

/// A large streamed report keeps of each hole only what its maps read (MappedHole), with the
/// totals counted as the holes went past and every row rendered ahead: rows rendered before a
/// later hole brought another budget term or the first δrobot split are widened (a dash cell for
/// each column they lacked, an unpredicted hole's reason spanning them): the bytes of the report
/// rendered from every hole, whatever the runs and their worker count.
TEST(Report, MappedHolesWidenTheRowsRenderedWithFewerColumns) {
  const size_t n = api::kReportAggregateAbove + 900;
  const Synthetic s = makeLarge(n);
  const std::vector<api::PredictedHole> holes =
      holesWithLateColumns(s, api::DeviationSplit{Vec3(1e-6, 0, 0), Vec3(0, 2e-6, 0)});
  const RobotCard card{};
  api::ReportInput in = largeReportInput(s, holes, card);
  const std::string expected = api::renderReport(in);
  ASSERT_NE(expected.find("u runout"), std::string::npos);
  ASSERT_NE(expected.find("\u2192 gravity"), std::string::npos);
  in.predicted.clear();
  for (const int threads : {1, 3}) {
    api::RowsAheadRenderer ahead(&card);
    api::StreamedTotals totals;
    std::vector<api::RenderedRows> rows;
    std::vector<api::MappedHole> mapped;
    for (size_t b = 0; b < n; b += 700) {
      const std::span<const api::PredictedHole> block =
          std::span(holes).subspan(b, std::min(n, b + 700) - b);
      totals.add(block);
      ahead.render(block, b, threads, rows);
      for (const api::PredictedHole& h : block)
        mapped.push_back({h.prediction, h.position, h.axis});
    }
    ASSERT_GE(rows.size(), 4u);
    EXPECT_EQ(rows.front().terms, 1u);
    EXPECT_FALSE(rows.front().split_columns);
    EXPECT_TRUE(rows.back().split_columns);
    in.mapped = mapped;
    in.totals = totals;
    in.rows_ahead = rows;
    EXPECT_TRUE(api::renderReport(in) == expected) << threads;
    std::string pieces;
    api::renderReport(in, [&](std::string_view b) { pieces += b; });
    EXPECT_TRUE(pieces == expected) << threads;
    // every row of a mapped job is rendered ahead
    in.rows_ahead.pop_back();
    EXPECT_THROW(api::renderReport(in), std::invalid_argument);
  }
}

/// Compensation: the offset per target (mm, deg), flags before → after, verdict before → after.
TEST(Report, CompensationShowsOffsetsFlagsAndVerdictsBeforeAfter) {
  const Synthetic s = makeSynthetic(20201);
  api::ReportInput in = makeInput(s, true);
  std::vector<HolePrediction> after(s.preds.size());
  for (size_t i = 0; i < in.holes.size(); ++i) {
    if (s.preds[i].status != HoleStatus::kOk) continue;
    Pose P = s.poses[i];
    P.translation() += Vec3(0.1e-3, -0.2e-3, 0.05e-3);
    P.linear() =
        P.linear() * Eigen::AngleAxisd(0.5 * kPi / 180.0, Vec3::UnitX()).toRotationMatrix();
    in.holes[i].T_W_programmed = P;
    in.holes[i].config_after = i == 3 ? std::string("S 010 T 000011") : s.preds[i].config;
    after[i] = s.preds[i];
    after[i].verdict = Verdict::kConforms;
    in.holes[i].after = &after[i];
  }
  const std::string html = api::renderReport(in);
  const std::vector<std::string> heads = tableHeads(html);
  const auto rows = tableRows(html);
  ASSERT_EQ(rows.size(), s.preds.size());
  const size_t cx = columnOf(heads, ">\u0394x<"), cy = columnOf(heads, ">\u0394y<");
  const size_t cz = columnOf(heads, ">\u0394z<"), cn = columnOf(heads, "|\u0394p|");
  const size_t cr = columnOf(heads, ">\u0394rot<"), cf = columnOf(heads, "Config before");
  const size_t cvb = columnOf(heads, "Verdict before"), cva = columnOf(heads, "Verdict after");
  EXPECT_NE(heads[cx].find("<small>mm</small>"), std::string::npos);
  EXPECT_NE(heads[cr].find("<small>deg</small>"), std::string::npos);
  for (size_t i = 0; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), heads.size()) << i;
    if (s.preds[i].status != HoleStatus::kOk) continue;
    EXPECT_EQ(rows[i][cx], "0.100");
    EXPECT_EQ(rows[i][cy], "-0.200");
    EXPECT_EQ(rows[i][cz], "0.050");
    EXPECT_EQ(rows[i][cn], "0.229");
    EXPECT_EQ(rows[i][cr], "0.500");
    EXPECT_EQ(rows[i][cva], "conforms");
    const std::string badge = s.preds[i].verdict == Verdict::kConforms     ? "conforms"
                              : s.preds[i].verdict == Verdict::kNotCapable ? "not capable"
                                                                           : "after comp.";
    EXPECT_EQ(rows[i][cvb], badge);
    const std::string flags = s.preds[i].config + " \u2192 " +
                              (i == 3 ? std::string("S 010 T 000011") : s.preds[i].config);
    EXPECT_EQ(rows[i][cf], flags) << i;
  }
  EXPECT_EQ(countOf(html, "class=\"l cfgchg\""), 1u);
}

TEST(ReportSample, CompensationReportOfTheSample) {
  const std::string dir = test::tempDir("report-compensate");
  api::CompensationJob job;
  const api::CompensationResult r = api::compensateJob(
      sample("cells/housing-kr120.xml"), sample("emotor-housing/housing_kr120.src"), job);
  const std::string html = api::compensationReport(r, "housing_kr120.src");
  const std::vector<std::string> heads = tableHeads(html);
  const auto rows = tableRows(html);
  ASSERT_EQ(rows.size(), r.holes.size());
  const size_t cn = columnOf(heads, "|\u0394p|"), cf = columnOf(heads, "Config before");
  for (size_t i = 0; i < rows.size(); ++i) {
    const HoleCompensation& h = r.holes[i];
    ASSERT_TRUE(h.ok) << h.id;
    const double dp =
        (h.T_programmed.translation() - r.context.job.requests[i].T_W_tcp.translation()).norm();
    EXPECT_NEAR(std::stod(rows[i][cn]), dp * 1e3, 0.0006) << h.id;
    EXPECT_EQ(rows[i][cf], h.config_before + " \u2192 " + h.config_text) << h.id;
  }
}

/// Why: per hole the rotation about the drill axis with its reason and the flag change with its
/// reason, in the report and in the CSV export (flip-free on the sample).
TEST(ReportSample, CompensationReasonsInTheReportAndTheCsv) {
  api::CompensationJob job;
  job.options.mode = OrientationMode::kFlipFree;
  api::CompensationResult r = api::compensateJob(sample("cells/housing-kr120.xml"),
                                                 sample("emotor-housing/housing_kr120.src"), job);
  // flip-free keeps every rotation and flag of the sample (nothing forces a change): give two
  // holes a change and its reason, with the characters CSV and HTML must escape
  ASSERT_GT(r.holes.size(), 5u);
  r.holes[3].psi = 30.0 * kDeg;
  r.holes[3].psi_reason = "\u03c8 = 0 leaves joint 6's limit, \"-360\" <deg>";
  r.holes[5].config_before = "S 2 T 3";
  r.holes[5].config_text = "S 2 T 35";
  r.holes[5].config_changed = true;
  r.holes[5].config_reason = "the target cannot be reached with T 3, A4 \u2192 -190";
  const std::string html = api::compensationReport(r, "housing_kr120.src");
  EXPECT_NE(html.find("\u03c8 = 0 leaves joint 6&#39;s limit, &quot;-360&quot; &lt;deg&gt;"),
            std::string::npos);
  const std::vector<std::string> heads = tableHeads(html);
  const auto rows = tableRows(html);
  ASSERT_EQ(rows.size(), r.holes.size());
  const size_t crot = columnOf(heads, "rot. about axis"), cwr = columnOf(heads, "Why rotated");
  const size_t cwc = columnOf(heads, "Why config changed");
  const std::string csv = api::compensationTargets(r, "housing_kr120.src", true);
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> names = csvFields(line);
  const auto col = [&](const std::string& n) {
    const auto it = std::find(names.begin(), names.end(), n);
    EXPECT_NE(it, names.end()) << n;
    return static_cast<size_t>(it - names.begin());
  };
  const size_t k_rot = col("rotation_about_axis_deg"), k_rr = col("rotation_reason");
  const size_t k_cb = col("config_before"), k_cc = col("config_changed");
  const size_t k_cr = col("config_reason"), k_cfg = col("config");
  int rotated = 0;
  for (size_t i = 0; i < rows.size(); ++i) {
    const HoleCompensation& h = r.holes[i];
    ASSERT_TRUE(h.ok) << h.id;
    EXPECT_NEAR(std::stod(rows[i][crot]), h.psi / kDeg, 0.006) << h.id;
    const std::string dash = "\u2014";
    const auto unescaped = [](std::string s) {
      for (const auto& [from, to] : {std::pair<std::string, std::string>{"&#39;", "'"},
                                     {"&quot;", "\""},
                                     {"&lt;", "<"},
                                     {"&gt;", ">"},
                                     {"&amp;", "&"}}) {
        for (size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + 1))
          s.replace(p, from.size(), to);
      }
      return s;
    };
    EXPECT_EQ(unescaped(rows[i][cwr]), h.psi_reason.empty() ? dash : h.psi_reason.str()) << h.id;
    EXPECT_EQ(unescaped(rows[i][cwc]), h.config_reason.empty() ? dash : h.config_reason.str())
        << h.id;
    // a rotation without a reason would be a change nobody asked for
    if (std::fabs(h.psi) > 1e-9) {
      ++rotated;
      EXPECT_NE(rows[i][cwr], dash) << h.id;
    }
    ASSERT_TRUE(std::getline(in, line));
    const std::vector<std::string> f = csvFields(line);
    ASSERT_EQ(f.size(), names.size()) << line;
    EXPECT_NEAR(std::stod(f[k_rot]), h.psi / kDeg, 1e-4) << h.id;
    EXPECT_EQ(f[k_rr], h.psi_reason) << h.id;
    EXPECT_EQ(f[k_cb], h.config_before) << h.id;
    EXPECT_EQ(f[k_cc], f[k_cb] != f[k_cfg] ? "1" : "0") << h.id;
    EXPECT_EQ(f[k_cr], h.config_reason) << h.id;
  }
  EXPECT_GE(rotated, 1);
  EXPECT_EQ(rows[5][columnOf(heads, "Config before")], "S 2 T 3 \u2192 S 2 T 35");
}

/// FANUC: the report's J1..J6 are the controller's (J3_ctrl = J3_urdf - J2_urdf, the card's
/// j23_coupling = -1, signs +1, offsets 0), and the JSON adds controller_joints_deg.
TEST(ReportSample, FanucJointsAsTheControllerShowsThem) {
  const std::string dir = test::tempDir("report-fanuc");
  const test::RunResult run = test::runRoprec(
      "predict --cell '" + sample("cells/housing-r2000.xml") + "' '" +
      sample("emotor-housing/housing_r2000.ls") + "' --frame cell --tool cell --json '" + dir +
      "/p.json' --report '" + dir + "/p.html'");
  ASSERT_LE(run.exit_code, 1) << run.err;
  const std::string html = test::readFile(dir + "/p.html");
  const std::string json = test::readFile(dir + "/p.json");
  const std::vector<std::string> heads = tableHeads(html);
  const auto rows = tableRows(html);
  const size_t c1 = columnOf(heads, ">J1<");
  for (int j = 0; j < 6; ++j)
    EXPECT_NE(heads[c1 + j].find("<small>deg, ctrl</small>"), std::string::npos) << j;
  EXPECT_NE(html.find("as the FANUC controller shows it"), std::string::npos);
  EXPECT_NE(html.find("J3<sub>ctrl</sub> = J3<sub>URDF</sub> \u2212 J2<sub>URDF</sub>"),
            std::string::npos);
  // the JSON's URDF joints, hole by hole, in table order
  const std::regex urdf(
      "\"joints_deg\": *\\[([^\\]]*)\\],\\s*\"controller_joints_deg\": *\\[([^\\]]*)\\]");
  size_t n = 0;
  double max_j3_gap = 0;
  for (std::sregex_iterator it(json.begin(), json.end(), urdf), end; it != end; ++it, ++n) {
    ASSERT_LT(n, rows.size());
    std::vector<double> q, qc;
    for (const auto& [text, out] : {std::pair{(*it)[1].str(), &q}, {(*it)[2].str(), &qc}}) {
      std::stringstream ss(text);
      for (std::string x; std::getline(ss, x, ',');) out->push_back(std::stod(x));
    }
    ASSERT_EQ(q.size(), 6u);
    const double j3_ctrl = q[2] - q[1];  // FANUC: J3 from the horizontal
    EXPECT_NEAR(qc[2], j3_ctrl, 1e-5) << n;
    EXPECT_NEAR(std::stod(rows[n][c1 + 2]), j3_ctrl, 0.051) << n;
    for (int j : {0, 1, 3, 4, 5}) {
      EXPECT_NEAR(std::stod(rows[n][c1 + j]), q[static_cast<size_t>(j)], 0.051) << n;
      EXPECT_NEAR(qc[static_cast<size_t>(j)], q[static_cast<size_t>(j)], 1e-9) << n;
    }
    max_j3_gap = std::max(max_j3_gap, std::fabs(q[1]));
  }
  EXPECT_EQ(n, rows.size());
  EXPECT_GT(n, 100u);
  EXPECT_GT(max_j3_gap, 5.0);  // J2 ≠ 0 somewhere: the two conventions differ on this job

  // the corrected-target CSV: j*_ctrl_deg next to the URDF j*_deg, the same rule
  const test::RunResult comp = test::runRoprec(
      "compensate --cell '" + sample("cells/housing-r2000.xml") + "' '" +
      sample("emotor-housing/housing_r2000.ls") + "' --frame cell --tool cell --quiet -o '" + dir +
      "/c.ls' --targets '" + dir + "/t.csv'");
  ASSERT_EQ(comp.exit_code, 0) << comp.err;
  std::istringstream csv(test::readFile(dir + "/t.csv"));
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> names = csvFields(line);
  const auto col = [&](const std::string& name) {
    return static_cast<size_t>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  ASSERT_LT(col("j6_ctrl_deg"), names.size());
  size_t targets = 0;
  for (; std::getline(csv, line); ++targets) {
    const std::vector<std::string> f = csvFields(line);
    ASSERT_EQ(f.size(), names.size());
    const double j2 = std::stod(f[col("j2_deg")]), j3 = std::stod(f[col("j3_deg")]);
    EXPECT_NEAR(std::stod(f[col("j3_ctrl_deg")]), j3 - j2, 2e-6) << f[0];
    for (const char* j : {"j1", "j2", "j4", "j5", "j6"})
      EXPECT_EQ(f[col(std::string(j) + "_ctrl_deg")], f[col(std::string(j) + "_deg")]) << f[0];
  }
  EXPECT_EQ(targets, rows.size());
}

// ------------------------------------------------------------------ large jobs in Chromium

/// 20,000 holes on a plate (top face, part frame rotated 30° about z in the base), 2 % not
/// conforming, 0.5 % unreachable.
Synthetic makeLarge(size_t n) {
  Synthetic s;
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> U01(0.0, 1.0);
  const int cols = 200;
  for (size_t i = 0; i < n; ++i) {
    HolePrediction p;
    p.id = "L" + std::to_string(i + 1);
    const size_t row = i / cols;
    const double x = 0.004 * static_cast<double>(i % cols), y = 0.004 * static_cast<double>(row);
    s.poses.push_back(toolPose(Vec3(1.0 + x, -0.2 + y, 0.5), -Vec3::UnitZ()));
    p.tolerance = 0.2e-3;
    p.diameter = 8e-3;
    p.config = "S 2 T 2";
    if (i % 200 == 199) {
      p.status = HoleStatus::kUnreachable;
      p.verdict = Verdict::kUnreachable;
      p.reason = "no IK solution within the joint limits";
      s.preds.push_back(p);
      continue;
    }
    p.d_robot = Vec3(20e-6 + 40e-6 * x, 10e-6 * U01(rng), -30e-6);
    p.d_work = p.d_robot;
    p.position_error = p.d_robot.head<2>().norm();
    p.U_work = p.U_work_exact = 40e-6 + 20e-6 * U01(rng);
    p.budget = {{"robot_repeatability", 16.6e-6, false}};
    p.verdict = i % 50 == 7 ? Verdict::kNotCapable : verdictFor(p.position_error, p.U_work, 0.2e-3);
    s.preds.push_back(p);
  }
  return s;
}

/// Wall time of one headless Chromium screenshot of `page` (s), or a negative value on failure.
double chromiumSeconds(const std::string& chromium, const std::string& dir, const std::string& page,
                       const std::string& png) {
  const std::string cmd =
      "timeout 120 '" + chromium +
      "' --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync "
      "--hide-scrollbars --user-data-dir='" +
      dir + "/profile' --window-size=1400,1600 --screenshot='" + png + "' 'file://" + page +
      "' >'" + dir + "/chromium.log' 2>&1 </dev/null";
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = std::system(cmd.c_str());
  const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return rc == 0 && fs::exists(png) ? t : -1.0;
}

TEST(ReportChromium, TwentyThousandHolesRenderInABrowser) {
  const std::string chromium = "/usr/bin/chromium";
  if (!fs::exists(chromium)) {
    const char* ci = std::getenv("CI");
    if (ci != nullptr && std::string(ci) == "true")
      FAIL() << "no " << chromium << " (scripts/setup.sh installs it)";
    GTEST_SKIP() << "no " << chromium << " (scripts/setup.sh installs it)";
  }
  const Synthetic s = makeLarge(20000);
  api::ReportInput in = makeInput(s, false);
  Pose T_W_part = Pose::Identity();
  T_W_part.linear() = Eigen::AngleAxisd(kPi / 6, Vec3::UnitZ()).toRotationMatrix();
  in.T_W_part = T_W_part;
  in.part_frame = "plate";
  const std::string html = api::renderReport(in);
  // aggregated: bins instead of 60,000 markers; every row in the script's array, a page in the DOM
  EXPECT_EQ(countOf(html, "class=\"mk "), 0u);
  EXPECT_GT(countOf(html, "<rect class=\"bin "), 300u);
  EXPECT_EQ(countOf(html, "<td class=\"c0\">"), 0u);
  EXPECT_EQ(countOf(html, "<td class=\\\"c0\\\">"), 20000u);
  const size_t failing = s.preds.size() - static_cast<size_t>(in.summary.conforms);
  EXPECT_EQ(countOf(html, "<tr class=\\\"pass\\\">"), 20000u - failing);
  EXPECT_EQ(html.find("</script>"), html.rfind("</script>"));  // no row ends the script
  EXPECT_LT(html.size(), 12u << 20) << "bytes";

  const std::string dir = test::tempDir("report-chromium-large");
  const std::string page = dir + "/large.html", blank = dir + "/blank.html";
  test::writeFile(page, html);
  test::writeFile(blank, "<!DOCTYPE html><html><body><p>blank</p></body></html>");
  // Chromium's own start-up is measured on a blank page and subtracted
  const double t_blank = chromiumSeconds(chromium, dir, blank, dir + "/blank.png");
  const double t_page = chromiumSeconds(chromium, dir, page, dir + "/large.png");
  ASSERT_GT(t_blank, 0) << test::readFile(dir + "/chromium.log");
  ASSERT_GT(t_page, 0) << test::readFile(dir + "/chromium.log");
  const double load = t_page - t_blank;
  RecordProperty("chromium_blank_s", std::to_string(t_blank));
  RecordProperty("chromium_report_s", std::to_string(t_page));
  std::printf("20,000-hole report: %.2f MB, Chromium %.2f s (blank page %.2f s) -> %.2f s\n",
              static_cast<double>(html.size()) / 1e6, t_page, t_blank, load);
  const Image img = decodePng(readBytes(dir + "/large.png"));
  EXPECT_EQ(img.w, 1400);
  if (!HasFailure()) fs::remove_all(dir);
}

/// The items of a large report's script array ROPREC_ROWS, decoded (JavaScript string escapes
/// undone, each unit separator back to "</td><td").
std::vector<std::string> scriptRows(const std::string& html) {
  std::vector<std::string> rows;
  const std::string open = "var ROPREC_ROWS=[";
  size_t k = html.find(open);
  if (k == std::string::npos) return rows;
  k += open.size();
  while (k < html.size() && html[k] == '"') {
    std::string row;
    for (++k; k < html.size() && html[k] != '"'; ++k) {
      if (html[k] != '\\') {
        row += html[k];
      } else if (html.compare(k, 4, "\\x1f") == 0) {
        row += "</td><td";
        k += 3;
      } else {
        ++k;
        row += html[k] == 'n' ? '\n' : html[k];
      }
    }
    rows.push_back(row);
    k += 1;                                      // the closing quote
    if (html.compare(k, 2, ",\n") == 0) k += 2;  // the next item
  }
  return rows;
}

/// The rows of a small report's per-hole table body, each "<tr…>…</tr>".
std::vector<std::string> bodyRows(const std::string& html) {
  std::vector<std::string> rows;
  const size_t table = html.find("id=\"holetable\"");
  const size_t b = html.find("<tbody>", table) + 7, e = html.find("</tbody>", b);
  for (size_t k = b; k < e;) {
    const size_t end = html.find("</tr>", k) + 5;
    rows.push_back(html.substr(k, end - k));
    k = end;
  }
  return rows;
}

/// A large job's table rows are rendered on the workers: the bytes do not depend on their count,
/// and each item of the script array is, decoded, the row a small job's table shows for that
/// hole (ids with quotes, backslashes, "</" and non-ASCII characters escaped and back).
TEST(Report, LargeTableRowsOnWorkersAreTheRowsOfTheSmallTable) {
  const size_t small = api::kReportAggregateAbove;
  Synthetic s = makeLarge(2 * small + 777);
  s.preds[3].id = "q\"b\\s</x>\u00e9";
  s.preds[small - 2].id = "line\nbreak";
  api::ReportInput in = makeInput(s, false);
  in.threads = 1;
  const std::string one = api::renderReport(in);
  in.threads = 3;
  EXPECT_TRUE(api::renderReport(in) == one) << "3 workers";
  const std::vector<std::string> large = scriptRows(one);
  ASSERT_EQ(large.size(), s.preds.size());
  Synthetic first;
  first.preds.assign(s.preds.begin(), s.preds.begin() + static_cast<std::ptrdiff_t>(small));
  first.poses.assign(s.poses.begin(), s.poses.begin() + static_cast<std::ptrdiff_t>(small));
  const std::vector<std::string> rows = bodyRows(api::renderReport(makeInput(first, false)));
  ASSERT_EQ(rows.size(), small);
  for (size_t i = 0; i < small; ++i) ASSERT_EQ(large[i], rows[i]) << i;
}

/// The maps' panels are drawn on the workers, each on its own: the bytes of one thread, for a
/// small job of two faces (markers) and a large one (bins), predict and compensate panels.
TEST(Report, MapsDrawnOnWorkersHaveTheBytesOfOneThread) {
  const Synthetic small = makeSynthetic(77);
  const Synthetic large = makeLarge(api::kReportAggregateAbove + 500);
  for (const auto& [s, compensation] :
       {std::pair<const Synthetic*, bool>{&small, false}, {&small, true}, {&large, false}}) {
    api::ReportInput in = makeInput(*s, compensation);
    const std::string one = api::renderReport(in);
    if (s == &small) {
      ASSERT_NE(one.find("Face B"), std::string::npos) << "two faces";
    }
    for (const int threads : {2, 5}) {
      in.threads = threads;
      EXPECT_TRUE(api::renderReport(in) == one) << threads << " threads";
    }
  }
}

/// verify's report: faces in the workobject frame with named axes, the decision on every residual
/// marker, the ids of failing holes written, a table with units and a "failing only" filter.
TEST(ReportSample, VerifyReportNamesAxesDecisionsAndFailingHoles) {
  const std::string dir = test::tempDir("report-verify");
  const std::string v = sample("verification/");
  const test::RunResult r = test::runRoprec(
      "verify --cell " + sample("cells/housing-kr120.xml") + " " + v + "test_kr120.src --holes " +
      v + "test_kr120_holes.csv --measured " + v + "measured.csv --register translation --report " +
      dir + "/v.html --json " + dir + "/v.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = test::readFile(dir + "/v.html");
  const std::string json = test::readFile(dir + "/v.json");
  // three faces (no duplicate from a −0.00 direction component), each drawn twice
  EXPECT_EQ(countOf(html, "<h3>drilled ("), 6u);
  EXPECT_FALSE(std::regex_search(html, std::regex("-0\\.0+[^0-9e]"))) << "a negative zero";
  EXPECT_NE(html.find("workobject X [mm]"), std::string::npos);
  EXPECT_NE(html.find("workobject Y [mm]"), std::string::npos);
  EXPECT_NE(html.find("workobject Z [mm]"), std::string::npos);
  // one residual marker per hole with its decision; failing holes (outside the region or
  // non-conformance proven) labelled and left visible by the filter
  EXPECT_EQ(countOf(html, "class=\"vmk\""), 24u);
  const size_t t0 = html.find("<table class=\"holes\" id=\"holetable\">");
  ASSERT_NE(t0, std::string::npos);
  const std::string table = html.substr(t0, html.find("</table>", t0) - t0);
  const size_t failing = countOf(table, "<tr><td>");
  EXPECT_EQ(countOf(table, "<tr class=\"pass\">") + failing, 24u);
  EXPECT_EQ(countOf(html, "class=\"flabel\""), failing);
  EXPECT_GT(failing, 0u);
  EXPECT_NE(html.find("id=\"failonly\""), std::string::npos);
  EXPECT_NE(html.find("|r|<br><small>\u00b5m</small>"), std::string::npos);
  // sortable like the prediction report: the same inline script, heads in a <thead>, text columns
  // marked; self-contained: that one inline script and nothing loaded
  EXPECT_EQ(countOf(html, "<script"), 1u);
  EXPECT_NE(html.find(std::string("<script>") + api::reportTableScript() + "</script>"),
            std::string::npos);
  EXPECT_EQ(html.find(" src="), std::string::npos);
  EXPECT_NE(table.find("<thead><tr><th>#</th><th class=\"l\" data-t=\"1\">id</th>"),
            std::string::npos);
  EXPECT_EQ(countOf(table, "<tbody>"), 1u);
  EXPECT_NE(html.find(".holes.fonly tr.pass{display:none}"), std::string::npos);
  EXPECT_EQ(countOf(json, "\"non-conformance-proven\"") > 0,
            html.find("#cf222e") != std::string::npos);
}

/// The verify report's table in a real browser: a click on the |r| head sorts the rows by |r|
/// (ascending, aria-sort set), the box hides the passing rows (class fonly on the table).
TEST(ReportChromium, VerifyTableSortsAndFilters) {
  const std::string chromium = "/usr/bin/chromium";
  if (!fs::exists(chromium)) GTEST_SKIP() << "no " << chromium << " (scripts/setup.sh installs it)";
  const std::string dir = test::tempDir("report-verify-sort");
  const std::string v = sample("verification/");
  const test::RunResult r = test::runRoprec(
      "verify --cell " + sample("cells/housing-kr120.xml") + " " + v + "test_kr120.src --holes " +
      v + "test_kr120_holes.csv --measured " + v + "measured.csv --report " + dir + "/v.html");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string html = test::readFile(dir + "/v.html");
  const size_t body_end = html.rfind("</body>");
  ASSERT_NE(body_end, std::string::npos);
  // the user's two clicks, after the report's own script has run
  html.insert(body_end,
              "<script>document.querySelectorAll('#holetable th')[4].click();"
              "document.getElementById('failonly').click();</script>");
  test::writeFile(dir + "/clicked.html", html);
  const test::RunResult dom = test::runCommand(
      "timeout 60 '" + chromium +
      "' --headless --no-sandbox --disable-gpu --no-first-run --disable-background-networking "
      "--user-data-dir='" +
      dir + "/profile' --dump-dom 'file://" + dir + "/clicked.html' 2>/dev/null");
  const size_t t0 = dom.out.find("id=\"holetable\"");
  ASSERT_NE(t0, std::string::npos) << dom.out.substr(0, 400);
  const std::string table = dom.out.substr(t0, dom.out.find("</table>", t0) - t0);
  EXPECT_NE(dom.out.find("<table class=\"holes fonly\" id=\"holetable\">"), std::string::npos);
  EXPECT_EQ(countOf(table, "aria-sort=\"ascending\""), 1u);
  const std::regex row(
      "<tr(?: class=\"pass\")?><td>\\d+</td><td class=\"l\">[^<]*</td><td>[^<]*"
      "</td><td>[^<]*</td><td>([^<]*)</td>");
  const auto column = [&](const std::string& text) {
    std::vector<double> values;
    for (std::sregex_iterator it(text.begin(), text.end(), row), end; it != end; ++it)
      values.push_back(std::stod((*it)[1].str()));
    return values;
  };
  const std::vector<double> before = column(html), after = column(table);
  ASSERT_EQ(before.size(), 24u);
  ASSERT_FALSE(std::is_sorted(before.begin(), before.end()));  // program order is not by |r|
  ASSERT_EQ(after.size(), 24u);
  EXPECT_TRUE(std::is_sorted(after.begin(), after.end()));
}

TEST(ReportSample, StatesTheRobotCardsEstimates) {
  // Every guess is visible in the report: the bundled KR 120's stiffness, balancer and
  // inertials are estimates; a card without an estimate shows none.
  const std::string dir = test::tempDir("report-estimates");
  const std::string src = test::sourceDir();
  const test::RunResult r = test::runRoprec(
      "predict --cell '" + src + "/samples/cells/housing-kr120.xml' '" + src +
      "/samples/emotor-housing/housing_kr120.src' --report '" + dir + "/p.html' --quiet --json -");
  ASSERT_LE(r.exit_code, 1) << r.err;
  const std::string html = test::readFile(dir + "/p.html");
  EXPECT_NE(html.find("<dt>Robot card estimates</dt>"), std::string::npos);
  EXPECT_NE(html.find("joint stiffness and servo gain k1, k2, k3, k4, k5, k6: estimate"),
            std::string::npos);
  EXPECT_NE(html.find("axis balancer: estimate"), std::string::npos);
  RobotCard card = loadRobotCard(src + "/robots/kuka-kr120-r2500-pro/robot.xml");
  EXPECT_FALSE(api::cardEstimates(card).empty());
  for (auto& j : card.joints) j.source = "identified (test)";
  card.rp_source = card.inertial_source = card.dimensions_source = card.counterbalance.source =
      "data sheet";
  for (auto& l : card.links) l.source = "measured";
  EXPECT_TRUE(api::cardEstimates(card).empty());
}

}  // namespace
}  // namespace roprec
