// Milling path compensation: every point of the sample wall pass is compensated
// with the coupled force solve; the commands, fed to an independent nonlinear joint-compliance
// equilibrium computed here with KDL (FK + RNE, same stiffness, tool mass, axis-2 balancer,
// mastering reference and converged milling force on the tool) plus the tool's bending on the
// spindle (F/k_t), put the tool tip on the nominal path ≤ 0.5 µm; through the CLI only the path
// targets' bytes change.
#include "compensator/compensation/milling_compensation.hpp"

#include <gtest/gtest.h>

#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <span>
#include <sstream>

#include "compensator/robot/counterbalance.hpp"
#include "compensator/support/c_format.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "postproc/program.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/part_registration.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

/// The wall-pass sample's context and the world poses of its linear targets, in program order
/// (every base frame resolved).
api::PredictionContext wallPass(std::vector<Pose>& points) {
  const std::string cell = test::sourceDir() + "/samples/cells/alu-milling-7075.xml";
  const std::string prog = test::sourceDir() + "/samples/milling/wall_pass.src";
  api::PredictionContext c = api::loadPredictionContext(cell, prog, std::nullopt, "", 0.5, false);
  const postproc::Program& p = *c.job.program;
  for (const postproc::Motion& m : p.motions) {
    if (m.type != postproc::MotionType::kLinear || m.target < 0) continue;
    const postproc::Frame& f = p.frames[static_cast<size_t>(m.base)];
    EXPECT_TRUE(f.resolved);
    points.push_back(f.pose * postproc::targetPose(p, p.targets()[static_cast<size_t>(m.target)]));
  }
  return c;
}

TEST(MillingCompensation, PathLandsOnTheNominalPathAgainstKdl) {
  std::vector<Pose> points;
  const api::PredictionContext c = wallPass(points);
  ASSERT_GE(points.size(), 25u);
  const auto comp = compensateMillingPath(c.model, points);
  // KDL: chain + tool segment; the milling force acts on the tool in the TCP frame (X feed = tool
  // x, Z = −tool z, Y = −tool y)
  const ChainDescription& ch = c.robot.chain;
  KDL::Chain kc = test::kdlChain(c.robot.card.urdf_path, ch.base_link, ch.tip_link);
  const Pose T_tcp_flange = c.tool.T_flange_tcp.inverse();
  const Vec3 com = T_tcp_flange * c.tool.com;
  kc.addSegment(
      KDL::Segment("tool", KDL::Joint(KDL::Joint::None), test::toKdl(c.tool.T_flange_tcp),
                   KDL::RigidBodyInertia(c.tool.mass, KDL::Vector(com.x(), com.y(), com.z()))));
  KDL::ChainIdSolver_RNE rne(kc, KDL::Vector(0, 0, -9.80665));
  KDL::ChainFkSolverPos_recursive fk(kc);
  // the controller's reference: mastering at the calibration pose (its gravity torque is in the
  // joint zero; the value itself is checked in the gravity tests); the axis-2 balancer's torque
  const Counterbalance& cb = c.robot.chain.counterbalance;
  ASSERT_NE(c.model.controller.kind, nc::ControllerReference::Kind::kGravityCompensated);
  nc::Vec6 off = nc::Vec6::Zero();
  if (c.model.controller.kind == nc::ControllerReference::Kind::kMastering)
    off = c.model.controller.calibration_pose_torque.cwiseQuotient(c.model.compliance.k);
  for (size_t i = 0; i < comp.size(); ++i) {
    ASSERT_TRUE(comp[i].ok) << i << ": " << comp[i].reason;
    EXPECT_TRUE(comp[i].coupling_converged);
    EXPECT_LE(comp[i].residual.norm(), 1e-7) << i;
    const Vec3 Ft(comp[i].force.x(), -comp[i].force.y(), -comp[i].force.z());
    nc::Vec6 th = comp[i].theta_cmd;
    for (int it = 0; it < 200; ++it) {
      KDL::JntArray q(6);
      KDL::JntArray z(6);
      KDL::JntArray t(6);
      for (unsigned j = 0; j < 6; ++j) q(j) = th[j];
      KDL::Wrenches f(kc.getNrOfSegments(), KDL::Wrench::Zero());
      f.back() = KDL::Wrench(KDL::Vector(Ft.x(), Ft.y(), Ft.z()), KDL::Vector::Zero());
      rne.CartToJnt(q, z, z, f, t);
      if (cb.present()) t(static_cast<unsigned>(cb.joint)) -= balancerTorque(cb, th[cb.joint]);
      for (int j = 0; j < 6; ++j)
        th[j] =
            comp[i].theta_cmd[j] + off[j] - t(static_cast<unsigned>(j)) / c.model.compliance.k[j];
    }
    KDL::JntArray q(6);
    for (unsigned j = 0; j < 6; ++j) q(j) = th[j];
    KDL::Frame F;
    fk.JntToCart(q, F);
    // the tool bends on the spindle by F/k_t in the milling XY plane (tool x, −tool y)
    const double kt = c.model.process.milling.tool_mode.stiffness;
    const Vec3 bending =
        points[i].linear() * Vec3(comp[i].force.x() / kt, -comp[i].force.y() / kt, 0.0);
    EXPECT_GT(bending.norm(), 1e-6);
    EXPECT_LE((Vec3(F.p.x(), F.p.y(), F.p.z()) + bending - points[i].translation()).norm(), 0.5e-6)
        << "point " << i;
  }
}

