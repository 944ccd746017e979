// Reading TOML (toml++) key by key, with every error naming file:line:column, the key
// path and what was expected, and every key nobody asked for rejected: the scene loader
// (renderer/scene/scene.cpp) is written with it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "renderer/util/error.hpp"
#include "renderer/util/math.hpp"

namespace hsr {

// A TOML integer's value, or nothing for any other node. (toml++'s value<int64_t>() also
// converts floats, through a cast that is undefined behaviour for 4e80: the scene fuzz
// target found it.)
inline std::optional<std::int64_t> integerOf(const toml::node& node) {
  if (const auto* integer = node.as_integer()) return integer->get();
  return std::nullopt;
}

// Reads one TOML table, remembering which keys were used, so that finish() can
// reject the keys nobody asked for. Every error names file:line:column, the key path
// and what was expected.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string path, const std::filesystem::path& file)
      : table_(table), path_(std::move(path)), file_(file) {}

  [[noreturn]] void fail(const toml::node* node, const std::string& key, const std::string& what) const {
    failAt(node ? node->source() : table_.source(), key, what);
  }

  [[noreturn]] void failAt(const toml::source_region& where, const std::string& key, const std::string& what) const {
    throw InputError(file_.string() + ":" + std::to_string(where.begin.line) + ":" +
                     std::to_string(where.begin.column) + ": " + keyPath(key) + ": " + what);
  }

  std::string keyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const std::filesystem::path& file() const { return file_; }

  const toml::node* find(const std::string& key) {
    used_.insert(key);
    return table_.get(key);
  }
  bool has(const std::string& key) const { return table_.contains(key); }

  double number(const std::string& key, std::optional<double> fallback, double min, double max) {
    const toml::node* node = find(key);
    if (!node) {
      if (!fallback) fail(nullptr, key, "missing; expected a number in " + range(min, max));
      return *fallback;
    }
    return checkedNumber(node, key, min, max);
  }

  int integer(const std::string& key, std::optional<int> fallback, int min, int max) {
    const toml::node* node = find(key);
    if (!node) {
      if (!fallback) fail(nullptr, key, "missing; expected an integer in " + range(min, max));
      return *fallback;
    }
    const auto value = integerOf(*node);
    if (!value || *value < min || *value > max)
      fail(node, key, "expected an integer in " + range(min, max) + ", got " + describe(*node));
    return static_cast<int>(*value);
  }

  bool boolean(const std::string& key, bool fallback) {
    const toml::node* node = find(key);
    if (!node) return fallback;
    if (!node->is_boolean()) fail(node, key, "expected true or false, got " + describe(*node));
    return *node->value<bool>();
  }

  std::string choice(const std::string& key, std::optional<std::string> fallback,
                     const std::vector<std::string>& allowed) {
    const toml::node* node = find(key);
    if (!node) {
      if (!fallback) fail(nullptr, key, "missing; expected one of " + join(allowed));
      return *fallback;
    }
    const auto value = node->value<std::string>();
    if (!value || std::find(allowed.begin(), allowed.end(), *value) == allowed.end())
      fail(node, key, "expected one of " + join(allowed) + ", got " + describe(*node));
    return *value;
  }

  std::string string(const std::string& key) {
    const toml::node* node = find(key);
    if (!node) fail(nullptr, key, "missing; expected a string");
    if (!node->is_string()) fail(node, key, "expected a string, got " + describe(*node));
    return *node->value<std::string>();
  }

  // Three numbers; with `allowScalar`, one number means the same on every axis.
  dvec3 vector3(const std::string& key, std::optional<dvec3> fallback, double min, double max,
                bool allowScalar = false) {
    const toml::node* node = find(key);
    const std::string expected = std::string(allowScalar ? "a number or " : "") + "an array of 3 numbers in " + range(min, max);
    if (!node) {
      if (!fallback) fail(nullptr, key, "missing; expected " + expected);
      return *fallback;
    }
    if (allowScalar && node->is_number()) return dvec3(checkedNumber(node, key, min, max));
    const toml::array* array = node->as_array();
    if (!array || array->size() != 3) fail(node, key, "expected " + expected + ", got " + describe(*node));
    dvec3 result;
    for (int axis = 0; axis < 3; ++axis) result[axis] = checkedNumber(array->get(axis), key, min, max);
    return result;
  }

