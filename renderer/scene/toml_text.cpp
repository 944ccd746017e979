#include "renderer/scene/toml_text.hpp"

#include <cstdint>
#include <map>
#include <set>
#include <string_view>
#include <utility>
#include <vector>

#include "renderer/util/error.hpp"

namespace hsr {
namespace {

// One step through UTF-8: the code point at `at` and its length in bytes, or {none, 1}
// for a byte that does not begin a well-formed sequence (overlong forms and surrogates are
// ill-formed, as toml++'s decoder also finds; it stops with its own error there).
constexpr char32_t kNotACodePoint = 0xFFFFFFFF;
std::pair<char32_t, std::size_t> decodeAt(std::string_view text, std::size_t at) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[at + i]); };
  const unsigned char lead = byte(0);
  if (lead < 0x80) return {lead, 1};
  const std::size_t length = lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 0;
  if (length == 0 || at + length > text.size()) return {kNotACodePoint, 1};
  char32_t codePoint = lead & (0x7F >> length);
  for (std::size_t i = 1; i < length; ++i) {
    if ((byte(i) & 0xC0) != 0x80) return {kNotACodePoint, 1};
    codePoint = (codePoint << 6) | (byte(i) & 0x3F);
  }
  constexpr char32_t kSmallestOfLength[] = {0, 0, 0x80, 0x800, 0x10000};
  if (codePoint < kSmallestOfLength[length] || codePoint > 0x10FFFF || (codePoint >= 0xD800 && codePoint <= 0xDFFF))
    return {kNotACodePoint, 1};
  return {codePoint, length};
}

std::string encode(char32_t codePoint) {
  if (codePoint < 0x80) return std::string(1, char(codePoint));
  if (codePoint < 0x800) return {char(0xC0 | (codePoint >> 6)), char(0x80 | (codePoint & 0x3F))};
  if (codePoint < 0x10000)
    return {char(0xE0 | (codePoint >> 12)), char(0x80 | ((codePoint >> 6) & 0x3F)), char(0x80 | (codePoint & 0x3F))};
  return {char(0xF0 | (codePoint >> 18)), char(0x80 | ((codePoint >> 12) & 0x3F)), char(0x80 | ((codePoint >> 6) & 0x3F)),
          char(0x80 | (codePoint & 0x3F))};
}

// Supplementary Private Use Area-A: no character there means anything to TOML.
constexpr char32_t kFirstStandIn = 0xF0000, kLastStandIn = 0xFFFFD;

// The text as toml++ may be shown it, and the way back.
class StandIns {
 public:
  StandIns(std::string_view text, const std::string& file) {
    std::set<char32_t> used;
    for (std::string_view part : {text, std::string_view(file)})
      for (std::size_t at = 0; at < part.size();) {
        const auto [codePoint, length] = decodeAt(part, at);
        used.insert(codePoint);
        at += length;
      }
    char32_t next = kFirstStandIn;
    for (const char32_t codePoint : used) {
      if (!tomlCannotTestForWhitespace(codePoint)) continue;
      while (used.count(next)) ++next;
      if (next > kLastStandIn)
        throw InputError(file + ": not readable: it uses so many characters of U+F0000–U+FFFFD that none is left to stand in "
                                "for its characters toml++ 3.3 cannot take; expected fewer distinct private-use characters");
      standIn_[codePoint] = next;
      original_[next] = codePoint;
      ++next;
    }
  }

  std::string shown(std::string_view text) const { return replaced(text, standIn_); }
  std::string restored(std::string_view text) const { return replaced(text, original_); }

  // Every string value and key of the parsed document, given its characters back. A key
  // is changed by inserting it anew (a std::map's keys are constant); its place is kept.
  void restore(toml::node& node) const {
    if (toml::value<std::string>* string = node.as_string()) string->get() = restored(string->get());
    if (toml::array* array = node.as_array())
      for (toml::node& element : *array) restore(element);
    toml::table* table = node.as_table();
    if (!table) return;
    std::vector<std::string> renamed;
    for (auto&& [key, value] : *table) {
      restore(value);
      if (restored(key.str()) != key.str()) renamed.emplace_back(key.str());
    }
    for (const std::string& name : renamed) {
      const auto entry = table->find(name);
      toml::key key(restored(name), entry->first.source());
      table->insert(std::move(key), std::move(entry->second));
      table->erase(name);
    }
  }

 private:
  static std::string replaced(std::string_view text, const std::map<char32_t, char32_t>& by) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t at = 0; at < text.size();) {
      const auto [codePoint, length] = decodeAt(text, at);
      const auto replacement = by.find(codePoint);
      if (replacement == by.end()) out.append(text.substr(at, length));
      else out += encode(replacement->second);
      at += length;
    }
    return out;
  }

  std::map<char32_t, char32_t> standIn_, original_;
};

// The code point at a line and column as toml++ counts them (columns in code points).
char32_t codePointAt(std::string_view text, std::size_t line, std::size_t column) {
  std::size_t atLine = 1, atColumn = 1;
  for (std::size_t at = 0; at < text.size();) {
    const auto [codePoint, length] = decodeAt(text, at);
    if (atLine == line && atColumn == column) return codePoint;
    if (codePoint == '\n') ++atLine, atColumn = 1;
    else ++atColumn;
    at += length;
  }
  return 0;
}

}  // namespace

bool tomlCannotTestForWhitespace(char32_t codePoint) {
  return (codePoint >= 0xA1 && codePoint <= 0x499) || (codePoint >= 0x2C5E && codePoint <= 0x3057 && codePoint != 0x3000) ||
         (codePoint >= 0xFB26 && codePoint <= 0xFEFE);
}

toml::table parseTomlText(const std::string& text, const std::string& file) {
  const StandIns standIns(text, file);
  try {
    toml::table root = toml::parse(standIns.shown(text), file);
    standIns.restore(root);
    return root;
  } catch (const toml::parse_error& error) {
    const toml::source_position where = error.source().begin;
    const char32_t atFault = codePointAt(text, where.line, where.column);
    const bool nonAscii = atFault >= 0x80 && atFault != kNotACodePoint;
    throw InputError(file + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) +
                     ": not valid TOML: " + standIns.restored(error.description()) +
                     (nonAscii ? " (TOML allows a non-ASCII character only between quotes or after #)" : ""));
  }
}

}  // namespace hsr
