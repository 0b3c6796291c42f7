// mocapsolve convert IN OUT: motion files to BVH, or into a glTF character; marker files
// between C3D and TRC.
#include <cstdio>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/delivery_flags.h"
#include "io/bvh_writer.h"
#include "io/fbx_writer.h"
#include "io/gltf_reader.h"
#include "io/gltf_writer.h"
#include "io/marker_file.h"
#include "io/motion_file.h"
#include "kinematics/rotation.h"
#include "problems/marker_solve/marker_observations.h"

DEFINE_double(scale, 1.0, "Multiply every length (offsets, translations) by this factor, e.g. "
              "5.6444 to turn CMU ASF units into cm.");
DEFINE_string(euler_order, "", "Write every joint's rotation channels in this order (XYZ, XZY, "
              "YXZ, YZX, ZXY, ZYX); default: keep each joint's order from the input.");
DEFINE_int32(precision, 6, "Significant digits of the written channel values.");
DEFINE_string(clip_name, "mocapsolve", "glTF output: name of the added animation; FBX output: the take's name.");
DEFINE_string(out_units, "", "Marker files: write OUT in this unit (mm, cm, m, in), the coordinates "
              "converted; default: IN's unit.");

DECLARE_string(axes);  // apps/main.cc

namespace mocapsolve {
namespace {

// IN's motion as delivered (--frames/--seconds, --out_fps: signal/clip_delivery.h).
Status LoadDeliveredMotion(const std::string& in, Skeleton* skeleton, Motion* motion) {
  ClipDelivery delivery;
  Status status = ClipDeliveryFromFlags(&delivery);
  if (status.ok()) status = LoadMotion(in, skeleton, motion);
  if (status.ok() && !delivery.keeps_clip()) {
    status = DeliverClip(*motion, delivery, motion);
    if (!status.ok()) status = Status::Error(in + ": " + status.message());
  }
  return status;
}

// IN's motion as a new animation of the --target character.
Status ConvertToGltf(const std::string& in, const std::string& out) {
  const std::string in_ext = FileExtension(in);
  const std::string target = !FLAGS_target.empty() ? FLAGS_target
                             : in_ext == ".glb" || in_ext == ".gltf" ? in
                                                                     : "";
  if (target.empty()) return Status::Error(out + ": glTF output needs --target=CHARACTER.glb");
  Status status = CheckNotAnInput(out, in);
  if (status.ok()) status = CheckNotAnInput(out, target);
  if (!status.ok()) return status;
  if (FLAGS_scale != 1.0 || !FLAGS_euler_order.empty()) {
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
  status = LoadDeliveredMotion(in, &skeleton, &motion);
  if (!status.ok()) return status;
  status = MotionForCharacter(skeleton, motion, character, &mapped);
  if (!status.ok()) return Status::Error(in + " onto " + target + ": " + status.message());
  status = WriteGltfWithAnimation(document, character, mapped, FLAGS_clip_name, out);
  if (!status.ok()) return status;
  std::printf("wrote %s: %s plus animation '%s' (%d frames at %.6g fps)\n", out.c_str(), target.c_str(),
              FLAGS_clip_name.c_str(), mapped.num_frames(), mapped.frame_rate);
  JsonObject report;
  report.Add("input", in).Add("output", out).Add("target", target).Add("clip_name", FLAGS_clip_name)
      .Add("joints", character.skeleton.num_joints()).Add("frames", mapped.num_frames());
  return WriteReport(report);
}

// IN's motion as binary FBX: the skeleton and the clip, or with --target (or a glTF IN) the
// character with its skinned mesh and the clip mapped onto it (io/fbx_writer.h).
Status ConvertToFbx(const std::string& in, const std::string& out) {
  const std::string in_ext = FileExtension(in);
  const std::string target = !FLAGS_target.empty() ? FLAGS_target
                             : in_ext == ".glb" || in_ext == ".gltf" ? in
                                                                     : "";
  Status status = CheckNotAnInput(out, in);
  if (status.ok() && !target.empty()) status = CheckNotAnInput(out, target);
  if (status.ok() && !FLAGS_skeleton.empty()) status = CheckNotAnInput(out, FLAGS_skeleton);
  if (!status.ok()) return status;
  if (FLAGS_scale != 1.0) return Status::Error("--scale applies to BVH output only");
  Skeleton skeleton;
  Motion motion;
  status = LoadDeliveredMotion(in, &skeleton, &motion);
  if (!status.ok()) return status;
  JsonObject report;
  report.Add("input", in).Add("output", out);
  if (!target.empty()) {
    if (!FLAGS_euler_order.empty()) return Status::Error("--euler_order: not with a glTF character (--target)");
    GltfCharacter character;
    status = ReadGltfCharacter(target, GltfReadOptions(), &character);
    if (!status.ok()) return status;
    Motion mapped;
    status = MotionForCharacter(skeleton, motion, character, &mapped);
    if (!status.ok()) return Status::Error(in + " onto " + target + ": " + status.message());
    status = WriteFbxCharacter(out, character, mapped, FLAGS_clip_name, false);
    if (!status.ok()) return status;
    std::printf("wrote %s: %s with take '%s' (%d frames at %.6g fps)\n", out.c_str(), target.c_str(),
                FLAGS_clip_name.c_str(), mapped.num_frames(), mapped.frame_rate);
    report.Add("target", target).Add("joints", character.skeleton.num_joints()).Add("frames", mapped.num_frames());
    return WriteReport(report);
  }
  FbxWriteOptions options;
  options.take_name = FLAGS_clip_name;
  if (!FLAGS_euler_order.empty()) {
    EulerOrder order;
    if (!ParseEulerOrder(FLAGS_euler_order, &order)) {
      return Status::Error("--euler_order: '" + FLAGS_euler_order + "' is not one of XYZ, XZY, YXZ, YZX, ZXY, ZYX");
    }
    options.euler_order = order;
  }
  status = WriteFbx(out, skeleton, motion, options);
  if (!status.ok()) return status;
  std::printf("wrote %s: %d joints, %d frames at %.6g fps\n", out.c_str(), skeleton.num_joints(),
              motion.num_frames(), motion.frame_rate);
  report.Add("joints", skeleton.num_joints()).Add("frames", motion.num_frames());
  return WriteReport(report);
}

// IN and OUT both marker files (C3D or TRC): the samples, labels, rate and first frame as
// they are, in --out_units and with OUT's axes (x, y, z) = IN's --axes (as for solving: y,z,x
// turns a Z-up file Y-up).
Status ConvertMarkers(const std::string& in, const std::string& out) {
  if (FLAGS_scale != 1.0 || !FLAGS_euler_order.empty() || !FLAGS_target.empty()) {
    return Status::Error("--scale, --euler_order and --target are for motions; marker files take --out_units and --axes");
  }
  ClipDelivery delivery;
  Status checked = ClipDeliveryFromFlags(&delivery);
  if (!checked.ok()) return checked;
  if (!delivery.keeps_clip()) return Status::Error("--frames, --seconds and --out_fps are for motions, not marker files");
  Status status = CheckNotAnInput(out, in);
  if (!status.ok()) return status;
  Eigen::Matrix3d out_from_in;
  status = ParseAxes(FLAGS_axes, &out_from_in);
  if (!status.ok()) return Status::Error("--axes: " + status.message());
  MarkerTrajectories markers;
  status = ReadMarkerFile(in, &markers);
  if (!status.ok()) return status;
  if (markers.num_markers() == 0) {
    return Status::Error(in + ": the take has no markers (a marker file needs at least one)");
  }
  if (!FLAGS_out_units.empty()) {
    const LengthUnit unit = LengthUnitFromName(FLAGS_out_units);
    if (!unit.known()) return Status::Error("--out_units='" + FLAGS_out_units + "': expected mm, cm, m or in");
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
  std::printf("wrote %s: %d markers x %d frames at %.6g fps (%s, axes %s of %s)\n", out.c_str(),
              markers.num_markers(), markers.num_frames(), markers.frame_rate, markers.unit.name.c_str(),
              FLAGS_axes.c_str(), in.c_str());
  JsonObject report;
  report.Add("input", in).Add("output", out).Add("markers", markers.num_markers())
      .Add("frames", markers.num_frames()).Add("unit", markers.unit.name).Add("axes", FLAGS_axes);
  return WriteReport(report);
}

Status RunConvert(const std::vector<std::string>& arguments) {
  if (arguments.size() != 2) return Status::Error("expected IN OUT (mocapsolve convert IN OUT)");
  const std::string& in = arguments[0];
  const std::string& out = arguments[1];
  const std::string out_ext = FileExtension(out);
  if (IsMarkerFile(in) || IsMarkerFile(out)) {
    if (!IsMarkerFile(in) || !IsMarkerFile(out)) {
      return Status::Error("marker files convert to marker files (.c3d, .trc): " + in + " -> " + out);
    }
    return ConvertMarkers(in, out);
  }
  if (!FLAGS_out_units.empty()) return Status::Error("--out_units is for marker files (.c3d, .trc)");
  if (out_ext == ".glb" || out_ext == ".gltf") return ConvertToGltf(in, out);
  if (out_ext == ".fbx") return ConvertToFbx(in, out);
  if (!IsTextOutputPath(out, ".bvh")) return Status::Error(out + ": output must be .bvh, .glb, .gltf or .fbx");
  Status status = CheckNotAnInput(out, in);
  if (status.ok() && !FLAGS_skeleton.empty()) status = CheckNotAnInput(out, FLAGS_skeleton);
  if (!status.ok()) return status;
  if (!(FLAGS_scale > 0.0)) return Status::Error("--scale must be positive");
  if (FLAGS_precision < 1 || FLAGS_precision > 17) {
    return Status::Error("--precision must be in [1, 17]");
  }
  BvhWriteOptions options;
  options.scale = FLAGS_scale;
  options.precision = FLAGS_precision;
  if (!FLAGS_euler_order.empty()) {
    EulerOrder order;
    if (!ParseEulerOrder(FLAGS_euler_order, &order)) {
      return Status::Error("--euler_order: '" + FLAGS_euler_order + "' is not one of XYZ, XZY, "
                           "YXZ, YZX, ZXY, ZYX");
    }
    options.euler_order = order;
  }
  Skeleton skeleton;
  Motion motion;
  status = LoadDeliveredMotion(in, &skeleton, &motion);
  if (!status.ok()) return status;
  status = WriteBvh(out, skeleton, motion, options);
  if (!status.ok()) return status;
  std::printf("wrote %s: %d joints, %d frames at %.6g fps\n", out.c_str(), skeleton.num_joints(),
              motion.num_frames(), motion.frame_rate);
  JsonObject report;
  report.Add("input", in).Add("output", out).Add("joints", skeleton.num_joints())
      .Add("frames", motion.num_frames()).Add("scale", FLAGS_scale);
  return WriteReport(report);
}

}  // namespace

extern const Command kConvertCommand = {
    "convert", "BVH, ASF/AMC, glTF/GLB or FBX in; BVH or FBX out, or a new clip of a glTF character",
    "mocapsolve convert IN.bvh|IN.amc|IN.glb|IN.gltf|IN.fbx OUT.bvh [--skeleton=X.asf] "
    "[--animation=NAME] [--scale=S] [--euler_order=ZXY]\n"
    "       mocapsolve convert IN OUT.glb|OUT.gltf [--target=CHARACTER.glb] [--clip_name=NAME]\n"
    "       mocapsolve convert IN OUT.fbx [--target=CHARACTER.glb] [--clip_name=NAME] [--euler_order=XYZ]\n"
    "       mocapsolve convert IN.c3d|IN.trc OUT.c3d|OUT.trc [--out_units=mm] [--axes=y,z,x]\n\n"
    "Reads a motion and writes it as BVH. Rest rotations of ASF skeletons are folded into\n"
    "the BVH rotation channels. With a .glb/.gltf OUT, the motion (whose skeleton must have\n"
    "the character's joints, e.g. a BVH converted from it) is added as a new animation to a\n"
    "copy of --target (default IN). With a .fbx OUT, binary FBX 7.4: the skeleton and the\n"
    "clip (take --clip_name), or with --target (default a glTF IN) the character, its skinned\n"
    "mesh and the clip. Marker files convert between C3D and TRC: labels, rate,\n"
    "first frame and missing samples kept, in --out_units, OUT's axes being IN's --axes.\n"
    "--frames=A:B or --seconds=A:B cut the motion, --out_fps=R resamples it (BVH, glTF, FBX).\n"
    "OUT is written atomically and may not be an input.",
    __FILE__, RunConvert, "skeleton,skeleton_units,amc_fps,animation,sample_fps,target,axes,report,quiet",
    {DeliverySettingOptions().Without("formats").options()}};

}  // namespace mocapsolve