// The cutting decision (docs/process.md §4.5) on hand-made points: speed above 1.5 vf (vf = fz Nt
// n/60 = 0.1 × 3 × 12000/60 = 60 mm/s) is rapid; with <stock top_z_mm="0"> the tool cuts at depth
// ≥ ap − 0.1 mm; without a stock, at the depth of the first feed move ±0.1 mm.
TEST(MillingCompensation, CuttingDecisionFromSpeedAndDepth) {
  MillingSpec s;
  s.cut.fz = 0.1e-3;
  s.tool.teeth = 3;
  s.cut.spindle_rpm = 12000;
  s.cut.ap = 5e-3;
  s.stock_top_z = 0.0;
  Pose wobj = Pose::Identity();
  wobj.translation() = Vec3(1.6, 0, 0.4);
  const auto at = [&](double z_mm, double v_mm_s) {
    Pose p = wobj;
    p.translation() += Vec3(0.01, 0, z_mm * 1e-3);
    return MillingPathPoint{p, v_mm_s * 1e-3};
  };
  const std::vector<MillingPathPoint> pts = {at(50, 250), at(-5, 250), at(-5, 60),
                                             at(-5, 89),  at(-5, 91),  at(-4.95, 60),
                                             at(-3, 60),  at(2, 60),   at(-5, -1)};
  const std::vector<CuttingDecision> d = decideCutting(s, wobj, pts);
  const bool expect[] = {false, false, true, true, false, true, false, false, true};
  for (size_t i = 0; i < pts.size(); ++i) EXPECT_EQ(d[i].cutting, expect[i]) << i << d[i].reason;
  EXPECT_NE(d[1].reason.find("rapid"), std::string::npos);
  EXPECT_NE(d[6].reason.find("not at the cutting depth"), std::string::npos);
  EXPECT_NE(d[7].reason.find("above the stock top by 2.000 mm"), std::string::npos);
  // no stock: the first feed move (z −5) is the reference
  s.stock_top_z.reset();
  const std::vector<CuttingDecision> n = decideCutting(s, wobj, pts);
  const bool expect_n[] = {false, false, true, true, false, true, false, false, true};
  for (size_t i = 0; i < pts.size(); ++i) EXPECT_EQ(n[i].cutting, expect_n[i]) << i << n[i].reason;
}

// The sample job through the API: approach and retract recognised as non-cutting (zero force, no
// coupling), every cutting point's uncompensated coupled solve converged with |r| ≤ 0.1 µm.
TEST(MillingCompensation, WallPassCuttingPointsConverge) {
  const api::MillingCompensationResult r =
      api::compensateMillingJob(test::sourceDir() + "/samples/cells/alu-milling-7075.xml",
                                test::sourceDir() + "/samples/milling/wall_pass.src");
  ASSERT_EQ(r.points_comp.size(), 27u);
  for (size_t i = 0; i < r.points_comp.size(); ++i) {
    const PathPointCompensation& p = r.points_comp[i];
    const bool edge = i == 0 || i + 1 == r.points_comp.size();
    EXPECT_EQ(p.cutting, !edge) << i << " " << p.cutting_reason;
    EXPECT_TRUE(p.ok) << i << " " << p.reason;
    if (edge) {
      EXPECT_EQ(p.force, Vec3::Zero());
      EXPECT_EQ(p.before_force, Vec3::Zero());
      EXPECT_EQ(p.before_status, "not_cutting");
      continue;
    }
    EXPECT_EQ(p.before_status, "converged") << i;
    EXPECT_LE(p.before_residual, 0.1e-6);
    EXPECT_TRUE(p.coupling_converged);
    EXPECT_LE(p.coupling_residual, 0.1e-6);
    EXPECT_LT(p.before_force.x(), -100.0);
  }
}

// The surface error is the deviation normal to the wall into the material: for this up-milling
// pass along base +X with the tool axis down (Z_mill = +z_base), n_wall = Z × X = +y_base, so it
// is the deviation's y (to 1e-12 m); the compensated tool leaves ≤ 0.01 µm on the wall.
TEST(MillingCompensation, SurfaceErrorIsTheDeviationNormalToTheWall) {
  const api::MillingCompensationResult r =
      api::compensateMillingJob(test::sourceDir() + "/samples/cells/alu-milling-7075.xml",
                                test::sourceDir() + "/samples/milling/wall_pass.src");
  ASSERT_EQ(r.points_comp.size(), 27u);
  for (const PathPointCompensation& p : r.points_comp) {
    if (!p.cutting) {
      EXPECT_EQ(p.surface_error_before, 0.0);
      continue;
    }
    EXPECT_NEAR(p.surface_error_before, p.deviation_before.y(), 1e-12);
    EXPECT_NEAR(p.surface_error, p.residual.y(), 1e-12);
    EXPECT_LT(std::abs(p.surface_error), 0.01e-6);
    EXPECT_GT(std::abs(p.surface_error_before), 10e-6);
  }
}

