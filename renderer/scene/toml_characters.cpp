#include "renderer/scene/toml_characters.hpp"

#include <algorithm>

#include "renderer/util/error.hpp"

namespace hsr {
namespace {

bool isAscii(char c) { return static_cast<unsigned char>(c) < 0x80; }
bool isSpaceOrLineBreak(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

// toml++ reads a value that starts with anything but a quote or a bracket (a number, a
// date, true, or a typo) on to the next of these, testing every character for
// whitespace: in `4E"x` or `0.3{"x` the quote opens no string.
bool endsBareValue(char c) { return isSpaceOrLineBreak(c) || c == ',' || c == ']' || c == '}' || c == '#'; }

// A walk over the text with TOML's lexical states: where strings and comments start and
// end, and where a value starts and a bare value runs on; everything else is read as
// "between tokens".
class CharacterCheck {
 public:
  CharacterCheck(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  void run() {
    if (startsWith("\xEF\xBB\xBF")) at_ = 3;  // a byte-order mark, which toml++ skips (Windows editors write one)
    while (at_ < text_.size()) {
      const char c = text_[at_];
      if (inBareValue_) {
        if (!isAscii(c)) failOutside();
        if (c == ' ' && continuesAsDateTime()) {
          // toml++ reads a date, a space and a digit as one date-time (1979-05-27
          // 07:32:00): it takes the space, the digit and the character after it whatever
          // they are, and reads on to the next terminator.
          for (int k = 0; k < 3 && at_ < text_.size(); ++k) {
            if (!isAscii(text_[at_])) failOutside();
            advance();
          }
          continue;
        }
        if (endsBareValue(c)) inBareValue_ = false;  // and the character is read below
        else {
          advance();
          continue;
        }
      }
      const bool valueStarts = lastToken_ == '=' || ((lastToken_ == '[' || lastToken_ == ',') && innermost() == 'a');
      if (c == '#') {
        skipComment();
        continue;
      }
      if (c == '"' || c == '\'') {
        skipString(c);
        lastToken_ = c;
        continue;
      }
      if (!isAscii(c)) failOutside();
      if (c == '[') {
        // An array where a value starts; else a table header, whose second '[' ([[x]])
        // is the same header.
        if (valueStarts) brackets_ += 'a';
        else if (!(innermost() == 'h' && lastToken_ == '[')) brackets_ += 'h';
      } else if (c == '{') {
        brackets_ += 't';
      } else if ((c == ']' || c == '}') && !brackets_.empty()) {
        brackets_.pop_back();
      } else if (valueStarts && !isSpaceOrLineBreak(c)) {
        inBareValue_ = true;
        bareValueStart_ = at_;
      }
      // A line break ends a key-value pair, except in an array, which may span lines.
      const bool blank = c == ' ' || c == '\t' || ((c == '\n' || c == '\r') && innermost() == 'a');
      if (!blank) lastToken_ = c;
      advance();
    }
  }

 private:
  bool startsWith(std::string_view prefix) const { return text_.substr(at_).starts_with(prefix); }

  // One byte on, keeping the line and column (in characters, as toml++ counts them).
  void advance() {
    const char c = text_[at_++];
    if (c == '\n') {
      ++line_;
      column_ = 1;
    } else if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) {  // not a UTF-8 continuation byte
      ++column_;
    }
  }

  void skipComment() {
    while (at_ < text_.size() && text_[at_] != '\n') advance();
  }

  // From an opening quote past the closing one. A basic string ("...") has escapes, a
  // literal one ('...') has none; tripled quotes open a multi-line string, which may end
  // in up to two more quotes that belong to it. An unclosed string stops at the line's
  // end (a one-line string) or the text's: toml++ reports it.
  void skipString(char quote) {
    const std::string delimiter(3, quote);
    const bool multiLine = startsWith(delimiter);
    for (std::size_t k = 0; k < (multiLine ? 3u : 1u); ++k) advance();
    while (at_ < text_.size()) {
      const char c = text_[at_];
      if (!multiLine && c == '\n') return;
      if (multiLine ? startsWith(delimiter) : c == quote) {
        while (at_ < text_.size() && text_[at_] == quote) advance();
        return;
      }
      advance();
      if (c == '\\' && quote == '"' && at_ < text_.size()) {
        // In a multi-line string toml++ tests the character after a backslash for
        // whitespace (a line-ending backslash), so it must be ASCII there; no escape
        // starts with anything else.
        if (multiLine && !isAscii(text_[at_]))
          fail("a backslash followed by a non-ASCII character; TOML's escapes are \\b \\t \\n \\f \\r \\\" \\\\ "
               "\\uXXXX and \\UXXXXXXXX");
        if (multiLine && isSpaceOrLineBreak(text_[at_])) {
          skipLineContinuation();
        } else if (multiLine || text_[at_] != '\n') {
          advance();  // the escaped character, which cannot close the string
        }  // (a one-line string's backslash at the end of its line escapes nothing: toml++ stops there)
      }
    }
  }

  // A line-ending backslash: toml++ skips the whitespace and line breaks after it, testing
  // each character for whitespace, so the first one that is not must be ASCII.
  void skipLineContinuation() {
    while (at_ < text_.size() && isSpaceOrLineBreak(text_[at_])) advance();
    if (at_ < text_.size() && !isAscii(text_[at_]))
      fail("a line continued by a backslash starts with a non-ASCII character, which the TOML reader here "
           "(toml++ 3.3) cannot take; move it onto the line before the backslash, or write it as \\uXXXX");
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(file_ + ":" + std::to_string(line_) + ":" + std::to_string(column_) + ": not valid TOML: " + what);
  }

  // Whether the bare value so far has a date's shape (ten digits and dashes, dashes at 4
  // and 7) and a digit follows the space here: toml++'s test for a date-time written
  // with a space instead of a T.
  bool continuesAsDateTime() const {
    const std::string_view value = text_.substr(bareValueStart_, at_ - bareValueStart_);
    const auto isDigit = [](char c) { return c >= '0' && c <= '9'; };
    return value.size() == 10 && value[4] == '-' && value[7] == '-' &&
           std::all_of(value.begin(), value.end(), [&](char c) { return isDigit(c) || c == '-'; }) && at_ + 1 < text_.size() &&
           isDigit(text_[at_ + 1]);
  }

  [[noreturn]] void failOutside() const {
    fail("a non-ASCII character outside a string or comment; TOML allows one only between quotes or after #");
  }
  // The innermost open bracket: 'a' an array, 't' an inline table, 'h' a table header.
  char innermost() const { return brackets_.empty() ? ' ' : brackets_.back(); }

  std::string_view text_;
  const std::string& file_;
  char lastToken_ = '\n';  // the last character outside strings that was not a space or tab
  std::string brackets_;    // the brackets open, outermost first
  bool inBareValue_ = false;
  std::size_t bareValueStart_ = 0;
  std::size_t at_ = 0;
  int line_ = 1, column_ = 1;
};

}  // namespace

void checkTomlCharacters(std::string_view text, const std::string& file) { CharacterCheck(text, file).run(); }

}  // namespace hsr
