// Every command refuses the flags it does not read (issue 17: `info --solver=foo` used to
// exit 0), and its --help lists the ones it accepts: one rule in apps/main.cc decides both.
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "settings/band_settings.h"
#include "settings/bench_settings.h"
#include "settings/console_settings.h"
#include "settings/delivery_settings.h"
#include "settings/corruption_settings.h"
#include "settings/edit_settings.h"
#include "settings/falloff_settings.h"
#include "settings/file_read_settings.h"
#include "settings/file_settings.h"
#include "settings/foot_joint_settings.h"
#include "settings/frame_limit_settings.h"
#include "settings/solver_agreement_settings.h"
#include "settings/repair_settings.h"
#include "settings/retarget_run_settings.h"
#include "settings/retarget_settings.h"
#include "settings/solver_settings.h"
#include "settings/take_settings.h"
#include "settings/view_settings.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

// The commands `mocapsolve --help` lists.
std::vector<std::string> Commands() {
  std::string output;
  testing::RunCli("--help", &output);
  std::vector<std::string> names;
  std::istringstream lines(output);
  bool in_list = false;
  for (std::string line; std::getline(lines, line);) {
    if (line == "commands:") {
      in_list = true;
      continue;
    }
    if (in_list && line.empty()) break;
    if (in_list && line.size() > 2 && line[0] == ' ') names.push_back(line.substr(2, line.find(' ', 2) - 2));
  }
  return names;
}

// The flags a command's --help lists ("  --NAME (TYPE) default: ..."), with their types.
std::map<std::string, std::string> HelpFlagTypes(const std::string& command) {
  std::string output;
  EXPECT_EQ(testing::RunCli(command + " --help", &output), 0) << command;
  std::map<std::string, std::string> flags;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("  --", 0) != 0) continue;
    const size_t name_end = line.find(' ', 4), type_start = line.find('(', name_end) + 1;
    flags[line.substr(4, name_end - 4)] = line.substr(type_start, line.find(')', type_start) - type_start);
  }
  return flags;
}

// The flags a command's --help lists.
std::set<std::string> HelpFlags(const std::string& command) {
  std::set<std::string> names;
  for (const auto& [name, type] : HelpFlagTypes(command)) names.insert(name);
  return names;
}

TEST(CommandFlags, AFlagACommandDoesNotReadIsRefused) {
  const std::vector<std::string> commands = Commands();
  ASSERT_GE(commands.size(), 20u);
  std::map<std::string, std::set<std::string>> listed;
  std::set<std::string> all;
  for (const std::string& command : commands) {
    listed[command] = HelpFlags(command);
    all.insert(listed[command].begin(), listed[command].end());
  }
  for (const std::string& command : commands) {
    // A flag another command reads and this one does not: refused, naming both.
    std::string foreign;
    for (const std::string& flag : all) {
      if (!listed[command].count(flag)) {
        foreign = flag;
        break;
      }
    }
    ASSERT_FALSE(foreign.empty()) << command;
    std::string output;
    EXPECT_EQ(testing::RunCli(command + " --" + foreign + "=1", &output), 1) << command << " --" << foreign;
    EXPECT_THAT(output, HasSubstr("--" + foreign + ": not a flag of `" + command + "`")) << output;
    EXPECT_EQ(output.find('\n'), output.size() - 1) << output;
  }
  // The observed cases.
  std::string output;
  EXPECT_EQ(testing::RunCli("info --solver=foo --loop=7 x.bvh", &output), 1);
  EXPECT_THAT(output, HasSubstr("not a flag of `info`"));
  EXPECT_EQ(testing::RunCli("repair --out=x.c3d", &output), 1);
  EXPECT_THAT(output, HasSubstr("--out: not a flag of `repair`"));
  // calibrate and markers listed every shared flag, retarget's --target among them.
  for (const char* command : {"calibrate", "markers"}) {
    EXPECT_EQ(testing::RunCli(std::string(command) + " --target=x.glb", &output), 1) << command;
    EXPECT_THAT(output, HasSubstr("--target: not a flag of `" + std::string(command) + "`"));
    EXPECT_EQ(HelpFlags(command).count("target"), 0u) << command;
  }
  // glog's own flags stay accepted everywhere.
  EXPECT_EQ(testing::RunCli("generate --v=0 --demo_out=" + testing::TempPath("walk.bvh"), &output), 0) << output;
}

// The default a --help text shows for a flag, "" if it does not list it.
std::string DefaultInHelp(const std::string& output, const std::string& flag) {
  const std::string key = "  --" + flag + " (";
  const size_t at = output.find(key);
  if (at == std::string::npos) return "";
  const size_t start = output.find("default: ", at) + 9;
  return output.substr(start, output.find('\n', start) - start);
}

// The default a command's --help shows for a flag.
std::string HelpDefault(const std::string& command, const std::string& flag) {
  std::string output;
  testing::RunCli(command + " --help", &output);
  return DefaultInHelp(output, flag);
}

