// Knobs: the settings of an algorithm or a culling stage that trade accuracy against
// time. Each is declared once, in a table beside the Knobs struct it sets (in the
// algorithm's own folder): its name, what it does, the values it takes, and the member
// it writes. The table
//   - turns a user's NAME=VALUE settings into that struct, checking each value once (an
//     error names the owner, the knob and what is allowed);
//   - spells a struct's values back, for tables, file names and `hsr list`;
//   - lists the knobs, with values worth sweeping, for `hsr list` and `hsr sweep`.
// A knob's default is the value the struct's member initializer gives it: written once.
//
//   struct Knobs { Variant variant = Variant::full; double budget = 1e9; };
//   const KnobTable<Knobs> table = KnobTable<Knobs>()
//       .choice("variant", &Knobs::variant, {{Variant::full, "full"}, {Variant::scanline, "scanline"}}, "help")
//       .number("budget", &Knobs::budget, {1, 1e15}, {"1e10"}, "help").onlyFor({"naive"});
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <typeindex>
#include <utility>
#include <vector>

#include "renderer/util/error.hpp"

namespace hsr {

// NAME=VALUE settings as the user gave them, in order.
using KnobSettings = std::vector<std::pair<std::string, std::string>>;

// "NAME=VALUE" split at the first '='; throws InputError naming `where` otherwise.
std::pair<std::string, std::string> parseKnobSetting(const std::string& text, const std::string& where);

// A number a knob may take as a percentage ("0.5%") of some scene size its help names.
struct KnobNumber {
  double value;
  bool percent = false;
  bool operator==(const KnobNumber&) const = default;
};

// One knob as `hsr list` prints it and `hsr sweep` enumerates it.
struct KnobSpec {
  std::string name, help;
  std::string defaultValue = {};  // spelled
  // A choice knob: every allowed value, in order. A numeric knob: the default, then
  // values worth sweeping.
  std::vector<std::string> choices = {};
  std::vector<std::string> choiceHelp = {};  // a line of help per choice, where the table gives one
  struct Range {
    double minimum, maximum;
    bool integer = false;
    bool percent = false;  // also "P%": a percentage of some scene size the help names
  };
  std::optional<Range> range = std::nullopt;  // set for a numeric knob
  std::vector<std::string> variants = {};     // the values of the owner's "variant" knob it applies to; empty: all
  // A choice that may also be given bare, as a value right after the variant
  // (occlusion:queries:chc for occlusion:queries:strategy=chc).
  bool bare = false;
  // A file name, any text but "none" (the default, meaning no file); no choices, no range.
  bool file = false;

  bool appliesTo(const std::string& variant) const;
};

// A number as knobs spell it: integers up to six digits as written ("100000"), others in
// the shortest form that reads back exactly ("1e9", "0.25", "1e-6"); "%" appended to a
// percentage.
std::string spellKnobNumber(double value);
std::string spellKnobNumber(const KnobNumber& number);

// One owner's knobs, checked and typed: its Knobs struct inside, and every knob's value
// spelled. Made by KnobTable::resolve.
class KnobValues {
 public:
  KnobValues() = default;
  template <typename Knobs>
  KnobValues(Knobs typed, std::map<std::string, std::string> spelled, std::string described)
      : typed_(std::make_shared<const Knobs>(std::move(typed))), type_(typeid(Knobs)), spelled_(std::move(spelled)),
        described_(std::move(described)) {}

  // The owner's Knobs struct; only its own table made it.
  template <typename Knobs>
  const Knobs& as() const {
    HSR_CHECK(typed_ && type_ == std::type_index(typeid(Knobs)));
    return *static_cast<const Knobs*>(typed_.get());
  }
  // A knob's value, spelled as `hsr list` would (InputError-free: the name must exist).
  const std::string& at(const std::string& name) const;
  // "name=value name=value" for the knobs that differ from their defaults, or "defaults".
  const std::string& described() const { return described_; }

  bool operator==(const KnobValues& other) const { return type_ == other.type_ && spelled_ == other.spelled_; }

