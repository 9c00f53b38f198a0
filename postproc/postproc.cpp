// Anchor translation unit of the postproc library (robot-program dialects).
namespace roprec::postproc {
const char* libraryName() { return "roprec_postproc"; }
}  // namespace roprec::postproc
