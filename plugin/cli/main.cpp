/// roprec — robot-process precision: predict and compensate where an industrial robot really
/// drills. This is the command dispatcher; every command lives in plugin/cmd_*.cpp.
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>
#include <sstream>
#include <streambuf>
#include <string>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/long_words.hpp"
#include "compensator/support/platform.hpp"
#include "plugin/api/job.hpp"
#include "plugin/cli/cli.hpp"

namespace {

void printHelp(std::ostream& out) {
  auto cmds = roprec::cli::commandRegistry();
  std::sort(cmds.begin(), cmds.end(), [](const auto& a, const auto& b) {
    return a.order != b.order ? a.order < b.order : a.name < b.name;
  });
  out << "roprec — predict and compensate where an industrial robot really drills and mills.\n\n"
         "usage: roprec COMMAND [options]   (roprec COMMAND --help for details)\n"
         "       roprec --version\n\n"
         "commands:\n";
  for (const auto& c : cmds) {
    out << "  " << c.name << std::string(c.name.size() < 12 ? 12 - c.name.size() : 1, ' ')
        << c.summary << "\n";
  }
  out << "\nUnits: mm and degrees in files and on the command line, SI inside, µm in reports.\n"
         "Exit codes: 0 done; 1 some items could not be handled (listed); 2 bad usage or input.\n";
}

/// The command's input files (arguments naming existing regular files), for "input too large".
std::string inputFiles(const std::vector<std::string>& tokens) {
  static const std::vector<std::string> outputs{"-o",       "--o",       "--json",
                                                "--csv",    "--report",  "--targets",
                                                "--output", "--summary", "--calibrate"};
  std::string s;
  for (size_t i = 0; i < tokens.size(); ++i) {
    const std::string& t = tokens[i];
    if (i > 0 && std::find(outputs.begin(), outputs.end(), tokens[i - 1]) != outputs.end())
      continue;  // an output file, not an input
    if (t.empty() || t[0] == '-' ||
        roprec::platform::fileStatus(t).kind != roprec::platform::Kind::kRegular)
      continue;
    s += (s.empty() ? "" : ", ") + t;
  }
  return s;
}

/// stderr a line at a time through clipLongWords: no message or note echoes a 1 MB name whole,
/// whichever command prints it. A partial line is passed on at each flush (progress lines).
class ClippedLines : public std::streambuf {
 public:
  explicit ClippedLines(std::streambuf* to) : to_(to) {}

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    line_ += traits_type::to_char_type(c);
    if (traits_type::to_char_type(c) == '\n') passOn();
    return c;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    for (std::streamsize i = 0; i < n; ++i) overflow(traits_type::to_int_type(s[i]));
    return n;
  }
  int sync() override {
    passOn();
    return to_->pubsync();
  }

 private:
  void passOn() {
    if (line_.empty()) return;
    const std::string c = roprec::clipLongWords(line_);
    to_->sputn(c.data(), static_cast<std::streamsize>(c.size()));
    line_.clear();
  }
  std::streambuf* to_;
  std::string line_;
};

using roprec::cli::writeStdout;

int stdoutFailed(int e) {
  std::cerr << "roprec: error: cannot write to standard output: " << roprec::platform::errorText(e)
            << "; nothing written\n";
  return 2;
}

/// Prints `text` on stdout and returns `rc`, or 2 when the write failed.
int printAndReturn(const std::string& text, int rc) {
  const int e = writeStdout(text);
  return e != 0 ? stdoutFailed(e) : rc;
}

}  // namespace

int main(int argc, char** argv) {
  roprec::platform::setUpStdio();
  // never destroyed: std::cerr writes through it until the process ends
  static auto* const clipped = new ClippedLines(std::cerr.rdbuf());  // NOLINT
  std::cerr.rdbuf(clipped);
  std::vector<std::string> tokens = roprec::platform::utf8Arguments(argc, argv);
  if (!tokens.empty()) tokens.erase(tokens.begin());  // the program's own name
  if (tokens.empty() || tokens[0] == "--help" || tokens[0] == "-h" || tokens[0] == "help") {
    std::ostringstream help;
    printHelp(help);
    return printAndReturn(help.str(), tokens.empty() ? 2 : 0);
  }
  if (tokens[0] == "--version") {
    return printAndReturn("roprec " + std::string(roprec::api::version()) + "\n", 0);
  }
  const std::string name = tokens[0];
  tokens.erase(tokens.begin());
  const auto& reg = roprec::cli::commandRegistry();
  const auto it =
      std::find_if(reg.begin(), reg.end(), [&](const auto& c) { return c.name == name; });
  if (it == reg.end()) {
    std::cerr << "roprec: error: unknown command '" << name << "' (roprec --help lists them)\n";
    return 2;
  }
  if (std::find(tokens.begin(), tokens.end(), "--help") != tokens.end()) {
    return printAndReturn(it->usage, 0);
  }
  roprec::cli::Args args(tokens);
  // stdout is held back until every output is staged, and written before the staged files are
  // renamed: a failed or short write to stdout (a full disk, /dev/full) is exit 2 with nothing
  // written; "wrote X" is never printed for a file that failed to stage.
  std::ostringstream out;
  roprec::cli::CommandContext ctx{out, std::cerr, false, roprec::platform::stderrIsTerminal()};
  ctx.quiet = args.flag("quiet");
  try {
    // Every file the command writes is staged and renamed only when the command succeeded:
    // all outputs or none (compensator/support/atomic_file.hpp).
    roprec::OutputSet outputs;
    const roprec::ScopedOutputSet scope(outputs);
    const int rc = it->run(args, ctx);
    if (const int e = writeStdout(out.str()); e != 0) {
      outputs.rollback();
      return stdoutFailed(e);
    }
    outputs.commit();
    for (const std::string& n : outputs.notes()) std::cerr << "roprec: note: " << n << "\n";
    return rc;
  } catch (const std::bad_alloc&) {
    const std::string files = inputFiles(tokens);
    std::cerr << "roprec: error: input too large: out of memory while running '" << name << "'"
              << (files.empty() ? std::string(" (check the numbers given on the command line)")
                                : " on " + files)
              << "; nothing written\n";
    return 2;
  } catch (const roprec::InternalError& e) {
    std::cerr << "roprec: internal error: " << e.what() << "; nothing written\n";
    return 2;
  } catch (const roprec::InputError& e) {
    std::cerr << "roprec: error: " << e.what() << "\n";
    return 2;
  } catch (const roprec::UsageError& e) {
    std::cerr << "roprec: error: " << e.what() << " (roprec " << name << " --help)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "roprec: error: " << e.what() << "\n";
    return 2;
  }
}
