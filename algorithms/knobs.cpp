#include "algorithms/knobs.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace hsr {
namespace {

std::string joined(const std::vector<std::string>& words) {
  std::string text;
  for (const auto& word : words) text += (text.empty() ? "" : ", ") + word;
  return text;
}

}  // namespace

std::pair<std::string, std::string> parseKnobSetting(const std::string& text, const std::string& where) {
  const auto equals = text.find('=');
  if (equals == std::string::npos || equals == 0) throw InputError(where + " " + text + ": expected NAME=VALUE");
  return {text.substr(0, equals), text.substr(equals + 1)};
}

bool KnobSpec::appliesTo(const std::string& variant) const {
  return variants.empty() || std::find(variants.begin(), variants.end(), variant) != variants.end();
}

std::string spellKnobNumber(double value) {
  char text[40];
  if (value == std::floor(value) && std::abs(value) < 1e6) {
    std::snprintf(text, sizeof text, "%.0f", value);
    return text;
  }
  // The fewest significant digits that read back as the same double.
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  // "1e+09" -> "1e9", "1e-06" -> "1e-6".
  std::string spelled = text;
  if (const auto e = spelled.find('e'); e != std::string::npos) {
    std::string exponent = spelled.substr(e + 1);
    const bool negative = exponent.front() == '-';
    exponent.erase(0, exponent.find_first_not_of("+-0"));
    spelled = spelled.substr(0, e + 1) + (negative ? "-" : "") + exponent;
  }
  return spelled;
}

std::string spellKnobNumber(const KnobNumber& number) { return spellKnobNumber(number.value) + (number.percent ? "%" : ""); }

const std::string& KnobValues::at(const std::string& name) const {
  const auto found = spelled_.find(name);
  HSR_CHECK(found != spelled_.end() && "a knob its owner does not have");
  return found->second;
}

namespace knob_parsing {

std::optional<KnobNumber> number(const KnobSpec::Range& range, std::string text) {
  const bool percent = range.percent && !text.empty() && text.back() == '%';
  if (percent) text.pop_back();
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
  if (value < range.minimum || value > range.maximum || (range.integer && value != std::floor(value))) return std::nullopt;
  return KnobNumber{value, percent};
}

std::string describeRange(const KnobSpec::Range& range) {
  const auto number = [](double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return std::string(text);
  };
  std::string text = std::string(range.integer ? "an integer" : "a number") + " in [" + number(range.minimum) + ", " +
                     number(range.maximum) + "]";
  if (range.percent) text += ", or a percentage P% with P in that range";
  return text;
}

void failUnknown(const std::string& owner, const std::vector<KnobSpec>& knobs, const std::string& name, const std::string& value,
                 const std::string& where) {
  std::vector<std::string> names;
  for (const KnobSpec& knob : knobs) names.push_back(knob.name);
  throw InputError(where + " " + name + "=" + value + ": " + owner + " has no knob '" + name + "'; expected one of " + joined(names));
}

void failValue(const std::string& owner, const KnobSpec& knob, const std::string& value, const std::string& where) {
  throw InputError(where + " " + knob.name + "=" + value + ": " + owner + " " + knob.name + " must be " +
                   (knob.range ? describeRange(*knob.range) : knob.file ? std::string("a file name") : "one of " + joined(knob.choices)));
}

void failVariant(const std::string& owner, const KnobSpec& knob, const std::string& value, const std::string& variant,
                 const std::string& where) {
  throw InputError(where + " " + knob.name + "=" + value + ": " + owner + " " + knob.name + " applies only to variant " +
                   joined(knob.variants) + ", not to variant " + variant);
}

}  // namespace knob_parsing

const KnobSpec* findKnob(const std::vector<KnobSpec>& knobs, const std::string& name) {
  for (const KnobSpec& knob : knobs)
    if (knob.name == name) return &knob;
  return nullptr;
}

}  // namespace hsr
