#pragma once
/// \file inspect_output.hpp
/// What `roprec inspect` prints (plugin/api/inspect.hpp reads the program): the JSON of
/// everything and the summary for a person.
///
/// Units: mm, deg (native values as the program states them).

#include <string>

#include "plugin/api/inspect.hpp"
#include "plugin/report/json.hpp"

namespace roprec::api {

/// program, dialect, files, drilling_axis_tcp, targets[], motions[], holes[], unresolved[],
/// notes[] (docs/contract.md §11).
Json inspectJson(const InspectedProgram& r);

/// A few lines: the program, its dialect and files, how many targets, motions and drill holes,
/// each unresolved reference and note.
std::string inspectSummaryText(const InspectSummary& s);

}  // namespace roprec::api
