// The streaming writers: the prediction JSON and the corrected-target exports are written
// hole by hole (JsonWriter, PredictionJsonStream, writeCompensationTargets) and must give the very
// bytes of the in-memory writers they replace: the Json tree of predictionJson()/holeJson() (kept
// for the C and Python hosts) and, for the target exports, the tree/ostringstream writers of the
// previous release, kept below as the reference (the JSON export may add members since: every
// line of the reference must still be there, in order). Non-finite numbers are still never written
// (one bad hole is reported as failed), the writer's buffer stays bounded, and a streamed output
// file is all-or-nothing like any other (OutputSet::stageStream).
#include <gtest/gtest.h>

#include <span>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <span>
#include <sstream>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/platform.hpp"
#include "plugin/api/job.hpp"
#include "plugin/report/exports.hpp"
#include "postproc/program_stream.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using api::Json;
using api::JsonWriter;

const double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string cellPath() { return test::sourceDir() + "/samples/cells/housing-kr120.xml"; }
std::string samplePath(const std::string& f) {
  return test::sourceDir() + "/samples/emotor-housing/" + f;
}

std::string streamed(const api::PredictionResult& r) {
  std::string out;
  api::PredictionJsonStream js(r.context, [&](std::string_view b) { out += b; });
  for (size_t i = 0; i < r.holes.size(); ++i) js.hole(r.holes[i], r.context.job.requests[i]);
  js.finish(r.summary);
  return out;
}

/// The same through PredictionJsonStream::holes(): blocks of `block` holes formatted on `threads`
/// workers.
std::string streamedInBlocks(const api::PredictionResult& r, size_t block, int threads) {
  std::string out;
  api::PredictionJsonStream js(r.context, [&](std::string_view b) { out += b; });
  const std::span<const HolePrediction> holes(r.holes);
  const std::span<const HoleRequest> requests(r.context.job.requests);
  for (size_t b = 0; b < holes.size(); b += block) {
    const size_t n = std::min(block, holes.size() - b);
    js.holes(holes.subspan(b, n), requests.subspan(b, n), threads);
  }
  js.finish(r.summary);
  return out;
}

// ---------------------------------------------------------------- JsonWriter vs Json::dump

TEST(JsonWriter, GivesTheBytesOfJsonDumpForEveryShape) {
  Json t = Json::object();
  t.set("empty_object", Json::object());
  t.set("empty_array", Json::array());
  t.set("empty_numbers", Json::vector(Eigen::VectorXd(0)));
  t.set("s", Json::str("quote \" backslash \\ tab \t nl \n ctl \x01 µm"));
  t.set("minus_zero", Json::number(-0.0, 3));
  t.set("small_negative_rounds_to_zero", Json::number(-0.0004, 3));
  t.set("shortest", Json::number(0.1 + 0.2));
  t.set("int", Json::integer(-1234567890123LL));
  t.set("yes", Json::boolean(true));
  t.set("nothing", Json());
  t.set("v", Json::vector(Eigen::Vector3d(1.5, -0.0, 1e-7), 6));
  Json strings = Json::array();
  strings.push(Json::str("a"));
  strings.push(Json::str("b\"c"));
  t.set("strings", strings);
  Json items = Json::array();
  Json inner = Json::object();
  inner.set("x", Json::number(2.25, 2));
  Json deep = Json::array();
  deep.push(Json::object());
  deep.push(Json::vector(Eigen::Vector2d(1, 2), 1));
  inner.set("deep", deep);
  items.push(inner);
  items.push(Json::object());
  t.set("items", items);

  JsonWriter w;
  w.beginObject();
  w.key("empty_object");
  w.beginObject();
  w.endObject();
  w.key("empty_array");
  w.beginArray();
  w.endArray();
  w.key("empty_numbers");
  w.numbers(Eigen::VectorXd(0));
  w.key("s");
  w.str("quote \" backslash \\ tab \t nl \n ctl \x01 µm");
  w.key("minus_zero");
  w.number(-0.0, 3);
  w.key("small_negative_rounds_to_zero");
  w.number(-0.0004, 3);
  w.key("shortest");
  w.number(0.1 + 0.2);
  w.key("int");
  w.integer(-1234567890123LL);
  w.key("yes");
  w.boolean(true);
  w.key("nothing");
  w.null();
  w.key("v");
  w.numbers(Eigen::Vector3d(1.5, -0.0, 1e-7), 6);
  w.key("strings");
  w.strings({"a", "b\"c"});
  w.key("items");
  w.beginArray();
  w.beginObject();
  w.key("x");
  w.number(2.25, 2);
  w.key("deep");
  w.beginArray();
  w.beginObject();
  w.endObject();
  w.value(Json::vector(Eigen::Vector2d(1, 2), 1));
  w.endArray();
  w.endObject();
  w.value(Json::object());
  w.endArray();
  w.endObject();
  w.finish();
  EXPECT_EQ(w.out(), t.dump());
  EXPECT_NE(w.out().find("\"minus_zero\": 0.000"), std::string::npos);
}

