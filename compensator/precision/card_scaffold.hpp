#pragma once
/// \file card_scaffold.hpp
/// A first robot card for a URDF (`roprec card new`, docs/cards.md): finds the serial 6R chain,
/// the base and flange links and the vendor's joint convention, and fills every number a URDF
/// lacks from the published class data, each with its `source` (`estimate:` where it is one).
///
/// Links (vendor conventions: compensator/robot/card_check.hpp):
///   flange_link = the first of `tool0`, `flange` whose z points out of the flange (ROS-Industrial
///                 `tool0` is z-out; their KUKA/FANUC `flange` is x-out and is skipped);
///   base_link   = the URDF root; FANUC: `base` when it lies on the J1 axis at J2 height (World).
/// Joint convention: controller_sign_i = sign(a_i · axis_i) (a_i URDF axis at q = 0, axis_i the
///   vendor's), offsets 0, FANUC j23_coupling = −sign_2; a URDF axis not along the vendor's
///   throws InputError at the URDF joint.
/// Numbers:
///   stiffness      stiffnessClass(P) (KR500 set, × P/120 kg below 120 kg), estimate;
///   position_gain  40 1/s, estimate;  repeatability  0.08 mm, estimate (class upper end);
///   inertials      the URDF's unless missing or placeholders (placeholderInertials), else a
///                  class estimate: robot mass M = 34 kg · (P/kg)^0.7 (fit to the data-sheet masses
///                  of 16–185 kg arms; or the given mass), moving bodies 30/18/22/5/2.5/0.5 % of M,
///                  each a solid cylinder along its link segment (joint origin → next joint
///                  origin, at least 0.2 m long, radius a quarter of that length), COM at its
///                  middle.
/// Rated payload P: the given value, else read from the URDF robot name (KUKA `kr<P>`, ABB
/// `irb<type>_<P>_<reach>`, FANUC `<series>ic<P>f` / `m<P>i`); none: UsageError.

#include <optional>
#include <string>
#include <vector>

#include "compensator/robot/robot_card.hpp"

namespace roprec {

struct CardScaffoldRequest {
  std::string urdf;                  ///< URDF path
  std::string card_path;             ///< where the card will be written (for the relative urdf=)
  std::optional<Vendor> vendor;      ///< absent: from the URDF robot name
  std::string model;                 ///< absent: the URDF robot name
  std::optional<double> payload_kg;  ///< rated payload, kg
  std::optional<double> mass_kg;     ///< total robot mass from the data sheet, kg
};

struct CardScaffold {
  std::string xml;                   ///< the card
  std::vector<std::string> confirm;  ///< what the user must still confirm, one item each
  std::string base_link, flange_link;
  Vendor vendor{Vendor::kGeneric};
  double payload_kg{0.0};
};

/// Throws UsageError when the vendor or payload cannot be found (give --vendor / --payload-kg),
/// InputError(URDF, line, …) when the URDF has no 6R chain, no z-out flange frame or a joint axis
/// off the vendor convention.
CardScaffold scaffoldCard(const CardScaffoldRequest& request);

/// The class estimate of the total robot mass, kg: 34 · P^0.7 (P in kg).
double classRobotMassKg(double payload_kg);

}  // namespace roprec
