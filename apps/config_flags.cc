#include "apps/config_flags.h"

#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include <gflags/gflags.h>

#include "io/json_reader.h"
#include "io/json_writer.h"
#include "apps/common_flags.h"

namespace mocapsolve {

Status ApplyConfigFile(const std::string& path, const std::string& flags) {
  JsonNode root;
  Status status = ReadJsonFile(path, &root);
  if (!status.ok()) return status;
  if (!root.is_object()) return Status::Error(root.Where(path) + ": expected an object of options");
  const std::vector<std::string> names = SplitCommaList(flags);
  const std::set<std::string> allowed(names.begin(), names.end());
  if (const auto* unknown = FindUnknownKey(root, allowed)) {
    return Status::Error(unknown->second.Where(path) + ": unknown option '" + unknown->first + "'");
  }
  for (const auto& [key, value] : root.members) {
    gflags::CommandLineFlagInfo info;
    if (!gflags::GetCommandLineFlagInfo(key.c_str(), &info)) {
      return Status::Error(value.Where(path) + ": unknown option '" + key + "'");
    }
    if (!info.is_default) continue;  // Given on the command line: it wins.
    std::string text;
    if (value.is_string()) {
      text = value.string;
    } else if (value.is_bool()) {
      text = value.boolean ? "true" : "false";
    } else if (value.is_number()) {
      char buffer[32];
      std::snprintf(buffer, sizeof(buffer), "%.17g", value.number);
      text = buffer;
    } else {
      return Status::Error(value.Where(path) + ": " + key + ": expected a number, string or boolean");
    }
    if ((info.type == "bool" && !value.is_bool()) ||
        ((info.type == "int32" || info.type == "int64" || info.type == "double") && !value.is_number()) ||
        (info.type == "string" && !value.is_string())) {
      return Status::Error(value.Where(path) + ": " + key + ": expected a " +
                           (info.type == "string" ? "string" : info.type == "bool" ? "boolean" : "number"));
    }
    if (gflags::SetCommandLineOption(key.c_str(), text.c_str()).empty()) {
      return Status::Error(value.Where(path) + ": " + key + ": invalid value '" + text + "'");
    }
  }
  ReadSharedOptions();  // A config may set shared options too.
  return Status::Ok();
}

namespace {

std::string FlagsJson(const std::string& flags, bool given_only, bool indent) {
  JsonObject config;
  for (const std::string& name : SplitCommaList(flags)) {
    gflags::CommandLineFlagInfo info;
    if (!gflags::GetCommandLineFlagInfo(name.c_str(), &info)) continue;
    if (given_only && info.is_default) continue;
    if (info.type == "bool") {
      config.Add(name, info.current_value == "true");
    } else if (info.type == "int32" || info.type == "int64" || info.type == "double") {
      config.Add(name, JsonValue(std::stod(info.current_value)));
    } else {
      config.Add(name, info.current_value);
    }
  }
  return config.ToString(indent);
}

}  // namespace

std::string ConfigJson(const std::string& flags) { return FlagsJson(flags, false, true); }

std::string GivenFlagsJson(const std::string& flags) { return FlagsJson(flags, true, false); }

}  // namespace mocapsolve
