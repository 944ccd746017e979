// Stats: named counters and phase times that every algorithm fills in, so that
// `hsr render --stats` and the tests can see what work was done (and what was not).
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "renderer/util/parallel.hpp"

namespace hsr {

class Stats {
 public:
  void add(const std::string& counter, std::int64_t amount = 1) { counters_[counter] += amount; }
  void addSeconds(const std::string& phase, double seconds) { seconds_[phase] += seconds; }
  // Of a phase's time, what ran outside parallel loops, and what the phase would take on
  // ParallelTime::kAmdahlCores cores by Amdahl's law (PhaseTimer measures both).
  struct SerialTime {
    double serial = 0, onAmdahlCores = 0;  // seconds
  };
  void addSerialTime(const std::string& phase, SerialTime time) {
    SerialTime& sum = serialTimes_[phase];
    sum.serial += time.serial, sum.onAmdahlCores += time.onAmdahlCores;
  }
  // A fact in words where a number would not say enough (which cell the eye is in, which
  // objects a set holds); the last note of a name is kept.
  void note(const std::string& name, std::string text) { notes_[name] = std::move(text); }

  // 0 for a counter nobody touched: "this stage never ran" reads the same as "ran on nothing".
  std::int64_t counter(const std::string& name) const;
  // Whether a pass counted `name` at all (a counter kept only by one path, say).
  bool counted(const std::string& name) const { return counters_.count(name) != 0; }
  double seconds(const std::string& phase) const;
  SerialTime serialTime(const std::string& phase) const;  // zeros for a phase timed inside a parallel loop

  std::vector<std::string> counterNames() const;
  std::vector<std::string> phaseNames() const;

  const std::string& noteOf(const std::string& name) const;  // empty where nothing was noted

  // One "name value" line each: counters, notes, then phase times, each phase followed by
  // its serial time and a pass ("pass: NAME") also by its time on kAmdahlCores cores.
  std::string report() const;

 private:
  std::map<std::string, std::int64_t> counters_;
  std::map<std::string, double> seconds_;
  std::map<std::string, SerialTime> serialTimes_;
  std::map<std::string, std::string> notes_;
};

// Adds the wall time of its own lifetime to a phase, and of it the time outside parallel
// loops (unless the timer itself runs inside one, where all of its time is the loop's).
class PhaseTimer {
 public:
  PhaseTimer(Stats& stats, std::string phase)
      : stats_(stats), phase_(std::move(phase)), start_(std::chrono::steady_clock::now()), loopsAtStart_(ParallelTime::totals()) {}
  ~PhaseTimer() {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    stats_.addSeconds(phase_, elapsed);
    if (ParallelTime::insideLoop()) return;
    const ParallelTime::Totals loops = ParallelTime::totals();
    const double inLoops = loops.seconds - loopsAtStart_.seconds;
    const double serial = std::max(0.0, elapsed - inLoops);
    stats_.addSerialTime(phase_, {serial, serial + loops.secondsOnAmdahlCores - loopsAtStart_.secondsOnAmdahlCores});
  }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  Stats& stats_;
  std::string phase_;
  std::chrono::steady_clock::time_point start_;
  ParallelTime::Totals loopsAtStart_;
};

}  // namespace hsr
