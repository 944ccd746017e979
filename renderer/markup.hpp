// Text placed in XML, SVG or HTML: the characters markup gives a meaning replaced by
// their entities, so that a name from a scene file ("<b>", "R&D") reads as written.
#pragma once

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

}  // namespace hsr
