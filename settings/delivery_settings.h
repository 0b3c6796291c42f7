// DeliverySettings: which files a take is delivered as. `pipeline` (and `batch`, which
// passes them to its workers) writes each character with its new clip in every format of
// --formats:
//   glb  the character's glTF form (<character>.glb, or .gltf for a .gltf character):
//        the character file plus the take (io/gltf_writer.h);
//   fbx  <character>.fbx, binary FBX 7.4: the character's skeleton, skinned mesh and the
//        take (io/fbx_writer.h);
//   bvh  <character>.bvh: the take on the character's skeleton (io/bvh_writer.h).
// --animation_only applies to glb and fbx (skeleton, skin and the take, no meshes).
// The clip each delivered file holds (pipeline's character files, retarget's --out and
// --out_bvh, convert's OUT) can be cut, --frames=A:B (first and last frame, both included,
// 0-based) or --seconds=A:B (the frames at times in [A, B]), either end left open ("A:",
// ":B"), and then resampled, --out_fps=R (0 keeps the rate): signal/clip_delivery.h.
// --fbx_key_tolerance=E (mm) lets the FBX writer drop keys that linear interpolation
// reproduces so that no joint or end site moves by more than E (io/fbx_writer.h); 0 keeps
// every key.
// Declared once; the CLI's flags, config keys and Python's keywords.
#ifndef MOCAPSOLVE_SETTINGS_DELIVERY_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_DELIVERY_SETTINGS_H_

#include <string>
#include <vector>

#include "settings/option.h"
#include "signal/clip_delivery.h"

namespace mocapsolve {

struct DeliverySettings {
  std::string formats = "glb";  // Comma-separated: glb, fbx, bvh.
  double out_fps = 0.0;         // Frames per second; 0 = the clip's.
  std::string frames;           // "A:B", frames of the clip; "" = all.
  std::string seconds;          // "A:B", seconds from the clip's start; "" = all.
  double fbx_key_tolerance = 0.0;  // mm; FBX key reduction (io/curve_key_reduction.h); 0 = exact.
};

const OptionGroup<DeliverySettings>& DeliverySettingOptions();

// The formats of `settings` in the order given ("fbx,glb" -> {"fbx", "glb"}); an error
// naming --formats when the value is not a list of them.
Status DeliveryFormats(const DeliverySettings& settings, std::vector<std::string>* formats);

// --frames, --seconds and --out_fps as a ClipDelivery; an error naming the option for a
// malformed range ("--frames: expected A:B ..., got '3-9'"), one whose first end is after
// its last, or both ranges given.
Status ClipDeliveryFromSettings(const DeliverySettings& settings, ClipDelivery* delivery);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_DELIVERY_SETTINGS_H_