TEST(JsonWriter, RefusesNonFiniteNumbersNamingThePlace) {
  JsonWriter w;
  w.beginObject();
  w.key("holes");
  w.beginArray();
  w.beginObject();
  w.endObject();
  w.beginObject();
  w.key("d");
  const size_t before = w.out().size();
  try {
    w.numbers(Eigen::Vector3d(1, kNaN, 3), 3);
    FAIL() << "a NaN was written";
  } catch (const api::JsonNonFinite& e) {
    EXPECT_EQ(e.where, "$.holes[1].d[1]");
    EXPECT_NE(std::string(e.what()).find("never written"), std::string::npos);
  }
  EXPECT_EQ(w.out().size(), before);  // nothing of the array was written
  EXPECT_THROW(w.number(std::numeric_limits<double>::infinity()), InternalError);
  Json bad = Json::object();
  bad.set("u", Json::number(-kNaN));
  EXPECT_THROW(w.value(bad), api::JsonNonFinite);
  EXPECT_EQ(w.out().size(), before);
}

TEST(JsonWriter, ItemsWrittenApartAndAppendedGiveTheSameBytes) {
  auto item = [](JsonWriter& w, int k) {
    w.beginObject();
    w.key("k");
    w.integer(k);
    w.key("v");
    w.numbers(Eigen::Vector2d(k, -k), 1);
    w.endObject();
  };
  auto open = [](JsonWriter& w) {
    w.beginObject();
    w.key("holes");
    w.beginArray();
  };
  JsonWriter one;
  open(one);
  for (int k = 0; k < 7; ++k) item(one, k);
  one.endArray();
  one.endObject();
  one.finish();
  // runs [0, 3) and [3, 7) written by forks, appended in order
  JsonWriter w;
  open(w);
  JsonWriter a = w.itemWriter(0);
  JsonWriter b = w.itemWriter(3);
  for (int k = 3; k < 7; ++k) item(b, k);
  for (int k = 0; k < 3; ++k) item(a, k);
  w.appendItems(a.out(), 3);
  w.appendItems(b.out(), 4);
  w.endArray();
  w.endObject();
  w.finish();
  EXPECT_EQ(w.out(), one.out());
  // a fork names its items' own indices; outside an array there is nothing to fork
  JsonWriter open_w;
  open(open_w);
  open_w.beginObject();
  open_w.endObject();
  JsonWriter d = open_w.itemWriter(4);
  d.beginObject();
  d.key("d");
  try {
    d.numbers(Eigen::Vector2d(1, kNaN), 3);
    FAIL() << "a NaN was written";
  } catch (const api::JsonNonFinite& e) {
    EXPECT_EQ(e.where, "$.holes[5].d[1]");
  }
  JsonWriter top;
  top.beginObject();
  EXPECT_THROW((void)top.itemWriter(0), InternalError);
  EXPECT_THROW(top.appendItems("x", 1), InternalError);
}

// ---------------------------------------------------------------- prediction JSON

