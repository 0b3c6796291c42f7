// Mesh retargeting (thesis chapter 4): a source motion (skinned glTF, or any skeleton
// motion with the target's mesh bound to it) onto a skinned glTF character.
#include "io/gltf_reader.h"
#include "io/bvh_writer.h"
#include "io/gltf_writer.h"
#include "io/motion_file.h"
#include "settings/retarget_settings.h"
#include "problems/retarget/retarget_character.h"
#include "python/bindings.h"
#include "python/keyword_docs.h"

namespace mocapsolve::python {

void BindRetarget(py::module_& m) {
  py::class_<RetargetSettings> settings(m, "RetargetSettings",
      "The retargeting options, one per flag of `mocapsolve retarget`/`pipeline` (same names and\n"
      "defaults; solver is dls | dls_generic | ceres). retarget() takes them as keywords.");
  settings.def(py::init<>(), "Every option at the CLI's default.");
#define MOCAPSOLVE_FIELD(name) settings.def_readwrite(#name, &RetargetSettings::name)
  MOCAPSOLVE_FIELD(solver); MOCAPSOLVE_FIELD(limit_weight); MOCAPSOLVE_FIELD(joint_map);
  MOCAPSOLVE_FIELD(plant_feet); MOCAPSOLVE_FIELD(plant_weight); MOCAPSOLVE_FIELD(plant_height);
  MOCAPSOLVE_FIELD(plant_speed); MOCAPSOLVE_FIELD(foot_joints); MOCAPSOLVE_FIELD(subsample);
  MOCAPSOLVE_FIELD(iterations); MOCAPSOLVE_FIELD(lambda); MOCAPSOLVE_FIELD(blend_mask);
  MOCAPSOLVE_FIELD(mapping_normal_weight); MOCAPSOLVE_FIELD(transfer_normals);
  MOCAPSOLVE_FIELD(normal_weight); MOCAPSOLVE_FIELD(smoothness); MOCAPSOLVE_FIELD(contact_height);
  MOCAPSOLVE_FIELD(ceres_trust_radius);
#undef MOCAPSOLVE_FIELD
  settings.def("validate", [](const RetargetSettings& s) {
        CharacterRetargetOptions options;
        ThrowIfError(RetargetOptionsFromSettings(s, &options));
      }, "Raises ValueError (the CLI's message) if a value is invalid.");
  m.attr("RETARGET_OPTION_NAMES") = RetargetSolverOptions().Names() + "," + RetargetSettingOptions().Names() + ",foot_joints";

  m.def("retarget", [](const std::string& source, const std::string& target, py::object skeleton,
                       bool source_mesh, const std::string& source_animation, double frame_rate,
                       int max_frames, double amc_fps, const std::string& out, const std::string& animation_name,
                       bool animation_only, const py::kwargs& keywords) {
        RetargetSettings retarget_settings;
        ApplyKeywords(keywords, {py::cast(&retarget_settings, py::return_value_policy::reference)},
                      RetargetSolverOptions().Names() + "," + RetargetSettingOptions().Names() + ",foot_joints");
        CharacterRetargetOptions options;
        ThrowIfError(RetargetOptionsFromSettings(retarget_settings, &options));
        if (max_frames < 0) throw py::value_error("--max_frames: must be >= 0");
        if (animation_only && (out.empty() || FileExtension(out) == ".bvh")) {
          throw py::value_error("--animation_only: applies to a .glb/.gltf --out");
        }
        RequireReadable(source);
        RequireReadable(target);
        const std::string skeleton_path = skeleton.is_none() ? std::string() : std::string(py::str(skeleton));
        GltfDocument target_document;
        auto target_character = std::make_shared<GltfCharacter>();
        GltfCharacter source_character;
        Skeleton source_skeleton;
        Motion clip;
        CharacterRetargetResult retarget;
        const std::string source_extension = FileExtension(source);
        const bool use_source_mesh = (source_extension == ".glb" || source_extension == ".gltf") && source_mesh;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = GltfDocument::Read(target, &target_document);
          if (status.ok()) {
            status = ReadGltfCharacter(target_document, GltfReadOptions(), target_character.get());
            if (!status.ok()) status = Status::Error("--target: " + status.message());
          }
          if (status.ok() && use_source_mesh) {
            GltfDocument source_document;
            status = GltfDocument::Read(source, &source_document);
            if (status.ok()) status = ReadGltfCharacter(source_document, GltfReadOptions(), &source_character);
            GltfAnimationOptions animation_options;
            animation_options.animation = source_animation;
            animation_options.frame_rate = frame_rate;
            if (status.ok()) status = ReadGltfAnimation(source_document, source_character, animation_options, &clip);
          } else if (status.ok()) {
            MotionFileOptions motion_options;
            motion_options.skeleton_path = skeleton_path;
            motion_options.amc_frame_rate = amc_fps;
            motion_options.animation = source_animation;
            motion_options.sample_rate = frame_rate;
            status = ReadMotionFile(source, motion_options, &source_skeleton, &clip);
          }
          if (status.ok() && clip.num_frames() == 0) status = Status::Error(source + ": the animation has no frames");
          if (status.ok()) {
            if (max_frames > 0 && clip.num_frames() > max_frames) clip.frames.resize(max_frames);
            RetargetCharacter source_view;
            if (use_source_mesh) {
              source_view = {&source_character.skeleton, &source_character.mesh, source_character.bind_pose,
                             source_character.rest_pose};
            } else {
              source_view.skeleton = &source_skeleton;
            }
            const RetargetCharacter target_view = {&target_character->skeleton, &target_character->mesh,
                                                   target_character->bind_pose, target_character->rest_pose};
            status = RetargetMotionOntoCharacter(source_view, clip, target_view, options, &retarget);
            if (!status.ok()) status = Status::Error(source + " -> " + target + ": " + status.message());
          }
          if (status.ok() && !out.empty()) {
            if (FileExtension(out) == ".bvh") {
              status = WriteBvh(out, target_character->skeleton, retarget.clip.motion);
            } else {
              const std::string name = animation_name.empty()
                                           ? "retargeted from " + (source_animation.empty()
                                                                       ? source.substr(source.find_last_of('/') + 1)
                                                                       : source_animation)
                                           : animation_name;
              GltfWriteOptions write_options;
              write_options.animation_only = animation_only;
              status = WriteGltfWithAnimation(target_document, *target_character, retarget.clip.motion, name, out,
                                              write_options);
            }
          }
        }
        ThrowIfError(status);
        const RetargetClipResult& result = retarget.clip;
        py::dict report;
        report["source_kind"] = retarget.skeleton_only ? "skeleton" : "mesh";
        report["frames"] = result.motion.num_frames();
        report["mapped_joints"] = retarget.joint_map.num_mapped();
        report["height_ratio"] = retarget.setup.scale;
        report["sigma_m"] = result.sigma;
        report["mean_position_error_fraction_of_height"] = result.mean_position_error;
        report["max_position_error_fraction_of_height"] = result.max_position_error;
        report["mean_normal_error_deg"] = result.mean_normal_error_deg;
        report["mean_final_cost"] = result.mean_final_cost;
        report["plant_joints"] = retarget.plant_joints;
        report["source_plant_skating_cm_per_s"] = retarget.source_plant_skating_cm_s;
        report["result_plant_skating_cm_per_s"] = retarget.result_plant_skating_cm_s;
        report["solve_seconds"] = result.solve_seconds;
        report["notes"] = retarget.notes;
        return py::make_tuple(target_character, result.motion, report);
      }, py::arg("source"), py::arg("target"), py::kw_only(), py::arg("skeleton") = py::none(),
      py::arg("source_mesh") = true, py::arg("source_animation") = "", py::arg("frame_rate") = 0.0,
      py::arg("max_frames") = 0, py::arg("amc_fps") = 120.0, py::arg("out") = "", py::arg("animation_name") = "",
      py::arg("animation_only") = false,
      (std::string(R"doc(Retargets a source motion onto a skinned glTF character, as `mocapsolve retarget`
(thesis chapter 4). source: a skinned .glb/.gltf (its mesh tracked unless
source_mesh=False) or a skeleton motion (.bvh, .amc with skeleton= its .asf, .fbx);
target: a .glb/.gltf character. out: also write a .glb/.gltf (the target plus the new
animation) or .bvh. source_animation: the source file's clip (a name or index; glTF/FBX);
frame_rate: resample the source to this rate (0 = its own); max_frames: only the first N
frames (0 = all); amc_fps: an .amc's frame rate (default 120); animation_name: the new
clip's name in the written glTF ('' = 'retargeted from <source clip>'); animation_only:
write the glTF out as the target's skeleton, skin and the new animation only, no meshes
(as the CLI's --animation_only).
Keywords: the RetargetSettings (solver='dls', iterations=10,
lambda=5, subsample=128, plant_feet=True, joint_map='map.json', ...).
Returns (target character, motion on the target skeleton, report dict). Releases the GIL.)doc") +
       KeywordDefaults("Retarget keywords and defaults (RetargetSettings)", py::cast(RetargetSettings()),
                       RetargetSolverOptions().Names() + "," + RetargetSettingOptions().Names() + ",foot_joints")).c_str());
}

}  // namespace mocapsolve::python
