#include "grading/run.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fstream>
#include <thread>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace hsr::grading {

std::string RunResult::outcome() const {
  if (!started) return "could not be started";
  if (timedOut) {
    char text[64];
    std::snprintf(text, sizeof text, "was stopped after %g s", seconds);
    return text;
  }
  if (signal != 0) return "crashed (signal " + std::to_string(signal) + ", " + strsignal(signal) + ")";
  return "exited with " + std::to_string(exitCode);
}

RunResult runCommand(const std::vector<std::string>& command, const std::filesystem::path& folder, const std::filesystem::path& log,
                     double seconds) {
  RunResult result;
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = fork();
  if (child < 0) {
    result.output = std::string("fork: ") + std::strerror(errno);
    return result;
  }
  if (child == 0) {
    // A process group of its own, so that a time-out kills what make started too.
    setpgid(0, 0);
    // No file of more than 512 MiB: a program that floods its output is stopped
    // (SIGXFSZ), not the grader's disk filled.
    const rlimit fileSize{rlim_t{512} << 20, rlim_t{512} << 20};
    setrlimit(RLIMIT_FSIZE, &fileSize);
    const int out = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int nothing = open("/dev/null", O_RDONLY);
    if (out < 0 || nothing < 0 || chdir(folder.c_str()) != 0) _exit(127);
    dup2(nothing, 0);
    dup2(out, 1);
    dup2(out, 2);
    std::vector<char*> arguments;
    for (const std::string& word : command) arguments.push_back(const_cast<char*>(word.c_str()));
    arguments.push_back(nullptr);
    execvp(arguments[0], arguments.data());
    std::fprintf(stderr, "%s: %s\n", arguments[0], std::strerror(errno));
    _exit(127);
  }
  setpgid(child, child);  // as the child does: whichever runs first
  result.started = true;
  int status = 0;
  while (true) {
    const pid_t done = waitpid(child, &status, WNOHANG);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (done == child) break;
    if (result.seconds > seconds) {
      kill(-child, SIGKILL);
      waitpid(child, &status, 0);
      result.timedOut = true;
      result.seconds = seconds;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(result.seconds < 1 ? 2 : 20));
  }
  kill(-child, SIGKILL);  // whatever it left running in the background
  if (!result.timedOut) {
    if (WIFEXITED(status)) result.exitCode = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  }
  // The log's last 2,000 characters, read from there: a program may have written
  // hundreds of megabytes.
  constexpr std::streamoff kTail = 2000;
  std::ifstream file(log, std::ios::binary | std::ios::ate);
  const std::streamoff size = file ? std::streamoff(file.tellg()) : 0;
  file.seekg(std::max<std::streamoff>(0, size - kTail));
  result.output.assign(std::size_t(std::min(size, kTail)), '\0');
  file.read(result.output.data(), std::streamsize(result.output.size()));
  if (size > kTail) result.output = "..." + result.output;
  // Plain text for every report: bytes that are not printable ASCII become '?'.
  for (char& c : result.output)
    if ((static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t') || static_cast<unsigned char>(c) >= 0x7F) c = '?';
  return result;
}

}  // namespace hsr::grading
