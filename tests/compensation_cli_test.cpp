// Compensation through the CLI: compensate a program (each bundled robot in its own dialect, each
// orientation mode), then predict the written program: the predicted real drill point of every
// hole lies on the original program's drilling axis within 0.1 µm (systematic residual).
#include <gtest/gtest.h>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <cmath>
#include <map>

#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using nlohmann::json;

struct Job {
  std::string cell;
  std::string program;
  std::string frames;  ///< --frame/--tool for frames only the controller defines
};

json predictJson(const std::string& cell, const std::string& prog, const std::string& dir,
                 const std::string& tag, const std::string& frames) {
  const std::string holes = test::sourceDir() + "/samples/emotor-housing/holes.csv";
  const auto r =
      test::runRoprec("predict --cell '" + cell + "' '" + prog + "' --holes '" + holes +
                      "' --match-tol 10 --quiet --json '" + dir + "/" + tag + ".json' " + frames);
  EXPECT_LE(r.exit_code, 1) << r.err;
  return json::parse(test::readFile(dir + "/" + tag + ".json"));
}

TEST(CompensationCli, RepredictingTheCompensatedProgramLeavesAtMostATenthOfAMicrometre) {
  const std::string s = test::sourceDir() + "/samples/";
  const std::vector<Job> jobs = {
      {s + "cells/housing-kr120.xml", s + "emotor-housing/housing_kr120.src", ""},
      {s + "cells/housing-irb6640.xml", s + "emotor-housing/housing_irb6640.mod", ""},
      // UFRAME[1]/UTOOL[1] live in the controller: the cell's workobject and tool are them
      {s + "cells/housing-r2000.xml", s + "emotor-housing/housing_r2000.ls",
       "--frame cell --tool cell"}};
  const std::string holes = s + "emotor-housing/holes.csv";
  for (const Job& job : jobs) {
    SCOPED_TRACE(job.program);
    const std::string dir = test::tempDir("rep");
    const json before = predictJson(job.cell, job.program, dir, "before", job.frames);
    // the original drill points and axes, by hole id
    std::map<std::string, std::pair<Eigen::Vector3d, Eigen::Vector3d>> nominal;
    for (const auto& h : before["holes"]) {
      const auto p = h["nominal"]["position_mm"];
      const auto a = h["nominal"]["axis"];
      nominal[h["id"]] = {Eigen::Vector3d(p[0], p[1], p[2]), Eigen::Vector3d(a[0], a[1], a[2])};
    }
    for (const char* mode : {"keep", "flip-free", "stiffest"}) {
      SCOPED_TRACE(mode);
      const std::string ext = job.program.substr(job.program.find_last_of('.'));
      const std::string out = dir + "/comp_" + mode + ext;
      const auto r = test::runRoprec("compensate --cell '" + job.cell + "' '" + job.program +
                                     "' --holes '" + holes + "' --orientation " + mode +
                                     " --grid 12 -o '" + out + "' " + job.frames);
      ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
      const json after = predictJson(job.cell, out, dir, std::string("after_") + mode, job.frames);
      ASSERT_EQ(after["holes"].size(), before["holes"].size());
      double worst = 0;
      for (const auto& h : after["holes"]) {
        ASSERT_TRUE(h.contains("deviation_um")) << h["id"] << " " << h.value("reason", "");
        const auto p = h["nominal"]["position_mm"];
        const auto w = h["deviation_um"]["work"];
        Eigen::Vector3d real;
        for (int k = 0; k < 3; ++k) real[k] = p[k].get<double>() + w[k].get<double>() * 1e-3;
        const auto& [p0, a0] = nominal.at(h["id"]);
        const Eigen::Vector3d d = real - p0;
        worst = std::max(worst, (d - d.dot(a0) * a0).norm() * 1e3);  // µm
      }
      EXPECT_LE(worst, 0.1) << "worst residual " << worst << " µm";
    }
  }
}

}  // namespace
}  // namespace roprec
