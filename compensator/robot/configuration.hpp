#pragma once
/// \file configuration.hpp
/// Vendor configuration flags ↔ IK solutions (docs/programs.md §2.4, §3.3, §4.5, §7, §9).
/// All flags are computed from the joint vector in the controller's own joint convention
/// (toControllerJoints of the robot card); the branch labels s (shoulder), e (elbow), w (wrist)
/// come from ikBranch (ik.hpp, §7.1): branch = 4 s + 2 e + w.
///
/// KUKA Status / Turn (E6POS `S`, `T`):
///   S bit 0 = s (1 = wrist centre behind axis 1, "overhead area"),
///   S bit 1 = 1 for elbow up (e = 0)  — ⚠ polarity uncertain (§9 item 2); chosen "1 = elbow up"
///   after
///             Siemens' KUKA-compatible STAT definition [S5] and the prevalence of S 2 / S 6 in
///             taught programs [S11]; RoboDK's corpus poses give S 2 / T 34 (see
///             docs/configuration.md),
///   S bit 2 = w (1 ⇔ A5 wrapped to [−180°, 180°) is < 0),
///   S bits 3.. copied from the original (`high_bits`),
///   T bit n = 1 ⇔ A(n+1) < 0 (n = 0..5).
///   String form: "S 2 T 34" (decimal). Parsing also accepts binary literals `S 'B010' T
///   'B100010'`, commas/braces (`{S 2, T 34}`), and either field alone (missing = unknown).
/// ABB confdata [cf1, cf4, cf6, cfx] (robtarget `robconf`, §3.3, §7.2):
///   cfN = floor(θN / 90°) for axes 1, 4, 6 (negative angles: −1 is [−90°, 0), −2 is [−180°,
///   −90°)); boundary choice: an angle within 1e-9 of a multiple of 90° counts as that multiple, so
///   θ6 = −180° gives −2 as RoboDK writes it [S8] and −179.9999999999° also gives −2 (⚠ §9 item 9).
///   cfx = branch = 4 s + 2 e + w.  String form: "[0,-1,2,1]"; parsing accepts brackets or not and
///   commas or blanks.
/// FANUC CONFIG 'F|N U|D T|B, t1, t2, t3' (§4.5):
///   F ⇔ J5 ≥ 0 (RoboDK: "F means axis 5 >= 0, N means axis 5 < 0" [S8]; i.e. w = 0), U ⇔ elbow up,
///   T ⇔ shoulder front; turn t = 0 for −180° < θ < 180°, +1 for 180° ≤ θ < 540°, −1 for
///   −540° < θ ≤ −180° (RoboDK `angle_2_turn` [S8]) for the axes in `fanuc_turn_axes` — default J1,
///   J4, J6 as RoboDK writes; ⚠ §9 item 1: FANUC's `$TURN_AXIS` may say J4, J5, J6. String form: "N
///   U T, 0, 0, 0"; parsing accepts surrounding quotes and blanks.
///
/// Reverse (flags + pose → the one solution): all IK solutions with every ±360° turn inside the
/// limits are enumerated; the branch must equal the flags' branch, then KUKA T must match the sign
/// of every axis, ABB cf1/cf4/cf6 the quadrants, FANUC the turn numbers. Among several exact
/// matches the one with the smallest Σ|θ| wins (deterministic). Without an exact match the
/// same-branch solution with the smallest mismatch is returned with `exact = false`.

#include <array>
#include <optional>
#include <string>

#include "compensator/robot/ik.hpp"
#include "compensator/robot/robot_card.hpp"

