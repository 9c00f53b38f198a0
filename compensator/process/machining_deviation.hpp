#pragma once
/// \file machining_deviation.hpp
/// Machining deviation δmach of a drilled hole's axis (position at the evaluation depth) and its
/// uncertainty components, for the budget δwork = δrobot + δmach (docs/process.md §5.7).
///
/// Three terms, all half-widths `a` at the hole, in the tool's XY plane:
///   δaxis    tool-axis deviation: the drill axis deviates from the programmed hole axis by up to
///   θa;
///            the hole axis, evaluated at the lever La (≈ mid-depth), is off by a = La tan θa.
///            Rectangular: u = a/√3 (GUM 4.3.7).
///   δρ       runout: the drill tip turns on a circle of radius ρ about the spindle axis; the hole
///            centre lies anywhere on it. Arcsine (U-shaped): u = a/√2, a = ρ.
///   δdeftool tool deflection under the rotating residual force Fr (drilling_forces.hpp, runout):
///            the drill is a carbide/HSS cantilever of stick-out L and equivalent diameter
///            d_e = κ·Dc (fluted section), in series with the spindle/holder compliance c_s:
///              a = Fr · (L³ / (3 E I_e) + c_s),  I_e = π d_e⁴ / 64.
///            The force rotates with the spindle: arcsine, u = a/√2.
/// Combined (independent, unit sensitivity): u_c = √(Σ u_i²) per in-plane axis; expanded
/// U = k u_c with the 2-D radial coverage factor k = √(−2 ln 0.05) = 2.4477 (95 % of an isotropic
/// in-plane scatter lies within U; docs/process.md §5.1) — the same U_mach `forces` and `predict`
/// report. (The ±30/±60 µm band below is a 1-D "±2σ" figure: 2 u_c.)
///
/// The three terms are zero-mean; the systematic part δmach = (L³/(3 E I_e) + c_s)·F_xy,static
/// comes only from a static in-plane force on the tool (e.g. a `wrench` process), in the tool
/// frame.
///
/// Defaults (defaultMachiningDeviation): θa = 0.03°, La = Dc, ρ = 0.25 µm/mm × L, L = 3·Dc,
/// κ = 0.8, E = 600 GPa (carbide) / 210 GPa (HSS), c_s = 0.29 µm/N — estimates chosen together so
/// that, for Al 6061-T6 at f = 0.2 mm/rev, 2·u_c is ≈ ±30 µm at Dc 8 mm and ≈ ±60 µm at
/// Dc 12 mm, the band Ferreras-Higuero et al. (RCIM 2020) report [P, not confirmed against the
/// paper text]. Every value can be overridden from the cell (<machining_deviation .../>).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "compensator/process/drill_geometry.hpp"

namespace roprec {

enum class Distribution { kNormal, kRectangular, kTriangular, kArcsine };
const char* distributionName(Distribution d);
/// Standard uncertainty of a half-width `a` (normal: `a` is already the standard uncertainty):
/// rectangular a/√3, triangular a/√6, arcsine a/√2 (GUM §4.3.7–4.3.9).
double standardUncertainty(double half_width, Distribution d);

struct UncertaintyComponent {
  std::string name;      ///< "delta_axis", "delta_runout", "delta_deftool"
  double half_width{0};  ///< a [m]
  Distribution distribution{Distribution::kRectangular};
  double standard{0};  ///< u [m]
  std::string source;
};

struct MachiningDeviationParams {
  double axis_tilt{0.03 * kDeg};          ///< θa [rad]
  double axis_lever{8e-3};                ///< La [m]
  double runout{6e-6};                    ///< ρ at the tip [m]
  double stickout{24e-3};                 ///< L [m]
  double equivalent_diameter_ratio{0.8};  ///< κ = d_e / Dc
  double youngs_modulus{600e9};           ///< E [Pa]
  double spindle_compliance{0.29e-6};     ///< c_s [m/N]
  std::string axis_source, runout_source, stickout_source, modulus_source, spindle_source;
};

/// Per-diameter defaults (see the file comment); `carbide` false selects HSS (E = 210 GPa).
MachiningDeviationParams defaultMachiningDeviation(double diameter, bool carbide = true);

struct MachiningDeviation {
  Eigen::Vector2d delta_tool{
      Eigen::Vector2d::Zero()};                  ///< systematic δmach in the tool XY plane [m]
  std::vector<UncertaintyComponent> components;  ///< δaxis, δρ, δdeftool
  double tool_compliance{0};                     ///< L³/(3 E I_e) + c_s [m/N]
  double lateral_force{0};                       ///< Fr used for δdeftool [N]
  double u_c{0};                                 ///< combined standard uncertainty [m]
  double k{2.4477};  ///< 2-D radial 95 % coverage factor √(−2 ln 0.05)
  double U{0};       ///< expanded, k·u_c [m] (radius)
};

/// `rotating_force` = |Fr| of the drilling model at the process feed; `static_force_xy` an optional
/// steady in-plane force on the tool (tool frame) [N].
MachiningDeviation machiningDeviation(
    const MachiningDeviationParams& p, const DrillGeometry& g, double rotating_force,
    const Eigen::Vector2d& static_force_xy = Eigen::Vector2d::Zero());

}  // namespace roprec
