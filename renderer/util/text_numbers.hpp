// A double read from text, correctly rounded on every target: std::from_chars where the
// standard library reads doubles with it (libstdc++), std::strtod elsewhere (libc++ 14,
// WebAssembly's, has no floating-point from_chars; musl's strtod rounds correctly, and
// there is no locale to change its decimal point).
#pragma once

#include <charconv>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>

namespace hsr {

// The number the whole token spells, or nothing.
inline std::optional<double> parseDouble(std::string_view token) {
  if (token.empty()) return std::nullopt;
  double value = 0;
#if defined(__cpp_lib_to_chars) || defined(__GLIBCXX__)
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size()) return std::nullopt;
#else
  // strtod reads what from_chars does and more (a leading '+' or spaces, hexadecimal):
  // refuse those first, so that both read the same tokens.
  if (token.front() == '+' || token.front() == ' ' || token.find_first_of("xX") != std::string_view::npos) return std::nullopt;
  const std::string text(token);
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return std::nullopt;
#endif
  return value;
}

}  // namespace hsr
