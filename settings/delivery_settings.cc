#include "settings/delivery_settings.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "io/comma_list.h"

namespace mocapsolve {

const OptionGroup<DeliverySettings>& DeliverySettingOptions() {
  using S = DeliverySettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .AddList(&S::formats, "formats",
               "Files written per character, comma-separated: glb (the character's glTF form, .glb or .gltf as "
               "read, with the take added), fbx (binary FBX 7.4: skeleton, skinned mesh and the take), bvh (the "
               "take on the character's skeleton). --animation_only applies to glb and fbx.",
               {"glb", "fbx", "bvh"})
      .Add(&S::out_fps, "out_fps", "fps",
           "Resample each delivered clip to this rate (an engine's 30 or 60): rotations by slerp, translations "
           "linearly, after --frames/--seconds; 0 keeps the clip's rate.", 0.0)
      .Add(&S::frames, "frames",
           "Deliver frames A:B of the clip only (first and last, both included, 0-based; 'A:' to the end, ':B' from "
           "the start); \"\" = all.")
      .Add(&S::seconds, "seconds",
           "Deliver the frames at times A:B seconds from the clip's start only ('A:' to the end, ':B' from the "
           "start); \"\" = all. Not with --frames.")
      .Add(&S::fbx_key_tolerance, "fbx_key_tolerance", "mm",
           "FBX files: drop the keys that linear interpolation between the kept ones reproduces so that no joint "
           "or end site moves by more than this distance (each joint's curves get a share of it, as a DCC "
           "tool's key reducer with a bound). FBX stores a time with every key of every curve; 0.05 mm made "
           "animation-only files of 120 fps takes 3-22 % smaller (largest error measured 0.012 mm). 0 keeps "
           "every frame's key (exact).", 0.0, 1000.0);
  return *group;
}

Status DeliveryFormats(const DeliverySettings& settings, std::vector<std::string>* formats) {
  Status status = DeliverySettingOptions().Validate(settings);
  if (!status.ok()) return status;
  *formats = SplitCommaList(settings.formats);
  return Status::Ok();
}

namespace {

// One end of "A:B": "" (open), else a number (a whole one for frames), >= 0.
bool ParseEnd(const std::string& text, bool whole, bool* given, double* value) {
  *given = !text.empty();
  if (text.empty()) return true;
  char* end = nullptr;
  errno = 0;
  *value = std::strtod(text.c_str(), &end);
  if (errno != 0 || end != text.c_str() + text.size() || !std::isfinite(*value) || *value < 0) return false;
  if (whole && (*value != std::floor(*value) || *value > 2147483647.0)) return false;
  return text.find_first_of("xXpP") == std::string::npos;  // No hexadecimal.
}

Status ParseRange(const std::string& name, const std::string& text, bool whole, ClipRange* range) {
  range->option = "--" + name + "=" + text;
  const size_t colon = text.find(':');
  if (colon == std::string::npos || text.find(':', colon + 1) != std::string::npos ||
      !ParseEnd(text.substr(0, colon), whole, &range->has_first, &range->first) ||
      !ParseEnd(text.substr(colon + 1), whole, &range->has_last, &range->last)) {
    return Status::Error("--" + name + ": expected A:B (" +
                         (whole ? "first and last frame, whole numbers >= 0" : "seconds >= 0") +
                         "; either may be left out), got '" + text + "'");
  }
  if (range->has_first && range->has_last && range->first > range->last) {
    return Status::Error("--" + name + ": the first end is after the last in '" + text + "'");
  }
  range->unit = whole ? ClipRange::Unit::kFrames : ClipRange::Unit::kSeconds;
  return Status::Ok();
}

}  // namespace

Status ClipDeliveryFromSettings(const DeliverySettings& settings, ClipDelivery* delivery) {
  Status status = DeliverySettingOptions().Validate(settings);
  if (!status.ok()) return status;
  *delivery = ClipDelivery();
  delivery->out_fps = settings.out_fps;
  delivery->fbx_key_tolerance_mm = settings.fbx_key_tolerance;
  if (!settings.frames.empty() && !settings.seconds.empty()) {
    return Status::Error("--frames and --seconds: give one range, not both");
  }
  if (!settings.frames.empty()) return ParseRange("frames", settings.frames, true, &delivery->range);
  if (!settings.seconds.empty()) return ParseRange("seconds", settings.seconds, false, &delivery->range);
  return Status::Ok();
}

}  // namespace mocapsolve