 private:
  std::shared_ptr<const void> typed_;
  std::type_index type_ = std::type_index(typeid(void));
  std::map<std::string, std::string> spelled_;
  std::string described_;
};

// The checks every table shares, by knob description: a value read against a spec.
namespace knob_parsing {
// The number a value spells ("12", "0.25", "1e9", and "0.5%" when allowed), or nothing
// when it spells none or lies outside the range.
std::optional<KnobNumber> number(const KnobSpec::Range& range, std::string text);
// "an integer in [1, 256], or a percentage P% with P in that range", for messages.
std::string describeRange(const KnobSpec::Range& range);
// The messages of KnobTable::resolve, one line each.
[[noreturn]] void failUnknown(const std::string& owner, const std::vector<KnobSpec>& knobs, const std::string& name,
                              const std::string& value, const std::string& where);
[[noreturn]] void failValue(const std::string& owner, const KnobSpec& knob, const std::string& value, const std::string& where);
[[noreturn]] void failVariant(const std::string& owner, const KnobSpec& knob, const std::string& value, const std::string& variant,
                              const std::string& where);
}  // namespace knob_parsing

template <typename Knobs>
class KnobTable {
 public:
  // A choice among named values (an enum): `names` spells each value, in the order hsr
  // list shows them.
  template <typename Value>
  KnobTable& choice(std::string name, Value Knobs::*member, std::vector<std::pair<Value, std::string>> names, std::string help) {
    KnobSpec spec{.name = std::move(name), .help = std::move(help)};
    for (const auto& [value, spelled] : names) spec.choices.push_back(spelled);
    const auto spell = [member, names](const Knobs& knobs) {
      for (const auto& [value, spelled] : names)
        if (value == knobs.*member) return spelled;
      HSR_CHECK(false && "a value without a name in its knob table");
      return std::string();
    };
    const auto set = [member, names](Knobs& knobs, const std::string& text) {
      for (const auto& [value, spelled] : names)
        if (spelled == text) return knobs.*member = value, true;
      return false;
    };
    return add(std::move(spec), spell, set);
  }

  // The "variant" knob with a line of help for each variant (culling stages: hsr list
  // prints a line per variant).
  template <typename Value>
  struct Variant {
    Value value;
    std::string name, help;
  };
  template <typename Value>
  KnobTable& variants(Value Knobs::*member, std::vector<Variant<Value>> variants, std::string help) {
    std::vector<std::pair<Value, std::string>> names;
    for (const Variant<Value>& variant : variants) names.emplace_back(variant.value, variant.name);
    choice("variant", member, names, std::move(help));
    for (const Variant<Value>& variant : variants) knobs_.back().spec.choiceHelp.push_back(variant.help);
    return *this;
  }

  // A switch spelled on or off.
  KnobTable& onOff(std::string name, bool Knobs::*member, std::string help) {
    return choice(std::move(name), member, {{true, "on"}, {false, "off"}}, std::move(help));
  }

  // A number in a range (an integer when the member is, or when the range says so; also a
  // percentage when the member is a KnobNumber and the range allows it). `sweep`: values
  // worth sweeping besides the default.
  template <typename Number>
  KnobTable& number(std::string name, Number Knobs::*member, KnobSpec::Range range, std::vector<std::string> sweep, std::string help) {
    range.integer = range.integer || std::is_integral_v<Number>;
    KnobSpec spec{.name = std::move(name), .help = std::move(help)};
    spec.choices = std::move(sweep);
    spec.range = range;
    const auto spell = [member](const Knobs& knobs) {
      if constexpr (std::is_same_v<Number, KnobNumber>) return spellKnobNumber(knobs.*member);
      else return spellKnobNumber(static_cast<double>(knobs.*member));
    };
    const auto set = [member, range](Knobs& knobs, const std::string& text) {
      const std::optional<KnobNumber> parsed = knob_parsing::number(range, text);
      if (!parsed) return false;
      if constexpr (std::is_same_v<Number, KnobNumber>) knobs.*member = *parsed;
      else knobs.*member = static_cast<Number>(parsed->value);
      return true;
    };
    return add(std::move(spec), spell, set);
  }

