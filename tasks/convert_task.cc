#include "tasks/convert_task.h"

#include "io/atomic_file.h"
#include "io/bvh_writer.h"
#include "io/fbx_writer.h"
#include "io/gltf_reader.h"
#include "io/gltf_writer.h"
#include "io/marker_file.h"
#include "kinematics/rotation.h"
#include "problems/marker_solve/marker_observations.h"
#include "tasks/console_text.h"

namespace mocapsolve {
namespace {

// IN's motion as delivered (cut and resampled as `delivery` says).
Status LoadDeliveredMotion(const ConvertInputs& inputs, const ClipDelivery& delivery, Skeleton* skeleton,
                           Motion* motion, std::vector<std::string>* warnings) {
  MotionFileOptions options = inputs.motion;
  options.warnings = warnings;
  Status status = ReadMotionFile(inputs.in, options, skeleton, motion);
  if (status.ok() && !delivery.keeps_clip()) {
    status = DeliverClip(*motion, delivery, motion);
    if (!status.ok()) status = Status::Error(inputs.in + ": " + status.message());
  }
  return status;
}

Status EulerOrderSetting(const ConvertSettings& settings, EulerOrder* order) {
  if (ParseEulerOrder(settings.euler_order, order)) return Status::Ok();
  return Status::Error("--euler_order: '" + settings.euler_order + "' is not one of XYZ, XZY, YXZ, YZX, ZXY, ZYX");
}

// The glTF character motions are written onto: --target, or IN when it is one.
std::string TargetCharacter(const ConvertInputs& inputs) {
  const std::string in_ext = FileExtension(inputs.in);
  if (!inputs.target.empty()) return inputs.target;
  return in_ext == ".glb" || in_ext == ".gltf" ? inputs.in : "";
}

// IN's motion as a new animation of the target character.
Status ConvertToGltf(const ConvertInputs& inputs, const ConvertSettings& settings, const ClipDelivery& delivery,
                     ConvertResult* result) {
  const std::string& in = inputs.in;
  const std::string& out = inputs.out;
  const std::string target = TargetCharacter(inputs);
  if (target.empty()) return Status::Error(out + ": glTF output needs --target=CHARACTER.glb");
  Status status = CheckNotAnInput(out, in);
  if (status.ok()) status = CheckNotAnInput(out, target);
  if (!status.ok()) return status;
  if (settings.scale != 1.0 || !settings.euler_order.empty()) {
    return Status::Error("--scale and --euler_order apply to BVH output only");
  }
  GltfDocument document;
  status = GltfDocument::Read(target, &document);
  if (!status.ok()) return status;
  GltfCharacter character;
  status = ReadGltfCharacter(document, GltfReadOptions(), &character);
  if (!status.ok()) return status;
  Skeleton skeleton;
  Motion motion, mapped;
  status = LoadDeliveredMotion(inputs, delivery, &skeleton, &motion, &result->warnings);
  if (!status.ok()) return status;
  status = MotionForCharacter(skeleton, motion, character, &mapped);
  if (!status.ok()) return Status::Error(in + " onto " + target + ": " + status.message());
  status = WriteGltfWithAnimation(document, character, mapped, settings.clip_name, out);
  if (!status.ok()) return status;
  AppendF(&result->summary, "wrote %s: %s plus animation '%s' (%d frames at %.6g fps)\n", out.c_str(),
          target.c_str(), settings.clip_name.c_str(), mapped.num_frames(), mapped.frame_rate);
  result->report.Add("input", in).Add("output", out).Add("target", target).Add("clip_name", settings.clip_name)
      .Add("joints", character.skeleton.num_joints()).Add("frames", mapped.num_frames());
  return Status::Ok();
}

// IN's motion as binary FBX: the skeleton and the clip, or with a target character (a glTF
// IN by default) the character with its skinned mesh and the clip mapped onto it.
Status ConvertToFbx(const ConvertInputs& inputs, const ConvertSettings& settings, const ClipDelivery& delivery,
                    ConvertResult* result) {
  const std::string& in = inputs.in;
  const std::string& out = inputs.out;
  const std::string target = TargetCharacter(inputs);
  Status status = CheckNotAnInput(out, in);
  if (status.ok()) status = CheckNotAnInput(out, target);
  if (status.ok()) status = CheckNotAnInput(out, inputs.motion.skeleton_path);
  if (!status.ok()) return status;
  if (settings.scale != 1.0) return Status::Error("--scale applies to BVH output only");
  Skeleton skeleton;
  Motion motion;
  status = LoadDeliveredMotion(inputs, delivery, &skeleton, &motion, &result->warnings);
  if (!status.ok()) return status;
  result->report.Add("input", in).Add("output", out);
  if (!target.empty()) {
    if (!settings.euler_order.empty()) return Status::Error("--euler_order: not with a glTF character (--target)");
    GltfCharacter character;
    status = ReadGltfCharacter(target, GltfReadOptions(), &character);
    if (!status.ok()) return status;
    Motion mapped;
    status = MotionForCharacter(skeleton, motion, character, &mapped);
    if (!status.ok()) return Status::Error(in + " onto " + target + ": " + status.message());
    status = WriteFbxCharacter(out, character, mapped, settings.clip_name, false, delivery.fbx_key_tolerance_mm);
    if (!status.ok()) return status;
    AppendF(&result->summary, "wrote %s: %s with take '%s' (%d frames at %.6g fps)\n", out.c_str(), target.c_str(),
            settings.clip_name.c_str(), mapped.num_frames(), mapped.frame_rate);
    result->report.Add("target", target).Add("joints", character.skeleton.num_joints())
        .Add("frames", mapped.num_frames());
    return Status::Ok();
  }
  FbxWriteOptions options;
  options.take_name = settings.clip_name;
  options.key_tolerance_mm = delivery.fbx_key_tolerance_mm;
  if (!settings.euler_order.empty()) {
    EulerOrder order;
    status = EulerOrderSetting(settings, &order);
    if (!status.ok()) return status;
    options.euler_order = order;
  }
  status = WriteFbx(out, skeleton, motion, options);
  if (!status.ok()) return status;
  AppendF(&result->summary, "wrote %s: %d joints, %d frames at %.6g fps\n", out.c_str(), skeleton.num_joints(),
          motion.num_frames(), motion.frame_rate);
  result->report.Add("joints", skeleton.num_joints()).Add("frames", motion.num_frames());
  return Status::Ok();
}

// IN and OUT both marker files (C3D or TRC): the samples, labels, rate and first frame as
// they are, in out_units and with OUT's axes (x, y, z) = IN's `axes` (as for solving: y,z,x
// turns a Z-up file Y-up).
Status ConvertMarkers(const ConvertInputs& inputs, const ConvertSettings& settings, const ClipDelivery& delivery,
                      ConvertResult* result) {
  const std::string& in = inputs.in;
  const std::string& out = inputs.out;
  if (settings.scale != 1.0 || !settings.euler_order.empty() || !inputs.target.empty()) {
    return Status::Error("--scale, --euler_order and --target are for motions; marker files take --out_units and --axes");
  }
  if (!delivery.keeps_clip()) return Status::Error("--frames, --seconds and --out_fps are for motions, not marker files");
  Status status = CheckNotAnInput(out, in);
  if (!status.ok()) return status;
  Eigen::Matrix3d out_from_in;
  status = ParseAxes(inputs.axes, &out_from_in);
  if (!status.ok()) return Status::Error("--axes: " + status.message());
  MarkerTrajectories markers;
  status = ReadMarkerFile(in, &markers);
  if (!status.ok()) return status;
  if (markers.num_markers() == 0) {
    return Status::Error(in + ": the take has no markers (a marker file needs at least one)");
  }
  if (!settings.out_units.empty()) {
    const LengthUnit unit = LengthUnitFromName(settings.out_units);
    if (!unit.known()) return Status::Error("--out_units='" + settings.out_units + "': expected mm, cm, m or in");
    if (!markers.unit.known()) return Status::Error(in + ": the file states no unit, so --out_units cannot convert it");
    markers.ScaleLengths(markers.unit.metres_per_unit / unit.metres_per_unit);
    markers.unit = unit;
  }
  if (!out_from_in.isIdentity()) {
    for (int f = 0; f < markers.num_frames(); ++f) {
      for (int m = 0; m < markers.num_markers(); ++m) {
        if (!markers.valid(f, m)) continue;
        markers.SetSample(f, m, out_from_in * markers.position(f, m), markers.residual(f, m),
                          markers.camera_mask(f, m));
      }
    }
  }
  status = WriteMarkerFile(out, markers);
  if (!status.ok()) return status;
  AppendF(&result->summary, "wrote %s: %d markers x %d frames at %.6g fps (%s, axes %s of %s)\n", out.c_str(),
          markers.num_markers(), markers.num_frames(), markers.frame_rate, markers.unit.name.c_str(),
          inputs.axes.c_str(), in.c_str());
  result->report.Add("input", in).Add("output", out).Add("markers", markers.num_markers())
      .Add("frames", markers.num_frames()).Add("unit", markers.unit.name).Add("axes", inputs.axes);
  return Status::Ok();
}

// IN's motion as BVH.
Status ConvertToBvh(const ConvertInputs& inputs, const ConvertSettings& settings, const ClipDelivery& delivery,
                    ConvertResult* result) {
  const std::string& in = inputs.in;
  const std::string& out = inputs.out;
  if (!IsTextOutputPath(out, ".bvh")) return Status::Error(out + ": output must be .bvh, .glb, .gltf or .fbx");
  Status status = CheckNotAnInput(out, in);
  if (status.ok()) status = CheckNotAnInput(out, inputs.motion.skeleton_path);
  if (!status.ok()) return status;
  if (!(settings.scale > 0.0)) return Status::Error("--scale must be positive");
  BvhWriteOptions options;
  options.scale = settings.scale;
  options.precision = settings.precision;
  if (!settings.euler_order.empty()) {
    EulerOrder order;
    status = EulerOrderSetting(settings, &order);
    if (!status.ok()) return status;
    options.euler_order = order;
  }
  Skeleton skeleton;
  Motion motion;
  status = LoadDeliveredMotion(inputs, delivery, &skeleton, &motion, &result->warnings);
  if (!status.ok()) return status;
  status = WriteBvh(out, skeleton, motion, options);
  if (!status.ok()) return status;
  AppendF(&result->summary, "wrote %s: %d joints, %d frames at %.6g fps\n", out.c_str(), skeleton.num_joints(),
          motion.num_frames(), motion.frame_rate);
  result->report.Add("input", in).Add("output", out).Add("joints", skeleton.num_joints())
      .Add("frames", motion.num_frames()).Add("scale", settings.scale);
  return Status::Ok();
}

}  // namespace

Status RunConvert(const ConvertInputs& inputs, const ConvertSettings& settings, const ClipDelivery& delivery,
                  ConvertResult* result) {
  *result = ConvertResult();
  Status status = ConvertSettingOptions().Validate(settings);
  if (!status.ok()) return status;
  const std::string out_ext = FileExtension(inputs.out);
  if (IsMarkerFile(inputs.in) || IsMarkerFile(inputs.out)) {
    if (!IsMarkerFile(inputs.in) || !IsMarkerFile(inputs.out)) {
      return Status::Error("marker files convert to marker files (.c3d, .trc): " + inputs.in + " -> " + inputs.out);
    }
    return ConvertMarkers(inputs, settings, delivery, result);
  }
  if (!settings.out_units.empty()) return Status::Error("--out_units is for marker files (.c3d, .trc)");
  if (out_ext == ".glb" || out_ext == ".gltf") return ConvertToGltf(inputs, settings, delivery, result);
  if (out_ext == ".fbx") return ConvertToFbx(inputs, settings, delivery, result);
  return ConvertToBvh(inputs, settings, delivery, result);
}

}  // namespace mocapsolve
