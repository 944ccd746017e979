// Running a submission's make, with a time limit: the grader waits for a program it did
// not write, so a program that hangs, crashes or floods its output must cost it nothing
// but that test.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace hsr::grading {

struct RunResult {
  bool started = false;   // false: the command could not be started (`output` says why)
  bool timedOut = false;  // killed at the time limit, with every process it started
  int exitCode = -1;      // when it exited
  int signal = 0;         // when a signal ended it (a crash: 11 is a segmentation fault)
  double seconds = 0;
  std::string output;     // the last 2,000 characters of its standard output and error
  bool succeeded() const { return started && !timedOut && signal == 0 && exitCode == 0; }
  // "exited with 2", "crashed (signal 11, segmentation fault)", "was stopped after 20 s"
  std::string outcome() const;
};

// Runs `command` in `folder`, its output to `log`, killing its whole process group
// after `seconds`.
RunResult runCommand(const std::vector<std::string>& command, const std::filesystem::path& folder, const std::filesystem::path& log,
                     double seconds);

}  // namespace hsr::grading
