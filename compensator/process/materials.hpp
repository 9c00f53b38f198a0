#pragma once
/// \file materials.hpp
/// Workpiece materials for the process models: Kienzle constants (milling, and the reference
/// of the drilling law) and the drilling coefficients of docs/process.md §2.1/§2.3, each number
/// with its source (or `estimate: why`).
///
/// Drilling law (docs/process.md §2.1, Ferreras-Higuero et al. form [P]):
///   kst = kst0 (at + bt γn + ct λs) (h / 1 mm)^−m,   ksa = ksa0 (aa + ba γn + ca λs) (h / 1 mm)^−m
/// with γn, λs in rad here (files and docs/process.md §2.3 give bt, ct, ba, ca per degree).
/// Milling (§4.1): Ft = kc1.1 ap (h / 1 mm)^(1−mc) · 1 mm, Fr = cr Ft, Fa = ca Ft.
/// Units: pressures in Pa (N/m²), i.e. N/mm² × 1e6.

#include <string>
#include <vector>

namespace roprec {

/// k = k0 (a + b γn + c λs) (h/h_ref)^−m, h clamped at h_min; the geometry factor is clamped at 0.
struct SpecificPressure {
  double k0{800e6};    ///< Pa at h = 1 mm, zero rake
  double a{1.0};       ///< constant term [-]
  double b{0.0};       ///< rake coefficient [1/rad]
  double c{0.0};       ///< inclination coefficient [1/rad]
  double m{0.25};      ///< size-effect exponent [-]
  double h_min{5e-6};  ///< chip-thickness floor (≈ edge radius) [m]
};

/// Chisel-edge thrust (docs/process.md §1.5).
///   kRatio:    F_ch = thrust_ratio · Fa_lips(engaged), M_ch = torque_ratio · M_lips
///              (the §2.3 default 1.2 gives a 55 % chisel share of the thrust).
///   kPressure: F_ch = pressure_ratio · ksa0 · a · f  (simple engineering form p_ch a f with
///              p_ch = pressure_ratio · ksa0; §1.5 suggests p_ch ≈ 4–6 kc1.1), M_ch = torque_ratio
///              · M_lips.
enum class ChiselModelKind { kRatio, kPressure };
struct ChiselModel {
  ChiselModelKind kind{ChiselModelKind::kRatio};
  double thrust_ratio{1.2};
  double pressure_ratio{5.0};
  double torque_ratio{0.0};
};

struct DrillingCoefficients {
  SpecificPressure tangential;  ///< kst
  SpecificPressure axial;       ///< ksa
  ChiselModel chisel;
};

struct MillingCoefficients {
  double kc11{800e6};         ///< Kienzle kc1.1 [Pa] at h = 1 mm
  double mc{0.25};            ///< Kienzle exponent
  double radial_ratio{0.35};  ///< Fr / Ft
  double axial_ratio{0.2};    ///< Fa / Ft
  double h_min{2e-6};         ///< chips thinner than this are not cut [m]
};

struct Material {
  std::string name;                  ///< canonical name, e.g. "Al 6061-T6"
  std::vector<std::string> aliases;  ///< matched case-insensitively, ignoring spaces, '-' and '_'
  std::string group;                 ///< ISCAR / VDI 3323 group
  double kc11{0};                    ///< [Pa]
  double mc{0};
  double hardness_HB{0};
  DrillingCoefficients drilling;
  MillingCoefficients milling;
  std::string kienzle_source;
  std::string drilling_source;
  std::string chisel_source;
  std::string milling_ratio_source;
};

/// The built-in materials (Al 6061-T6, Al 7075-T6, AlSi7Mg (A356), AlSi9Cu3, ...).
const std::vector<Material>& materialTable();
/// Finds a material by name or alias; nullptr when unknown.
const Material* findMaterial(const std::string& name);
/// Comma-separated canonical names (for error messages).
std::string materialNames();

}  // namespace roprec
