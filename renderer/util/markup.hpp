// Text placed in XML, SVG, HTML or JSON: the characters each gives a meaning replaced,
// so that a name from a scene file ("<b>", "R&D", a quote) reads as written.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace hsr {

inline std::string escapedMarkup(const std::string& text) {
  std::string escaped;
  for (const char c : text) {
    switch (c) {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

// Text as a JSON string, quotes included: quote and backslash escaped, control
// characters as \u00XX.
inline std::string jsonString(const std::string& text) {
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      quoted += '\\';
      quoted += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\u%04x", c);
      quoted += escape;
    } else {
      quoted += c;
    }
  }
  return quoted + "\"";
}

// JSON text placed in an HTML <script> element: "</script" would end the element and
// "<!--" change how it is read, so every "<" (which JSON holds only inside strings) is
// written "\u003c", which JSON reads back as the same character.
inline std::string jsonInScript(const std::string& json) {
  std::string safe;
  for (const char c : json) safe += c == '<' ? std::string("\\u003c") : std::string(1, c);
  return safe;
}

// A number as JSON: all 17 significant digits, so that it reads back as the same double;
// null for NaN and the infinities, which JSON cannot hold.
inline std::string jsonNumber(double value) {
  if (!std::isfinite(value)) return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

}  // namespace hsr
