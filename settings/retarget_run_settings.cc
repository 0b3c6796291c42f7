#include "settings/retarget_run_settings.h"

namespace mocapsolve {

const OptionGroup<RetargetRunSettings>& RetargetRunSettingOptions() {
  using S = RetargetRunSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::source_animation, "source_animation", "Animation of the source, by name or index (default: the first).")
      .Add(&S::source_skin, "source_skin", "Skin of the source file (name or index; default: skin 0).")
      .Add(&S::target_skin, "target_skin", "Skin of the target file (name or index; default: skin 0).")
      .Add(&S::source_mesh, "source_mesh",
           "Track a skinned glTF source's own mesh; false: treat it as a skeleton only (the target's mesh is bound "
           "to its skeleton, as for BVH/AMC/FBX).")
      .Add(&S::frame_rate, "frame_rate", "Hz", "Sampling rate of the source animation; 0 = its key rate.", 0)
      .Add(&S::loop, "loop", "", "Repeat the source clip N times (timing long clips).", 1, 1000)
      .Add(&S::animation_name, "animation_name",
           "Name of the new animation in --out (.glb/.gltf); default: 'retargeted from <source animation or "
           "file>'.")
      .Add(&S::animation_only, "animation_only",
           "Write each retargeted .glb/.gltf as an animation-only glTF: the character's skeleton nodes (same names "
           "and rest transforms), its skin and the new animation, without meshes, materials or images; Blender "
           "(scripts/apply_animation_gltf.py) and three.js play it on the character file they already have.")
      .Add(&S::stage_times, "stage_times",
           "Time FK, skinning, Jacobian and solve separately (dls only; the report gets each stage's share of an "
           "iteration, thesis Table 3).");
  return *group;
}

}  // namespace mocapsolve
