#include "settings/delivery_settings.h"

#include "io/comma_list.h"

namespace mocapsolve {

const OptionGroup<DeliverySettings>& DeliverySettingOptions() {
  using S = DeliverySettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .AddList(&S::formats, "formats",
               "Files written per character, comma-separated: glb (the character's glTF form, .glb or .gltf as "
               "read, with the take added), fbx (binary FBX 7.4: skeleton, skinned mesh and the take), bvh (the "
               "take on the character's skeleton). --animation_only applies to glb and fbx.",
               {"glb", "fbx", "bvh"});
  return *group;
}

Status DeliveryFormats(const DeliverySettings& settings, std::vector<std::string>* formats) {
  Status status = DeliverySettingOptions().Validate(settings);
  if (!status.ok()) return status;
  *formats = SplitCommaList(settings.formats);
  return Status::Ok();
}

}  // namespace mocapsolve
