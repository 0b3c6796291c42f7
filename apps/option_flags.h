// The command line's side of settings/option.h. main.cc registers the options the running
// command declares (Command::options) as gflags flags of this process, with the command's
// own defaults and help, before gflags parses the command line: a name means one thing in
// one run, and --help, --config, --print_config and the report's "options" see them as the
// command's own flags. The parsed values then fill the settings through the declarations.
#ifndef MOCAPSOLVE_APPS_OPTION_FLAGS_H_
#define MOCAPSOLVE_APPS_OPTION_FLAGS_H_

#include <string>
#include <vector>

#include <gflags/gflags.h>
#include <glog/logging.h>

#include "kinematics/status.h"
#include "settings/option.h"

namespace mocapsolve {

// Registers each option as a flag defined in `source` (the command's __FILE__). Once per
// process, before gflags::ParseCommandLineFlags.
void RegisterOptionFlags(const std::vector<Option>& options, const char* source);

// Every declared option's value as parsed (or set by --config) passes its declaration's
// check: one message per option whatever the surface (a Python keyword gets the same).
Status CheckOptionFlags(const std::vector<std::vector<Option>>& groups);

// The flag values of the group's options (as parsed, or set by --config) into their fields
// of `settings` (other fields untouched); an option this run did not register gets the
// group's default. CheckOptionFlags passed every value before any command reads one, so a
// value failing here is a bug.
template <class Settings>
void ReadOptionFlags(const OptionGroup<Settings>& group, Settings* settings) {
  for (const Option& option : group.options()) {
    std::string text;
    if (!gflags::GetCommandLineOption(option.name.c_str(), &text)) text = option.default_value;
    const Status status = group.Set(option.name, text, settings);
    CHECK(status.ok()) << status.message();
  }
}

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_OPTION_FLAGS_H_