TEST(StreamingOutput, PredictionJsonIsByteIdenticalToTheInMemoryTree) {
  struct Case {
    std::string program;
    std::optional<std::string> holes;
  };
  // a program with its hole list (from_nominal_axis, surface points), a hole-list job, and a
  // hole list with unreachable and far-away holes (other statuses, reasons)
  const std::string dir = test::tempDir("stream_pred");
  test::writeFile(dir + "/mixed.csv",
                  "id,x,y,z,i,j,k,diameter,depth,tolerance\n"
                  "A1,0,0,250,0,0,-1,6.8,16,0.2\n"
                  "FAR,90000,0,250,0,0,-1,6.8,16,0.2\n"
                  "A2,30,-20,250,0,0,-1,8.5,20,0.05\n"
                  "UP,0,0,250,0,0,1,6.8,16,0.2\n"
                  "A3,-40,10,250,0,0,-1,10.2,30,0.2\n");
  const std::vector<Case> cases = {{samplePath("housing_kr120.src"), samplePath("holes.csv")},
                                   {samplePath("holes.csv"), std::nullopt},
                                   {dir + "/mixed.csv", std::nullopt}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.program);
    api::JobOptions opt;
    opt.holes = c.holes;
    opt.match_tol_mm = 10;
    const api::PredictionResult r = api::predictJob(cellPath(), c.program, opt);
    ASSERT_FALSE(r.holes.empty());
    if (c.program == dir + "/mixed.csv") {  // unreachable holes too
      EXPECT_GE(r.failed(), 2);
    }
    const std::string tree = api::predictionJson(r).dump();
    EXPECT_EQ(streamed(r), tree);

    // predictJobStreaming: the same holes in the same order, the same summary, none kept
    std::string out;
    std::optional<api::PredictionJsonStream> js;
    size_t next = 0;
    const api::PredictionResult s = api::predictJobStreaming(
        cellPath(), c.program, opt,
        [&](size_t i, const HolePrediction& h, const HoleRequest& q) {
          EXPECT_EQ(i, next++);
          js->hole(h, q);
        },
        [&](const api::PredictionContext& ctx) {
          js.emplace(ctx, [&](std::string_view b) { out += b; });
        });
    js->finish(s.summary);
    EXPECT_TRUE(s.holes.empty());
    EXPECT_EQ(next, r.holes.size());
    EXPECT_EQ(out, tree);
  }
}

// predictJobStreaming sets a program's holes up block by block (JobHoles::deferred) and releases
// the program's bytes once it is read; a KRL program is read by windows (JobHoles::streamed): its
// JSON is the bytes of predictJob's tree for programs whose base frame and tool the options
// resolve, for more than one block of holes and for a program of more than one window.
TEST(StreamingOutput, AProgramSetUpBlockByBlockGivesTheBytesOfTheWholeJob) {
  const std::string dir = test::tempDir("stream_deferred");
  // KUKA: the base frame lives in $config.dat (BASE_DATA[1]), given by name
  std::string krl = test::readFile(samplePath("housing_kr120.src"));
  const std::string base = "$BASE = {FRAME: X 1350.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C 0.000}";
  ASSERT_NE(krl.find(base), std::string::npos);
  krl.replace(krl.find(base), base.size(), "$BASE = BASE_DATA[1]");
  test::writeFile(dir + "/bd.src", krl);
  // 15,000 drill cycles (blocks of the streaming predict, windows of the reading) on the housing's
  // top face
  test::writeFile(dir + "/big.src", test::krlDrillCycles(15000));
  ASSERT_GT(std::filesystem::file_size(dir + "/big.src"), postproc::ProgramStream::kWindowBytes);
  struct Case {
    std::string cell;
    std::string program;
    api::JobOptions opt;
  };
  std::vector<Case> cases(4);
  cases[0] = {cellPath(), samplePath("housing_kr120.src"), {}};
  cases[1] = {cellPath(), dir + "/bd.src", {}};
  cases[1].opt.frames.push_back({"BASE_DATA[1]", Pose(Eigen::Translation3d(1.35, 0, 0.3))});
  cases[2] = {test::sourceDir() + "/samples/cells/housing-r2000.xml",
              test::sourceDir() + "/samples/emotor-housing/housing_r2000.ls",
              {}};
  cases[2].opt.frame_cell = true;  // UFRAME[1] and UTOOL[1] are controller data
  cases[2].opt.tool = "cell";
  cases[3] = {cellPath(), dir + "/big.src", {}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.program);
    for (const int threads : {1, 2}) {
      api::JobOptions opt = c.opt;
      opt.threads = threads;
      const api::PredictionResult r = api::predictJob(c.cell, c.program, opt);
      ASSERT_FALSE(r.holes.empty());
      if (c.program == dir + "/big.src") {
        EXPECT_EQ(r.holes.size(), 15000U);
      }
      std::string out;
      std::optional<api::PredictionJsonStream> js;
      const api::PredictionResult s = api::predictJobStreaming(
          c.cell, c.program, opt,
          [&](size_t, std::span<const HolePrediction> h, std::span<const HoleRequest> q, int t) {
            js->holes(h, q, t);
          },
          [&](const api::PredictionContext& ctx) {
            js.emplace(ctx, [&](std::string_view b) { out += b; });
          });
      js->finish(s.summary);
      EXPECT_TRUE(out == api::predictionJson(r).dump()) << threads << " threads";
      EXPECT_EQ(s.context.job.notes, r.context.job.notes);
      EXPECT_TRUE(s.context.job.deferred);
      EXPECT_EQ(s.context.job.streamed, c.program.ends_with(".src"));
      EXPECT_TRUE(s.context.job.requests.empty());
      EXPECT_TRUE(s.context.job.program->files.front().bytes.empty());
      EXPECT_EQ(s.summary.holes, static_cast<int>(r.holes.size()));
    }
  }
}