TEST(MillingCompensation, CliChangesOnlyThePathTargets) {
  const std::string dir = test::tempDir("mill");
  const std::string prog = test::sourceDir() + "/samples/milling/wall_pass.src";
  const auto r = test::runRoprec("compensate --cell '" + test::sourceDir() +
                                 "/samples/cells/alu-milling-7075.xml' '" + prog + "' -o '" + dir +
                                 "/out.src' --targets '" + dir + "/t.json'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // the compensated program is marked (docs/programs.md §15): one comment line after DEF
  std::string out = test::readFile(dir + "/out.src");
  const std::size_t mark = out.find(";roprec compensated: cell ");
  ASSERT_NE(mark, std::string::npos);
  out.erase(mark, out.find('\n', mark) + 1 - mark);
  std::istringstream a(test::readFile(prog));
  std::istringstream b(out);
  std::string la;
  std::string lb;
  int changed = 0;
  while (std::getline(a, la)) {
    ASSERT_TRUE(std::getline(b, lb));
    if (la == lb) continue;
    ++changed;
    EXPECT_EQ(la.rfind("LIN {", 0), 0u) << la;
  }
  EXPECT_FALSE(std::getline(b, lb));
  EXPECT_EQ(changed, 27);
  // the export says which points cut and how each coupled solve ended
  const auto t = nlohmann::json::parse(test::readFile(dir + "/t.json"));
  ASSERT_EQ(t["points"].size(), 27u);
  int cutting = 0;
  for (const auto& p : t["points"]) {
    EXPECT_TRUE(p["ok"].get<bool>());
    EXPECT_TRUE(p.contains("force_fixed_point_iterations") ||
                p["coupling"].contains("force_fixed_point_iterations"));
    if (!p["cutting"].get<bool>()) {
      EXPECT_FALSE(p["cutting_reason"].get<std::string>().empty());
      EXPECT_EQ(p["before"]["coupling_status"], "not_cutting");
      continue;
    }
    ++cutting;
    EXPECT_EQ(p["before"]["coupling_status"], "converged");
    EXPECT_LE(p["before"]["coupling_residual_um"].get<double>(), 0.1);
    EXPECT_LE(p["coupling"]["residual_um"].get<double>(), 0.1);
  }
  EXPECT_EQ(cutting, 25);  // approach and retract do not cut
  EXPECT_FALSE(t["points"][0]["cutting"].get<bool>());
  EXPECT_FALSE(t["points"][26]["cutting"].get<bool>());
  // every cutting point carries its chatter check; the sample cut is below the limit
  for (const auto& p : t["points"]) {
    if (!p["cutting"].get<bool>()) continue;
    ASSERT_TRUE(p["stability"]["checked"].get<bool>());
    EXPECT_TRUE(p["stability"]["stable"].get<bool>());
    EXPECT_GT(p["stability"]["margin"].get<double>(), 1.0);
  }
}

// `--targets F.csv` writes the milling export as CSV (the extension names the format): one row
// per path point with the same programmed positions as the JSON export.
TEST(MillingCompensation, TargetsExportFollowsTheExtension) {
  const std::string dir = test::tempDir("mill");
  const std::string base = "compensate --cell '" + test::sourceDir() +
                           "/samples/cells/alu-milling-7075.xml' '" + test::sourceDir() +
                           "/samples/milling/wall_pass.src' -o '" + dir;
  const auto rj = test::runRoprec(base + "/a.src' --targets '" + dir + "/t.json'");
  const auto rc = test::runRoprec(base + "/b.src' --targets '" + dir + "/t.csv'");
  ASSERT_EQ(rj.exit_code, 0) << rj.err;
  ASSERT_EQ(rc.exit_code, 0) << rc.err;
  const std::string csv = test::readFile(dir + "/t.csv");
  ASSERT_NE(csv.front(), '{');
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("point,target,line,cutting,ok,x_mm,y_mm,z_mm,", 0), 0u);
  const auto t = nlohmann::json::parse(test::readFile(dir + "/t.json"));
  size_t rows = 0;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::istringstream ls(line);
    for (std::string c; std::getline(ls, c, ',');) f.push_back(c);
    ASSERT_GE(f.size(), 12u);
    const auto& p = t["points"][rows];
    const auto& pos = p["programmed"]["position_mm"];
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(std::stod(f[static_cast<size_t>(5 + k)]),
                  pos[static_cast<size_t>(k)].get<double>(), 1e-3);
    // the surface error normal to the wall (the sample's wall normal is the base y axis) before
    // and after compensation, in both exports, only where the tool cuts
    if (p["cutting"].get<bool>()) {
      const double before = p["before"]["surface_error_um"].get<double>();
      EXPECT_NEAR(before, p["before"]["deviation_um"][1].get<double>(), 1e-3);
      EXPECT_GT(std::abs(before), 10.0);
      EXPECT_NEAR(std::stod(f[10]), before, 1e-3);
      EXPECT_NEAR(std::stod(f[11]), p["surface_error_um"].get<double>(), 1e-4);
      EXPECT_LT(std::abs(std::stod(f[11])), 0.01);
    } else {
      EXPECT_TRUE(f[10].empty() && f[11].empty()) << line;
      EXPECT_FALSE(p["before"].contains("surface_error_um"));
    }
    ++rows;
  }
  EXPECT_EQ(rows, t["points"].size());
}

// With a box stock the targets export carries each chain's engagement: pass 2 without
// compensation cuts what pass 1 really left (not the programmed ae), the compensated tool the
// programmed engagement (pass 1 compensated leaves the wall where it was programmed).
TEST(MillingCompensation, TargetsExportCarriesBothChainsEngagement) {
  const std::string dir = test::tempDir("millbox");
  const auto r = test::runRoprec("compensate --cell '" + test::sourceDir() +
                                 "/samples/milling/box-stock-7075.xml' '" + test::sourceDir() +
                                 "/samples/milling/box_passes.src' -o '" + dir +
                                 "/c.src' --targets '" + dir + "/t.json'");
  ASSERT_LE(r.exit_code, 1) << r.err;  // 1: the sample's chatter points
  const auto t = nlohmann::json::parse(test::readFile(dir + "/t.json"));
  int engaged = 0;
  int moved = 0;
  for (const auto& p : t["points"]) {
    if (!p.contains("programmed_ae_mm") || !p["before"].contains("ae_mm")) continue;
    ++engaged;
    const double programmed = p["programmed_ae_mm"].get<double>();
    EXPECT_NEAR(p["ae_mm"].get<double>(), programmed, 1e-3);
    if (std::abs(p["before"]["ae_mm"].get<double>() - programmed) > 0.005) ++moved;
  }
  EXPECT_GT(engaged, 20);
  EXPECT_GT(moved, 5);
}

/// A milling cell on the KR120 (the sample wall pass's cell) with the given <mill>s; the process
/// <cut> is shared, a mill's own <cut> overrides it.
std::string millCell(const std::string& mills) {
  return "<cell name=\"mills\">\n  <robot ref=\"kuka-kr120-r2500-pro\"/>\n"
         "  <tool name=\"spindle\" xyz=\"0 0 300\" rpy=\"0 0 0\" mass_kg=\"30\" com_mm=\"0 0 "
         "140\"/>\n"
         "  <workobject xyz=\"1600 0 400\" rpy=\"0 0 0\"/>\n  <process type=\"milling\">\n" +
         mills +
         "    <cut ap_mm=\"5\" ae_mm=\"2\" fz_mm=\"0.1\" mode=\"up\" spindle_rpm=\"12000\"/>\n"
         "    <material name=\"Al 7075-T6\"/>\n"
         "    <coupling tolerance_um=\"0.1\" max_iterations=\"50\" solver=\"newton\"/>\n"
         "    <stock top_z_mm=\"0\"/>\n  </process>\n</cell>\n";
}
const std::string kMill1 =
    "diameter_mm=\"10\" teeth=\"3\" helix_angle_deg=\"30\" runout_mm=\"0.005\"";
const std::string kMill2 = "diameter_mm=\"6\" teeth=\"4\" helix_angle_deg=\"35\"";
const std::string kMill2Cut = "<cut ae_mm=\"1\" fz_mm=\"0.06\"/>";

/// One pass of a KRL milling program: select `tool`, approach, 9 feed points along x at y, z −5
/// (at ap below the stock top), retract.
std::string millPass(const std::string& tool, double y) {
  const auto pt = [&](double x, double z) {
    return "LIN {X " + std::to_string(x) + ",Y " + std::to_string(y) + ",Z " + std::to_string(z) +
           ",A 0.0,B 0.0,C 180.0} C_DIS\n";
  };
  std::string s = tool.empty() ? "" : "$TOOL = " + tool + "\n";
  s += "$VEL.CP = 0.25\n" + pt(-60, 50) + pt(-60, -5) + "$VEL.CP = 0.06\n";
  for (int k = 0; k < 9; ++k) s += pt(-50 + 5 * k, -5);
  return s + "$VEL.CP = 0.25\n" + pt(-10, 50);
}

