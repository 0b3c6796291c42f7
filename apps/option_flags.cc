#include "apps/option_flags.h"

#include <cstdint>
#include <deque>

namespace mocapsolve {

void RegisterOptionFlags(const std::vector<Option>& options, const char* source) {
  // gflags keeps the name and help pointers for the life of the process (it never frees a
  // flag); a deque never moves its strings, and holds them reachable (no leak reported).
  static std::deque<std::string>* const texts = new std::deque<std::string>();
  for (const Option& option : options) {
    const char* name = texts->emplace_back(option.name).c_str();
    const char* help = texts->emplace_back(option.Description()).c_str();
    const std::string& value = option.default_value;
    switch (option.type) {
      case OptionType::kBool:
        gflags::FlagRegisterer(name, help, source, new bool(value == "true"), new bool(value == "true"));
        break;
      case OptionType::kInt:
        gflags::FlagRegisterer(name, help, source, new gflags::int32(std::stoi(value)),
                               new gflags::int32(std::stoi(value)));
        break;
      case OptionType::kDouble:
        gflags::FlagRegisterer(name, help, source, new double(std::stod(value)), new double(std::stod(value)));
        break;
      case OptionType::kString:
        gflags::FlagRegisterer(name, help, source, new std::string(value), new std::string(value));
        break;
    }
  }
}

Status CheckOptionFlags(const std::vector<std::vector<Option>>& groups) {
  for (const std::vector<Option>& group : groups) {
    for (const Option& option : group) {
      std::string text;
      if (!gflags::GetCommandLineOption(option.name.c_str(), &text)) continue;
      Status status = option.Check(text);
      if (!status.ok()) return status;
    }
  }
  return Status::Ok();
}

}  // namespace mocapsolve
