// The characters toml++ 3.3 (Debian's) cannot be given: where its parser asks whether
// a character is whitespace, some non-ASCII characters reach a __builtin_unreachable()
// in toml++'s unicode tables (its issues 190 and 295, fixed upstream in 2026), which is
// undefined behaviour, not an error. The scene fuzz target found it with `a = [1§]`.
// This check runs first and refuses those places with a message of our own.
#pragma once

#include <string>
#include <string_view>

namespace hsr {

// Throws InputError ("FILE:LINE:COLUMN: not valid TOML: ...") at the first non-ASCII
// character toml++ would test for whitespace: one outside strings and comments (never
// valid TOML), and in a """multi-line""" string one right after a backslash (no escape)
// or first on a line continued by a line-ending backslash. Non-ASCII characters anywhere
// else inside strings and comments pass.
void checkTomlCharacters(std::string_view text, const std::string& file);

}  // namespace hsr