std::string millProgram(const std::string& name, const std::string& passes) {
  return "DEF " + name +
         " ( )\nBAS (#INITMOV,0 )\n$BASE = {FRAME: X 1600.0,Y 0.0,Z 400.0,A 0.0,B 0.0,C 0.0}\n"
         "TOOL_DATA[1] = {X 0.0,Y 0.0,Z 300.0,A 0.0,B 0.0,C 0.0}\n"
         "TOOL_DATA[2] = {X 0.0,Y 0.0,Z 300.0,A 0.0,B 0.0,C 0.0}\n"
         "PTP {X -60.0,Y 0.0,Z 80.0,A 0.0,B 0.0,C 180.0}\n" +
         passes + "END\n";
}

// Two mills (Ø10 × 3 teeth, Ø6 × 4 teeth with its own cut) selected by $TOOL = TOOL_DATA[n]: each
// pass gets the forces, coupling and compensation of a single-mill cell of its mill running that
// pass alone (the cells without a tool table), to 1e-9 relative.
TEST(MillingCompensation, ToolTableMillsEachPassAsItsSingleMillCell) {
  const std::string dir = test::tempDir("mills");
  test::writeFile(dir + "/two.xml", millCell("    <mill tool=\"1\" " + kMill1 + "/>\n" +
                                             "    <mill tool=\"2\" name=\"E6\" " + kMill2 + ">" +
                                             kMill2Cut + "</mill>\n"));
  test::writeFile(dir + "/one.xml", millCell("    <mill " + kMill1 + "/>\n"));
  test::writeFile(dir + "/two_only.xml",
                  millCell("    <mill " + kMill2 + ">" + kMill2Cut + "</mill>\n"));
  const std::string pass1 = millPass("TOOL_DATA[1]", 0);
  const std::string pass2 = millPass("TOOL_DATA[2]", 20);
  test::writeFile(dir + "/both.src", millProgram("both", pass1 + pass2));
  test::writeFile(dir + "/p1.src", millProgram("p1", pass1));
  test::writeFile(dir + "/p2.src", millProgram("p2", pass2));
  const api::MillingCompensationResult both =
      api::compensateMillingJob(dir + "/two.xml", dir + "/both.src");
  const api::MillingCompensationResult r1 =
      api::compensateMillingJob(dir + "/one.xml", dir + "/p1.src");
  const api::MillingCompensationResult r2 =
      api::compensateMillingJob(dir + "/two_only.xml", dir + "/p2.src");
  ASSERT_EQ(r1.points_comp.size(), 12u);
  ASSERT_EQ(r2.points_comp.size(), 12u);
  ASSERT_EQ(both.points_comp.size(), 24u);
  const auto rel = [](const Vec3& a, const Vec3& b) {
    return (a - b).norm() / std::max(1.0, b.norm());
  };
  int cutting = 0;
  for (size_t i = 0; i < both.points_comp.size(); ++i) {
    const PathPointCompensation& p = both.points_comp[i];
    const PathPointCompensation& q = i < 12 ? r1.points_comp[i] : r2.points_comp[i - 12];
    EXPECT_EQ(both.mill[i], i < 12 ? 0 : 1) << i;
    EXPECT_EQ(api::millOf(both, i).tool.teeth, i < 12 ? 3 : 4);
    ASSERT_TRUE(p.ok && q.ok) << i << " " << p.reason << " " << q.reason;
    EXPECT_EQ(p.cutting, q.cutting) << i;
    cutting += p.cutting;
    EXPECT_LE(rel(p.before_force, q.before_force), 1e-9) << i;
    EXPECT_LE(rel(p.force, q.force), 1e-9) << i;
    EXPECT_LE(rel(p.deviation_before * 1e6, q.deviation_before * 1e6), 1e-9) << i;
    EXPECT_LE(rel(p.T_programmed.translation() * 1e3, q.T_programmed.translation() * 1e3), 1e-9);
  }
  EXPECT_EQ(cutting, 18);  // the 9 feed points of each pass, not the rapid plunge and retract
  // the two mills cut differently: the Ø6 × 4 mill at ae 1, fz 0.06 pulls less than the Ø10 one
  EXPECT_LT(both.points_comp[16].before_force.norm(), both.points_comp[4].before_force.norm());
}

// Which mill cuts must be known: a tool the mills do not have (a drill's number), no tool with
// several mills, and two tools with one mill are errors at the motion's line (exit 2).
TEST(MillingCompensation, PathToolNotAMillOfTheTableIsRefusedAtItsLine) {
  const std::string dir = test::tempDir("mills");
  test::writeFile(dir + "/two.xml", millCell("    <mill tool=\"1\" " + kMill1 + "/>\n" +
                                             "    <mill tool=\"2\" " + kMill2 + "/>\n"));
  test::writeFile(dir + "/one.xml", millCell("    <mill " + kMill1 + "/>\n"));
  const auto firstLin = [&](const std::string& file, const std::string& after) {
    std::istringstream in(test::readFile(file));
    std::string l;
    bool seen = after.empty();
    for (int n = 1; std::getline(in, l); ++n) {
      seen = seen || l.find(after) != std::string::npos;
      if (seen && l.rfind("LIN ", 0) == 0) return n;
    }
    return 0;
  };
  const auto run = [&](const std::string& cell, const std::string& prog) {
    return test::runRoprec("forces --cell '" + dir + "/" + cell + "' --program '" + dir + "/" +
                           prog + "'");
  };
  test::writeFile(dir + "/drill.src",
                  millProgram("drill", millPass("TOOL_DATA[1]", 0) + millPass("TOOL_DATA[3]", 20)));
  test::RunResult r = run("two.xml", "drill.src");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(
                dir + "/drill.src:" + std::to_string(firstLin(dir + "/drill.src", "TOOL_DATA[3]")) +
                ": path point 13 is milled with tool TOOL_DATA[3], which is not a mill of "
                "the cell's tool table (tool 1 (Ø10 mm, 3 teeth), tool 2 (Ø6 mm, 4 "
                "teeth)); hint: select a mill's tool"),
            std::string::npos)
      << r.err;
  test::writeFile(dir + "/none.src", millProgram("none", millPass("", 0)));
  r = run("two.xml", "none.src");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(dir + "/none.src:" + std::to_string(firstLin(dir + "/none.src", "")) +
                       ": path point 1: nothing selects a tool, and the cell's tool table has 2 "
                       "mills"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("which mill cuts?"), std::string::npos) << r.err;
  test::writeFile(dir + "/change.src", millProgram("change", millPass("TOOL_DATA[1]", 0) +
                                                                 millPass("TOOL_DATA[2]", 20)));
  r = run("one.xml", "change.src");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(dir + "/change.src:" +
                       std::to_string(firstLin(dir + "/change.src", "$TOOL = TOOL_DATA[2]")) +
                       ": path point 13 is milled with tool TOOL_DATA[2], TOOL_DATA[1] before it"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("but the cell has one mill, the cell's mill (Ø10 mm, 3 teeth); hint"),
            std::string::npos)
      << r.err;
  // one tool with one mill is that mill (no tool table needed)
  test::writeFile(dir + "/one.src", millProgram("one", millPass("TOOL_DATA[2]", 0)));
  EXPECT_LT(run("one.xml", "one.src").exit_code, 2);
}

