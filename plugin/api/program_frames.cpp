/// A program read with caller-given frames (plugin/api/program_frames.hpp).
#include "plugin/api/program_frames.hpp"

namespace roprec::api {

postproc::Program readProgramWithFrames(const std::string& path,
                                        const std::vector<FrameDefinition>& frames) {
  postproc::Program p = postproc::readProgram(path);
  for (const FrameDefinition& f : frames) postproc::resolveFrame(p, f.ref, f.pose);
  return p;
}

}  // namespace roprec::api
