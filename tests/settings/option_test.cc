// settings/option.h: the declaration's checks and messages, and the groups every surface is
// made from (their defaults are the settings structs' initializers, their names unique).
#include "settings/option.h"

#include <set>
#include <string>

#include <gtest/gtest.h>

#include "settings/batch_settings.h"
#include "settings/calibrate_settings.h"
#include "settings/convert_settings.h"
#include "settings/corruption_settings.h"
#include "settings/delivery_settings.h"
#include "settings/falloff_settings.h"
#include "settings/method_settings.h"
#include "settings/plot_settings.h"
#include "settings/propagate_settings.h"
#include "settings/repair_settings.h"
#include "settings/retarget_settings.h"
#include "settings/skeleton_fit_settings.h"
#include "settings/solver_settings.h"
#include "settings/view_page_settings.h"

namespace mocapsolve {
namespace {

struct Knobs {
  bool on = true;
  int count = 3;
  double weight = 0.25;
  std::string kind = "a";
};

OptionGroup<Knobs> KnobOptions() {
  return OptionGroup<Knobs>()
      .Add(&Knobs::on, "on", "Switch.")
      .Add(&Knobs::count, "count", "frames", "How many.", 1, 10)
      .Add(&Knobs::weight, "weight", "mm/rad", "How much.", 0)
      .Add(&Knobs::kind, "kind", "Which.", {"a", "b"});
}

std::string Message(const Status& status) { return status.ok() ? "ok" : status.message(); }

TEST(Option, DefaultsComeFromTheStructAndReadBack) {
  const OptionGroup<Knobs> group = KnobOptions();
  ASSERT_EQ(group.Names(), "on,count,weight,kind");
  EXPECT_EQ(group.options()[0].default_value, "true");
  EXPECT_EQ(group.options()[1].default_value, "3");
  EXPECT_EQ(group.options()[2].default_value, "0.25");
  EXPECT_EQ(group.options()[3].default_value, "a");
  EXPECT_EQ(group.options()[2].Description(), "How much. [mm/rad]");
  Knobs knobs;
  ASSERT_TRUE(group.Set("count", "7", &knobs).ok());
  ASSERT_TRUE(group.Set("on", "false", &knobs).ok());
  ASSERT_TRUE(group.Set("weight", "1e-06", &knobs).ok());
  ASSERT_TRUE(group.Set("kind", "b", &knobs).ok());
  EXPECT_EQ(knobs.count, 7);
  EXPECT_FALSE(knobs.on);
  EXPECT_EQ(knobs.weight, 1e-6);
  EXPECT_EQ(knobs.kind, "b");
  EXPECT_EQ(group.Get("weight", knobs), "1e-06");
  EXPECT_EQ(group.Get("on", knobs), "false");
}

TEST(Option, EveryBadValueIsOneLineNamingTheOption) {
  const OptionGroup<Knobs> group = KnobOptions();
  Knobs knobs;
  EXPECT_EQ(Message(group.Set("kind", "c", &knobs)), "--kind: unknown 'c' (a, b)");
  EXPECT_EQ(Message(group.Set("count", "1.5", &knobs)), "--count: expected an integer, got '1.5'");
  EXPECT_EQ(Message(group.Set("count", "0", &knobs)), "--count: expected a value in [1, 10], got 0");
  EXPECT_EQ(Message(group.Set("count", "99999999999", &knobs)), "--count: expected an integer, got '99999999999'");
  EXPECT_EQ(Message(group.Set("weight", "-1", &knobs)), "--weight: expected a value >= 0, got -1");
  EXPECT_EQ(Message(group.Set("weight", "nan", &knobs)), "--weight: expected a finite number, got 'nan'");
  EXPECT_EQ(Message(group.Set("weight", "inf", &knobs)), "--weight: expected a finite number, got 'inf'");
  EXPECT_EQ(Message(group.Set("weight", "2x", &knobs)), "--weight: expected a number, got '2x'");
  EXPECT_EQ(Message(group.Set("on", "maybe", &knobs)), "--on: expected true or false, got 'maybe'");
  EXPECT_EQ(Message(group.Set("colour", "red", &knobs)), "--colour: not an option here");
  // Nothing was stored by a failed Set.
  EXPECT_EQ(knobs.kind, "a");
  EXPECT_EQ(knobs.count, 3);
  // A struct filled directly (as Python does) gets the same messages.
  knobs.kind = "z";
  EXPECT_EQ(Message(group.Validate(knobs)), "--kind: unknown 'z' (a, b)");
}

// A list option: comma-separated choices, at least one, none twice; the message names the
// option and the item.
TEST(Option, AListOptionChecksEachItem) {
  struct Outputs {
    std::string formats = "glb";
  };
  const OptionGroup<Outputs> group = OptionGroup<Outputs>().AddList(&Outputs::formats, "formats", "Files.",
                                                                    {"glb", "fbx", "bvh"});
  Outputs outputs;
  EXPECT_EQ(Message(group.Set("formats", "glb,fbx,bvh", &outputs)), "ok");
  EXPECT_EQ(outputs.formats, "glb,fbx,bvh");
  EXPECT_EQ(Message(group.Set("formats", "bvh", &outputs)), "ok");
  EXPECT_EQ(Message(group.Set("formats", "glb,obj", &outputs)), "--formats: unknown 'obj' (glb, fbx, bvh)");
  EXPECT_EQ(Message(group.Set("formats", "glb,,fbx", &outputs)), "--formats: unknown '' (glb, fbx, bvh)");
  EXPECT_EQ(Message(group.Set("formats", "glb,fbx,", &outputs)), "--formats: unknown '' (glb, fbx, bvh)");
  EXPECT_EQ(Message(group.Set("formats", "fbx,glb,fbx", &outputs)), "--formats: 'fbx' given twice in 'fbx,glb,fbx'");
  EXPECT_EQ(Message(group.Set("formats", "", &outputs)),
            "--formats: expected a comma-separated list of glb, fbx, bvh");
  EXPECT_EQ(outputs.formats, "bvh");
  // The delivery settings' list, in the order given.
  DeliverySettings delivery;
  delivery.formats = "fbx,glb";
  std::vector<std::string> formats;
  ASSERT_EQ(Message(DeliveryFormats(delivery, &formats)), "ok");
  EXPECT_EQ(formats, (std::vector<std::string>{"fbx", "glb"}));
  delivery.formats = "GLB";
  EXPECT_EQ(Message(DeliveryFormats(delivery, &formats)), "--formats: unknown 'GLB' (glb, fbx, bvh)");
}

TEST(Option, ACommandDeclaresItsOwnDefaultOrAPart) {
  const OptionGroup<Knobs> group = KnobOptions().WithDefault("kind", "b", "Which, here.");
  EXPECT_EQ(group.options()[3].default_value, "b");
  EXPECT_EQ(group.options()[3].help, "Which, here.");
  EXPECT_EQ(group.Defaults().kind, "b");
  EXPECT_EQ(KnobOptions().Defaults().kind, "a");
  EXPECT_EQ(KnobOptions().Only("kind,on").Names(), "on,kind");
  EXPECT_EQ(KnobOptions().Without("kind,on").Names(), "count,weight");
}

TEST(Option, NumbersAreWrittenAsPeopleWriteThem) {
  EXPECT_EQ(OptionNumberText(20.0), "20");
  EXPECT_EQ(OptionNumberText(1e-6), "1e-06");
  EXPECT_EQ(OptionNumberText(0.1), "0.1");
  EXPECT_EQ(OptionNumberText(-1.0), "-1");
  const double third = 1.0 / 3.0;
  EXPECT_EQ(std::stod(OptionNumberText(third)), third);
}

// Each declared group: unique names, a help text, defaults that pass their own checks and
// are the settings structs' initializers (so the struct, the flags and Python agree).
template <class S>
void ExpectWellDeclared(const OptionGroup<S>& group, const S& expected_defaults) {
  std::set<std::string> names;
  const S defaults = group.Defaults();
  for (const Option& option : group.options()) {
    EXPECT_TRUE(names.insert(option.name).second) << option.name;
    EXPECT_FALSE(option.help.empty()) << option.name;
    EXPECT_TRUE(option.Check(option.default_value).ok()) << option.name << ": " << option.default_value;
    EXPECT_EQ(group.Get(option.name, defaults), group.Get(option.name, expected_defaults)) << option.name;
  }
  EXPECT_TRUE(group.Validate(defaults).ok());
}

TEST(Option, TheDeclaredGroupsAreWellFormed) {
  ExpectWellDeclared(SolverOptions(), SolverSettings());
  EXPECT_EQ(SolverOptions().options().size(), 26u);
  SolverSettings repair_defaults;
  repair_defaults.solver = "dls";
  ExpectWellDeclared(RepairSolverOptions(), repair_defaults);
  ExpectWellDeclared(RetargetSolverOptions(), RetargetSettings());
  ExpectWellDeclared(RetargetSettingOptions(), RetargetSettings());
  ExpectWellDeclared(RepairSettingOptions(), RepairSettings());
  EXPECT_EQ(RepairSettingOptions().options().size(), 30u);
  ExpectWellDeclared(CorruptionSettingOptions(), CorruptionSettings());
  ExpectWellDeclared(FalloffSettingOptions(), FalloffSettings());
  ExpectWellDeclared(DeliverySettingOptions(), DeliverySettings());
  ExpectWellDeclared(SkeletonFitSettingOptions(), SkeletonFitSettings());
  ExpectWellDeclared(CalibrateSettingOptions(), CalibrateSettings());
  ExpectWellDeclared(ConvertSettingOptions(), ConvertSettings());
  ExpectWellDeclared(BatchSettingOptions(), BatchSettings());
  ExpectWellDeclared(PropagateSettingOptions(), PropagateSettings());
  ExpectWellDeclared(ViewPageOption(), ViewPageSetting());
  ExpectWellDeclared(SolvePlotOption(), PlotSetting());
  ExpectWellDeclared(DistancePlotOption(), PlotSetting());
}

// Each command's own --method and --view: one name, the command's own default and check.
TEST(Option, ACommandsOwnDefaultIsItsDeclaration) {
  EXPECT_EQ(DefaultMethod(EvaluateMethodOption()), "repair");
  EXPECT_EQ(DefaultMethod(PropagateMethodOption()), "green");
  EXPECT_EQ(DefaultMethod(DistanceMethodOption()), "green");
  EXPECT_EQ(DefaultMethod(BlendMethodOption()), "multires");
  EXPECT_EQ(TakeViewPageOption().Defaults().view, "auto");
  EXPECT_EQ(ViewPageOption().Defaults().view, "");
  EXPECT_EQ(PropagateMethodOption().Validate(MethodSetting{"multires"}).message(),
            "--method: unknown 'multires' (green, harmonic, spline)");
  EXPECT_TRUE(BlendMethodOption().Validate(MethodSetting{"multires"}).ok());
}

TEST(Option, TheSettingsConversionsCheckAgainstTheDeclarations) {
  SolverSettings settings;
  settings.max_iterations = 0;
  MarkerSolveOptions options;
  EXPECT_EQ(Message(MarkerSolveOptionsFromSettings(settings, LengthUnit(), &options)),
            "--max_iterations: expected a value >= 1, got 0");
  settings = SolverSettings();
  settings.mode = "batch";
  ClipSolveOptions clip;
  EXPECT_EQ(Message(ClipSolveOptionsFromSettings(settings, &clip)), "--mode: unknown 'batch' (frame, clip)");
  RetargetSettings retarget;
  retarget.solver = "newton";
  CharacterRetargetOptions retarget_options;
  EXPECT_EQ(Message(RetargetOptionsFromSettings(retarget, &retarget_options)),
            "--solver: unknown 'newton' (dls, dls_generic, ceres)");
}

}  // namespace
}  // namespace mocapsolve
