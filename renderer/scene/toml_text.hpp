// Parsing TOML text with toml++ 3.3 (Debian's), which must not be shown some non-ASCII
// characters. Wherever its parser asks whether a character is whitespace, the characters
// U+00A1–U+0499, U+2C5E–U+3057 (but U+3000) and U+FB26–U+FEFE reach a
// __builtin_unreachable() in its Unicode table (toml++'s issues 190 and 295, fixed
// upstream in 2026): undefined behaviour, not an error. The scene fuzz target found it with `a = [1§]`, and `é` is one
// of them, so a student's `name = "café"` must still read.
//
// toml++ is therefore shown a copy of the text in which each such character is replaced
// by a stand-in from the Private Use Area (U+F0000 on, one the text does not use), and
// the parsed strings, keys and error messages get the original characters back. Nothing
// has to know where toml++ tests for whitespace, and positions agree: toml++ counts
// columns in characters, not bytes.
#pragma once

#include <string>

#include <toml++/toml.h>

namespace hsr {

// Whether toml++ 3.3's whitespace test cannot take the code point (the ranges above).
bool tomlCannotTestForWhitespace(char32_t codePoint);

// The parsed text, or InputError "FILE:LINE:COLUMN: not valid TOML: WHAT" with toml++'s
// WHAT, and a hint when the character at fault is a non-ASCII one outside quotes.
toml::table parseTomlText(const std::string& text, const std::string& file);

}  // namespace hsr