  // A file the owner reads (a cache, say): any text; "none", the default, is no file.
  KnobTable& file(std::string name, std::string Knobs::*member, std::string help) {
    KnobSpec spec{.name = std::move(name), .help = std::move(help)};
    spec.file = true;
    const auto spell = [member](const Knobs& knobs) { return (knobs.*member).empty() ? std::string("none") : knobs.*member; };
    const auto set = [member](Knobs& knobs, const std::string& text) {
      if (text.empty()) return false;
      knobs.*member = text == "none" ? std::string() : text;
      return true;
    };
    return add(std::move(spec), spell, set);
  }

  // The knob declared last applies only to these values of the "variant" knob: given
  // with another variant, it is an error rather than something silently ignored.
  KnobTable& onlyFor(std::vector<std::string> variants) {
    knobs_.back().spec.variants = std::move(variants);
    return *this;
  }

  // The knob declared last (a choice) may also be given as a bare value right after the
  // variant it applies to.
  KnobTable& bare() {
    knobs_.back().spec.bare = true;
    return *this;
  }

  // Every knob, its default spelled from Knobs{}.
  std::vector<KnobSpec> specs() const {
    std::vector<KnobSpec> specs;
    for (const Knob& knob : knobs_) specs.push_back(knob.spec);
    return specs;
  }

  // The struct with the settings applied to the defaults. Throws InputError for an
  // unknown knob, a value outside its choices or range, or a knob of another variant,
  // naming `where` (the option that gave it), the owner and what is allowed.
  KnobValues resolve(const std::string& owner, const KnobSettings& settings, const std::string& where) const {
    const std::vector<KnobSpec> all = specs();
    Knobs knobs;
    for (const auto& [name, value] : settings) {
      const Knob* knob = find(name);
      if (!knob) knob_parsing::failUnknown(owner, all, name, value, where);
      if (!knob->set(knobs, value)) knob_parsing::failValue(owner, knob->spec, value, where);
    }
    // A knob of one variant given with another is a mistake, not something to ignore.
    for (const auto& [name, value] : settings) {
      const Knob* knob = find(name);
      if (const Knob* variant = find("variant"); variant && !knob->spec.appliesTo(variant->spell(knobs)))
        knob_parsing::failVariant(owner, knob->spec, value, variant->spell(knobs), where);
    }
    return valuesOf(std::move(knobs));
  }

  // A struct as KnobValues, spelled.
  KnobValues valuesOf(Knobs knobs) const {
    const Knobs defaults;
    std::map<std::string, std::string> spelled;
    std::string described;
    for (const Knob& knob : knobs_) {
      const std::string value = knob.spell(knobs);
      if (value != knob.spell(defaults)) described += (described.empty() ? "" : " ") + knob.spec.name + "=" + value;
      spelled.emplace(knob.spec.name, value);
    }
    return KnobValues(std::move(knobs), std::move(spelled), described.empty() ? "defaults" : described);
  }

 private:
  struct Knob {
    KnobSpec spec;
    std::function<std::string(const Knobs&)> spell;
    std::function<bool(Knobs&, const std::string&)> set;  // false when the text is not an allowed value
  };

  template <typename Spell, typename Set>
  KnobTable& add(KnobSpec spec, Spell spell, Set set) {
    HSR_CHECK(!find(spec.name) && "a knob declared twice");
    spec.defaultValue = spell(Knobs{});
    if (spec.range) spec.choices.insert(spec.choices.begin(), spec.defaultValue);
    knobs_.push_back({std::move(spec), spell, set});
    return *this;
  }

  const Knob* find(const std::string& name) const {
    for (const Knob& knob : knobs_)
      if (knob.spec.name == name) return &knob;
    return nullptr;
  }

  std::vector<Knob> knobs_;
};

// The spec of that name among `knobs`, or nullptr.
const KnobSpec* findKnob(const std::vector<KnobSpec>& knobs, const std::string& name);

}  // namespace hsr
