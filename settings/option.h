// An option declared once. Every knob a user sets is one Option: its name (the flag, the
// config-file key, the Python keyword and the key in a report's "options"), its type, its
// default, its unit, its help text and its check. An OptionGroup<Settings> binds each
// option to a field of a settings struct, and the field's initializer is the option's
// default, so the struct and the option cannot disagree. The surfaces are made from the
// declarations: the command line's flags, --help and config keys (apps/option_flags.h),
// the Python keyword docstrings (python/keyword_docs.h), the options recorded in reports.
//
// A command that needs another default for an option declares it where it lists its
// options (OptionGroup::WithDefault), not in a table elsewhere.
//
// Checks are the same on every surface: a bool is true/false, an int an integer, a double
// a finite number, within [min, max] when the option has a range; a string one of its
// choices when it lists them, or for a list option (AddList) a comma-separated list of
// them, at least one, none twice. Each failure is one line naming the option:
//   --solver: unknown 'x' (ceres, dls, dls_generic)
//   --formats: unknown 'obj' (glb, fbx, bvh)
//   --max_iterations: expected an integer, got '1.5'
#ifndef MOCAPSOLVE_SETTINGS_OPTION_H_
#define MOCAPSOLVE_SETTINGS_OPTION_H_

#include <limits>
#include <cstdlib>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "kinematics/status.h"

namespace mocapsolve {

enum class OptionType { kBool, kInt, kDouble, kString };

// gflags' name of the type: bool, int32, double, string.
const char* OptionTypeName(OptionType type);

struct Option {
  std::string name;
  OptionType type = OptionType::kString;
  std::string default_value;         // As the command line writes it: 20, 1e-06, ceres, true.
  std::string unit;                  // mm, cm, deg, frames, mm/rad, ... ("" = none).
  std::string help;
  std::vector<std::string> choices;  // A string option's allowed values (empty: any text).
  bool list = false;                 // A comma-separated list of choices ("glb,fbx").
  double min = -std::numeric_limits<double>::infinity();  // A number option's closed range.
  double max = std::numeric_limits<double>::infinity();

  // Ok when `text` is a value of this option, else one line naming it ("--name: ...").
  Status Check(const std::string& text) const;
  // The help line with the unit and the choices: "Weight of ... [mm/rad]".
  std::string Description() const;
};

// A number as the command line writes it back: %.17g shortened to the shortest text that
// reads back to the same double (20, 1e-06, 0.1).
std::string OptionNumberText(double value);

// Options bound to the fields of Settings. Declare a group once (a function returning a
// static group), then Set/Get values by name as text.
template <class Settings>
class OptionGroup {
 public:
  OptionGroup& Add(bool Settings::*field, const char* name, const char* help) {
    return Push(field, Make(name, OptionType::kBool, "", help, Settings().*field ? "true" : "false"));
  }
  OptionGroup& Add(int Settings::*field, const char* name, const char* unit, const char* help,
                   double min = -std::numeric_limits<double>::infinity(),
                   double max = std::numeric_limits<double>::infinity()) {
    Option option = Make(name, OptionType::kInt, unit, help, std::to_string(Settings().*field));
    option.min = min, option.max = max;
    return Push(field, std::move(option));
  }
  OptionGroup& Add(double Settings::*field, const char* name, const char* unit, const char* help,
                   double min = -std::numeric_limits<double>::infinity(),
                   double max = std::numeric_limits<double>::infinity()) {
    Option option = Make(name, OptionType::kDouble, unit, help, OptionNumberText(Settings().*field));
    option.min = min, option.max = max;
    return Push(field, std::move(option));
  }
  OptionGroup& Add(std::string Settings::*field, const char* name, const char* help,
                   std::vector<std::string> choices = {}) {
    Option option = Make(name, OptionType::kString, "", help, Settings().*field);
    option.choices = std::move(choices);
    return Push(field, std::move(option));
  }

  // A comma-separated list of `choices` (see Option::list), e.g. "glb,fbx".
  OptionGroup& AddList(std::string Settings::*field, const char* name, const char* help,
                       std::vector<std::string> choices) {
    Option option = Make(name, OptionType::kString, "", help, Settings().*field);
    option.choices = std::move(choices);
    option.list = true;
    return Push(field, std::move(option));
  }

  // This group with option `name` defaulting to `value` (and, when given, another help
  // text): how a command declares its own default.
  OptionGroup WithDefault(const std::string& name, const std::string& value, const std::string& help = "") const {
    OptionGroup copy = *this;
    for (Option& option : copy.options_) {
      if (option.name != name) continue;
      option.default_value = value;
      if (!help.empty()) option.help = help;
    }
    return copy;
  }

