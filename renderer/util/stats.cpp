#include "renderer/util/stats.hpp"

#include <cstdio>

namespace hsr {

std::int64_t Stats::counter(const std::string& name) const {
  auto found = counters_.find(name);
  return found == counters_.end() ? 0 : found->second;
}

double Stats::seconds(const std::string& phase) const {
  auto found = seconds_.find(phase);
  return found == seconds_.end() ? 0.0 : found->second;
}

Stats::SerialTime Stats::serialTime(const std::string& phase) const {
  auto found = serialTimes_.find(phase);
  return found == serialTimes_.end() ? SerialTime{} : found->second;
}

const std::string& Stats::noteOf(const std::string& name) const {
  static const std::string kNone;
  auto found = notes_.find(name);
  return found == notes_.end() ? kNone : found->second;
}

std::vector<std::string> Stats::counterNames() const {
  std::vector<std::string> names;
  for (const auto& [name, value] : counters_) names.push_back(name);
  return names;
}

std::vector<std::string> Stats::phaseNames() const {
  std::vector<std::string> names;
  for (const auto& [name, value] : seconds_) names.push_back(name);
  return names;
}

std::string Stats::report() const {
  std::string text;
  char line[256];
  for (const auto& [name, value] : counters_) {
    std::snprintf(line, sizeof line, "%-32s %lld\n", name.c_str(), static_cast<long long>(value));
    text += line;
  }
  for (const auto& [name, value] : notes_) text += (name + std::string(name.size() < 32 ? 32 - name.size() : 0, ' ')) + " " + value + "\n";
  auto timeLine = [&](const std::string& name, double seconds) {
    std::snprintf(line, sizeof line, "%-32s %.3f ms\n", name.c_str(), seconds * 1e3);
    text += line;
  };
  for (const auto& [name, value] : seconds_) {
    timeLine(name + " time", value);
    const auto serial = serialTimes_.find(name);
    if (serial == serialTimes_.end()) continue;
    timeLine(name + " serial time", serial->second.serial);
    if (name.rfind("pass: ", 0) == 0)
      timeLine(name + " on " + std::to_string(ParallelTime::kAmdahlCores) + " cores (Amdahl) time", serial->second.onAmdahlCores);
  }
  return text;
}

}  // namespace hsr