  vec3 color(const std::string& key, vec3 fallback) { return vec3(vector3(key, dvec3(fallback), 0.0, 1.0)); }

  const toml::table* table(const std::string& key) {
    const toml::node* node = find(key);
    if (node && !node->is_table()) fail(node, key, "expected a table, got " + describe(*node));
    return node ? node->as_table() : nullptr;
  }

  const toml::array* array(const std::string& key) {
    const toml::node* node = find(key);
    if (node && !node->is_array()) fail(node, key, "expected an array, got " + describe(*node));
    return node ? node->as_array() : nullptr;
  }

  void finish(const std::vector<std::string>& allowed) const {
    for (const auto& [key, node] : table_) {
      const std::string name(key.str());
      if (!used_.count(name)) failUnknown(name, node, key.source(), allowed);
    }
  }

  // finish()'s check made before anything is read: a mistyped table ([[object]] for
  // [[objects]]) is reported as itself, at its line, not as the table it was meant to be
  // found missing.
  void rejectUnknown(const std::vector<std::string>& allowed) const {
    for (const auto& [key, node] : table_) {
      const std::string name(key.str());
      if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) failUnknown(name, node, key.source(), allowed);
    }
  }

  [[noreturn]] void failUnknown(const std::string& name, const toml::node& node, const toml::source_region& where,
                                const std::vector<std::string>& allowed) const {
    const bool isTable = node.is_table() || (node.is_array() && !node.as_array()->empty() && node.as_array()->get(0)->is_table());
    const std::string nearest = nearestName(name, allowed);
    failAt(where, name, std::string(isTable ? "unknown table" : "unknown key") + "; expected one of " + join(allowed) +
                            (nearest.empty() ? "" : " (did you mean " + nearest + "?)"));
  }

  // The allowed name within two edits (insertions, deletions, substitutions) of `name`,
  // the closest first; empty if none is that close.
  static std::string nearestName(const std::string& name, const std::vector<std::string>& allowed) {
    std::string nearest;
    std::size_t best = 3;
    for (const std::string& candidate : allowed) {
      std::vector<std::size_t> row(candidate.size() + 1);
      for (std::size_t j = 0; j <= candidate.size(); ++j) row[j] = j;
      for (std::size_t i = 1; i <= name.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= candidate.size(); ++j) {
          const std::size_t above = row[j];
          row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (name[i - 1] == candidate[j - 1] ? 0 : 1)});
          diagonal = above;
        }
      }
      if (row.back() < best) best = row.back(), nearest = candidate;
    }
    return nearest;
  }

  static std::string join(const std::vector<std::string>& words) {
    std::string text;
    for (const std::string& word : words) text += (text.empty() ? "" : ", ") + word;
    return text;
  }

  static std::string describe(const toml::node& node) {
    std::ostringstream text;
    if (node.is_table()) return "a table";
    if (node.is_array()) {
      text << "an array of " << node.as_array()->size();
      return text.str();
    }
    node.visit([&](const auto& value) { text << value; });
    return text.str();
  }

 private:
  static std::string range(double min, double max) {
    std::ostringstream text;
    text << "[" << min << ", " << max << "]";
    return text.str();
  }

  double checkedNumber(const toml::node* node, const std::string& key, double min, double max) const {
    const auto value = node ? node->value<double>() : std::nullopt;
    if (!node || !node->is_number() || !value || !std::isfinite(*value) || *value < min || *value > max)
      fail(node, key, "expected a finite number in " + range(min, max) + (node ? ", got " + describe(*node) : ""));
    return *value;
  }

  const toml::table& table_;
  std::string path_;
  const std::filesystem::path& file_;
  std::set<std::string> used_;
};


}  // namespace hsr
