// DeliverySettings: which files a take is delivered as. `pipeline` (and `batch`, which
// passes them to its workers) writes each character with its new clip in every format of
// --formats:
//   glb  the character's glTF form (<character>.glb, or .gltf for a .gltf character):
//        the character file plus the take (io/gltf_writer.h);
//   fbx  <character>.fbx, binary FBX 7.4: the character's skeleton, skinned mesh and the
//        take (io/fbx_writer.h);
//   bvh  <character>.bvh: the take on the character's skeleton (io/bvh_writer.h).
// --animation_only applies to glb and fbx (skeleton, skin and the take, no meshes).
// Declared once; the CLI's flags, config keys and Python's keywords.
#ifndef MOCAPSOLVE_SETTINGS_DELIVERY_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_DELIVERY_SETTINGS_H_

#include <string>
#include <vector>

#include "settings/option.h"

namespace mocapsolve {

struct DeliverySettings {
  std::string formats = "glb";  // Comma-separated: glb, fbx, bvh.
};

const OptionGroup<DeliverySettings>& DeliverySettingOptions();

// The formats of `settings` in the order given ("fbx,glb" -> {"fbx", "glb"}); an error
// naming --formats when the value is not a list of them.
Status DeliveryFormats(const DeliverySettings& settings, std::vector<std::string>* formats);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_DELIVERY_SETTINGS_H_