// Engagement from the program (box stock): samples/milling/box_passes.src in the block y ≥ 3 mm,
// z ≤ 0 of box-stock-7075.xml. Closed forms on the programmed path (tool D 10 at y_c, material
// y ≥ y_wall): pass 1 (y 0, z −5) ae = 0 + 5 − 3 = 2, ap = 5; pass 2 (y 2) cuts what pass 1 left,
// y ≥ 5: ae = 2; pass 3 (y 2, z −10) the column 3 ≤ y ≤ 7 below pass 1–2's floor: ae = 4, ap = 5.
// Points in the box's middle (x −20 … 60, clear of the entry) are checked to 0.01 µm (the
// tracker's refined run ends); before the box nothing is engaged; every engaged point is coupled
// with its own ae/ap (the force grows with ae: pass 3 > pass 1).
TEST(MillingCompensation, EngagementFromTheBoxStockAndTheEarlierPasses) {
  const std::string cell = test::sourceDir() + "/samples/milling/box-stock-7075.xml";
  const std::string prog = test::sourceDir() + "/samples/milling/box_passes.src";
  const api::MillingCompensationResult r = api::compensateMillingJob(cell, prog);
  struct Pass {
    double y, z, ae, ap;
  };
  const Pass passes[] = {
      {0, -5e-3, 2e-3, 5e-3}, {2e-3, -5e-3, 2e-3, 5e-3}, {2e-3, -10e-3, 4e-3, 5e-3}};
  const Pose T_wobj_W = r.context.cell.T_base_wobj.inverse();
  int checked[3] = {0, 0, 0};
  double force[3] = {0, 0, 0};
  bool before_box = false;
  for (size_t i = 0; i < r.points.size(); ++i) {
    const Vec3 x = T_wobj_W * r.points[i].translation();
    const CuttingDecision& d = r.cutting[i];
    const PathPointCompensation& p = r.points_comp[i];
    for (int k = 0; k < 3; ++k) {
      if (std::abs(x.y() - passes[k].y) > 1e-6 || std::abs(x.z() - passes[k].z) > 1e-6) continue;
      if (x.x() >= -20e-3 && x.x() <= 60e-3) {
        ASSERT_TRUE(d.cutting) << i << ": " << d.reason;
        ASSERT_TRUE(d.engagement.has_value());
        EXPECT_NEAR(d.engagement->ae, passes[k].ae, 1e-8) << "pass " << k + 1;
        EXPECT_NEAR(d.engagement->ap, passes[k].ap, 1e-9) << "pass " << k + 1;
        EXPECT_TRUE(p.ok) << p.reason;
        force[k] = p.before_force.head<2>().norm();
        ++checked[k];
      }
      // before the box (x −45: the leading half reaches x −40 only at the wall side's
      // centre line, where y < 3) nothing is engaged: not cutting, unlike a plane stock
      if (k == 0 && std::abs(x.x() + 45e-3) < 1e-6) before_box = !d.cutting;
    }
  }
  for (int k = 0; k < 3; ++k) EXPECT_GE(checked[k], 15) << "pass " << k + 1;
  EXPECT_GT(force[2], force[0]);
  EXPECT_TRUE(before_box);
}

