// mocapsolve: motion-capture problems as nonlinear least squares.
#include <cmath>
#include <cstdio>
#include <cerrno>
#include <cstring>
#include <exception>
#include <new>
#include <set>
#include <string>
#include <vector>

#include <gflags/gflags.h>
#include <glog/logging.h>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "io/atomic_file.h"
#include "io/file_transaction.h"
#include "io/marker_file.h"
#include "io/marker_set_file.h"
#include "io/motion_file.h"
#include "kinematics/quote_token.h"
#include "kinematics/marker_trajectories.h"

namespace mocapsolve {
namespace {

int exit_code_on_success = 0;

void PrintCommandList() {
  std::printf(
      "mocapsolve: motion-capture problems as nonlinear least squares.\n\n"
      "usage: mocapsolve <command> [--flags] [arguments]\n"
      "       mocapsolve --version\n"
      "       mocapsolve <command> --help   (that command's flags)\n\ncommands:\n");
  for (const Command& command : AllCommands()) {
    std::printf("  %-10s %s\n", command.name, command.summary);
  }
  std::printf(
      "\nCommon flags: --quiet (no progress on stderr), --v=1 (per-iteration detail).\n"
      "Files: BVH, ASF/AMC (--skeleton=X.asf goes with an .amc), glTF/GLB and FBX\n"
      "(--animation=NAME picks a clip). Lengths stay in the\n"
      "file's units unless a command says otherwise.\n");
}

bool EndsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// A default as people write it: 1e-06 and 0.25, not gflags' 9.9999999999999995e-07.
std::string ShownDefault(const gflags::CommandLineFlagInfo& flag) {
  if (flag.type == "string") return "\"" + flag.default_value + "\"";
  if (flag.type != "double") return flag.default_value;
  char text[32];
  std::snprintf(text, sizeof(text), "%g", std::strtod(flag.default_value.c_str(), nullptr));
  return text;
}

// The flags a command reads: the options it declares, which main registers as flags of
// its own file. Its --help shows exactly these, and main refuses any other of ours (glog's
// and gflags' own, such as --v, stay accepted everywhere).
bool CommandReadsFlag(const Command& command, const gflags::CommandLineFlagInfo& flag) {
  return EndsWith(flag.filename, command.source) || EndsWith(command.source, flag.filename);
}

bool IsOurFlag(const gflags::CommandLineFlagInfo& flag) {
  return flag.filename.find("apps/") != std::string::npos;
}

// A flag given on the command line that the command does not read is an error, not a
// silent no-op (`info --solver=foo`).
Status CheckGivenFlags(const Command& command) {
  std::vector<gflags::CommandLineFlagInfo> flags;
  gflags::GetAllFlags(&flags);
  for (const auto& flag : flags) {
    if (flag.is_default || !IsOurFlag(flag) || CommandReadsFlag(command, flag)) continue;
    return Status::Error("--" + flag.name + ": not a flag of `" + command.name + "` (mocapsolve " + command.name +
                         " --help lists its flags)");
  }
  return Status::Ok();
}

// No option of ours takes NaN or an infinity (gflags' strtod accepts "nan" and "inf", and
// a NaN passes every `x < bound` check downstream): one message for every number flag.
Status CheckFiniteFlags(const Command& command) {
  std::vector<gflags::CommandLineFlagInfo> flags;
  gflags::GetAllFlags(&flags);
  for (const auto& flag : flags) {
    if (flag.type != "double" || !IsOurFlag(flag) || !CommandReadsFlag(command, flag)) continue;
    if (!std::isfinite(std::strtod(flag.current_value.c_str(), nullptr))) {
      return Status::Error("--" + flag.name + ": expected a finite number, got '" + flag.current_value + "'");
    }
  }
  return Status::Ok();
}

// The options the command declares become this run's flags, the command's own (a name
// two of its groups declare: the first group's).
void RegisterCommandOptions(const Command& command) {
  std::set<std::string> registered;
  std::vector<std::vector<Option>> groups = command.options;
  groups.push_back(ConsoleSettingOptions().Only("quiet").options());  // Every command's.
  for (const std::vector<Option>& group : groups) {
    std::vector<Option> fresh;
    for (const Option& option : group) {
      if (registered.count(option.name)) continue;
      gflags::CommandLineFlagInfo existing;
      // A declared option that is also a DEFINE_* somewhere would be that flag, silently.
      CHECK(!gflags::GetCommandLineFlagInfo(option.name.c_str(), &existing))
          << "--" << option.name << " is declared for `" << command.name << "` and also defined in "
          << existing.filename;
      registered.insert(option.name);
      fresh.push_back(option);
    }
    RegisterOptionFlags(fresh, command.source);
  }
}

// A flag only other commands declare is not a flag of this run at all; say so as
// CheckGivenFlags does for the others, not with gflags' "unknown command line flag".
Status CheckOtherCommandsOptions(const Command& command, int argc, char** argv) {
  for (int i = 2; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--") break;
    if (argument.size() < 2 || argument[0] != '-') continue;
    const std::string flag = argument.substr(argument[1] == '-' ? 2 : 1);
    const std::string name = flag.substr(0, flag.find('='));
    gflags::CommandLineFlagInfo registered;
    if (gflags::GetCommandLineFlagInfo(name.c_str(), &registered)) continue;
    for (const Command& other : AllCommands()) {
      for (const std::vector<Option>& group : other.options) {
        for (const Option& option : group) {
          if (name != option.name && name != "no" + option.name) continue;
          return Status::Error("--" + option.name + ": not a flag of `" + command.name + "` (mocapsolve " +
                               command.name + " --help lists its flags)");
        }
      }
    }
  }
  return Status::Ok();
}

// The command's own defaults for the shared flags it overrides; an explicit flag still wins.
void PrintCommandHelp(const Command& command) {
  std::printf("usage: %s\n\n", command.usage);
  std::vector<gflags::CommandLineFlagInfo> flags;
  gflags::GetAllFlags(&flags);
  bool header = false;
  for (const auto& flag : flags) {
    if (!CommandReadsFlag(command, flag)) continue;
    if (!header) std::printf("flags:\n"), header = true;
    std::printf("  --%s (%s) default: %s\n      %s\n", flag.name.c_str(), flag.type.c_str(),
                ShownDefault(flag).c_str(), flag.description.c_str());
  }
}

}  // namespace
}  // namespace mocapsolve