TEST(StreamingOutput, AHoleWithANonFiniteNumberIsWrittenAsFailedLikeTheTree) {
  api::JobOptions opt;
  api::PredictionResult r = api::predictJob(cellPath(), samplePath("holes.csv"), opt);
  ASSERT_GE(r.holes.size(), 10U);
  ASSERT_EQ(r.holes[3].status, HoleStatus::kOk);
  r.holes[3].d_robot.y() = kNaN;                                        // in a vector
  r.holes[7].budget.at(0).u = std::numeric_limits<double>::infinity();  // in the budget object
  const std::string tree = api::predictionJson(r).dump();
  const std::string s = streamed(r);
  EXPECT_EQ(s, tree);
  // formatted apart on the workers, in runs of holes (the failed ones in two different blocks)
  for (const int threads : {1, 2, 3}) {
    for (const size_t block : {size_t{5}, size_t{64}, r.holes.size()})
      EXPECT_TRUE(streamedInBlocks(r, block, threads) == tree) << threads << " threads, " << block;
  }
  EXPECT_EQ(s.find("nan"), std::string::npos);
  EXPECT_EQ(s.find("inf"), std::string::npos);
  const std::string failed = "\"id\": \"" + r.holes[3].id + "\",\n";
  const size_t at = s.find(failed);
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(s.compare(s.find("\"status\": ", at), 20, "\"status\": \"failed\",\n"), 0);
  // a non-finite number outside the per-hole array (the summary) is an internal error
  api::PredictionResult bad = r;
  bad.summary.mc_time_total = kNaN;
  EXPECT_THROW(streamed(bad), InternalError);
}

TEST(StreamingOutput, ThePredictionWriterHoldsAboutOneChunkWhateverTheJobSize) {
  // 1,500 holes (~2.5 MB of JSON): the sink never receives (so the writer never held) more than
  // its 64 KiB chunk plus one hole
  const std::string dir = test::tempDir("stream_chunks");
  std::ostringstream csv;
  csv << "id,x,y,z,i,j,k,diameter,depth,tolerance\n";
  for (int k = 0; k < 1500; ++k) {
    const int row = k / 50;
    csv << "H" << k << "," << -30 + 1.2 * (k % 50) << "," << -20 + 1.2 * row
        << ",250,0,0,-1,6.8,16,0.2\n";
  }
  test::writeFile(dir + "/job.csv", csv.str());
  size_t total = 0;
  size_t largest = 0;
  std::optional<api::PredictionJsonStream> js;
  const api::PredictionResult s = api::predictJobStreaming(
      cellPath(), dir + "/job.csv", {},
      [&](size_t, const HolePrediction& h, const HoleRequest& q) { js->hole(h, q); },
      [&](const api::PredictionContext& c) {
        js.emplace(c, [&](std::string_view b) {
          total += b.size();
          largest = std::max(largest, b.size());
        });
      });
  js->finish(s.summary);
  EXPECT_EQ(s.summary.holes, 1500);
  EXPECT_GT(total, 2'000'000U);
  EXPECT_LT(largest, 64U * 1024U + 4096U);
}

