// Stats: named counters and phase times that every algorithm fills in, so that
// `hsr render --stats` and the tests can see what work was done (and what was not).
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace hsr {

class Stats {
 public:
  void add(const std::string& counter, std::int64_t amount = 1) { counters_[counter] += amount; }
  void addSeconds(const std::string& phase, double seconds) { seconds_[phase] += seconds; }
  // A fact in words where a number would not say enough (which cell the eye is in, which
  // objects a set holds); the last note of a name is kept.
  void note(const std::string& name, std::string text) { notes_[name] = std::move(text); }

  // 0 for a counter nobody touched: "this stage never ran" reads the same as "ran on nothing".
  std::int64_t counter(const std::string& name) const;
  // Whether a pass counted `name` at all (a counter kept only by one path, say).
  bool counted(const std::string& name) const { return counters_.count(name) != 0; }
  double seconds(const std::string& phase) const;

  std::vector<std::string> counterNames() const;
  std::vector<std::string> phaseNames() const;

  const std::string& noteOf(const std::string& name) const;  // empty where nothing was noted

  std::string report() const;  // one "name value" line each: counters, notes, then phase times

 private:
  std::map<std::string, std::int64_t> counters_;
  std::map<std::string, double> seconds_;
  std::map<std::string, std::string> notes_;
};

// Adds the wall time of its own lifetime to a phase.
class PhaseTimer {
 public:
  PhaseTimer(Stats& stats, std::string phase)
      : stats_(stats), phase_(std::move(phase)), start_(std::chrono::steady_clock::now()) {}
  ~PhaseTimer() {
    stats_.addSeconds(phase_, std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
  }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  Stats& stats_;
  std::string phase_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace hsr
