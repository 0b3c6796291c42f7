#include "settings/option.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace mocapsolve {

const char* OptionTypeName(OptionType type) {
  switch (type) {
    case OptionType::kBool: return "bool";
    case OptionType::kInt: return "int32";
    case OptionType::kDouble: return "double";
    case OptionType::kString: return "string";
  }
  return "string";
}

std::string OptionNumberText(double value) {
  // The fewest digits that read back to `value`; of those texts, the first without an
  // exponent (20, not 2e+01), else the shortest (1e-06).
  std::string shortest;
  for (int digits = 1; digits <= 17; ++digits) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.*g", digits, value);
    if (std::strtod(text, nullptr) != value) continue;
    if (shortest.empty()) shortest = text;
    if (std::string(text).find('e') == std::string::npos) return text;
  }
  return shortest;
}

namespace {

std::string JoinChoices(const std::vector<std::string>& choices) {
  std::string text;
  for (const std::string& choice : choices) text += (text.empty() ? "" : ", ") + choice;
  return text;
}

// The whole of `text` as a number (strtod / strtol), and nothing else.
bool ParseNumber(const std::string& text, bool integer, double* value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  if (integer) {
    const long parsed = std::strtol(text.c_str(), &end, 10);
    if (errno != 0 || parsed < -2147483647L - 1 || parsed > 2147483647L) return false;
    *value = static_cast<double>(parsed);
  } else {
    *value = std::strtod(text.c_str(), &end);
  }
  return end == text.c_str() + text.size();
}

// A list option's value: items separated by single commas, each one of `choices`, none twice.
Status CheckList(const std::string& prefix, const std::string& text, const std::vector<std::string>& choices) {
  if (text.empty()) return Status::Error(prefix + "expected a comma-separated list of " + JoinChoices(choices));
  std::vector<std::string> seen;
  size_t begin = 0;
  while (true) {
    const size_t end = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, end - begin);
    bool known = false;
    for (const std::string& choice : choices) known = known || item == choice;
    if (!known) return Status::Error(prefix + "unknown '" + item + "' (" + JoinChoices(choices) + ")");
    for (const std::string& earlier : seen) {
      if (earlier == item) return Status::Error(prefix + "'" + item + "' given twice in '" + text + "'");
    }
    seen.push_back(item);
    if (end == text.size()) return Status::Ok();
    begin = end + 1;
  }
}

}  // namespace

Status Option::Check(const std::string& text) const {
  const std::string prefix = "--" + name + ": ";
  switch (type) {
    case OptionType::kBool:
      if (text == "true" || text == "false" || text == "1" || text == "0") return Status::Ok();
      return Status::Error(prefix + "expected true or false, got '" + text + "'");
    case OptionType::kString: {
      if (choices.empty()) return Status::Ok();
      if (list) return CheckList(prefix, text, choices);
      for (const std::string& choice : choices) {
        if (text == choice) return Status::Ok();
      }
      return Status::Error(prefix + "unknown '" + text + "' (" + JoinChoices(choices) + ")");
    }
    case OptionType::kInt:
    case OptionType::kDouble: {
      const bool integer = type == OptionType::kInt;
      double value = 0;
      if (!ParseNumber(text, integer, &value)) {
        return Status::Error(prefix + "expected " + (integer ? "an integer" : "a number") + ", got '" + text + "'");
      }
      if (!std::isfinite(value)) return Status::Error(prefix + "expected a finite number, got '" + text + "'");
      if (value < min || value > max) {
        const std::string range = std::isinf(max)   ? ">= " + OptionNumberText(min)
                                  : std::isinf(min) ? "<= " + OptionNumberText(max)
                                                    : "in [" + OptionNumberText(min) + ", " + OptionNumberText(max) + "]";
        return Status::Error(prefix + "expected a value " + range + ", got " + text);
      }
      return Status::Ok();
    }
  }
  return Status::Ok();
}

std::string Option::Description() const {
  std::string text = help;
  if (!unit.empty()) text += " [" + unit + "]";
  return text;
}

}  // namespace mocapsolve
