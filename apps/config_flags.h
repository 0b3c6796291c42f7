// Config files: a command's options as a JSON object whose keys are the command's flag
// names, {"dp_max_cm": 10, "solver": "dls", ...}. The flags stay the one source of
// defaults and help; a config file only sets the flags that the command line did not
// (the command line wins), and a key that is not one of the command's flags is an
// error naming the file, line and key.
#ifndef MOCAPSOLVE_APPS_CONFIG_FLAGS_H_
#define MOCAPSOLVE_APPS_CONFIG_FLAGS_H_

#include <string>
#include <vector>

#include "io/comma_list.h"  // SplitCommaList, for the commands.
#include "kinematics/status.h"

namespace mocapsolve {

// `flags`: the names the config may set (comma-separated).
Status ApplyConfigFile(const std::string& path, const std::string& flags);

// The flags' current values as an indented JSON object, in the order given (numbers and
// booleans as JSON values, the rest as strings): what --print_config shows.
std::string ConfigJson(const std::string& flags);

// The same for the flags the command line (or a config file) set, on one line ("{}" for
// none): what `batch` passes on to every take.
std::string GivenFlagsJson(const std::string& flags);


}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_CONFIG_FLAGS_H_
