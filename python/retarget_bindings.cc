// Mesh retargeting (thesis chapter 4): a source motion (skinned glTF, or any skeleton
// motion with the target's mesh bound to it) onto a skinned glTF character.
#include "io/gltf_reader.h"
#include "io/motion_file.h"
#include "settings/delivery_settings.h"
#include "settings/retarget_settings.h"
#include "problems/retarget/retarget_character.h"
#include "settings/file_read_settings.h"
#include "settings/frame_limit_settings.h"
#include "settings/retarget_run_settings.h"
#include "python/bindings.h"
#include "python/keyword_docs.h"
#include "tasks/joint_map_task.h"
#include "tasks/retarget_task.h"

namespace mocapsolve::python {

void BindRetarget(py::module_& m) {
  py::class_<RetargetSettings> settings(m, "RetargetSettings",
      "The retargeting options, one per flag of `mocapsolve retarget`/`pipeline` (same names and\n"
      "defaults; solver is dls | dls_generic | ceres). retarget() takes them as keywords.");
  settings.def(py::init<>(), "Every option at the CLI's default.");
  BindOptionFields(settings, RetargetSolverOptions());
  BindOptionFields(settings, RetargetSettingOptions());
  settings.def_readwrite("foot_joints", &RetargetSettings::foot_joints);  // Not a declared option of this group.
  settings.def("validate", [](const RetargetSettings& s) {
        CharacterRetargetOptions options;
        ThrowIfError(RetargetOptionsFromSettings(s, &options));
      }, "Raises ValueError (the CLI's message) if a value is invalid.");
  m.attr("RETARGET_OPTION_NAMES") = RetargetSolverOptions().Names() + "," + RetargetSettingOptions().Names() + ",foot_joints";

  m.def("retarget", [](const std::string& source, const std::string& target, py::object skeleton,
                       bool source_mesh, const std::string& source_animation, const std::string& source_skin,
                       const std::string& target_skin, double frame_rate, int max_frames, double amc_fps,
                       const std::string& out, const std::string& animation_name, bool animation_only,
                       const py::kwargs& keywords) {
        RetargetConfig config;
        DeliverySettings delivery;  // Its --frames, --seconds, --out_fps (not pipeline's --formats).
        const std::string names = RetargetSolverOptions().Names() + "," + RetargetSettingOptions().Names() +
                                  ",foot_joints," + DeliverySettingOptions().Without("formats").Names();
        if (keywords.contains("formats")) throw py::type_error("unexpected keyword argument 'formats' (options: " + names + ")");
        ApplyKeywords(keywords, {py::cast(&config.retarget, py::return_value_policy::reference),
                                 py::cast(&delivery, py::return_value_policy::reference)}, names);
        CharacterRetargetOptions checked;  // Option errors before the files'.
        ThrowIfError(RetargetOptionsFromSettings(config.retarget, &checked));
        ThrowIfError(ClipDeliveryFromSettings(delivery, &config.delivery));
        if (animation_only && (out.empty() || FileExtension(out) == ".bvh")) {
          throw py::value_error("--animation_only: applies to a .glb/.gltf --out");
        }
        RequireReadable(source);
        RequireReadable(target);
        RetargetInputs inputs;
        inputs.source = source;
        inputs.target = target;
        inputs.skeleton = skeleton.is_none() ? std::string() : std::string(py::str(skeleton));
        inputs.source_mesh = source_mesh;
        inputs.source_animation = source_animation;
        inputs.source_skin = source_skin;
        inputs.target_skin = target_skin;
        inputs.frame_rate = frame_rate;
        inputs.max_frames = max_frames;
        inputs.amc_fps = amc_fps;
        auto task = std::make_shared<RetargetTaskResult>();
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = RunRetarget(inputs, config, nullptr, task.get());
          if (status.ok() && !out.empty()) {
            status = WriteRetargeted(out, *task, RetargetAnimationName(inputs, animation_name), animation_only,
                                     config.delivery.fbx_key_tolerance_mm);
          }
        }
        ThrowIfError(status);
        auto target_character = std::make_shared<GltfCharacter>(std::move(task->target));
        return py::make_tuple(target_character, std::move(task->delivered), ReportToPython(task->report));
      }, py::arg("source"), py::arg("target"), py::kw_only(), py::arg("skeleton") = py::none(),
      py::arg("source_mesh") = DeclaredDefault(RetargetRunSettingOptions(), "source_mesh"),
      py::arg("source_animation") = DeclaredDefault(RetargetRunSettingOptions(), "source_animation"),
      py::arg("source_skin") = DeclaredDefault(RetargetRunSettingOptions(), "source_skin"),
      py::arg("target_skin") = DeclaredDefault(RetargetRunSettingOptions(), "target_skin"),
      py::arg("frame_rate") = DeclaredDefault(RetargetRunSettingOptions(), "frame_rate"),
      py::arg("max_frames") = DeclaredDefault(FrameLimitOption(), "max_frames"),
      py::arg("amc_fps") = DeclaredDefault(FileReadSettingOptions(), "amc_fps"),
      py::arg("out") = "", py::arg("animation_name") = DeclaredDefault(RetargetRunSettingOptions(), "animation_name"),
      py::arg("animation_only") = DeclaredDefault(RetargetRunSettingOptions(), "animation_only"),
      (std::string(R"doc(Retargets a source motion onto a skinned glTF character, as `mocapsolve retarget`
(thesis chapter 4). source: a skinned .glb/.gltf (its mesh tracked unless
source_mesh=False) or a skeleton motion (.bvh, .amc with skeleton= its .asf, .fbx);
target: a .glb/.gltf character. out: also write a .glb/.gltf (the target plus the new
animation) or .bvh. source_animation: the source file's clip (a name or index; glTF/FBX);
source_skin, target_skin: the skin of each glTF (a name or index; '' = skin 0);
frame_rate: resample the source to this rate (0 = its own); max_frames: only the first N
frames (0 = all); amc_fps: an .amc's frame rate (default 120); animation_name: the new
clip's name in the written glTF ('' = 'retargeted from <source clip>'); animation_only:
write the glTF out as the target's skeleton, skin and the new animation only, no meshes
(as the CLI's --animation_only).
Keywords: the RetargetSettings (listed below with their defaults; joint_map='map.json' names a
joint map file), and frames='A:B' /
seconds='A:B' and out_fps, which cut and resample the result (as the CLI's flags).
Returns (target character, motion on the target skeleton, report): the report is what
`mocapsolve retarget --report` writes (errors as fractions of the target's height, the
joint map, per-frame errors, 'notes'). Releases the GIL.)doc") +
       KeywordDefaults("Retarget keywords and defaults (RetargetSettings)", py::cast(RetargetSettings()),
                       RetargetSolverOptions().Names() + "," + RetargetSettingOptions().Names() + ",foot_joints")).c_str());
  m.def("joint_map", [](const std::string& source, const std::string& target, py::object skeleton,
                        const std::string& source_skin, const std::string& target_skin, const std::string& joint_map) {
        RequireReadable(source);
        RequireReadable(target);
        JointMapInputs inputs;
        inputs.source = source;
        inputs.target = target;
        inputs.skeleton = skeleton.is_none() ? std::string() : std::string(py::str(skeleton));
        inputs.source_skin = source_skin;
        inputs.target_skin = target_skin;
        JointMapConfig config;
        config.joint_map = joint_map;
        JointMapTaskResult result;
        ThrowIfError(RunJointMap(inputs, config, &result));
        return ReportToPython(result.json);
      }, py::arg("source"), py::arg("target"), py::kw_only(), py::arg("skeleton") = py::none(),
      py::arg("source_skin") = DeclaredDefault(RetargetRunSettingOptions(), "source_skin"),
      py::arg("target_skin") = DeclaredDefault(RetargetRunSettingOptions(), "target_skin"),
      py::arg("joint_map") = DeclaredDefault(RetargetSettingOptions(), "joint_map"),
      R"doc(The automatic joint map from source to target, as `mocapsolve joint_map` prints it: a
dict with 'confidence' (0..1), 'source_skeleton' and 'target_skeleton' (the humanoid roles
found, or why not), 'roles' ({role: {'source', 'target', 'how'}}) and 'joints' ({source
joint: target joint}). source, target: motion or character files (.glb/.gltf, .bvh, .amc
with skeleton= its .asf, .fbx); source_skin, target_skin: a glTF's skin (name or index);
joint_map: a joint map file whose entries override the automatic map. Save the dict as
JSON, edit it and pass it to retarget(joint_map=...).)doc");
}

}  // namespace mocapsolve::python
