#include "settings/method_settings.h"

namespace mocapsolve {
namespace {

using Group = OptionGroup<MethodSetting>;

const Group* MethodOption(const char* default_value, const char* help, std::vector<std::string> choices) {
  return new Group(Group().Add(&MethodSetting::method, "method", help, std::move(choices))
                       .WithDefault("method", default_value));
}

}  // namespace

const Group& EvaluateMethodOption() {
  static const Group* const group = MethodOption(
      "repair",
      "repair: damage the markers and score repair against the usual fills (Table 1); leave_one_out: predict each "
      "marker from the solve of the others, on the take as it is; small_errors: recall and precision of the "
      "repair's detections on 1-4 cm jumps and jitter; retarget: --motion onto each --target character, limb "
      "directions, skate, penetration and coverage.",
      {"repair", "leave_one_out", "small_errors", "retarget"});
  return *group;
}

const Group& PropagateMethodOption() {
  static const Group* const group = MethodOption(
      "green", "green | harmonic | spline: the falloff that carries the edit to the other frames.",
      {"green", "harmonic", "spline"});
  return *group;
}

const Group& DistanceMethodOption() {
  // A comma-separated list: checked by the distance task (each name, no repeats).
  static const Group* const group = MethodOption(
      "green",
      "green | diffusion | isomap, comma-separated for several: the distances to compute (the first fills "
      "distance,weight; the others add columns).",
      {});
  return *group;
}

const Group& BlendMethodOption() {
  static const Group* const group = MethodOption(
      "multires", "multires (per-band weighted sum, section 3) or weighted (plain weighted sum, eq. 6).",
      {"multires", "weighted"});
  return *group;
}

}  // namespace mocapsolve