namespace mocapsolve {

Status LoadMotion(const std::string& path, Skeleton* skeleton, Motion* motion) {
  MotionFileOptions options = MotionReadOptionsOf(FileReading(), Files().skeleton);
  std::vector<std::string> warnings;
  options.warnings = &warnings;
  Status status = ReadMotionFile(path, options, skeleton, motion);
  for (const std::string& warning : warnings) std::fprintf(stderr, "warning: %s\n", TerminalText(warning).c_str());
  return status;
}

Status ApplySkeletonUnits(Skeleton* skeleton) { return SetSkeletonUnits(FileReading().skeleton_units, skeleton); }

Status LoadSkeleton(const std::string& path, Skeleton* skeleton) {
  Status status = ReadSkeletonFile(path, skeleton);
  return status.ok() ? ApplySkeletonUnits(skeleton) : status;
}

namespace {

// The mapping flags a subject file replaces, and whether each was given.
std::vector<std::string> GivenMappingFlags() {
  std::vector<std::string> given;
  for (const char* name : {"skeleton", "skeleton_units", "markerset", "axes", "marker_scale"}) {
    if (GivenOnCommandLine(name)) given.push_back(name);
  }
  return given;
}

}  // namespace

bool GivenOnCommandLine(const std::string& name) {
  gflags::CommandLineFlagInfo info;
  return gflags::GetCommandLineFlagInfo(name.c_str(), &info) && !info.is_default;
}

Status LoadSubjectFromFlags(Subject* subject) {
  if (!Files().subject.empty()) {
    const std::vector<std::string> given = GivenMappingFlags();
    if (!given.empty()) {
      return Status::Error("--subject and --" + given[0] + " both given: the subject file holds the skeleton, "
                           "marker set, axes and units (give one or the other)");
    }
    return ReadSubject(Files().subject, subject);
  }
  SubjectFiles files;
  files.skeleton_path = Files().skeleton;
  files.skeleton_units = FileReading().skeleton_units;
  files.markerset_path = Files().markerset;
  files.axes = FileReading().axes;
  files.marker_scale = FileReading().marker_scale;
  files.amc_fps = FileReading().amc_fps;
  return LoadSubjectFromFiles(files, subject);
}

Status MarkerTakeInputs(std::vector<std::string>* inputs) {
  if (!Files().subject.empty()) {
    if (Files().markers.empty()) return Status::Error("--markers is required (with --subject)");
    *inputs = {Files().subject, Files().markers};
    return Status::Ok();
  }
  if (Files().skeleton.empty() || Files().markers.empty() || Files().markerset.empty()) {
    return Status::Error("--markers and either --subject or --skeleton and --markerset are required");
  }
  *inputs = {Files().skeleton, Files().markers, Files().markerset};
  return Status::Ok();
}

Status LoadMarkerTake(MarkerTake* take) {
  Subject subject;
  Status status = LoadSubjectFromFlags(&subject);
  if (!status.ok()) return status;
  status = LoadTakeForSubject(subject, Files().markers, take);
  return status.ok() ? RequireTakeData(Files().markers, *take) : status;
}

Status LoadObservations(const std::string& path, const Skeleton& skeleton, const MarkerSet& markers,
                        MarkerTrajectories* trajectories, MarkerFileToModel* transform,
                        std::vector<std::vector<Eigen::Vector3d>>* observed) {
  Subject subject;
  subject.skeleton = skeleton;
  subject.markers = markers;
  subject.axes = FileReading().axes;
  subject.marker_scale = FileReading().marker_scale;
  MarkerTake take;
  Status status = LoadTakeForSubject(subject, path, &take);
  if (status.ok()) status = RequireTakeData(path, take);
  if (!status.ok()) return status;
  *trajectories = std::move(take.trajectories);
  *transform = take.transform;
  *observed = std::move(take.observed);
  return Status::Ok();
}

namespace {

const Command* running_command = nullptr;  // Set by main before the command runs.
std::string running_stage = "arguments";   // SetStage.

// The flags the command reads, with the values in force (numbers and booleans typed).
JsonObject OptionsOf(const Command& command) {
  std::vector<gflags::CommandLineFlagInfo> flags;
  gflags::GetAllFlags(&flags);
  JsonObject options;
  for (const auto& flag : flags) {
    if (!CommandReadsFlag(command, flag) || flag.name == "report") continue;
    if (flag.type == "bool") {
      options.Add(flag.name, flag.current_value == "true");
    } else if (flag.type == "string") {
      options.Add(flag.name, flag.current_value);
    } else {
      options.Add(flag.name, std::strtod(flag.current_value.c_str(), nullptr));
    }
  }
  return options;
}

std::vector<JsonObject> InputsRead() {
  std::vector<JsonObject> inputs;
  if (const FileTransaction* files = FileTransaction::Current()) {
    for (const FileTransaction::InputFile& file : files->InputFiles()) {
      JsonObject o;
      o.Add("path", file.path).Add("bytes", static_cast<double>(file.bytes)).Add("fnv1a64", file.hash);
      inputs.push_back(o);
    }
  }
  return inputs;
}

}  // namespace

void SetStage(const std::string& stage) { running_stage = stage; }

JsonObject OptionsInForce() { return running_command != nullptr ? OptionsOf(*running_command) : JsonObject(); }

// Every report opens with what it is and where it came from (docs/schemas/report.schema.json):
// status, command, version, then the command's own members, then the options in force and
// each input read (path, size, content hash), unless the command reported those itself.
Status WriteReport(const JsonObject& report) {
  if (Files().report.empty()) return Status::Ok();
  JsonObject full;
  full.Add("status", "ok").Add("version", Version());
  if (running_command != nullptr) full.Add("command", running_command->name);
  full.Merge(report);
  if (running_command != nullptr && !full.Has("options")) full.Add("options", OptionsOf(*running_command));
  if (!full.Has("inputs")) full.Add("inputs", InputsRead());
  return WriteFileAtomically(Files().report, full.ToString() + "\n");
}

// Early, before any work: --report and --plot must not name a file that another argument
// names (an input, or another output). The FileTransaction checks every output again
// when it is written; this only spares a long run that would end in that error.
Status CheckReportPaths(const std::vector<std::string>& positional) {
  std::vector<gflags::CommandLineFlagInfo> flags;
  gflags::GetAllFlags(&flags);
  for (const char* name : {"report", "plot"}) {
    gflags::CommandLineFlagInfo output;
    if (!gflags::GetCommandLineFlagInfo(name, &output) || output.current_value.empty()) continue;
    const std::string& path = output.current_value;
    auto same = [&](const std::string& other) {
      return other == path || SameFile(other, path);
    };
    for (const auto& flag : flags) {
      if (flag.is_default || flag.type != "string" || flag.name == name) continue;
      if (same(flag.current_value)) {
        return Status::Error("--" + std::string(name) + "=" + path + ": names the same file as --" + flag.name);
      }
    }
    for (const std::string& argument : positional) {
      if (same(argument)) return Status::Error("--" + std::string(name) + "=" + path + ": names the same file as " + argument);
    }
  }
  return Status::Ok();
}

// True if a flag the command reads, or a positional argument, is "-" (the standard
// output as an output path): then only the outputs go to stdout.
bool NamesStandardOutput(const Command& command, const std::vector<std::string>& positional) {
  for (const std::string& argument : positional) {
    if (IsStandardOutput(argument)) return true;
  }
  std::vector<gflags::CommandLineFlagInfo> flags;
  gflags::GetAllFlags(&flags);
  for (const auto& flag : flags) {
    if (flag.type == "string" && IsStandardOutput(flag.current_value) && CommandReadsFlag(command, flag)) return true;
  }
  return false;
}

// A failed run still answers --report, so a pipeline reads failures as it reads results:
// {"status": "error", "command", "version", "message"}. Written outside the failed
// transaction (whose outputs are dropped); not over an input or another argument's file.
void WriteFailureReport(const char* command, const std::string& message,
                        const std::vector<std::string>& positional, const FileTransaction& files) {
  if (Files().report.empty() || !CheckReportPaths(positional).ok() || files.NamesAnInput(Files().report)) return;
  gflags::CommandLineFlagInfo report_flag;
  gflags::GetCommandLineFlagInfo("report", &report_flag);
  if (running_command != nullptr && !CommandReadsFlag(*running_command, report_flag)) return;  // Not its flag.
  JsonObject report;
  report.Add("status", "error").Add("version", Version()).Add("command", command).Add("message", message);
  report.Add("stage", running_stage);
  if (running_command != nullptr) report.Add("options", OptionsOf(*running_command));
  report.Add("inputs", InputsRead());
  StagedFile staged;
  if (StagedFile::Create(Files().report, report.ToString() + "\n", &staged).ok()) (void)staged.Publish();
}

void SetExitCodeOnSuccess(int code) { exit_code_on_success = code; }

const char* Version() { return MOCAPSOLVE_VERSION; }

namespace {

// What the command printed must have reached stdout: `info x.bvh > /dev/full` fails at
// the flush, and is then an error (exit 1), before any output file is published.
Status FlushStandardOutput() {
  errno = 0;
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return Status::Ok();
  const int error = errno;
  return Status::Error(std::string("writing the standard output failed (") +
                       (error != 0 ? std::strerror(error) : "write error") + ")");
}

// The command and the publication of its outputs, with a last line of defence: an
// exception no reader caught (std::bad_alloc from a size a check missed, ...) is a
// one-line error and exit 1 like any other, not an abort (exit 134) or a core dump.
Status RunCommand(const Command& command, const std::vector<std::string>& positional, FileTransaction* files) {
  try {
    SetStage("run");
    Status status = command.run(positional);
    if (status.ok()) status = FlushStandardOutput();
    if (status.ok()) {
      SetStage("outputs");
      status = files->Commit();
    }
    return status;
  } catch (const std::bad_alloc&) {
    return Status::Error("out of memory (stage " + running_stage + "); an input asks for more than this machine has");
  } catch (const std::exception& e) {
    return Status::Error(std::string("internal error (stage ") + running_stage + "): " + e.what());
  }
}

}  // namespace


Status CheckOutputsApart(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs) {
  for (size_t a = 0; a < outputs.size(); ++a) {
    if (outputs[a].empty()) continue;
    for (const std::string& input : inputs) {
      Status status = input.empty() ? Status::Ok() : CheckNotAnInput(outputs[a], input);
      if (!status.ok()) return status;
    }
    for (size_t b = a + 1; b < outputs.size(); ++b) {
      if (outputs[a] == outputs[b]) return Status::Error(outputs[a] + ": named by two output flags");
    }
  }
  return Status::Ok();
}

}  // namespace mocapsolve