/// The engagement of a tool (radius R) at tip b moving from tip a (workobject frame, XY) against
/// material at y ≥ wall(x): the leading half-circle's points p(s) = b + s l + √(R² − s²) f are in
/// material from the offset s* where p(s*).y = wall(p(s*).x) up to s = R (l = +y side), so
/// ae = R − s* (s* by bisection; the wall is a function of x, not the tracker's capsules).
double aeAgainstWall(const Vec3& a, const Vec3& b, const std::function<double(double)>& wall) {
  const double R = 5e-3;
  const Eigen::Vector2d f = (b - a).head<2>().normalized();
  const Eigen::Vector2d l(-f.y(), f.x());
  const auto inside = [&](double s) {
    const Eigen::Vector2d p = b.head<2>() + s * l + std::sqrt(R * R - s * s) * f;
    return p.y() >= wall(p.x());
  };
  double lo = -R;  // outside
  double hi = R;   // inside
  for (int k = 0; k < 80; ++k) (inside(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
  return R - 0.5 * (lo + hi);
}

/// The wall a pass left (material at y ≥ wall(x)): its tips' y, linearly between them, + R.
std::function<double(double)> wallLeftBy(std::vector<Vec3> tips) {
  std::sort(tips.begin(), tips.end(), [](const Vec3& u, const Vec3& v) { return u.x() < v.x(); });
  return [tips](double x) {
    const auto it = std::lower_bound(tips.begin(), tips.end(), x,
                                     [](const Vec3& t, double v) { return t.x() < v; });
    if (it == tips.begin() || it == tips.end()) return -1.0;
    const Vec3& u = *(it - 1);
    const Vec3& v = *it;
    return u.y() + (x - u.x()) / (v.x() - u.x()) * (v.y() - u.y()) + 5e-3;
  };
}

// The real path's engagement (box_passes in the box stock): without compensation each pass cuts
// what the earlier ones really left — pass 2's ae against the wall of pass 1's real tips (path
// point + deviation_before, the wall their y + R between them), queried from its own tool without
// the milling force (path point + deviation_free); passes 1 and 3 against the box face y = 3 mm
// — all from the geometry above (not the tracker), to 0.02 µm, and pass 2's ae differs from the
// programmed 2 mm by pass 1's surface error (several µm). With compensation, pass 2 cuts what the
// compensated pass 1 left (path point + residual): its ae equals the programmed one within pass
// 1's residual.
TEST(MillingCompensation, EachPassCutsWhatTheEarlierPassesReallyLeft) {
  const std::string cell = test::sourceDir() + "/samples/milling/box-stock-7075.xml";
  const std::string prog = test::sourceDir() + "/samples/milling/box_passes.src";
  MillingPathOptions options;
  options.resolve_edges = false;  // not needed here
  const api::MillingCompensationResult r = api::compensateMillingJob(cell, prog, false, options);
  const Pose T_wobj_W = r.context.cell.T_base_wobj.inverse();
  const auto wobj = [&](size_t i, const Vec3& dev) {
    return Vec3(T_wobj_W * (r.points[i].translation() + dev));
  };
  std::vector<size_t> pass[3];
  const double ys[] = {0, 2e-3, 2e-3};
  const double zs[] = {-5e-3, -5e-3, -10e-3};
  for (size_t i = 0; i < r.points.size(); ++i) {
    const Vec3 x = wobj(i, Vec3::Zero());
    for (int k = 0; k < 3; ++k)
      if (std::abs(x.y() - ys[k]) < 1e-6 && std::abs(x.z() - zs[k]) < 1e-6 && r.cutting[i].cutting)
        pass[k].push_back(i);
  }
  for (int k = 0; k < 3; ++k) ASSERT_GE(pass[k].size(), 20u) << k;
  std::vector<Vec3> real1, compensated1;
  double residual1 = 0;
  for (const size_t i : pass[0]) {
    real1.push_back(wobj(i, r.points_comp[i].deviation_before));
    compensated1.push_back(wobj(i, r.points_comp[i].residual));
    residual1 = std::max(residual1, r.points_comp[i].residual.norm());
  }
  const std::function<double(double)> face = [](double) { return 3e-3; };
  const std::function<double(double)> walls[] = {face, wallLeftBy(real1), face};
  double change = 0;
  int checked = 0;
  for (int k = 0; k < 3; ++k) {
    for (const size_t i : pass[k]) {
      const double x = wobj(i, Vec3::Zero()).x();
      if (x < -20e-3 || x > 60e-3) continue;
      const PathPointCompensation& p = r.points_comp[i];
      const PathPointCompensation& q = r.points_comp[i - 1];
      ASSERT_TRUE(p.ok && p.cutting && p.cutting_after) << i << " " << p.reason;
      const Vec3 a = wobj(i - 1, q.deviation_free);
      const Vec3 b = wobj(i, p.deviation_free);
      EXPECT_NEAR(p.ae, aeAgainstWall(a, b, walls[k]), 0.02e-6) << "pass " << k + 1 << " " << i;
      if (k < 2) {
        EXPECT_NEAR(p.ap, -b.z(), 1e-9) << "pass " << k + 1;
      }
      if (k == 1) {
        change = std::max(change, std::abs(p.ae - r.cutting[i].engagement->ae));
        const Vec3 an = wobj(i - 1, Vec3::Zero());
        const Vec3 bn = wobj(i, Vec3::Zero());
        EXPECT_NEAR(p.ae_after, aeAgainstWall(an, bn, wallLeftBy(compensated1)), 0.02e-6) << i;
        EXPECT_NEAR(p.ae_after, r.cutting[i].engagement->ae, residual1 + 0.02e-6) << i;
      }
      ++checked;
    }
  }
  EXPECT_GE(checked, 45);
  EXPECT_GT(change, 2e-6);  // the real path changes pass 2's engagement measurably
  EXPECT_LT(residual1, 0.5e-6);
}

// The compensated force fixed point F = Φ(F) on a map whose Jacobian has a spectral radius above 1
// (as strong previous-edge coupling gives: −∂Φ/∂F = M, eigenvalues 1.6, 0.4, −1.3) with a small
// quadratic term: the plain iteration F ← Φ(F) diverges from a start 1 N off; Broyden's method
// converges to the known root F* (closed form) in ≤ 20 evaluations: |Φ(F) − F| ≤ 1e-9 N, so
// |F − F*| ≤ |(I + M)⁻¹| 1e-9 N ≈ 3.4e-9 N (the eigenvalue −1.3 of M).
TEST(MillingCompensation, BroydenForceFixedPointConvergesWhereThePlainIterationDiverges) {
  const Vec3 F_star(-180.0, 95.0, -12.0);
  Mat3 Q;
  Q = Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Mat3 M = Q * Vec3(1.6, 0.4, -1.3).asDiagonal() * Q.transpose();
  const auto phi = [&](const Vec3& F, Vec3& out) {
    const Vec3 e = F - F_star;
    out = F_star - M * e + 1e-3 * e.squaredNorm() * Vec3::UnitX();
    return true;
  };
  const Vec3 F0 = F_star + Vec3(0.6, -0.5, 0.62);
  const ForceFixedPoint plain = solveForceFixedPoint(phi, F0, ForceUpdate::kPlain);
  EXPECT_FALSE(plain.converged);
  EXPECT_GT((plain.force - F_star).norm(), 10 * (F0 - F_star).norm());
  const ForceFixedPoint broyden = solveForceFixedPoint(phi, F0, ForceUpdate::kBroyden);
  EXPECT_TRUE(broyden.converged);
  EXPECT_LE(broyden.evaluations, 20);
  EXPECT_LT((broyden.force - F_star).norm(), 4e-9);
  // a Φ that cannot be evaluated far from the root: Broyden halves the step and still converges
  const auto guarded = [&](const Vec3& F, Vec3& out) {
    return (F - F_star).norm() < 3.0 && phi(F, out);
  };
  const ForceFixedPoint halved = solveForceFixedPoint(guarded, F0, ForceUpdate::kBroyden);
  EXPECT_TRUE(halved.converged);
  EXPECT_LT((halved.force - F_star).norm(), 4e-9);
}

/// samples/milling/wall_pass.src with its feed points replaced by n points `step` apart from
/// x −50 mm.
std::string fineWallPass(int n, double step_mm) {
  const std::string text = test::readFile(test::sourceDir() + "/samples/milling/wall_pass.src");
  const std::string feed = "$VEL.CP = 0.06000\r\n";  // the sample's lines end in CR LF
  const size_t head = text.find(feed) + feed.size();
  const size_t tail = text.find("LIN {X 70.000");
  std::string s = text.substr(0, head);
  for (int i = 0; i < n; ++i)
    s += "LIN {X " + cFixed(-50 + step_mm * i, 4) +
         ",Y 0.000,Z -5.000,A 0.000,B 0.000,C 180.000} C_DIS\r\n";
  return s + text.substr(tail);
}

// One tooth pass between points (6 µm apart at fz 0.1 mm: spacing / fz rounds to 0, at least 1,
// taken from the program since the cell gives none): the feed term's previous-edge coupling makes
// ∂Φ/∂F's spectral radius exceed 1 — the plain force iteration fails ("the force fixed point did
// not converge") while Broyden's compensates every cutting point to ≤ 0.5 µm.
TEST(MillingCompensation, OneToothPassPerPointCompensatesEveryCuttingPoint) {
  const std::string dir = test::tempDir("mill-fine");
  test::writeFile(dir + "/fine.src", fineWallPass(60, 0.006));
  const std::string cell = test::sourceDir() + "/samples/cells/alu-milling-7075.xml";
  const api::MillingCompensationResult r = api::compensateMillingJob(cell, dir + "/fine.src");
  MillingPathOptions plain_options;
  plain_options.force_update = ForceUpdate::kPlain;
  const api::MillingCompensationResult plain =
      api::compensateMillingJob(cell, dir + "/fine.src", false, plain_options);
  int cutting = 0;
  int plain_failed = 0;
  for (size_t i = 0; i < r.points_comp.size(); ++i) {
    const PathPointCompensation& p = r.points_comp[i];
    if (!p.cutting) continue;
    ++cutting;
    EXPECT_TRUE(p.ok) << i << " " << p.reason;
    EXPECT_LT(p.residual.norm(), 0.5e-6) << i;
    EXPECT_FALSE(p.teeth_from_cell);
    if (i >= 2 && i <= 60) {  // after the first fine point, to the last (then x 70 follows)
      EXPECT_EQ(p.teeth_between_points, 1) << i;
    }
    if (!plain.points_comp[i].ok) {
      ++plain_failed;
      EXPECT_EQ(plain.points_comp[i].reason, "the force fixed point did not converge") << i;
    }
  }
  EXPECT_GE(cutting, 60);
  EXPECT_GT(plain_failed, 30);
  std::printf("one tooth pass per point: %d cutting points, the plain update failed %d\n", cutting,
              plain_failed);
}

// The tooth passes between points: from the program's spacing (wall_pass: 5 mm / fz 0.1 = 50, the
// first feed point 10 mm after the plunge: 100) unless the cell's <coupling> gives them.
TEST(MillingCompensation, TeethBetweenPointsFromTheSpacingUnlessTheCellGivesThem) {
  const std::string cell = test::sourceDir() + "/samples/cells/alu-milling-7075.xml";
  const std::string prog = test::sourceDir() + "/samples/milling/wall_pass.src";
  const api::MillingCompensationResult r = api::compensateMillingJob(cell, prog);
  const std::string dir = test::tempDir("mill-teeth");
  std::string text = test::readFile(cell);
  const size_t at = text.find("<coupling ") + std::string("<coupling ").size();
  text.insert(at, "teeth_between_points=\"7\" ");
  test::writeFile(dir + "/seven.xml", text);
  const api::MillingCompensationResult g = api::compensateMillingJob(dir + "/seven.xml", prog);
  int checked = 0;
  for (size_t i = 2; i < r.points_comp.size(); ++i) {
    if (!r.points_comp[i].cutting) continue;
    const double spacing = (r.points[i].translation() - r.points[i - 1].translation()).norm();
    EXPECT_EQ(r.points_comp[i].teeth_between_points, std::round(spacing / 0.1e-3)) << i;
    EXPECT_FALSE(r.points_comp[i].teeth_from_cell);
    EXPECT_EQ(g.points_comp[i].teeth_between_points, 7) << i;
    EXPECT_TRUE(g.points_comp[i].teeth_from_cell);
    ++checked;
  }
  EXPECT_GE(checked, 20);
}

// The pipeline (the uncompensated chain of a block while the compensated chain runs over the
// block before it, the revolutions on the workers) changes nothing: blocks of 7 points on 2
// threads give every field bit for bit as one block on one thread, on passes whose engagement
// changes (box stock); without the revolutions every other field is the same too.
TEST(MillingCompensation, PipelinedBlocksOnTwoThreadsGiveTheOneThreadResults) {
  const std::string cell = test::sourceDir() + "/samples/milling/box-stock-7075.xml";
  const std::string prog = test::sourceDir() + "/samples/milling/box_passes.src";
  MillingPathOptions one;
  one.block = 100000;
  const api::MillingCompensationResult a = api::compensateMillingJob(cell, prog, false, one);
  MillingPathOptions two;
  two.threads = 2;
  two.block = 7;
  const api::MillingCompensationResult b = api::compensateMillingJob(cell, prog, false, two);
  MillingPathOptions bare = two;
  bare.resolve_edges = false;
  const api::MillingCompensationResult c = api::compensateMillingJob(cell, prog, false, bare);
  ASSERT_GT(a.points_comp.size(), 3 * two.block);
  ASSERT_EQ(b.points_comp.size(), a.points_comp.size());
  ASSERT_EQ(c.points_comp.size(), a.points_comp.size());
  int edges = 0;
  for (size_t i = 0; i < a.points_comp.size(); ++i) {
    const PathPointCompensation& x = a.points_comp[i];
    for (const PathPointCompensation* y : {&b.points_comp[i], &c.points_comp[i]}) {
      EXPECT_EQ(x.ok, y->ok) << i;
      EXPECT_EQ(x.reason, y->reason) << i;
      EXPECT_EQ(x.cutting, y->cutting) << i;
      EXPECT_EQ(x.ae, y->ae) << i;
      EXPECT_EQ(x.ap, y->ap) << i;
      EXPECT_EQ(x.cutting_after, y->cutting_after) << i;
      EXPECT_EQ(x.ae_after, y->ae_after) << i;
      EXPECT_EQ(x.ap_after, y->ap_after) << i;
      EXPECT_EQ(x.deviation_free, y->deviation_free) << i;
      EXPECT_EQ(x.theta_d, y->theta_d) << i;
      EXPECT_EQ(x.theta_cmd, y->theta_cmd) << i;
      EXPECT_EQ(x.T_programmed.matrix(), y->T_programmed.matrix()) << i;
      EXPECT_EQ(x.deviation_before, y->deviation_before) << i;
      EXPECT_EQ(x.residual, y->residual) << i;
      EXPECT_EQ(x.force, y->force) << i;
      EXPECT_EQ(x.before_force, y->before_force) << i;
      EXPECT_EQ(x.before_loop_gain, y->before_loop_gain) << i;
      EXPECT_EQ(x.loop_gain, y->loop_gain) << i;
      EXPECT_EQ(x.coupling_status, y->coupling_status) << i;
      EXPECT_EQ(x.force_iterations, y->force_iterations) << i;
      EXPECT_EQ(x.config_text, y->config_text) << i;
      EXPECT_EQ(x.stability_checked, y->stability_checked) << i;
      EXPECT_EQ(x.ap_limit, y->ap_limit) << i;
      EXPECT_EQ(x.chatter_hz, y->chatter_hz) << i;
    }
    const PathPointCompensation& y = b.points_comp[i];
    EXPECT_EQ(x.edges_checked, y.edges_checked) << i;
    EXPECT_EQ(x.tooth_feed, y.tooth_feed) << i;
    EXPECT_EQ(x.peak_xy, y.peak_xy) << i;
    EXPECT_EQ(x.peak_xy_nominal, y.peak_xy_nominal) << i;
    EXPECT_EQ(x.vibration_pp, y.vibration_pp) << i;
    EXPECT_FALSE(c.points_comp[i].edges_checked) << i;
    edges += x.edges_checked ? 1 : 0;
  }
  EXPECT_GT(edges, 3 * static_cast<int>(two.block));  // the revolutions were resolved
}

// The results handed block by block (compensateMillingPath with a sink, the path's results never
// all in memory): every block size (1 point, 5, the whole path) on 1 and 2 threads hands each
// point exactly once, in path order, in blocks of the asked size, with every field bit for bit as
// the whole-path vector on one thread.
TEST(MillingCompensation, ResultsHandedBlockByBlockAreTheWholePathResults) {
  std::vector<Pose> points;
  const api::PredictionContext c = wallPass(points);
  ASSERT_GE(points.size(), 25u);
  MillingPathOptions whole;
  whole.block = points.size();
  const std::vector<PathPointCompensation> ref =
      compensateMillingPath(c.model, points, nullptr, nullptr, whole);
  for (const size_t block : {size_t{1}, size_t{5}, points.size()}) {
    for (const int threads : {1, 2}) {
      MillingPathOptions o;
      o.block = block;
      o.threads = threads;
      size_t next = 0;
      int blocks = 0;
      compensateMillingPath(
          c.model, points, nullptr, nullptr, o,
          [&](size_t first, std::span<PathPointCompensation> got) {
            ++blocks;
            ASSERT_EQ(first, next) << "block " << block << ", threads " << threads;
            ASSERT_EQ(got.size(), std::min(block, points.size() - first));
            for (size_t k = 0; k < got.size(); ++k) {
              const PathPointCompensation& x = ref[first + k];
              const PathPointCompensation& y = got[k];
              EXPECT_EQ(x.ok, y.ok) << first + k;
              EXPECT_EQ(x.theta_d, y.theta_d) << first + k;
              EXPECT_EQ(x.theta_cmd, y.theta_cmd) << first + k;
              EXPECT_EQ(x.T_programmed.matrix(), y.T_programmed.matrix()) << first + k;
              EXPECT_EQ(x.deviation_before, y.deviation_before) << first + k;
              EXPECT_EQ(x.residual, y.residual) << first + k;
              EXPECT_EQ(x.force, y.force) << first + k;
              EXPECT_EQ(x.loop_gain, y.loop_gain) << first + k;
              EXPECT_EQ(x.teeth_between_points, y.teeth_between_points) << first + k;
              EXPECT_EQ(x.ap_limit, y.ap_limit) << first + k;
              EXPECT_EQ(x.tooth_feed, y.tooth_feed) << first + k;
              EXPECT_EQ(x.config_text, y.config_text) << first + k;
            }
            next = first + got.size();
          });
      EXPECT_EQ(next, points.size()) << "block " << block << ", threads " << threads;
      EXPECT_EQ(blocks, static_cast<int>((points.size() + block - 1) / block));
    }
  }
}

// A milling cell with a <part_registration> (verify --write-cell): every path point is aimed
// where the registration found the part — the nominal path moved by G = T_W_wobj · F⁻¹ ·
// T_W_wobj⁻¹ computed by hand, to 1e-12 m — with the same cutting decisions (the stock moves with
// the part), and the compensation lands on the moved path as it lands on the nominal one.
TEST(MillingCompensation, ARegisteredCellCompensatesTheRegisteredPath) {
  const std::string cell = test::sourceDir() + "/samples/cells/alu-milling-7075.xml";
  const std::string prog = test::sourceDir() + "/samples/milling/wall_pass.src";
  const std::string dir = test::tempDir("mill-registered");
  const std::string text = test::withPartRegistration(test::readFile(cell));
  ASSERT_FALSE(text.empty());
  const std::string registered = dir + "/registered.xml";
  test::writeFile(registered, text);
  const api::MillingCompensationResult plain = api::compensateMillingJob(cell, prog, false);
  const api::MillingCompensationResult reg = api::compensateMillingJob(registered, prog, false);
  const Pose F = test::partRegistration();  // the registration by hand
  const Pose T_W_wobj = plain.context.cell.T_base_wobj;
  const Pose G = T_W_wobj * F.inverse() * T_W_wobj.inverse();
  ASSERT_EQ(reg.points.size(), plain.points.size());
  double worst_plain = 0;
  double worst_reg = 0;
  for (size_t i = 0; i < reg.points.size(); ++i) {
    const Pose moved = G * plain.points[i];
    EXPECT_LT((reg.points[i].translation() - moved.translation()).norm(), 1e-12) << i;
    EXPECT_LT((reg.points[i].linear() - moved.linear()).norm(), 1e-12) << i;
    EXPECT_EQ(reg.cutting[i].cutting, plain.cutting[i].cutting) << i;
    ASSERT_EQ(reg.points_comp[i].ok, plain.points_comp[i].ok) << i;
    if (!reg.points_comp[i].ok) continue;
    worst_plain = std::max(worst_plain, plain.points_comp[i].residual.norm());
    worst_reg = std::max(worst_reg, reg.points_comp[i].residual.norm());
    EXPECT_GT((reg.points_comp[i].T_programmed.translation() -
               plain.points_comp[i].T_programmed.translation())
                  .norm(),
              0.1e-3)
        << i;
  }
  EXPECT_LE(worst_reg, worst_plain + 1e-6);
}

}  // namespace
}  // namespace roprec