// ---------------------------------------------------------------- corrected-target exports

// The previous release's writers (Json tree / ostringstream), the reference for the streamed ones.
namespace reference {

double perpNorm(const Vec3& v, const Vec3& a) { return (v - v.dot(a) * a).norm(); }

const Pose& nominalOf(const api::CompensationResult& r, size_t i) {
  return r.holes[i].ok ? r.holes[i].T_nominal : r.context.job.requests[i].T_W_tcp;
}

Json poseJsonContract(const Pose& T) {
  Json j = Json::object();
  j.set("position_mm", Json::vector(T.translation() * 1e3, 6));
  const Eigen::Quaterniond q = quaternionFromRotation(T.linear());
  j.set("quaternion_wxyz", Json::vector(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()), 9));
  return j;
}

Json uncertaintyJson(const HolePrediction& u) {
  Json un = Json::object();
  un.set("U_robot", Json::number(u.U_robot * 1e6, 3));
  un.set("U_mach", Json::number(u.U_mach * 1e6, 3));
  un.set("U_work", Json::number(u.U_work * 1e6, 3));
  un.set("U_work_anisotropic", Json::number(u.U_work_exact * 1e6, 3));
  un.set("k", Json::number(u.k, 4));
  return un;
}

void csvQuaternion(std::ostringstream& s, const Mat3& R) {
  const Eigen::Quaterniond q = quaternionFromRotation(R);
  s << "," << api::formatNumber(q.w(), 9) << "," << api::formatNumber(q.x(), 9) << ","
    << api::formatNumber(q.y(), 9) << "," << api::formatNumber(q.z(), 9);
}

std::string targetsCsv(const api::CompensationResult& r) {
  std::ostringstream s;
  s << "id,status,nominal_x_mm,nominal_y_mm,nominal_z_mm,nominal_qw,nominal_qx,nominal_qy,"
       "nominal_qz,before_dx_um,before_dy_um,before_dz_um,before_rx_urad,before_ry_urad,"
       "before_rz_urad,programmed_x_mm,programmed_y_mm,programmed_z_mm,programmed_qw,"
       "programmed_qx,programmed_qy,programmed_qz,j1_deg,j2_deg,j3_deg,j4_deg,j5_deg,j6_deg,"
       "config,rotation_about_axis_deg,residual_um,U_robot_um,U_mach_um,U_work_um,k,verdict,"
       "reason\n";
  for (size_t i = 0; i < r.holes.size(); ++i) {
    const HoleCompensation& h = r.holes[i];
    const Pose& N = nominalOf(r, i);
    const Pose& P = h.ok ? h.T_programmed : N;
    s << h.id << "," << (h.ok ? "compensated" : "original-kept");
    for (int k = 0; k < 3; ++k) s << "," << api::formatNumber(N.translation()[k] * 1e3, 6);
    csvQuaternion(s, N.linear());
    for (int k = 0; k < 3; ++k) s << "," << api::formatNumber(h.before.d_work[k] * 1e6, 3);
    for (int k = 0; k < 3; ++k) s << "," << api::formatNumber(h.before.d_rot[k] * 1e6, 3);
    for (int k = 0; k < 3; ++k) s << "," << api::formatNumber(P.translation()[k] * 1e3, 6);
    csvQuaternion(s, P.linear());
    for (int k = 0; k < 6; ++k)
      s << "," << api::formatNumber((h.ok ? h.theta_cmd[k] : h.before.joints[k]) / kDeg, 6);
    s << ",\"" << (h.ok ? h.config_text : h.before.config) << "\","
      << api::formatNumber(h.psi / kDeg, 4);
    const Vec3 a = N.linear().col(2);
    s << ","
      << api::formatNumber(h.ok ? perpNorm(h.residual, a) * 1e6 : h.before.position_error * 1e6, 4);
    const HolePrediction& u = h.ok ? h.after : h.before;
    s << "," << api::formatNumber(u.U_robot * 1e6, 3) << "," << api::formatNumber(u.U_mach * 1e6, 3)
      << "," << api::formatNumber(u.U_work * 1e6, 3) << "," << api::formatNumber(u.k, 4) << ","
      << verdictName(u.verdict) << ",\"";
    for (const char ch : h.reason) s << (ch == '"' ? "\"\"" : std::string(1, ch));  // RFC 4180
    s << "\"\n";
  }
  return s.str();
}

