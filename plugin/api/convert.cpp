/// Program conversion (plugin/api/convert.hpp).
#include "plugin/api/convert.hpp"

#include <functional>

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
  NoteGroups notes;
  report.on_note = [&notes](const std::string& n) { notes.add(n); };
  postproc::convertProgram(
      p, postproc::dialectFromName(*request.to), request.output, report, request.all_lines,
      [&r](const std::string& path, const std::function<void(const ByteWriter&)>& produce) {
        writeFileAtomicStream(path, produce);
        r.written.push_back(path);
      });
  r.notes = notes.lines();
  r.skipped = report.skipped;
  r.not_carried = report.not_carried;
  return r;
}

void NoteGroups::add(const std::string& note) {
  const std::size_t c = note.find(": ");
  std::string key = c == std::string::npos ? note : note.substr(c + 2);
  auto it = groups_.find(key);
  if (it == groups_.end()) {
    order_.push_back(key);
    it = groups_.emplace(std::move(key), Group{}).first;
  }
  Group& g = it->second;
  if (g.names.size() < 3) g.names.push_back(c == std::string::npos ? "" : note.substr(0, c));
  ++g.count;
}

std::vector<std::string> NoteGroups::lines() const {
  std::vector<std::string> out;
  for (const std::string& key : order_) {
    const Group& g = groups_.at(key);
    if (g.count == 1) {
      out.push_back((g.names[0].empty() ? "" : g.names[0] + ": ") + key);
      continue;
    }
    std::string line = key + " (" + std::to_string(g.count) + " items: ";
    for (std::size_t i = 0; i < g.names.size(); ++i) line += (i ? ", " : "") + g.names[i];
    line += g.count > 3 ? ", ...)" : ")";
    out.push_back(line);
  }
  return out;
}

std::vector<std::string> groupNotes(const std::vector<std::string>& notes) {
  NoteGroups g;
  for (const std::string& n : notes) g.add(n);
  return g.lines();
}

}  // namespace roprec::api
