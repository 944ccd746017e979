// A small strict JSON reader for the tests that check what hsr writes: objects,
// arrays, strings (with the escapes hsr emits), numbers, true/false/null. Throws
// std::runtime_error on anything malformed, so a parse is itself an assertion.
#pragma once

#include <cstdlib>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace hsr::test {

struct JsonValue {
  std::variant<std::nullptr_t, bool, double, std::string, std::vector<JsonValue>, std::map<std::string, JsonValue>> value;

  const std::vector<JsonValue>& array() const { return std::get<std::vector<JsonValue>>(value); }
  const std::map<std::string, JsonValue>& object() const { return std::get<std::map<std::string, JsonValue>>(value); }
  double number() const { return std::get<double>(value); }
  const std::string& string() const { return std::get<std::string>(value); }
  const JsonValue& operator[](const std::string& key) const {
    const auto found = object().find(key);
    if (found == object().end()) throw std::runtime_error("json: no key " + key);
    return found->second;
  }
};

class JsonReader {
 public:
  explicit JsonReader(const std::string& text) : text_(text) {}

  JsonValue document() {
    JsonValue value = parse();
    skipSpace();
    if (at_ != text_.size()) fail("trailing text");
    return value;
  }

 private:
  [[noreturn]] void fail(const std::string& what) { throw std::runtime_error("json: " + what + " at " + std::to_string(at_)); }
  void skipSpace() {
    while (at_ < text_.size() && std::string(" \t\r\n").find(text_[at_]) != std::string::npos) ++at_;
  }
  void expect(char c) {
    skipSpace();
    if (at_ >= text_.size() || text_[at_] != c) fail(std::string("expected '") + c + "'");
    ++at_;
  }
  bool next(char c) {
    skipSpace();
    if (at_ < text_.size() && text_[at_] == c) return ++at_, true;
    return false;
  }

  JsonValue parse() {
    skipSpace();
    if (at_ >= text_.size()) fail("unexpected end");
    const char c = text_[at_];
    if (c == '{') {
      ++at_;
      std::map<std::string, JsonValue> members;
      if (!next('}')) {
        do {
          skipSpace();
          std::string key = parseString();
          expect(':');
          members.emplace(std::move(key), parse());
        } while (next(','));
        expect('}');
      }
      return {members};
    }
    if (c == '[') {
      ++at_;
      std::vector<JsonValue> items;
      if (!next(']')) {
        do items.push_back(parse());
        while (next(','));
        expect(']');
      }
      return {items};
    }
    if (c == '"') return {parseString()};
    for (const auto& [word, value] : {std::pair{"true", JsonValue{true}}, {"false", JsonValue{false}}, {"null", JsonValue{nullptr}}})
      if (text_.compare(at_, std::string(word).size(), word) == 0) {
        at_ += std::string(word).size();
        return value;
      }
    char* end = nullptr;
    const double number = std::strtod(text_.c_str() + at_, &end);
    if (end == text_.c_str() + at_) fail("expected a value");
    at_ = std::size_t(end - text_.c_str());
    return {number};
  }

  std::string parseString() {
    if (at_ >= text_.size() || text_[at_] != '"') fail("expected a string");
    std::string result;
    for (++at_; at_ < text_.size() && text_[at_] != '"'; ++at_) {
      if (text_[at_] != '\\') {
        result += text_[at_];
        continue;
      }
      const char escaped = text_.at(++at_);
      if (escaped == 'u') {
        result += char(std::stoi(text_.substr(at_ + 1, 4), nullptr, 16));
        at_ += 4;
      } else {
        result += escaped;
      }
    }
    if (at_ >= text_.size()) fail("unterminated string");
    ++at_;
    return result;
  }

  const std::string& text_;
  std::size_t at_ = 0;
};

inline JsonValue parseJson(const std::string& text) { return JsonReader(text).document(); }

}  // namespace hsr::test