Json targetJson(const api::CompensationResult& r, size_t i) {
  const HoleCompensation& h = r.holes[i];
  Json j = Json::object();
  j.set("id", Json::str(h.id));
  j.set("status", Json::str(h.ok ? "compensated" : "original-kept"));
  if (!h.ok) j.set("reason", Json::str(h.reason));
  const Pose& N = nominalOf(r, i);
  j.set("nominal", poseJsonContract(N));
  Json b = Json::object();
  Json dev = Json::object();
  dev.set("translation", Json::vector(h.before.d_work * 1e6, 3));
  dev.set("rotation_urad", Json::vector(h.before.d_rot * 1e6, 3));
  b.set("deviation_um", dev);
  b.set("verdict", Json::str(verdictName(h.before.verdict)));
  j.set("before", b);
  if (h.ok) {
    Json p = poseJsonContract(h.T_programmed);
    p.set("joints_deg", Json::vector(h.theta_cmd / kDeg, 6));
    p.set("config", Json::str(h.config_text));
    j.set("programmed", p);
    j.set("rotation_about_axis_deg", Json::number(h.psi / kDeg, 4));
    j.set("residual_um", Json::number(perpNorm(h.residual, N.linear().col(2)) * 1e6, 4));
    j.set("residual_vector_um", Json::vector(h.residual * 1e6, 4));
    j.set("branch_changed", Json::boolean(h.branch_changed));
    if (!h.note.empty()) j.set("note", Json::str(h.note.str()));
  }
  const HolePrediction& u = h.ok ? h.after : h.before;
  j.set("uncertainty_um", uncertaintyJson(u));
  j.set("verdict", Json::str(verdictName(u.verdict)));
  return j;
}

std::string targetsJson(const api::CompensationResult& r, const std::string& program_path) {
  Json root = Json::object();
  root.set("robot", Json::str(r.context.robot.card.name));
  root.set("cell", Json::str(r.context.cell.name));
  root.set("program", Json::str(std::filesystem::path(program_path).filename().string()));
  root.set("orientation", Json::str(r.orientation));
  Json hs = Json::array();
  for (size_t i = 0; i < r.holes.size(); ++i) {
    hs.push(api::finiteOrFailed(targetJson(r, i), r.holes[i].id, r.context.job.requests[i].line));
  }
  root.set("holes", hs);
  return root.dump();
}

}  // namespace reference

/// True when every line of `reference` appears in `text`, in order (trailing commas aside): the
/// streamed export keeps every member and number of the previous writer byte for byte; members
/// added since (rotation and flag reasons) are extra lines.
::testing::AssertionResult keepsEveryLineInOrder(const std::string& text,
                                                 const std::string& reference) {
  auto lines = [](const std::string& t) {
    std::vector<std::string> v;
    std::istringstream in(t);
    for (std::string l; std::getline(in, l);) {
      if (!l.empty() && l.back() == ',') l.pop_back();
      v.push_back(l);
    }
    return v;
  };
  const std::vector<std::string> a = lines(text);
  const std::vector<std::string> b = lines(reference);
  size_t i = 0;
  for (size_t k = 0; k < b.size(); ++k) {
    while (i < a.size() && a[i] != b[k]) ++i;
    if (i == a.size())
      return ::testing::AssertionFailure() << "reference line " << k + 1 << " missing: " << b[k];
    ++i;
  }
  return ::testing::AssertionSuccess();
}

