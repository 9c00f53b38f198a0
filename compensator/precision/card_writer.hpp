#pragma once
/// \file card_writer.hpp
/// The re-identified robot card (`roprec verify --calibrate NEW_CARD.xml`): a byte-for-byte copy
/// of the original card (robots/README.md schema) in which each identified joint's `stiffness`
/// attribute holds the identified k_j (N·m/rad, 4 significant digits, the cards' `2.413e6` style)
/// and its `source` becomes
///
///   identified: N holes from FILE by roprec verify (σ = S N·m/rad); before: OLD SOURCE
///
/// (the old source is kept after "; before: " because it also sources the joint's other numbers
/// — servo gains, motor inertia; an old source that was itself identified keeps only its own
/// "before" part, so repeated calibrations do not nest). Everything else — comments, attribute
/// order, quoting, whitespace, line ends, other joints — is unchanged.

#include <string>
#include <vector>

#include "compensator/precision/identification.hpp"
#include "compensator/support/c_format.hpp"  // formatCardNumber, the stiffness style

namespace roprec {

struct CardStiffnessUpdate {
  int joint{0};         ///< 0..5, chain order (the card's <joint> elements in document order)
  double stiffness{0};  ///< k_j, N m/rad (> 0)
  double sigma{0};      ///< its standard uncertainty, N m/rad
};

/// The identified joints of a result (joint_identified), with k_j and σ_kj.
std::vector<CardStiffnessUpdate> cardUpdates(const IdentificationResult& r);

/// "identified: N holes from FILE by roprec verify (σ = S N·m/rad)".
std::string identifiedSource(int holes, const std::string& measured_file, double sigma);

/// Rewrites `card_text` (the original robot.xml bytes). `card_path` names the card in errors.
/// Throws InputError(card_path, line, …) when the card does not hold exactly 6 <joint> elements
/// (comments ignored), a tag is unterminated, or an update names a joint outside 0..5 or a
/// non-positive stiffness. A joint without a stiffness/source attribute gets one appended to its
/// tag.
std::string updateCardStiffness(const std::string& card_text, const std::string& card_path,
                                const std::vector<CardStiffnessUpdate>& updates, int holes,
                                const std::string& measured_file);

/// Writes the card's geometric calibration back: `card_text` with its `<calibration>` element
/// (comments skipped; from the start of its line to the end of the line of `</calibration>` or of
/// its `/>`) replaced by `block` (calibrationXml, whole lines), or `block` inserted on the line
/// before `</robot>` when the card has none. Everything else stays byte-identical. Throws
/// InputError(card_path, line, …) for an unterminated element or a card without `</robot>`.
std::string replaceCardCalibration(const std::string& card_text, const std::string& card_path,
                                   const std::string& block);

}  // namespace roprec
