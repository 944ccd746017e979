// The characters toml++ 3.3 cannot be given (renderer/scene/toml_characters.hpp): every
// non-ASCII character in every place toml++ tests for whitespace is refused with a line
// of our own, and non-ASCII text in strings and comments still reads. Under the sanitizer
// build a character that slipped through would stop the test at toml++'s unreachable().
#include <gtest/gtest.h>

#include <string>

#include "renderer/scene/scene.hpp"
#include "renderer/scene/toml_characters.hpp"
#include "renderer/util/error.hpp"

namespace hsr {
namespace {

std::string utf8(char32_t c) {
  std::string out;
  if (c < 0x80) {
    out += char(c);
  } else if (c < 0x800) {
    out += char(0xC0 | (c >> 6));
    out += char(0x80 | (c & 0x3F));
  } else {
    out += char(0xE0 | (c >> 12));
    out += char(0x80 | ((c >> 6) & 0x3F));
    out += char(0x80 | (c & 0x3F));
  }
  return out;
}

// The message parseScene gives for a text, or "" when it reads.
std::string messageOf(const std::string& text) {
  try {
    parseScene(text, "s.toml");
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

const std::string kCamera = "[camera]\neye = [0, 0, 5]\ntarget = [0, 0, 0]\n";

// Every code point of the Basic Multilingual Plane from U+0080 to U+FFFD (surrogates
// have no UTF-8 form) in each place toml++ would test it for whitespace: after a value in
// an array (where the fuzz target found it), as a key (on the second line: first, U+FEFF
// is a byte-order mark), between a key and '=', after a value, after a quote inside a
// malformed value, right after a backslash in a multi-line string, and first on a line
// continued by a backslash.
TEST(TomlCharacters, EveryNonAsciiCharacterWhereTomlTestsForWhitespaceIsRefusedWithItsPlace) {
  const std::string outside = "not valid TOML: a non-ASCII character outside a string or comment; "
                              "TOML allows one only between quotes or after #";
  for (char32_t c = 0x80; c <= 0xFFFD; ++c) {
    if (c >= 0xD800 && c <= 0xDFFF) continue;
    const std::string ch = utf8(c);
    const std::string places[][2] = {
        {"a = [1" + ch + "]\n", "s.toml:1:7: " + outside},
        {"b = 2\n" + ch + " = 1\n", "s.toml:2:1: " + outside},
        {"a " + ch + "= 1\n", "s.toml:1:3: " + outside},
        {"a = 1" + ch + "\n", "s.toml:1:6: " + outside},
        // A quote inside a malformed value opens no string: toml++ reads on to the next
        // space or comma (the fuzz target's second and fourth finds).
        {"a = 4E\"" + ch + "\", 1\n", "s.toml:1:8: " + outside},
        {"a = [1.6, 0.3{\"" + ch + "\"]\n", "s.toml:1:16: " + outside},
        {"a = [\n  4E\"" + ch + "\"]\n", "s.toml:2:6: " + outside},
        // A date, a space and a digit: toml++ reads on as a date-time, past a quote, a
        // '#' or a comma right after the digit (found by a review).
        {"d = 1979-05-27 07\"" + ch + "\"\n", "s.toml:1:19: " + outside},
        {"d = 1979-05-27 0#" + ch + "\n", "s.toml:1:18: " + outside},
        {"d = [1979-05-27 0,\"" + ch + "\"]\n", "s.toml:1:20: " + outside},
        // The fuzz target's third find, and toml++'s issue 190.
        {"s = \"\"\"\\" + ch + "\"\"\"\n", "s.toml:1:9: not valid TOML: a backslash followed by a non-ASCII character"},
        {"s = \"\"\"\\\n  " + ch + "\"\"\"\n", "s.toml:2:3: not valid TOML: a line continued by a backslash starts with a non-ASCII"}};
    for (const auto& [text, expected] : places) {
      const std::string message = messageOf(text + kCamera);
      ASSERT_EQ(message.substr(0, expected.size()), expected) << "U+" << std::hex << unsigned(c) << ": " << message;
    }
  }
}

TEST(TomlCharacters, OnlyTheCharactersTomlTestsAreRefusedInMultiLineStrings) {
  // A non-ASCII character after the first on a continued line, after an escaped
  // backslash, or after a backslash in a multi-line literal string (which has no
  // escapes) is text toml++ does not test.
  const std::string texts[] = {"s = \"\"\"\\\n  x\xC2\xA7\"\"\"\n", "s = \"\"\"\\\\\n\xC2\xA7\"\"\"\n",
                               "s = '''\\\xC2\xA7'''\n"};
  for (const std::string& text : texts) {
    EXPECT_NO_THROW(checkTomlCharacters(text, "s.toml")) << text;
    EXPECT_EQ(messageOf(text + kCamera), "s.toml:1:1: s: unknown key; expected one of image, camera, effects, shadows, fog, outline, ambient, lights, objects, cells, portals") << text;
  }
}

// A backslash at the end of a one-line string's line escapes nothing: the string (and
// toml++) stop there, and the next line is read as keys again.
TEST(TomlCharacters, AOneLineStringEndsAtItsLineEvenAfterABackslash) {
  const std::string message = messageOf("a = \"x\\\nb = \"caf\xC3\xA9\"\n" + kCamera);
  EXPECT_EQ(message.rfind("s.toml:1:", 0), 0u) << message;
  EXPECT_EQ(message.find("non-ASCII"), std::string::npos) << message;
}

TEST(TomlCharacters, NonAsciiTextInStringsAndCommentsStillReads) {
  const std::string cafe = "caf\xC3\xA9", cjk = "\xE3\x80\x80\xE6\xBC\xA2";  // café, U+3000 U+6F22
  const std::string texts[] = {
      "# " + cafe + "\n",
      "a = \"" + cafe + "\" # " + cjk + "\n",
      "a = '" + cjk + "'\n",
      "a = \"\\\"" + cafe + "\"\n",                           // an escaped quote does not close it
      "a = \"\"\"\n" + cafe + "\n\"\" " + cjk + "\"\"\"\n",  // two quotes do not close a multi-line one
      "a = '''" + cafe + "''''\n",                            // nor do the extra quotes at its end open one
      "\"" + cafe + "\" = 1\n",
      // Dates, and a date-time written with a space, before a comment or a string.
      "d = 1979-05-27 07:32:00Z # " + cafe + "\ne = 1979-05-27 # " + cjk + "\nf = [1979-05-27, \"" + cafe + "\"]\n",
      // Strings in every place the walk tells keys from values.
      "a = [\n  \"" + cafe + "\",\n  '" + cjk + "' , # " + cafe + "\n  \"" + cjk + "\"\n]\n",
      "t = { b.\"" + cafe + "\" = 1, \"c\" = \"" + cjk + "\" }\n",
      "a = [[1, \"" + cafe + "\"], {x = \"" + cjk + "\"}]\n",
      "a.b.\"" + cafe + "\" = 1979-05-27T07:32:00Z # " + cjk + "\n",
      "[\"" + cafe + "\".x]\nk = 1\n[[\"" + cjk + "\"]]\n",
      "\xEF\xBB\xBF# a byte-order mark first, as Windows editors write\n"};
  for (const std::string& text : texts) {
    EXPECT_NO_THROW(checkTomlCharacters(text, "s.toml")) << text;
    const std::string message = messageOf(text + kCamera);
    EXPECT_EQ(message.find("non-ASCII"), std::string::npos) << text << "\n" << message;
  }
  // A whole scene with a non-ASCII comment and object name reads them as written.
  const Scene scene = parseScene(
      "# " + cafe + "\n" + kCamera + "[[objects]]\nname = \"" + cafe + "\"\nshape = \"box\" # " + cjk + "\n", "s.toml");
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].name, cafe);
}

}  // namespace
}  // namespace hsr