int main(int argc, char** argv) {
  using mocapsolve::AllCommands;
  if (argc >= 2 && (std::strcmp(argv[1], "--version") == 0 || std::strcmp(argv[1], "version") == 0)) {
    std::printf("mocapsolve %s\n", mocapsolve::Version());
    return 0;
  }
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0 ||
      std::strcmp(argv[1], "help") == 0) {
    mocapsolve::PrintCommandList();
    return argc < 2 ? 1 : 0;
  }
  const mocapsolve::Command* command = nullptr;
  for (const auto& candidate : AllCommands()) {
    if (candidate.name == std::string(argv[1])) command = &candidate;
  }
  if (command == nullptr) {
    std::fprintf(stderr, "mocapsolve: unknown command '%s' (mocapsolve --help lists them)\n",
                 argv[1]);
    return 1;
  }
  mocapsolve::RegisterCommandOptions(*command);
  const mocapsolve::Status foreign = mocapsolve::CheckOtherCommandsOptions(*command, argc, argv);
  if (!foreign.ok()) {
    std::fprintf(stderr, "mocapsolve %s: %s\n", command->name, mocapsolve::TerminalText(foreign.message()).c_str());
    return 1;
  }
  for (int i = 2; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0 ||
        std::strcmp(argv[i], "--helpshort") == 0) {
      mocapsolve::PrintCommandHelp(*command);
      return 0;
    }
  }
  // Drop the command name, then let gflags take the flags (unknown ones are an error).
  std::vector<char*> args = {argv[0]};
  for (int i = 2; i < argc; ++i) args.push_back(argv[i]);
  int count = static_cast<int>(args.size());
  char** data = args.data();
  gflags::SetUsageMessage(command->usage);
  // Ceres warns when LM retries a step whose normal equations were singular; that is
  // handled and expected, so only errors are logged unless --minloglevel=0 asks.
  FLAGS_minloglevel = 2;
  FLAGS_v = 0;
  gflags::ParseCommandLineFlags(&count, &data, /*remove_flags=*/true);
  if (FLAGS_v > 0) FLAGS_minloglevel = std::min<int>(FLAGS_minloglevel, 0);
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(argv[0]);
  const std::vector<std::string> positional(data + 1, data + count);
  // Every file the command reads is an input no output may overwrite; its outputs are
  // published together when it succeeds, and none of them when it fails.
  mocapsolve::FileTransaction files;
  mocapsolve::running_command = command;
  mocapsolve::SetStage("arguments");
  mocapsolve::Status status = mocapsolve::CheckGivenFlags(*command);
  if (status.ok()) status = mocapsolve::CheckOptionFlags(command->options);
  mocapsolve::ReadSharedOptions();
  if (status.ok()) status = mocapsolve::CheckFiniteFlags(*command);
  if (status.ok()) status = mocapsolve::CheckReportPaths(positional);
  if (status.ok() && mocapsolve::NamesStandardOutput(*command, positional)) mocapsolve::ReserveStandardOutputForData();
  if (status.ok()) status = mocapsolve::RunCommand(*command, positional, &files);
  if (!status.ok()) mocapsolve::WriteFailureReport(command->name, status.message(), positional, files);
  if (!status.ok()) {
    // One line, whatever a message quotes from a file or an argument.
    std::fprintf(stderr, "mocapsolve %s: %s\n", command->name, mocapsolve::TerminalText(status.message()).c_str());
    return 1;
  }
  // Closing stdout can still fail (NFS, a full pipe buffer flushed late).
  if (std::fclose(stdout) != 0) {
    std::fprintf(stderr, "mocapsolve %s: closing the standard output failed (%s)\n", command->name,
                 std::strerror(errno));
    return 1;
  }
  return mocapsolve::exit_code_on_success;
}
