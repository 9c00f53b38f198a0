#include "tests/support/process.hpp"

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#ifdef _WIN32
#ifndef NOMINMAX
#define NOMINMAX
#endif
#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#include <windows.h>
#else
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
extern char** environ;  // NOLINT: POSIX
#endif

#include "compensator/support/platform.hpp"

namespace fs = std::filesystem;

namespace roprec::test {

namespace {

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Two fresh file names for stdout and stderr in the temporary folder.
std::pair<fs::path, fs::path> captureFiles() {
  static std::atomic<unsigned> n{0};
  const std::string stem =
      "roprec-run-" + std::to_string(platform::processId()) + "-" + std::to_string(n.fetch_add(1));
  const fs::path dir = fs::temp_directory_path();
  return {dir / (stem + ".out"), dir / (stem + ".err")};
}

/// The environment of this process with `extra` ("NAME=VALUE") added or replacing; a bare
/// "NAME" in `extra` removes NAME.
std::vector<std::string> mergedEnvironment(const std::vector<std::string>& extra,
                                           const std::vector<std::string>& own) {
  std::vector<std::string> env;
  const auto name = [](const std::string& kv) { return kv.substr(0, kv.find('=')); };
  for (const std::string& kv : own) {
    bool replaced = false;
    for (const std::string& e : extra) replaced = replaced || name(e) == name(kv);
    if (!replaced) env.push_back(kv);
  }
  for (const std::string& e : extra)
    if (e.find('=') != std::string::npos) env.push_back(e);
  return env;
}

#ifdef _WIN32
std::wstring wide(const std::string& s) { return platform::fromUtf8(s).native(); }

/// One argument quoted for CommandLineToArgvW / the C runtime's parser.
std::wstring quoteArgument(const std::wstring& a) {
  if (!a.empty() && a.find_first_of(L" \t\n\v\"") == std::wstring::npos) return a;
  std::wstring q = L"\"";
  for (std::size_t i = 0;; ++i) {
    std::size_t slashes = 0;
    while (i < a.size() && a[i] == L'\\') {
      ++i;
      ++slashes;
    }
    if (i == a.size()) {
      q.append(slashes * 2, L'\\');
      break;
    }
    if (a[i] == L'"') {
      q.append(slashes * 2 + 1, L'\\');
    } else {
      q.append(slashes, L'\\');
    }
    q.push_back(a[i]);
  }
  q.push_back(L'"');
  return q;
}

HANDLE inheritable(const std::wstring& path, bool write) {
  SECURITY_ATTRIBUTES sa{sizeof(SECURITY_ATTRIBUTES), nullptr, TRUE};
  return ::CreateFileW(path.c_str(), write ? GENERIC_WRITE : GENERIC_READ,
                       FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE, &sa,
                       write ? CREATE_ALWAYS : OPEN_EXISTING, FILE_ATTRIBUTE_NORMAL, nullptr);
}

std::vector<std::string> ownEnvironment() {
  std::vector<std::string> env;
  wchar_t* block = ::GetEnvironmentStringsW();
  for (const wchar_t* p = block; p != nullptr && *p != L'\0'; p += std::wcslen(p) + 1) {
    if (*p != L'=') env.push_back(platform::toUtf8(fs::path(std::wstring(p))));
  }
  ::FreeEnvironmentStringsW(block);
  return env;
}

int spawnAndWait(const std::vector<std::string>& argv, const std::vector<std::string>& env,
                 const fs::path& out, const fs::path& err) {
  std::wstring cmd;
  for (const std::string& a : argv) cmd += (cmd.empty() ? L"" : L" ") + quoteArgument(wide(a));
  std::wstring block;
  for (const std::string& kv : env) block += wide(kv) + L'\0';
  block += L'\0';
  STARTUPINFOW si{};
  si.cb = sizeof si;
  si.dwFlags = STARTF_USESTDHANDLES;
  si.hStdInput = inheritable(L"NUL", false);
  si.hStdOutput = inheritable(out.native(), true);
  si.hStdError = inheritable(err.native(), true);
  PROCESS_INFORMATION pi{};
  const std::wstring app = wide(argv.at(0));
  const BOOL ok = ::CreateProcessW(app.c_str(), cmd.data(), nullptr, nullptr, TRUE,
                                   CREATE_UNICODE_ENVIRONMENT, block.data(), nullptr, &si, &pi);
  ::CloseHandle(si.hStdInput);
  ::CloseHandle(si.hStdOutput);
  ::CloseHandle(si.hStdError);
  if (!ok) throw std::runtime_error("cannot start " + argv.at(0));
  ::WaitForSingleObject(pi.hProcess, INFINITE);
  DWORD code = 0;
  ::GetExitCodeProcess(pi.hProcess, &code);
  ::CloseHandle(pi.hThread);
  ::CloseHandle(pi.hProcess);
  return static_cast<int>(code);
}
#else
std::vector<std::string> ownEnvironment() {
  std::vector<std::string> env;
  for (char** e = environ; *e != nullptr; ++e) env.emplace_back(*e);
  return env;
}

int spawnAndWait(const std::vector<std::string>& argv, const std::vector<std::string>& env,
                 const fs::path& out, const fs::path& err) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));  // NOLINT
  args.push_back(nullptr);
  std::vector<char*> envp;
  for (const std::string& kv : env) envp.push_back(const_cast<char*>(kv.c_str()));  // NOLINT
  envp.push_back(nullptr);
  pid_t pid = 0;
  const int rc = ::posix_spawn(&pid, argv.at(0).c_str(), &fa, nullptr, args.data(), envp.data());
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) throw std::runtime_error("cannot start " + argv.at(0) + ": " + std::strerror(rc));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 128;
}
#endif

}  // namespace

std::vector<std::string> shellWords(std::string_view line) {
  std::vector<std::string> words;
  std::string w;
  bool in_word = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == ' ' || c == '\t' || c == '\n') {
      if (in_word) words.push_back(std::move(w));
      w.clear();
      in_word = false;
    } else if (c == '\'') {
      const std::size_t end = line.find('\'', i + 1);
      if (end == std::string_view::npos) throw std::invalid_argument("unclosed ' in a command");
      w.append(line.substr(i + 1, end - i - 1));
      i = end;
      in_word = true;
    } else if (c == '"') {
      for (++i; i < line.size() && line[i] != '"'; ++i) {
        if (line[i] == '\\' && i + 1 < line.size() &&
            std::string_view("\"\\$`").find(line[i + 1]) != std::string_view::npos) {
          ++i;
        }
        w.push_back(line[i]);
      }
      if (i >= line.size()) throw std::invalid_argument("unclosed \" in a command");
      in_word = true;
    } else if (c == '\\' && i + 1 < line.size()) {
      w.push_back(line[++i]);
      in_word = true;
    } else {
      w.push_back(c);
      in_word = true;
    }
  }
  if (in_word) words.push_back(std::move(w));
  return words;
}

bool isShellOperator(const std::string& word) {
  static const char* const ops[] = {"|", "||", "&&", ";", "&", ">", ">>", "<", "2>", "2>&1", ">&2"};
  for (const char* op : ops) {
    if (word == op) return true;
  }
  return false;
}

ProcessResult runProcess(const std::vector<std::string>& argv,
                         const std::vector<std::string>& env) {
  const auto [out, err] = captureFiles();
  ProcessResult r;
  r.exit_code = spawnAndWait(argv, mergedEnvironment(env, ownEnvironment()), out, err);
  r.out = readAll(out);
  r.err = readAll(err);
  std::error_code ec;
  fs::remove(out, ec);
  fs::remove(err, ec);
  return r;
}

}  // namespace roprec::test
