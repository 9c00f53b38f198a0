// Anchor translation unit of the postproc library (robot-program dialects); the model and the
// dialects live in program.cpp, krl.cpp, rapid.cpp, tp.cpp, table.cpp, drill.cpp, convert.cpp.
namespace roprec::postproc {
const char* libraryName() { return "roprec_postproc"; }
}  // namespace roprec::postproc
