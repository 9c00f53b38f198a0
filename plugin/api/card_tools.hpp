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

/// Warnings of a card check as notes ("robot card: ..."), for the outputs of predict/compensate;
/// throws the first error (throwFirstCardError). Does nothing for a robot without a card file.
std::vector<std::string> cardCheckOnLoad(const Robot& robot);

}  // namespace roprec::api