// A shared flag shows, for each command, the default that command applies (issue 17:
// retarget --help said ceres and ran dls; distance said multires and ran green).
TEST(CommandFlags, SharedFlagsShowEachCommandsOwnDefault) {
  // One default per concept: every solving command's --solver is dls.
  for (const char* command : {"solve", "fit_skeleton", "propagate", "repair", "retarget", "pipeline", "evaluate"}) {
    EXPECT_EQ(HelpDefault(command, "solver"), "\"dls\"") << command;
  }
  EXPECT_EQ(HelpDefault("blend", "method"), "\"multires\"");
  EXPECT_EQ(HelpDefault("distance", "method"), "\"green\"");
  EXPECT_EQ(HelpDefault("propagate", "method"), "\"green\"");
  EXPECT_EQ(HelpDefault("evaluate", "method"), "\"repair\"");
  // The text is the command's own.
  std::string output;
  testing::RunCli("distance --help", &output);
  EXPECT_THAT(output, HasSubstr("distance curves (1 - weight)"));
  EXPECT_EQ(output.find("RMS marker residual"), std::string::npos);
  // And the run applies it: the pipeline's printed config says dls.
  testing::RunCli("pipeline --print_config", &output);
  EXPECT_THAT(output, HasSubstr("\"solver\": \"dls\""));
  // A given value still wins.
  testing::RunCli("pipeline --print_config --solver=ceres", &output);
  EXPECT_THAT(output, HasSubstr("\"solver\": \"ceres\""));
}

// The text a command's --help gives for a flag (the line under "  --NAME (TYPE) default: ...").
std::string HelpText(const std::string& help, const std::string& flag) {
  const size_t at = help.find("  --" + flag + " (");
  if (at == std::string::npos) return "";
  const size_t start = help.find("\n      ", at) + 7;
  return help.substr(start, help.find('\n', start) - start);
}

