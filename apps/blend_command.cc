// mocapsolve blend --a=A.bvh --b=B.bvh --transition=S:E [--method=multires|weighted]
// --out=OUT.bvh: a transition from A to B (Huang, Boulic & Thalmann, section 3).
// signal/motion_blend.h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "apps/command.h"
#include "apps/pyramid_flags.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "settings/method_settings.h"
#include "io/bvh_writer.h"
#include "io/motion_file.h"
#include "signal/motion_blend.h"

DEFINE_string(a, "", "The first motion (.bvh, or .amc with --skeleton).");
DEFINE_string(b, "", "The second motion, same skeleton (joint names and order) as --a.");
DEFINE_string(transition, "", "START:END of the transition window, in frames of --a (0-based), "
              "or in seconds of --a with an 's' suffix on both (1.5s:2s).");
DEFINE_int32(b_start, -1, "Frame of --a at which --b's frame 0 lies (-1: the transition start). "
             "If --b ends before --a, --b lies inside --a and the blend returns to --a.");
DEFINE_int32(blend_levels, 4, "Pyramid levels of the multires blend (0 = as many as fit).");

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

Status RunBlend(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (FLAGS_a.empty() || FLAGS_b.empty() || FLAGS_out.empty() || FLAGS_transition.empty()) {
    return Status::Error("--a, --b, --transition and --out are required");
  }
  if (!IsTextOutputPath(FLAGS_out, ".bvh")) return Status::Error(FLAGS_out + ": expected a .bvh");
  Status status = CheckNotAnInput(FLAGS_out, FLAGS_a);
  if (status.ok()) status = CheckNotAnInput(FLAGS_out, FLAGS_b);
  if (!status.ok()) return status;
  BlendOptions options;
  MethodSetting method;
  ReadOptionFlags(BlendMethodOption(), &method);
  if (method.method == "multires") {
    options.method = BlendMethod::kMultiresolution;
  } else if (method.method == "weighted") {
    options.method = BlendMethod::kWeightedSum;
  } else {
    return Status::Error("--method: unknown '" + method.method + "' (multires, weighted)");
  }
  if (FLAGS_blend_levels < 0 || FLAGS_blend_levels > 30) {
    return Status::Error("--blend_levels must be in [0, 30]");
  }
  status = PyramidOptionsFromFlags(FLAGS_blend_levels, &options.pyramid);
  if (!status.ok()) return status;

  Skeleton skeleton_a, skeleton_b;
  Motion a, b, blended;
  status = LoadMotion(FLAGS_a, &skeleton_a, &a);
  if (status.ok()) status = RequireFrames(FLAGS_a, a);
  if (!status.ok()) return status;
  status = LoadMotion(FLAGS_b, &skeleton_b, &b);
  if (status.ok()) status = RequireFrames(FLAGS_b, b);
  if (!status.ok()) return status;
  if (skeleton_a.num_joints() != skeleton_b.num_joints()) {
    return Status::Error(FLAGS_b + ": " + std::to_string(skeleton_b.num_joints()) +
                         " joints, but " + FLAGS_a + " has " +
                         std::to_string(skeleton_a.num_joints()));
  }
  for (int j = 0; j < skeleton_a.num_joints(); ++j) {
    if (skeleton_a.name(j) != skeleton_b.name(j)) {
      return Status::Error(FLAGS_b + ": joint " + std::to_string(j) + " is '" + skeleton_b.name(j) +
                           "', " + FLAGS_a + " has '" + skeleton_a.name(j) + "'");
    }
  }
  const size_t colon = FLAGS_transition.find(':');
  if (colon == std::string::npos ||
      !ParseTime(FLAGS_transition.substr(0, colon), a.frame_rate, &options.transition_start) ||
      !ParseTime(FLAGS_transition.substr(colon + 1), a.frame_rate, &options.transition_end)) {
    return Status::Error("--transition: expected START:END in frames (120:150) or seconds "
                         "(1s:1.25s), got '" + FLAGS_transition + "'");
  }
  options.b_offset = FLAGS_b_start >= 0 ? FLAGS_b_start : options.transition_start;
  status = BlendMotions(a, b, options, &blended);
  if (!status.ok()) return Status::Error("--transition/--b_start: " + status.message());
  status = WriteBvh(FLAGS_out, skeleton_a, blended);
  if (!status.ok()) return status;

  // Velocity jumps (skeleton units per frame): the blend around the window against the
  // largest each input has anywhere.
  const std::vector<double> jumps = VelocityJumps(skeleton_a, blended);
  const int s = options.transition_start, e = options.transition_end;
  const int margin = 1 << std::max(1, options.pyramid.levels == 0 ? 4 : options.pyramid.levels);
  const double blend_jump = MaxOver(jumps, s - margin, e + margin);
  const double a_jump = MaxOver(VelocityJumps(skeleton_a, a), 0, a.num_frames());
  const double b_jump = MaxOver(VelocityJumps(skeleton_b, b), 0, b.num_frames());
  const std::string units =
      skeleton_a.unit().known() ? skeleton_a.unit().name : std::string("file units");
  std::printf("wrote %s: %d frames, %s blend over frames %d:%d (B from frame %d)\n"
              "largest velocity jump (%s/frame): transition +-%d frames %.4g; input A %.4g, "
              "input B %.4g\n",
              FLAGS_out.c_str(), blended.num_frames(), method.method.c_str(), s, e,
              options.b_offset, units.c_str(), margin, blend_jump, a_jump, b_jump);
  JsonObject report;
  report.Add("a", FLAGS_a).Add("b", FLAGS_b).Add("out", FLAGS_out).Add("method", method.method)
      .Add("transition_start", s).Add("transition_end", e).Add("b_start", options.b_offset)
      .Add("frames", blended.num_frames()).Add("transition_velocity_jump", blend_jump)
      .Add("a_velocity_jump", a_jump).Add("b_velocity_jump", b_jump)
      .Add("units", units);
  return WriteReport(report);
}

}  // namespace

extern const Command kBlendCommand = {
    "blend", "transition from one motion to another (multiresolution or weighted sum)",
    "mocapsolve blend --a=A.bvh --b=B.bvh --transition=START:END [--method=multires|weighted]\n"
    "    --out=OUT.bvh\n\n"
    "Plays A, then B from A's frame --b_start (default START), blending over the window\n"
    "START:END (frames of A, 0-based, or seconds with an 's' suffix). weighted: the plain\n"
    "ease-in/ease-out weighted sum (Huang, Boulic & Thalmann, eq. 6); multires: the same\n"
    "weights applied per band of Laplacian pyramids (section 3), which spreads each band's\n"
    "seam over its own wavelength. Rotations are blended as sign-continuous quaternions\n"
    "(B's sign matched to A's at START) and renormalized (nlerp). Prints the largest\n"
    "velocity jump near the window and in each input.",
    __FILE__, RunBlend,
    "out,skeleton,skeleton_units,amc_fps,animation,sample_fps,report,quiet",
    {PyramidSettingOptions().options(), BlendMethodOption().options()}};

}  // namespace mocapsolve
