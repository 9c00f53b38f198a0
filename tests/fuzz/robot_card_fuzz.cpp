// libFuzzer harness for the robot card (roprec::loadRobotCard, then loadRobot: the URDF, the
// <link> overrides, the balancer and the calibration pose checks, the gravity-model check). The
// card takes a path: each input is written to <scratch>/robot.xml, next to copies of the bundled
// robots' URDFs (so a card may say urdf="kr120r2500pro.urdf", "irb6640_185_280.urdf" or
// "r2000ic165f.urdf"). Documented errors: roprec::InputError. Anything else, a crash or a
// sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "compensator/robot/robot_card.hpp"
#include "compensator/support/error.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path& cardFolder() {
  static const fs::path dir = [] {
    const fs::path d = roprec::fuzz::scratchDir("card");
    for (const auto& e : fs::recursive_directory_iterator(roprec::fuzz::sourceDir() + "/robots")) {
      if (e.path().extension() == ".urdf")
        fs::copy_file(e.path(), d / e.path().filename(), fs::copy_options::overwrite_existing);
    }
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = roprec::fuzz::writeInput(cardFolder() / "robot.xml", data, size);
  try {
    const roprec::RobotCard card = roprec::loadRobotCard(path);
    static_cast<void>(roprec::vendorCalibrationPoseDeg(card.vendor));
    const roprec::Robot robot = roprec::loadRobot({path, "", ""});
    static_cast<void>(roprec::gravityNotModelledNote(robot.card));
    const Eigen::Matrix<double, 6, 1> q = Eigen::Matrix<double, 6, 1>::Zero();
    static_cast<void>(
        roprec::fromControllerJoints(robot.card, roprec::toControllerJoints(robot.card, q)));
    roprec::requireGravityModel(robot);
  } catch (const roprec::InputError& e) {
    roprec::fuzz::rejected(e);
  }
  return 0;
}
