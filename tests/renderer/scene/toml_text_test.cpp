// Parsing TOML past toml++ 3.3's whitespace table (renderer/scene/toml_text.hpp): every
// non-ASCII character reads as written between quotes and after #, and anywhere else
// gives toml++'s own line with the character and its place, never a stand-in. Under the
// sanitizer build a character shown to toml++'s table would stop the test at its
// __builtin_unreachable().
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/scene/scene.hpp"
#include "renderer/scene/toml_text.hpp"
#include "renderer/util/error.hpp"

namespace hsr {
namespace {

std::string utf8(char32_t c) {
  if (c < 0x80) return std::string(1, char(c));
  if (c < 0x800) return {char(0xC0 | (c >> 6)), char(0x80 | (c & 0x3F))};
  if (c < 0x10000) return {char(0xE0 | (c >> 12)), char(0x80 | ((c >> 6) & 0x3F)), char(0x80 | (c & 0x3F))};
  return {char(0xF0 | (c >> 18)), char(0x80 | ((c >> 12) & 0x3F)), char(0x80 | ((c >> 6) & 0x3F)), char(0x80 | (c & 0x3F))};
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

bool holdsAStandIn(const std::string& text) {
  for (char32_t c = 0xF0000; c <= 0xFFFFD; c += 0x40)  // every UTF-8 prefix of the area
    if (text.find(utf8(c).substr(0, 3)) != std::string::npos) return true;
  return false;
}

const std::string kCamera = "[camera]\neye = [0, 0, 5]\ntarget = [0, 0, 0]\n";

// Code points U+0080 to U+FFFD of the Basic Multilingual Plane (surrogates have no UTF-8
// form), and the ones toml++ 3.3 cannot take with the Unicode whitespace beside them.
std::vector<char32_t> basicMultilingualPlane() {
  std::vector<char32_t> all;
  for (char32_t c = 0x80; c <= 0xFFFD; ++c)
    if (c < 0xD800 || c > 0xDFFF) all.push_back(c);
  return all;
}
std::vector<char32_t> theHardOnes() {
  std::vector<char32_t> hard;
  for (char32_t c : basicMultilingualPlane())
    if (tomlCannotTestForWhitespace(c) || toml::impl::is_whitespace(c)) hard.push_back(c);
  return hard;
}
bool isHorizontalWhitespace(char32_t c) {
  return !tomlCannotTestForWhitespace(c) && toml::impl::is_non_ascii_horizontal_whitespace(c);
}

// The ranges are exactly toml++ 3.3's gap: every other code point it can test (under the
// sanitizers, one it could not would stop here), and just those it can are whitespace.
TEST(TomlText, EveryCodePointOutsideTheRangesIsOneTomlCanTestForWhitespace) {
  const std::vector<char32_t> spaces = {0xA0, 0x1680, 0x180E, 0x2000, 0x2001, 0x2002, 0x2003, 0x2004, 0x2005, 0x2006,
                                        0x2007, 0x2008, 0x2009, 0x200A, 0x200B, 0x202F, 0x205F, 0x2060, 0x3000, 0xFEFF};
  int tested = 0;
  for (char32_t c = 0x80; c <= 0x10FFFF; ++c) {
    if (tomlCannotTestForWhitespace(c)) continue;
    const bool space = std::find(spaces.begin(), spaces.end(), c) != spaces.end();
    ASSERT_EQ(toml::impl::is_non_ascii_horizontal_whitespace(c), space) << std::hex << "U+" << std::uint32_t(c);
    ++tested;
  }
  EXPECT_EQ(tested, 0x10FFFF - 0x7F - (0x499 - 0xA1 + 1) - (0x3057 - 0x2C5E) - (0xFEFE - 0xFB26 + 1));
}

// Between quotes, every character reads as written; the hard ones also first on a line a
// backslash continues (where toml++ skips whitespace) and in a quoted key.
TEST(TomlText, EveryCharacterBetweenQuotesReadsAsWritten) {
  for (char32_t c : basicMultilingualPlane()) {
    const std::string ch = utf8(c);
    const Scene scene = parseScene(kCamera + "[[objects]]\nshape = \"box\"\nname = \"a" + ch + "b\"\n", "s.toml");
    ASSERT_EQ(scene.objects.at(0).name, "a" + ch + "b") << std::hex << std::uint32_t(c);
  }
  for (char32_t c : theHardOnes()) {
    const std::string ch = utf8(c);
    const Scene continued = parseScene(kCamera + "[[objects]]\nshape = \"box\"\nname = \"\"\"\\\n" + ch + "b\"\"\"\n", "s.toml");
    ASSERT_EQ(continued.objects.at(0).name, (isHorizontalWhitespace(c) ? "" : ch) + "b") << std::hex << std::uint32_t(c);
    const std::string unknown = messageOf(kCamera + "[[objects]]\nshape = \"box\"\n\"n" + ch + "\" = 1\n");
    ASSERT_NE(unknown.find("objects[0].n" + ch + ": unknown key"), std::string::npos) << unknown;
  }
}

// Outside quotes, every character in an array (where the fuzz target found toml++'s gap)
// gives toml++'s line with its place and the character itself, not its stand-in.
TEST(TomlText, EveryCharacterInAnArrayGivesALineWithItself) {
  for (char32_t c : basicMultilingualPlane()) {
    const std::string message = messageOf(kCamera + "a = [1" + utf8(c) + "]\n");
    ASSERT_EQ(message.rfind("s.toml:4:7: not valid TOML: ", 0), 0u) << message;
    ASSERT_FALSE(holdsAStandIn(message)) << message;
  }
}

// The characters toml++ 3.3 cannot take, and the whitespace, everywhere the fuzz target
// and a review of toml++'s parser found it asks: each gives a line or reads.
TEST(TomlText, TheHardCharactersEverywhereGiveALineOrRead) {
  for (char32_t c : theHardOnes()) {
    const std::string ch = utf8(c);
    const std::vector<std::string> places = {
        ch + " = 1\n",           "a " + ch + "= 1\n",         "a = 1 " + ch + "\n",
        "a = tru" + ch + "\n",   "height = 4E\"" + ch + "\n", "s = \"\"\"\\" + ch + "\"\"\"\n",
        "t = {b = 1" + ch + "}\n", "[t" + ch + "]\n",          "d = 1979-$5-27 07\"" + ch + "\"\n",
        "d = 1979-05-27 07\"" + ch + "\"\n", "[1.6, 0.3{\"mu" + ch + "\n", "# " + ch + "\n"};
    for (const std::string& place : places) {
      const std::string message = messageOf(kCamera + place);
      ASSERT_TRUE(message.empty() || message.rfind("s.toml:", 0) == 0) << message;
      ASSERT_FALSE(holdsAStandIn(message)) << message;
    }
  }
}

TEST(TomlText, ACharacterOutsideQuotesIsNamedWithItsPlaceAndAHint) {
  EXPECT_EQ(messageOf("a = [1\xC2\xA7]\n"),
            "s.toml:1:7: not valid TOML: Error while parsing decimal integer: expected digit, saw '\xC2\xA7' "
            "(TOML allows a non-ASCII character only between quotes or after #)");
  // Columns count characters: é is two bytes, one column.
  EXPECT_EQ(messageOf("# caf\xC3\xA9\nn = \"\xC3\xA9\" x\n").rfind("s.toml:2:9: not valid TOML: ", 0), 0u);
}

// A text may already use the Private Use Area; the stand-ins are ones it does not use.
TEST(TomlText, StandInsAreCharactersTheTextDoesNotUse) {
  const std::string privateUse = utf8(0xF0000) + utf8(0xF0001), e = "\xC3\xA9";
  const Scene scene = parseScene(kCamera + "[[objects]]\nshape = \"box\"\nname = \"" + privateUse + e + "\"\n", "s.toml");
  EXPECT_EQ(scene.objects.at(0).name, privateUse + e);
  std::string all = "# ";
  for (char32_t c = 0xF0000; c <= 0xFFFFD; ++c) all += utf8(c);
  EXPECT_EQ(messageOf(all + "\n# " + e + "\n" + kCamera).rfind("s.toml: not readable: it uses so many characters of U+F0000", 0), 0u);
}

// A whole scene with non-ASCII comments, keys and names reads them as written.
TEST(TomlText, NonAsciiTextInStringsCommentsAndKeysReads) {
  const std::string cafe = "caf\xC3\xA9", cjk = "\xE3\x80\x80\xE6\xBC\xA2";  // café, U+3000 U+6F22
  const Scene scene = parseScene("\xEF\xBB\xBF# " + cafe + "\n" + kCamera + "[[objects]]\nname = '" + cafe + "'\n" +
                                     "shape = \"box\" # " + cjk + "\n[[cells]]\nname = \"" + cjk + "\"\nfrom = [-1, -1, -1]\n" +
                                     "to = [1, 1, 1]\n",
                                 "s.toml");
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].name, cafe);
  ASSERT_EQ(scene.cells.size(), 1u);
  EXPECT_EQ(scene.cells[0].name, cjk);
}

}  // namespace
}  // namespace hsr
