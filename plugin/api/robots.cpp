/// The bundled robots and their estimates (plugin/api/robots.hpp).
#include "plugin/api/robots.hpp"

namespace roprec::api {

std::vector<RobotCard> bundledRobotCards() {
  std::vector<RobotCard> cards;
  for (const std::string& name : bundledRobotNames())
    cards.push_back(loadRobotCard(bundledRobotsDir() + "/" + name + "/robot.xml"));
  return cards;
}

namespace {
bool isEstimate(const std::string& source) { return source.rfind("estimate", 0) == 0; }
}  // namespace

std::vector<std::string> cardEstimates(const RobotCard& card) {
  std::vector<std::string> out;
  std::string joints;
  std::string why;
  for (std::size_t i = 0; i < card.joints.size(); ++i) {
    if (!card.joints[i].estimated()) continue;
    joints += (joints.empty() ? "k" : ", k") + std::to_string(i + 1);
    if (why.empty()) why = card.joints[i].source;
  }
  if (!joints.empty()) out.push_back("joint stiffness and servo gain " + joints + ": " + why);
  if (isEstimate(card.rp_source)) out.push_back("repeatability RP: " + card.rp_source);
  if (isEstimate(card.inertial_source)) out.push_back("link inertials: " + card.inertial_source);
  for (const auto& l : card.links) {
    if (isEstimate(l.source)) out.push_back("inertial of " + l.name + ": " + l.source);
  }
  if (card.counterbalance.present() && isEstimate(card.counterbalance.source))
    out.push_back("axis balancer: " + card.counterbalance.source);
  if (isEstimate(card.dimensions_source)) out.push_back("dimensions: " + card.dimensions_source);
  return out;
}

}  // namespace roprec::api