namespace roprec {

struct KukaConfig {
  std::optional<int> status;  ///< S (bits 0..2 branch, higher bits copied)
  std::optional<int> turn;    ///< T
};

struct AbbConfig {
  int cf1{0};
  int cf4{0};
  int cf6{0};
  int cfx{0};
};

struct FanucConfig {
  bool flip{false};  ///< F (J5 ≥ 0) / N
  bool up{true};     ///< U / D
  bool top{true};    ///< T (front) / B (back)
  std::array<int, 3> turns{0, 0, 0};
};

struct ConfigurationOptions {
  std::array<int, 3> fanuc_turn_axes{1, 4, 6};  ///< 1-based joint numbers of the three turn digits
  int kuka_status_high_bits{0};                 ///< S bits 3.. to keep (e.g. the original S & ~7)
};

struct VendorConfig {
  Vendor vendor{Vendor::kGeneric};
  KukaConfig kuka;
  AbbConfig abb;
  FanucConfig fanuc;
  int branch{0};  ///< 4 s + 2 e + w (generic robots)
};

/// Turn number of an angle (rad) as FANUC / RoboDK `angle_2_turn`.
int fanucTurn(double theta);
/// ABB quadrant floor(θ / 90°) with the boundary rule above.
int abbQuadrant(double theta);

KukaConfig kukaConfig(const IkModel& model, const RobotCard& card, const Vec6& q_urdf,
                      const ConfigurationOptions& options = {});
AbbConfig abbConfig(const IkModel& model, const RobotCard& card, const Vec6& q_urdf);
FanucConfig fanucConfig(const IkModel& model, const RobotCard& card, const Vec6& q_urdf,
                        const ConfigurationOptions& options = {});
/// The card's vendor's flags (generic: branch index only).
VendorConfig configurationOf(const IkModel& model, const RobotCard& card, const Vec6& q_urdf,
                             const ConfigurationOptions& options = {});

/// Branch index 4 s + 2 e + w encoded by the flags (KUKA: S bits 0..2; ABB: cfx; FANUC: letters).
/// Returns nothing when a KUKA S is absent.
std::optional<int> branchOfConfig(const VendorConfig& config);

std::string formatKuka(const KukaConfig& c);      ///< "S 2 T 34" (absent fields omitted)
std::string formatAbb(const AbbConfig& c);        ///< "[0,-1,2,1]"
std::string formatFanuc(const FanucConfig& c);    ///< "N U T, 0, 0, 0"
std::string formatConfig(const VendorConfig& c);  ///< the vendor's form; generic: "branch 5"

/// Parsers throw InputError(file, line, message) on malformed text (file/line give the context of
/// the text, e.g. the program line it came from; empty/0 for the command line).
KukaConfig parseKuka(const std::string& text, const std::string& file = "", int line = 0);
AbbConfig parseAbb(const std::string& text, const std::string& file = "", int line = 0);
FanucConfig parseFanuc(const std::string& text, const std::string& file = "", int line = 0);
VendorConfig parseConfig(Vendor vendor, const std::string& text, const std::string& file = "",
                         int line = 0);

/// Flags + pose → the one IK solution.
struct ConfiguredSolution {
  bool found{false};  ///< a solution of the flags' branch exists (within limits)
  bool exact{false};  ///< every flag (branch and turns) matches
  int mismatch{0};    ///< KUKA: differing T bits; ABB: Σ|Δcf|; FANUC: Σ|Δturn|
  IkSolution solution;
  std::string reason;  ///< why not found / not exact
};
ConfiguredSolution solveIkWithConfiguration(const IkModel& model, const RobotCard& card,
                                            const Pose& target, const VendorConfig& config,
                                            const ConfigurationOptions& options = {});

/// Joints this close to the boundary of a flag (KUKA T: 0°; ABB cfN: multiples of 90°; FANUC
/// turn: ±180° + k·360°) match the flag on either side (docs/configuration.md §5): an angle at the
/// boundary — a hand-written A1 = 0 that a compensation offset of a few µrad moves to −0.0001° —
/// keeps the programmed flag instead of flipping it. 0.5° exceeds every joint offset the
/// compensation applies on the bundled sample jobs (≤ 0.04°, 0.21° on the FANUC wrist axes 4/6
/// near θ5 = 0) and is far below any posture change.
constexpr double kFlagBoundaryTolerance = 0.5 * kDeg;

/// How the seeded overload resolves what the flags leave open.
struct ConfigurationMatch {
  const Vec6* seed{nullptr};       ///< among matching solutions the one nearest this (URDF, rad)
  double boundary_tolerance{0.0};  ///< rad, see kFlagBoundaryTolerance
  /// Describe a found but inexact solution in `reason` (false: left empty, no allocation; the
  /// prediction and the compensation read `reason` only when nothing is found).
  bool explain_inexact{true};
};
/// Flags + pose → the solution nearest `match.seed` (Σ (θ − seed)²) among those of the flags'
/// branch whose turn flags match (joints within `boundary_tolerance` of a flag boundary match
/// either side); without a seed as the overload above. Same result fields.
ConfiguredSolution solveIkWithConfiguration(const IkModel& model, const RobotCard& card,
                                            const Pose& target, const VendorConfig& config,
                                            const ConfigurationOptions& options,
                                            const ConfigurationMatch& match);

/// The turn flags of `config` that the joint vector q (URDF, rad) does not meet, e.g.
/// "cf6 -2 -> 2 (axis 6 at 181.6 deg)" or "T bit 0 (A1 at -3.2 deg)"; joints within `tolerance`
/// (rad) of the flag's boundary meet it. Empty when every turn flag matches. The branch is not
/// compared (see branchOfConfig).
std::string turnFlagMismatch(const IkModel& model, const RobotCard& card, const Vec6& q,
                             const VendorConfig& config, const ConfigurationOptions& options,
                             double tolerance);

}  // namespace roprec
