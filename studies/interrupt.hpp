// Ctrl-C during a long measurement (hsr sweep, hsr study): the first SIGINT asks the
// loop to stop after the row it is measuring, so that the rows already measured are
// written, complete, as if the run had been planned that short; a second SIGINT ends
// the process at once (and, as any kill, leaves no output file: OutputFiles writes
// under temporary names and renames only at the end).
#pragma once

#include <cstddef>

namespace hsr::studies {

// While one lives, SIGINT is caught as above; the previous handler comes back after.
class InterruptibleRun {
 public:
  InterruptibleRun();
  ~InterruptibleRun();
  InterruptibleRun(const InterruptibleRun&) = delete;
  InterruptibleRun& operator=(const InterruptibleRun&) = delete;

  // Has Ctrl-C been pressed since the run began?
  static bool requested();
};

// The exit status of a run cut short by Ctrl-C (128 + SIGINT, as a shell reports it).
inline constexpr int kInterruptedExit = 130;

// One line on stderr saying what was kept: "hsr: interrupted: 3 of 12 rows measured and written".
void reportInterrupted(std::size_t measured, std::size_t planned, const char* what);

}  // namespace hsr::studies
