#pragma once
/// \file card_tools.hpp
/// `roprec card new` and `roprec card check` as plain calls (docs/cards.md): a first robot card
/// for a URDF (compensator/precision/card_scaffold.hpp) and the checks of a card against its URDF,
/// the vendor conventions and the class data (compensator/robot/card_check.hpp), with the text the
/// CLI prints.
///
/// Errors: InputError (`FILE:LINE: what`) for unreadable cards/URDFs/cells, UsageError for
/// missing or bad options. Thread safety: no shared state.

#include <optional>
#include <string>
#include <vector>

#include "compensator/precision/card_scaffold.hpp"
#include "compensator/robot/card_check.hpp"

namespace roprec::api {

struct CardNewResult {
  CardScaffold card;
  std::string summary;  ///< what was found and what the user must still confirm (stderr text)
};

/// Scaffolds the card (scaffoldCard) and writes the summary.
CardNewResult cardNew(const CardScaffoldRequest& request);

struct CardCheckResult {
  CardCheckReport report;
  std::string table;     ///< the summary table (stdout)
  std::string findings;  ///< "FILE:LINE: error|warning: message\n  hint: ...\n" lines (stderr)
  int exit_code{0};      ///< 2 when there is an error, else 0
};

/// Checks `card_path` (robot.xml); with a cell, also the cell's tool against the rated payload.
/// An empty card_path takes the cell's robot card. Throws InputError for files that do not load
/// (a card the loader refuses, e.g. without <repeatability>), UsageError when neither is given or
/// the cell names a bundled robot without a card path.
CardCheckResult cardCheck(const std::string& card_path, const std::optional<std::string>& cell);

/// `roprec card import-calibration --urdf CALIBRATED.urdf CARD.xml -o NEW.xml` (docs/cards.md
/// §5): the card's text with the <calibration> block that turns the card's URDF chain into the
/// calibrated URDF's (calibrationFromChains; the old block replaced), its urdf= re-written relative
/// to the folder of `out_path` when that differs from the card's. Throws InputError for cards and
/// URDFs that do not load or whose joints differ.
struct CardImportResult {
  std::string card_text;
  GeometryCalibration calibration;
  std::string summary;  ///< the largest offsets (stderr text)
};
CardImportResult cardImportCalibration(const std::string& card_path,
                                       const std::string& calibrated_urdf,
                                       const std::string& out_path);

/// `roprec card export-urdf CARD.xml -o real.urdf`: the card's URDF with its calibration written
/// into the joint origins (calibratedUrdf). Throws InputError at the card when it has no
/// <calibration> (its URDF already is the model).
std::string cardExportUrdf(const std::string& card_path);

/// One note for the outputs of a calibrated robot ("robot card: calibrated geometry: …"), "" for
/// a robot without <calibration>.
std::string calibrationNote(const RobotCard& card);

/// Warnings of a card check as notes ("robot card: ..."), for the outputs of predict/compensate;
/// throws the first error (throwFirstCardError). Does nothing for a robot without a card file.
std::vector<std::string> cardCheckOnLoad(const Robot& robot);

}  // namespace roprec::api
