/// What a robot program contains (plugin/api/inspect.hpp).
#include "plugin/api/inspect.hpp"

#include <utility>

namespace roprec::api {

InspectedProgram inspectProgram(const InspectRequest& request) {
  InspectedProgram r;
  r.path = request.program;
  r.program = readProgramWithFrames(request.program, request.frames);
  const postproc::Program& p = r.program;
  postproc::RecognitionOptions ro;
  if (request.tool_axis) ro.tool_axis = *request.tool_axis;
  r.tool_axis = ro.tool_axis;
  std::vector<postproc::Hole> holes = postproc::recognizeHoles(p, ro);
  HoleListMatch& list = r.list;
  if (request.hole_list) {
    list.specs = postproc::readHoleList(*request.hole_list);
    // the hole list is drilling evidence too (a cycle with a dwell alone)
    holes = postproc::withHoleListEvidence(p, std::move(holes), list.specs,
                                           request.match_tolerance_mm, ro);
    list.matches = postproc::matchHoles(holes, p, list.specs, request.match_tolerance_mm);
  }
  r.holes = std::move(holes);
  return r;
}

InspectSummary inspectSummary(const InspectedProgram& r) {
  const postproc::Program& p = r.program;
  InspectSummary summary{r.path,
                         postproc::dialectName(p.dialect),
                         p.files.size(),
                         p.targets().size(),
                         p.motions.size(),
                         r.holes.size(),
                         {},
                         p.notes};
  for (const auto& u : p.unresolved) {
    const std::string file = u.file >= 0 ? p.files[static_cast<std::size_t>(u.file)].path : r.path;
    summary.unresolved.push_back(file + ":" + std::to_string(u.line) + ": " + u.ref + ": " +
                                 u.what);
  }
  return summary;
}

}  // namespace roprec::api
