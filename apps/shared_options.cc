// The shared options (apps/common_flags.h): which a command lists, and this run's values.
#include <string>
#include <vector>

#include "apps/common_flags.h"
#include "apps/option_flags.h"

namespace mocapsolve {
namespace {

FileSettings files;
FileReadSettings file_reading;
ConsoleSettings console;

bool Named(const std::string& names, const std::string& name) {
  return ("," + names + ",").find("," + name + ",") != std::string::npos;
}

template <class Settings>
void Append(const OptionGroup<Settings>& group, const std::string& names, std::vector<Option>* options) {
  const OptionGroup<Settings> part = group.Only(names);  // Alive through the loop.
  for (const Option& option : part.options()) options->push_back(option);
}

// ReadOptionFlags without its check: a value that failed CheckOptionFlags keeps the
// default here, and the run stops at that check's error (whose report still needs --report).
template <class Settings>
void ReadLeniently(const OptionGroup<Settings>& group, Settings* settings) {
  for (const Option& option : group.options()) {
    std::string text;
    if (gflags::GetCommandLineOption(option.name.c_str(), &text)) (void)group.Set(option.name, text, settings);
  }
}

}  // namespace

std::vector<Option> SharedOptions(const std::string& names) {
  std::string all = names;
  if (Named(names, "markers")) all += ",include_model_outputs,subject_prefix,ignore_markers";
  std::vector<Option> options;
  Append(FileSettingOptions(), all, &options);
  Append(FileReadSettingOptions(), all, &options);
  Append(ConsoleSettingOptions(), all, &options);
  return options;
}

const FileSettings& Files() { return files; }
const FileReadSettings& FileReading() { return file_reading; }
const ConsoleSettings& Console() { return console; }

void ReadSharedOptions() {
  files = FileSettings();
  file_reading = FileReadSettings();
  console = ConsoleSettings();
  ReadLeniently(FileSettingOptions(), &files);
  ReadLeniently(FileReadSettingOptions(), &file_reading);
  ReadLeniently(ConsoleSettingOptions(), &console);
  SetDefaultMarkerReadOptions(MarkerReadOptionsOf(file_reading));
}

}  // namespace mocapsolve