TEST(StreamingOutput, TargetExportsKeepEveryByteOfThePreviousWriters) {
  const std::string program = samplePath("housing_kr120.src");
  api::CompensationJob job;
  job.allow_partial = true;
  for (const OrientationMode mode : {OrientationMode::kKeep, OrientationMode::kFlipFree}) {
    job.options.mode = mode;
    job.options.grid = 12;
    api::CompensationResult r = api::compensateJob(cellPath(), program, job);
    ASSERT_FALSE(r.holes.empty());
    // one hole kept original (the other branch of every column), one with a note
    r.holes[1].ok = false;
    r.holes[1].reason = "kept for the test, \"quoted\"";
    r.holes[2].note = "a note";
    // CSV: every row starts with the previous writer's row (the controller joints
    // and the rotation/flag reasons follow as further columns)
    {
      std::istringstream now(api::compensationTargets(r, program, true));
      std::istringstream before(reference::targetsCsv(r));
      size_t rows = 0;
      for (std::string a, b; std::getline(before, b); ++rows) {
        ASSERT_TRUE(std::getline(now, a)) << "row " << rows;
        EXPECT_EQ(a.substr(0, b.size()), b) << "row " << rows;
        EXPECT_TRUE(a.size() == b.size() || a[b.size()] == ',') << "row " << rows;
      }
      EXPECT_EQ(rows, r.holes.size() + 1);
    }
    const std::string json = api::compensationTargets(r, program, false);
    EXPECT_TRUE(keepsEveryLineInOrder(json, reference::targetsJson(r, program)));
    // streamed in pieces: the same bytes as the whole string
    std::string pieces;
    api::writeCompensationTargets(r, program, false, [&](std::string_view b) { pieces += b; });
    EXPECT_EQ(pieces, json);
    // a non-finite number in one hole: that hole is written as failed, like before, and only it
    r.holes[4].residual.x() = kNaN;
    const std::string failed = api::compensationTargets(r, program, false);
    EXPECT_TRUE(keepsEveryLineInOrder(failed, reference::targetsJson(r, program)));
    EXPECT_EQ(failed.find("nan"), std::string::npos);
    const size_t at = failed.find("\"id\": \"" + r.holes[4].id + "\"");
    ASSERT_NE(at, std::string::npos);
    EXPECT_EQ(failed.compare(failed.find("\"status\": ", at), 18, "\"status\": \"failed\""), 0);
    EXPECT_EQ(failed.find("\"failed\"", at + 1), failed.rfind("\"failed\""));
  }
}

// ---------------------------------------------------------------- streamed output files

TEST(StreamingOutput, AStreamedOutputIsAllOrNothing) {
  const std::string dir = test::tempDir("stream_files");
  const std::string a = dir + "/a.json";
  const std::string b = dir + "/b.json";
  test::writeFile(a, "old a");
  {
    OutputSet set;
    set.stageStream(a, [](const ByteWriter& w) {
      for (int i = 0; i < 1000; ++i) w("0123456789");
    });
    // the producer of the second output fails half-way: its temporary is removed at once
    EXPECT_THROW(set.stageStream(b,
                                 [](const ByteWriter& w) {
                                   w("half");
                                   throw InputError("x.src", 3, "bad");
                                 }),
                 InputError);
    EXPECT_FALSE(std::filesystem::exists(outputTemporaryPath(b, platform::processId())));
    set.rollback();
  }
  EXPECT_EQ(test::readFile(a), "old a");
  EXPECT_FALSE(std::filesystem::exists(b));
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_FALSE(isOutputTemporaryName(e.path().filename().string())) << e.path();
  {
    OutputSet set;
    const ScopedOutputSet scope(set);
    writeFileAtomicStream(a, [](const ByteWriter& w) {
      w("new ");
      w("a");
    });
    EXPECT_EQ(test::readFile(a), "old a");  // staged, not yet committed
    set.commit();
  }
  EXPECT_EQ(test::readFile(a), "new a");
}

}  // namespace
}  // namespace roprec
