#include "tasks/view_task.h"

#include <cmath>

#include "io/atomic_file.h"
#include "io/csv_columns.h"
#include "io/gltf_reader.h"
#include "io/gltf_writer.h"
#include "io/marker_file.h"
#include "io/motion_file.h"
#include "kinematics/motion_on_skeleton.h"
#include "pipeline/take_view.h"
#include "viewer/repair_intervals.h"
#include "viewer/view_page.h"

namespace mocapsolve {
namespace {

Status UpAxis(const std::string& up, const std::vector<std::vector<Eigen::Vector3d>>& points, int* axis) {
  if (up == "auto") {
    *axis = GuessUpAxis(points);
  } else if (up == "x" || up == "y" || up == "z") {
    *axis = up[0] - 'x';
  } else {
    return Status::Error("--up=" + up + ": expected auto, x, y or z");
  }
  return Status::Ok();
}

// A motion file in its own world (up, its unit or a guess).
Status MotionTransform(const std::string& path, const Skeleton& skeleton, const Motion& motion,
                       const ViewConfig& config, ViewTransform* transform) {
  int up = -1;
  if (config.up != "auto") {
    Status status = UpAxis(config.up, {}, &up);
    if (!status.ok()) return status;
  }
  return MakeMotionViewTransform(path, skeleton, motion, up, transform);
}

Status MarkerTransform(const std::string& path, const MarkerTrajectories& t, const ViewConfig& config,
                       ViewTransform* transform) {
  const std::vector<std::vector<Eigen::Vector3d>> points = TrajectoryObservations(t);
  int up = 1;
  Status status = UpAxis(config.up, points, &up);
  if (!status.ok()) return status;
  return MakeViewTransform(path, up, t.unit, 0.0, transform);
}

// A motion with frames. The skeleton (which may be the subject's, for the markers) only
// goes with an .amc: a BVH or glTF motion carries its own.
Status LoadViewMotion(const std::string& path, const ViewInputs& in, Skeleton* skeleton, Motion* motion,
                      std::vector<std::string>* warnings) {
  MotionFileOptions options;
  options.animation = in.animation;
  options.sample_rate = in.sample_fps;
  options.skeleton_units = in.skeleton_units;
  if (FileExtension(path) == ".amc") {
    options.skeleton_path = in.skeleton;
    options.amc_frame_rate = in.amc_fps;
    options.warnings = warnings;
  }
  Status status = ReadMotionFile(path, options, skeleton, motion);
  return status.ok() ? RequireFrames(path, *motion) : status;
}

Status AddCharacters(const ViewInputs& in, const ViewConfig& config, ViewScene* scene) {
  for (const std::string& path : in.characters) {
    const std::string ext = FileExtension(path);
    if (ext != ".glb" && ext != ".gltf") return Status::Error(path + ": --character takes .glb or .gltf files");
    GltfDocument document;
    Status status = GltfDocument::Read(path, &document);
    GltfCharacter character;
    if (status.ok()) status = ReadGltfCharacter(document, {}, &character);
    if (!status.ok()) return status;
    if (character.animation_names.empty()) return Status::Error(path + ": the character has no animation to play");
    if (!config.character_animation.empty()) {
      bool found = false;
      for (const std::string& name : character.animation_names) found = found || name == config.character_animation;
      if (!found) return Status::Error(path + ": no animation named '" + config.character_animation + "'");
    }
    ViewCharacter c;
    c.name = FileStem(path);
    c.animation = config.character_animation;
    // A .glb as it is; a .gltf (its buffers and images in other files or data: URIs) as
    // one self-contained .glb, since the page has no files beside it.
    status = ext == ".glb" ? ReadFileToString(path, &c.glb) : SerializeGltfAsGlb(document, &c.glb);
    if (!status.ok()) return status;
    scene->characters.push_back(std::move(c));
  }
  return Status::Ok();
}

Status AddFalloff(const std::string& path, ViewScene* scene) {
  if (path.empty()) return Status::Ok();
  CsvColumns table;
  Status status = ReadCsvColumns(path, &table);
  if (!status.ok()) return status;
  if (table.names.size() < 2 || table.names[0] != "frame") {
    return Status::Error(path + ": expected columns frame,weight... (propagate --weights_csv)");
  }
  for (size_t c = 1; c < table.names.size(); ++c) {
    ViewCurve curve;
    curve.name = "falloff " + table.names[c];
    for (size_t row = 0; row < table.columns[0].size(); ++row) {
      const double frame = table.columns[0][row];
      if (frame < 0 || frame > 1e7 || frame != static_cast<int>(frame)) {
        return Status::Error(path + ": row " + std::to_string(row + 1) + ": frame is not a frame index");
      }
      if (static_cast<int>(frame) >= static_cast<int>(curve.values.size())) curve.values.resize(static_cast<int>(frame) + 1, std::nanf(""));
      curve.values[static_cast<int>(frame)] = static_cast<float>(table.columns[c][row]);
    }
    scene->curves.push_back(std::move(curve));
  }
  return Status::Ok();
}

// The world of a take mapped onto its subject (set by AddSubjectTake), for the files
// drawn with it.
struct TakeWorld {
  bool active = false;
  Skeleton skeleton;        // The subject's.
  ViewTransform transform;  // TakeViewTransform.
};

// The markers mapped onto the subject (axes, units, label prefix) with the motion drawn on
// the subject's skeleton and its marker residual; compared markers mapped the same way.
Status AddSubjectTake(const ViewInputs& in, const Skeleton& motion_skeleton, Motion* motion, bool compare_markers,
                      ViewResult* result, TakeWorld* world) {
  MarkerTake take;
  Status status = LoadTakeForSubject(*in.subject, in.markers, &take);
  if (status.ok()) status = RequireTakeData(in.markers, take);
  if (!status.ok()) return status;
  const bool solved = !in.motion.empty();
  if (solved) {
    // The motion in the subject's frame: its file's skeleton may lack the subject's rest
    // rotations (a BVH written by solve from an ASF subject folds them into the angles),
    // so its rotations are re-expressed on the subject's skeleton before they are drawn
    // and compared with the markers.
    status = MotionOnSkeleton(motion_skeleton, *motion, take.skeleton, motion);
    if (!status.ok()) return Status::Error(in.motion + ": " + status.message());
  }
  TakeViewInputs inputs;
  inputs.skeleton = &take.skeleton;
  inputs.markers = &take.markers;
  inputs.observed = &take.observed;
  inputs.motion = solved ? motion : nullptr;
  inputs.frame_rate = take.trajectories.frame_rate > 0 ? take.trajectories.frame_rate : (solved ? motion->frame_rate : 0.0);
  status = MakeTakeViewScene(inputs, &result->scene);
  if (status.ok()) status = TakeViewTransform(inputs, &world->transform);
  if (!status.ok()) return status;
  world->active = true;
  result->marker_rms_mm = TakeMarkerRmsMm(inputs, &result->residual_samples);
  if (compare_markers) {
    MarkerTake other;
    status = LoadTakeForSubject(*in.subject, in.compare, &other);
    if (!status.ok()) return status;
    std::vector<std::string> labels;
    for (int m = 0; m < take.markers.num_markers(); ++m) labels.push_back(take.markers.label(m));
    result->scene.markers.push_back(
        MakeViewMarkers(FileStem(in.compare) + " (compare)", labels, other.observed, world->transform));
  }
  world->skeleton = std::move(take.skeleton);
  return Status::Ok();
}

// A marker file as read, in its own world.
Status LoadMarkersInOwnWorld(const std::string& path, const ViewConfig& config, MarkerTrajectories* trajectories,
                             ViewTransform* transform) {
  Status status = ReadMarkerFile(path, trajectories);
  if (status.ok()) status = RequireMarkerData(path, *trajectories);
  if (status.ok()) status = MarkerTransform(path, *trajectories, config, transform);
  return status;
}

// Without a subject: the markers (and compared markers) and the motion each in its own world.
Status AddFileWorlds(const ViewInputs& in, const ViewConfig& config, const Skeleton& skeleton, const Motion& motion,
                     bool compare_markers, ViewScene* scene) {
  if (!in.markers.empty()) {
    MarkerTrajectories trajectories;
    ViewTransform transform;
    Status status = LoadMarkersInOwnWorld(in.markers, config, &trajectories, &transform);
    if (!status.ok()) return status;
    scene->notes.push_back(transform.note);
    scene->frame_rate = trajectories.frame_rate;
    scene->markers.push_back(MakeViewMarkers("markers", trajectories, transform));
    if (compare_markers) {
      MarkerTrajectories other;
      ViewTransform other_transform;
      status = LoadMarkersInOwnWorld(in.compare, config, &other, &other_transform);
      if (!status.ok()) return status;
      scene->markers.push_back(MakeViewMarkers(FileStem(in.compare) + " (compare)", other, other_transform));
    }
  }
  if (!in.motion.empty()) {
    ViewTransform motion_transform;
    Status status = MotionTransform(in.motion, skeleton, motion, config, &motion_transform);
    if (!status.ok()) return status;
    scene->notes.push_back(motion_transform.note);
    scene->skeletons.push_back(MakeViewSkeleton(FileStem(in.motion), skeleton, motion, motion_transform));
    if (in.markers.empty()) scene->frame_rate = motion.frame_rate;
  }
  return Status::Ok();
}

// A compared motion, ghosted: in the take's world when it is a motion of the subject's
// skeleton (as the motion), else in its own.
Status AddCompareMotion(const ViewInputs& in, const ViewConfig& config, const TakeWorld& take, ViewResult* result) {
  Skeleton other_skeleton;
  Motion other;
  Status status = LoadViewMotion(in.compare, in, &other_skeleton, &other, &result->warnings);
  if (!status.ok()) return status;
  const std::string name = FileStem(in.compare) + " (compare)";
  Motion on_subject;
  ViewSkeleton ghost;
  if (take.active && MotionOnSkeleton(other_skeleton, other, take.skeleton, &on_subject).ok()) {
    ghost = MakeViewSkeleton(name, take.skeleton, on_subject, take.transform);
  } else {
    ViewTransform transform;
    status = MotionTransform(in.compare, other_skeleton, other, config, &transform);
    if (!status.ok()) return status;
    if (take.active) result->scene.notes.push_back(name + ": not the subject's skeleton; drawn in its own world");
    ghost = MakeViewSkeleton(name, other_skeleton, other, transform);
  }
  ghost.ghost = true;
  result->scene.skeletons.push_back(std::move(ghost));
  return Status::Ok();
}

// What each input needs besides itself.
Status CheckInputs(const ViewInputs& in, bool compare_markers) {
  if (in.markers.empty() && in.motion.empty() && in.characters.empty()) {
    return Status::Error("nothing to show: give --markers, --motion and/or --character");
  }
  if (!in.repair_report.empty() && in.markers.empty()) return Status::Error("--repair_report needs --markers");
  if (!in.compare.empty() && in.markers.empty() && in.motion.empty()) {
    return Status::Error("--compare needs --markers or --motion to compare with");
  }
  if (compare_markers && in.markers.empty()) return Status::Error("--compare=" + in.compare + ": a marker file needs --markers");
  if (!in.compare.empty() && !compare_markers && in.motion.empty()) {
    return Status::Error("--compare=" + in.compare + ": a motion needs --motion");
  }
  return Status::Ok();
}

// The repair report's intervals on the first marker set, its samples coloured by reason.
Status AddRepairReport(const std::string& path, ViewScene* scene) {
  ViewMarkers& markers = scene->markers[0];
  std::vector<ReportedInterval> detected, filled;
  Status status = ReadRepairReport(path, markers.labels, markers.num_frames, &detected, &filled);
  if (!status.ok()) return status;
  scene->intervals = RepairedViewIntervals(detected, filled);
  MarkRepairedSamples(scene->intervals, &markers);
  return Status::Ok();
}

}  // namespace

Status RunView(const ViewInputs& inputs, const ViewConfig& config, ViewResult* result) {
  *result = ViewResult();
  const bool compare_markers = !inputs.compare.empty() && IsMarkerFile(inputs.compare);
  Status status = CheckInputs(inputs, compare_markers);
  if (!status.ok()) return status;
  // The runtime first: a missing install is the first thing to say.
  std::string runtime_path;
  status = FindViewerRuntime(&runtime_path);
  if (!status.ok()) return status;

  ViewScene& scene = result->scene;
  std::vector<std::string> names;
  Skeleton skeleton;
  Motion motion;
  if (!inputs.motion.empty()) {
    status = LoadViewMotion(inputs.motion, inputs, &skeleton, &motion, &result->warnings);
    if (!status.ok()) return status;
    names.push_back(FileStem(inputs.motion));
  }
  if (!inputs.markers.empty()) names.insert(names.begin(), FileStem(inputs.markers));
  TakeWorld take;
  status = !inputs.markers.empty() && inputs.subject != nullptr
               ? AddSubjectTake(inputs, skeleton, &motion, compare_markers, result, &take)
               : AddFileWorlds(inputs, config, skeleton, motion, compare_markers, &scene);
  if (status.ok() && !inputs.compare.empty() && !compare_markers) status = AddCompareMotion(inputs, config, take, result);
  if (status.ok() && !inputs.repair_report.empty()) status = AddRepairReport(inputs.repair_report, &scene);
  if (status.ok()) status = AddFalloff(inputs.falloff, &scene);
  if (status.ok()) status = AddCharacters(inputs, config, &scene);
  if (!status.ok()) return status;
  if (!(scene.frame_rate > 0.0)) scene.frame_rate = 30.0;
  if (!config.title.empty()) {
    scene.title = config.title;
  } else {
    for (const std::string& name : names) scene.title += (scene.title.empty() ? "" : " + ") + name;
    for (const ViewCharacter& c : scene.characters) scene.title += (scene.title.empty() ? "" : " + ") + c.name;
  }
  std::string runtime;
  status = ReadFileToString(runtime_path, &runtime);
  if (status.ok()) status = BuildViewPage(scene, runtime, &result->html);
  if (!status.ok()) return Status::Error(config.page_name + ": " + status.message());
  return Status::Ok();
}

}  // namespace mocapsolve
