#include "tasks/blend_task.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "settings/method_settings.h"
#include "signal/motion_blend.h"
#include "tasks/console_text.h"

namespace mocapsolve {
namespace {

// "120" (frames) or "1.5s" (seconds at frame_rate) -> frame index.
bool ParseTime(const std::string& text, double frame_rate, int* frame) {
  if (text.empty()) return false;
  const bool seconds = text.back() == 's';
  const std::string number = seconds ? text.substr(0, text.size() - 1) : text;
  char* stop = nullptr;
  const double value = std::strtod(number.c_str(), &stop);
  if (number.empty() || *stop != '\0' || !std::isfinite(value) || value < 0.0) return false;
  const double frames = seconds ? value * frame_rate : value;
  if (!seconds && frames != std::floor(frames)) return false;
  if (frames > 1e9) return false;
  *frame = static_cast<int>(std::lround(frames));
  return true;
}

double MaxOver(const std::vector<double>& values, int first, int last) {
  double result = 0.0;
  for (int i = std::max(0, first); i <= std::min(last, static_cast<int>(values.size()) - 1); ++i) {
    result = std::max(result, values[i]);
  }
  return result;
}

Status CheckSameJoints(const BlendInputs& in) {
  const Skeleton& a = *in.skeleton_a;
  const Skeleton& b = *in.skeleton_b;
  if (a.num_joints() != b.num_joints()) {
    return Status::Error(in.b_name + ": " + std::to_string(b.num_joints()) + " joints, but " + in.a_name + " has " +
                         std::to_string(a.num_joints()));
  }
  for (int j = 0; j < a.num_joints(); ++j) {
    if (a.name(j) != b.name(j)) {
      return Status::Error(in.b_name + ": joint " + std::to_string(j) + " is '" + b.name(j) + "', " + in.a_name +
                           " has '" + a.name(j) + "'");
    }
  }
  return Status::Ok();
}

}  // namespace

Status RunBlend(const BlendInputs& inputs, const std::string& method, const BlendSettings& settings,
                const PyramidOptions& pyramid, BlendTaskResult* result) {
  Status status = BlendMethodOption().Validate(MethodSetting{method});
  if (status.ok()) status = BlendSettingOptions().Validate(settings);
  if (status.ok()) status = CheckSameJoints(inputs);
  if (!status.ok()) return status;
  const Motion& a = *inputs.a;
  const Motion& b = *inputs.b;
  BlendOptions options;
  options.method = method == "multires" ? BlendMethod::kMultiresolution : BlendMethod::kWeightedSum;
  options.pyramid = pyramid;
  const size_t colon = settings.transition.find(':');
  if (colon == std::string::npos ||
      !ParseTime(settings.transition.substr(0, colon), a.frame_rate, &options.transition_start) ||
      !ParseTime(settings.transition.substr(colon + 1), a.frame_rate, &options.transition_end)) {
    return Status::Error("--transition: expected START:END in frames (120:150) or seconds (1s:1.25s), got '" +
                         settings.transition + "'");
  }
  options.b_offset = settings.b_start >= 0 ? settings.b_start : options.transition_start;
  status = BlendMotions(a, b, options, &result->blended);
  if (!status.ok()) return Status::Error("--transition/--b_start: " + status.message());

  // Velocity jumps (skeleton units per frame): the blend around the window against the
  // largest each input has anywhere.
  const Skeleton& skeleton_a = *inputs.skeleton_a;
  const std::vector<double> jumps = VelocityJumps(skeleton_a, result->blended);
  const int s = options.transition_start, e = options.transition_end;
  const int margin = 1 << std::max(1, options.pyramid.levels == 0 ? 4 : options.pyramid.levels);
  const double blend_jump = MaxOver(jumps, s - margin, e + margin);
  const double a_jump = MaxOver(VelocityJumps(skeleton_a, a), 0, a.num_frames());
  const double b_jump = MaxOver(VelocityJumps(*inputs.skeleton_b, b), 0, b.num_frames());
  const std::string units = skeleton_a.unit().known() ? skeleton_a.unit().name : std::string("file units");
  AppendF(&result->summary,
          "%d frames, %s blend over frames %d:%d (B from frame %d)\n"
          "largest velocity jump (%s/frame): transition +-%d frames %.4g; input A %.4g, input B %.4g\n",
          result->blended.num_frames(), method.c_str(), s, e, options.b_offset, units.c_str(), margin, blend_jump,
          a_jump, b_jump);
  result->report.Add("method", method).Add("transition_start", s).Add("transition_end", e)
      .Add("b_start", options.b_offset).Add("frames", result->blended.num_frames())
      .Add("transition_velocity_jump", blend_jump).Add("a_velocity_jump", a_jump).Add("b_velocity_jump", b_jump)
      .Add("units", units);
  return Status::Ok();
}

}  // namespace mocapsolve
