/// Program conversion (plugin/api/convert.hpp).
#include "plugin/api/convert.hpp"

#include <algorithm>
#include <map>

#include "compensator/support/atomic_file.hpp"
#include "postproc/convert.hpp"

namespace roprec::api {

ConvertResult convertProgramFile(const ConvertRequest& request) {
  const postproc::Program p = readProgramWithFrames(request.program, request.frames);
  ConvertResult r;
  if (!request.to) {
    postproc::writeProgram(p, request.output);
    r.written = postproc::outputPaths(p, request.output);
    return r;
  }
  postproc::ConversionReport report;
  const auto files = postproc::convertProgram(p, postproc::dialectFromName(*request.to),
                                              request.output, report, request.all_lines);
  for (const auto& [path, bytes] : files) {
    writeFileAtomic(path, bytes);
    r.written.push_back(path);
  }
  r.notes = groupNotes(report.notes);
  r.skipped = report.skipped;
  r.not_carried = report.not_carried;
  return r;
}

std::vector<std::string> groupNotes(const std::vector<std::string>& notes) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<std::string>> who;
  for (const std::string& n : notes) {
    const std::size_t c = n.find(": ");
    const std::string key = c == std::string::npos ? n : n.substr(c + 2);
    const std::string name = c == std::string::npos ? "" : n.substr(0, c);
    if (!who.count(key)) order.push_back(key);
    who[key].push_back(name);
  }
  std::vector<std::string> out;
  for (const std::string& key : order) {
    const auto& names = who[key];
    if (names.size() == 1) {
      out.push_back((names[0].empty() ? "" : names[0] + ": ") + key);
      continue;
    }
    std::string line = key + " (" + std::to_string(names.size()) + " items: ";
    for (size_t i = 0; i < std::min<size_t>(names.size(), 3); ++i)
      line += (i ? ", " : "") + names[i];
    line += names.size() > 3 ? ", ...)" : ")";
    out.push_back(line);
  }
  return out;
}

}  // namespace roprec::api