  // This group's options named in `names` (comma-separated), for a command that reads
  // only some of them.
  OptionGroup Only(const std::string& names) const {
    OptionGroup part;
    for (size_t i = 0; i < options_.size(); ++i) {
      if (("," + names + ",").find("," + options_[i].name + ",") == std::string::npos) continue;
      part.options_.push_back(options_[i]);
      part.fields_.push_back(fields_[i]);
    }
    return part;
  }

  // This group without the options named in `names` (comma-separated).
  OptionGroup Without(const std::string& names) const {
    std::string kept;
    for (const Option& option : options_) {
      if (("," + names + ",").find("," + option.name + ",") == std::string::npos) kept += option.name + ",";
    }
    return Only(kept);
  }

  const std::vector<Option>& options() const { return options_; }
  // The names, comma-separated, in declaration order.
  std::string Names() const {
    std::string names;
    for (const Option& option : options_) names += (names.empty() ? "" : ",") + option.name;
    return names;
  }

  // Every field of `settings` checked as its option (what Python or a caller filled in
  // directly gets the command line's messages).
  Status Validate(const Settings& settings) const {
    for (const Option& option : options_) {
      Status status = option.Check(Get(option.name, settings));
      if (!status.ok()) return status;
    }
    return Status::Ok();
  }

  // Settings() with this group's defaults.
  Settings Defaults() const {
    Settings settings;
    for (const Option& option : options_) {
      if (!Set(option.name, option.default_value, &settings).ok()) std::abort();  // A declaration's own bug.
    }
    return settings;
  }

  // Checks `text` against the option and stores it; an unknown name or a bad value is an
  // error naming the option.
  Status Set(const std::string& name, const std::string& text, Settings* settings) const {
    for (size_t i = 0; i < options_.size(); ++i) {
      if (options_[i].name != name) continue;
      Status status = options_[i].Check(text);
      if (!status.ok()) return status;
      std::visit([&](auto field) { Store(text, &(settings->*field)); }, fields_[i]);
      return Status::Ok();
    }
    return Status::Error("--" + name + ": not an option here");
  }

  // Calls visit(option, field) for each option in order, `field` its `T Settings::*` (T: bool,
  // int, double or std::string): how a front end binds the fields themselves (Python's
  // attributes) from the declarations.
  template <class Visit>
  void VisitFields(Visit visit) const {
    for (size_t i = 0; i < options_.size(); ++i) {
      std::visit([&](auto field) { visit(options_[i], field); }, fields_[i]);
    }
  }

  // The value of option `name` in `settings`, as text ("" for an unknown name).
  std::string Get(const std::string& name, const Settings& settings) const {
    for (size_t i = 0; i < options_.size(); ++i) {
      if (options_[i].name == name) {
        return std::visit([&](auto field) { return Text(settings.*field); }, fields_[i]);
      }
    }
    return "";
  }

 private:
  using Field = std::variant<bool Settings::*, int Settings::*, double Settings::*, std::string Settings::*>;

  static Option Make(const char* name, OptionType type, const char* unit, const char* help, std::string value) {
    Option option;
    option.name = name;
    option.type = type;
    option.unit = unit;
    option.help = help;
    option.default_value = std::move(value);
    return option;
  }
  OptionGroup& Push(Field field, Option option) {
    fields_.push_back(field);
    options_.push_back(std::move(option));
    return *this;
  }
  // Only after Check: the text is a valid value of the field's type. GCC 12 instantiates every
  // alternative of the visit in Set and, on a settings struct smaller than a double, warns that
  // the double's store is out of bounds (-Warray-bounds), though only the field's own type is
  // ever stored: a false positive, silenced here alone.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Warray-bounds"
#endif
  static void Store(const std::string& text, bool* value) { *value = text == "true" || text == "1"; }
  static void Store(const std::string& text, int* value) { *value = std::stoi(text); }
  static void Store(const std::string& text, double* value) { *value = std::stod(text); }
  static void Store(const std::string& text, std::string* value) { *value = text; }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
  static std::string Text(bool value) { return value ? "true" : "false"; }
  static std::string Text(int value) { return std::to_string(value); }
  static std::string Text(double value) { return OptionNumberText(value); }
  static std::string Text(const std::string& value) { return value; }

  std::vector<Option> options_;
  std::vector<Field> fields_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_OPTION_H_
