#pragma once
/// \file drill_geometry.hpp
/// Conventional two-lip twist drill: the cutting-edge geometry as a function of radius
/// (docs/process.md §1.2) and the edge frame built point by point with unit quaternions (§1.4).
///
/// Tool frame (used everywhere in the process layer):
///   z  = drill axis, +z into the workpiece (feed direction); the spindle turns about +z (M03).
///   Lip 1 is the straight line y = +w, x > 0 on the point cone, tangent t = (sin p, 0, -cos p);
///   lip k is lip 1 turned by k·2π/lips about z. "Spindle angle 0" means this placement.
/// Units: SI (m, rad). Files give mm and degrees (see process_spec.hpp).
///
/// Closed forms for a straight lip (a <= r <= R, a = w / sin ψ) [docs/process.md §1.2, D/L]:
///   sin ω = w/r,  tan δ(r) = (r/R) tan δ0,  sin λs = (w/r) sin p,  tan κr = tan p cos ω,
///   tan γn = tan δ(r) cos²λs / (sin p cos ω) − cos p tan ω,
///   h(r) = (f/2) sin κr  (per lip, two lips),  db = dr / sin κr  ⇒  h·db = (f/2)·dr.
/// Working angles with feed f: the cutting velocity is v_e = normalize(2πr e_θ + f z) instead of
/// e_θ (≈ γn + η_f sin κr / cos λs, η_f = atan(f / 2πr)).
///
/// "Paper-compatibility" angle law (Ferreras-Higuero et al. 2020 [P], docs/process.md §1.3):
///   tan γn = (r/R) tan γn0,  tan λs = (r/R) tan λs0,  κr = p, with γn0, λs0 the geometric
///   corner values. It disagrees with the geometry near the web (never negative rake); kept only
///   as an option.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

#include "compensator/support/rotation.hpp"

namespace roprec {

enum class AngleLaw {
  kGeometric,          ///< §1.2 / §1.4 geometry (default)
  kPaperProportional,  ///< §1.3 proportional laws, κr = p
};

struct DrillGeometry {
  double diameter{10e-3};           ///< Dc = 2R [m]
  double point_angle{118 * kDeg};   ///< 2p, included angle between the lips [rad], in (60°, 180°)
  double helix_angle{30 * kDeg};    ///< δ0, helix at the periphery [rad]
  double web_thickness{1.6e-3};     ///< 2w, web at the point [m], 0 <= 2w < Dc
  double chisel_angle{125 * kDeg};  ///< ψ, obtuse end-view angle chisel edge / lip [rad]
  int lips{2};                      ///< number of lips (cutting edges)
  double runout{0.0};               ///< ρ, parallel-axis offset of the drill [m]

  [[nodiscard]] double radius() const { return 0.5 * diameter; }
  [[nodiscard]] double halfPoint() const { return 0.5 * point_angle; }
  [[nodiscard]] double halfWeb() const { return 0.5 * web_thickness; }
  /// a = w / sin ψ: chisel half-length = radius of the inner end of the lips [m].
  [[nodiscard]] double chiselHalfLength() const;
  /// Axial distance from the inner lip end to the corner,
  /// (√(R²−w²) − √(a²−w²)) cot p [m] (§1.2).
  [[nodiscard]] double pointLength() const;
};

/// Checks the ranges above; returns an empty string when valid, else what is wrong
/// (the spec parser turns it into an InputError at the element's line).
std::string drillGeometryProblem(const DrillGeometry& g);

/// Closed-form edge angles at radius r (§1.2). All angles in rad; λs is the magnitude.
struct EdgeAngles {
  double gamma_n{0};   ///< normal rake γn
  double lambda_s{0};  ///< inclination |λs|
  double kappa_r{0};   ///< tool cutting-edge angle κr
  double omega{0};     ///< web (end-view) angle ω
  double helix{0};     ///< local helix δ(r)
};
EdgeAngles closedFormEdgeAngles(const DrillGeometry& g, double r);

/// The paper's proportional laws (§1.3) with the geometric corner angles as γn0, λs0.
EdgeAngles paperEdgeAngles(const DrillGeometry& g, double r);

/// Edge frame at radius r on lip `lip` (0-based), built with quaternions exactly as §1.4.
/// All vectors are unit vectors in the tool frame at spindle angle 0.
struct EdgeFrame {
  Vec3 position{Vec3::Zero()};   ///< point on the lip (z = 0 at the inner lip end) [m]
  Vec3 t{Vec3::Zero()};          ///< edge tangent, outward
  Vec3 e_r{Vec3::Zero()};        ///< radial direction
  Vec3 e_theta{Vec3::Zero()};    ///< tangential direction (direction of rotation)
  Vec3 v{Vec3::Zero()};          ///< cutting velocity direction (static e_θ, or working with feed)
  Vec3 helix{Vec3::Zero()};      ///< flute helix tangent, pointing up the flute
  Vec3 n_gamma{Vec3::Zero()};    ///< rake-face normal, n·v > 0
  Vec3 v_n{Vec3::Zero()};        ///< velocity projected on the normal plane Pn
  Vec3 c{Vec3::Zero()};          ///< chip-thickness direction in Pn, c·z < 0
  Vec3 chip_flow{Vec3::Zero()};  ///< chip-flow direction on the rake face (Stabler ηc = λs)
  double gamma_n{0};             ///< normal rake [rad]
  double lambda_s{0};  ///< signed inclination, sin λs = t·v (negative on a standard drill)
  double kappa_r{0};   ///< tool cutting-edge angle [rad]
};

/// feed_per_rev = 0 gives the static frame; > 0 the working frame (v_e includes the feed) [m/rev].
EdgeFrame edgeFrame(const DrillGeometry& g, double r, int lip, double feed_per_rev = 0.0);

/// Edge angles under the chosen law; `feed_per_rev` > 0 selects working angles (geometric law
/// only).
EdgeAngles edgeAngles(const DrillGeometry& g, AngleLaw law, double r, double feed_per_rev = 0.0);

}  // namespace roprec