// Every option a command declares (settings/option.h) is that command's flag with the
// declaration's type, default, text and check, and a config key of pipeline: the
// declarations are the one source of each surface.
TEST(CommandFlags, DeclaredOptionsAreEachCommandsFlags) {
  struct Use {
    std::string command;
    std::vector<Option> options;
  };
  const std::vector<Use> uses = {
      {"solve", SolverOptions().options()},
      {"fit_skeleton", SolverOptions().Without("mode").options()},
      {"bench", SolverOptions().Without("mode").options()},
      {"repair", RepairSolverOptions().options()},
      {"evaluate", RepairSolverOptions().options()},
      {"evaluate", SolverOptions().Only("mode").options()},
      {"pipeline", RepairSolverOptions().options()},
      {"repair", RepairSettingOptions().options()},
      {"evaluate", RepairSettingOptions().options()},
      {"pipeline", RepairSettingOptions().options()},
      {"corrupt", CorruptionSettingOptions().options()},
      {"evaluate", CorruptionSettingOptions().options()},
      {"distance", FalloffSettingOptions().options()},
      {"propagate", FalloffSettingOptions().Only("sigma,sigma_scale,eigenpairs,region,knn,falloff_kernel,"
                                                 "feature_joints,joint_weights,temporal_weight").options()},
      {"retarget", RetargetSolverOptions().options()},
      {"retarget", RetargetSettingOptions().options()},
      {"pipeline", RetargetSettingOptions().options()},
      {"pipeline", DeliverySettingOptions().options()},
      {"batch", DeliverySettingOptions().options()},
      {"propagate", SolverOptions().Only("solver,prior_weight,max_iterations,marker_weight,dls_lambda,dls_damping,"
                                         "sparse_library").options()},
      // The shared options: files, how files are read, the console.
      {"repair", FileSettingOptions().Only("subject,skeleton,markers,markerset,out_markers,out_motion,report").options()},
      {"view", FileSettingOptions().Only("markers,motion,character,out,repair_report,falloff,compare").options()},
      {"view", FileReadSettingOptions().options()},
      {"info", FileReadSettingOptions().Without("axes,marker_scale").options()},
      {"solve", ConsoleSettingOptions().Only("quiet").options()},
      {"pipeline", ConsoleSettingOptions().options()},
      // One command's knobs, and those two or three commands share.
      {"view", ViewSettingOptions().options()},
      {"bench", BenchRunSettingOptions().options()},
      {"filter", BandSettingOptions().Only("levels").options()},
      {"bands", BandSettingOptions().Only("weights").options()},
      {"distance", EditSettingOptions().Only("frame").options()},
      {"propagate", EditSettingOptions().options()},
      {"propagate", FootJointOption().options()},
      {"retarget", FootJointOption().options()},
      {"pipeline", FootJointOption().options()},
      {"retarget", RetargetRunSettingOptions().options()},
      {"joint_map", RetargetRunSettingOptions().Only("source_skin,target_skin").options()},
      {"pipeline", RetargetRunSettingOptions().Only("animation_only").options()},
      {"pipeline", TakeSettingOptions().options()},
      {"solve", FrameLimitOption().options()},
      {"retarget", FrameLimitOption().options()},
      {"solve", SolverAgreementOptions().options()}};
  for (const Use& use : uses) {
    std::string help;
    ASSERT_EQ(testing::RunCli(use.command + " --help", &help), 0) << use.command;
    const std::map<std::string, std::string> types = HelpFlagTypes(use.command);
    for (const Option& option : use.options) {
      const std::string where = use.command + " --" + option.name;
      ASSERT_EQ(types.count(option.name), 1u) << where;
      EXPECT_EQ(types.at(option.name), OptionTypeName(option.type)) << where;
      std::string shown = option.default_value;
      if (option.type == OptionType::kString) shown = "\"" + shown + "\"";
      if (option.type == OptionType::kDouble) {
        char text[32];
        std::snprintf(text, sizeof(text), "%g", std::stod(option.default_value));
        shown = text;
      }
      EXPECT_EQ(DefaultInHelp(help, option.name), shown) << where;
      // The command's own text where it declares one (pipeline's --solver), else the group's.
      const std::string text = HelpText(help, option.name);
      if (!option.unit.empty()) {
        EXPECT_THAT(text, HasSubstr("[" + option.unit + "]")) << where;
      }
      if (use.command != "pipeline" && use.command != "evaluate") {
        EXPECT_EQ(text, option.Description()) << where;
      }
      // The declaration's check, with its message, before any work.
      std::string output;
      if (!option.choices.empty()) {
        EXPECT_EQ(testing::RunCli(use.command + " --" + option.name + "=bogus_value", &output), 1) << where;
        EXPECT_THAT(output, HasSubstr("--" + option.name + ": unknown 'bogus_value' (")) << output;
      }
      if (std::isfinite(option.min)) {
        const std::string below = OptionNumberText(option.min - 1);
        EXPECT_EQ(testing::RunCli(use.command + " --" + option.name + "=" + below, &output), 1) << where;
        EXPECT_THAT(output, HasSubstr("--" + option.name + ": expected a value ")) << output;
      }
    }
  }
  // --mode only where a command reads it (solve; evaluate's leave_one_out).
  for (const char* command : {"pipeline", "repair", "fit_skeleton", "bench"}) {
    std::string output;
    EXPECT_EQ(testing::RunCli(std::string(command) + " --mode=clip", &output), 1) << command;
    EXPECT_THAT(output, HasSubstr("--mode: not a flag of `" + std::string(command) + "`")) << output;
  }
  // pipeline's config keys: every declared option, its default as --print_config writes it.
  std::string config;
  ASSERT_EQ(testing::RunCli("pipeline --print_config", &config), 0) << config;
  std::vector<Option> pipeline_options = RepairSolverOptions().options();
  pipeline_options.insert(pipeline_options.end(), RepairSettingOptions().options().begin(),
                          RepairSettingOptions().options().end());
  pipeline_options.insert(pipeline_options.end(), DeliverySettingOptions().options().begin(),
                          DeliverySettingOptions().options().end());
  for (const Option& option : pipeline_options) {
    const std::string value = option.type == OptionType::kString ? "\"" + option.default_value + "\""
                                                                 : option.default_value;
    EXPECT_THAT(config, HasSubstr("\"" + option.name + "\": " + value)) << option.name;
  }
  // A config file's bad value gets the flag's message.
  const std::string file = testing::TempPath("bad_config.json");
  testing::WriteTextFile(file, "{\"dls_damping\": \"none\"}");
  std::string output;
  EXPECT_EQ(testing::RunCli("pipeline --print_config --config=" + file, &output), 1);
  EXPECT_THAT(output, HasSubstr("--dls_damping: unknown 'none' (adaptive, fixed)")) << output;
}

// The number flags a command's --help lists (type double).
std::vector<std::string> NumberFlags(const std::string& command) {
  std::vector<std::string> flags;
  for (const auto& [name, type] : HelpFlagTypes(command)) {
    if (type == "double") flags.push_back(name);
  }
  return flags;
}

// NaN and infinities pass every `x < bound` check: each number flag of each command refuses
// them before any work, naming the flag (the probe found batch --take_timeout=nan,
// pipeline --mapping_normal_weight=nan, repair --tracker_function_tolerance=nan accepted).
TEST(CommandFlags, EveryNumberFlagRefusesNanAndInfinity) {
  size_t checked = 0;
  for (const std::string& command : Commands()) {
    const std::vector<std::string> flags = NumberFlags(command);
    for (size_t i = 0; i < flags.size(); ++i) {
      const std::string value = i % 3 == 0 ? "nan" : i % 3 == 1 ? "inf" : "-inf";
      std::string output;
      EXPECT_EQ(testing::RunCli(command + " --" + flags[i] + "=" + value, &output), 1) << command << " " << flags[i];
      EXPECT_THAT(output, HasSubstr("--" + flags[i] + ": expected a finite number")) << command << ": " << output;
      EXPECT_EQ(output.find('\n'), output.size() - 1) << output;
      ++checked;
    }
  }
  EXPECT_GE(checked, 50u);
}

}  // namespace
}  // namespace mocapsolve
