// mocapsolve view: one self-contained HTML page (viewer/view_page.h) that shows markers,
// a motion, characters, a repair and a falloff in a browser, offline.
//
// Worlds: with a subject (--subject, or --skeleton and --markerset) the markers are mapped
// onto the skeleton (--axes, units) and shown in its frame with the per-frame marker
// residual of --motion (pipeline/take_view.h), whose rotations are first re-expressed on
// the subject's skeleton (a BVH has no rest rotations: one written from an ASF subject
// folds them into its angles; kinematics/motion_on_skeleton.h); a --compare motion of the
// same skeleton is drawn there too. Without a subject, each file is shown in its own
// unit with its up axis from --up (default: guessed per file, viewer/view_scene.h).
#include <cstdio>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/config_flags.h"
#include "io/atomic_file.h"
#include "io/csv_columns.h"
#include "io/gltf_reader.h"
#include "io/gltf_writer.h"
#include "io/marker_file.h"
#include "io/motion_file.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/motion_on_skeleton.h"
#include "pipeline/take_view.h"
#include "problems/marker_repair/marker_repair.h"
#include "viewer/repair_intervals.h"
#include "viewer/view_page.h"

DEFINE_string(character_animation, "", "The characters' animation to play (name); default: each "
              "file's first animation (the one retarget/pipeline/convert added).");
DEFINE_string(repair_report, "", "A repair report (repair/pipeline --report JSON): colours the "
              "repaired samples of --markers by reason and draws the intervals on the timeline.");
DEFINE_string(falloff, "", "A falloff weights CSV (propagate --weights_csv): drawn on the timeline.");
DEFINE_string(compare, "", "A second take drawn ghosted over the first: a marker file (.c3d/.trc, "
              "compared with --markers) or a motion (compared with --motion).");
DEFINE_string(up, "auto", "Up axis of files without a subject: auto (guessed per file from how "
              "its points spread), x, y or z.");
DEFINE_string(title, "", "The page's title (default: the files' names).");

namespace mocapsolve {
namespace {

Status UpAxisFromFlag(const std::vector<std::vector<Eigen::Vector3d>>& points, int* axis) {
  if (FLAGS_up == "auto") {
    *axis = GuessUpAxis(points);
  } else if (FLAGS_up == "x" || FLAGS_up == "y" || FLAGS_up == "z") {
    *axis = FLAGS_up[0] - 'x';
  } else {
    return Status::Error("--up=" + FLAGS_up + ": expected auto, x, y or z");
  }
  return Status::Ok();
}

// A motion file in its own world (--up, its unit or a guess).
Status MotionTransform(const std::string& path, const Skeleton& skeleton, const Motion& motion,
                       ViewTransform* transform) {
  int up = -1;
  if (FLAGS_up != "auto") {
    Status status = UpAxisFromFlag({}, &up);
    if (!status.ok()) return status;
  }
  return MakeMotionViewTransform(path, skeleton, motion, up, transform);
}

Status MarkerTransform(const std::string& path, const MarkerTrajectories& t, ViewTransform* transform) {
  const std::vector<std::vector<Eigen::Vector3d>> points = TrajectoryObservations(t);
  int up = 1;
  Status status = UpAxisFromFlag(points, &up);
  if (!status.ok()) return status;
  return MakeViewTransform(path, up, t.unit, 0.0, transform);
}

// LoadMotion, except that --skeleton (which may be the subject's, for the markers) only
// goes with an .amc: a BVH or glTF motion carries its own skeleton.
Status LoadViewMotion(const std::string& path, Skeleton* skeleton, Motion* motion) {
  if (FileExtension(path) == ".amc") {
    Status status = LoadMotion(path, skeleton, motion);
    return status.ok() ? RequireFrames(path, *motion) : status;
  }
  MotionFileOptions options;
  options.animation = FLAGS_animation;
  options.sample_rate = FLAGS_sample_fps;
  Status status = ReadMotionFile(path, options, skeleton, motion);
  if (status.ok()) status = RequireFrames(path, *motion);
  return status.ok() ? ApplySkeletonUnits(skeleton) : status;
}

bool HaveSubject() { return !FLAGS_subject.empty() || !FLAGS_markerset.empty(); }

Status AddCharacters(ViewScene* scene) {
  for (const std::string& path : SplitCommaList(FLAGS_character)) {
    const std::string ext = FileExtension(path);
    if (ext != ".glb" && ext != ".gltf") return Status::Error(path + ": --character takes .glb or .gltf files");
    GltfDocument document;
    Status status = GltfDocument::Read(path, &document);
    GltfCharacter character;
    if (status.ok()) status = ReadGltfCharacter(document, {}, &character);
    if (!status.ok()) return status;
    if (character.animation_names.empty()) return Status::Error(path + ": the character has no animation to play");
    if (!FLAGS_character_animation.empty()) {
      bool found = false;
      for (const std::string& name : character.animation_names) found = found || name == FLAGS_character_animation;
      if (!found) return Status::Error(path + ": no animation named '" + FLAGS_character_animation + "'");
    }
    ViewCharacter c;
    c.name = FileStem(path);
    c.animation = FLAGS_character_animation;
    // A .glb as it is; a .gltf (its buffers and images in other files or data: URIs) as
    // one self-contained .glb, since the page has no files beside it.
    status = ext == ".glb" ? ReadFileToString(path, &c.glb) : SerializeGltfAsGlb(document, &c.glb);
    if (!status.ok()) return status;
    scene->characters.push_back(std::move(c));
  }
  return Status::Ok();
}

Status AddFalloff(ViewScene* scene) {
  if (FLAGS_falloff.empty()) return Status::Ok();
  CsvColumns table;
  Status status = ReadCsvColumns(FLAGS_falloff, &table);
  if (!status.ok()) return status;
  if (table.names.size() < 2 || table.names[0] != "frame") {
    return Status::Error(FLAGS_falloff + ": expected columns frame,weight... (propagate --weights_csv)");
  }
  for (size_t c = 1; c < table.names.size(); ++c) {
    ViewCurve curve;
    curve.name = "falloff " + table.names[c];
    for (size_t row = 0; row < table.columns[0].size(); ++row) {
      const double frame = table.columns[0][row];
      if (frame < 0 || frame > 1e7 || frame != static_cast<int>(frame)) {
        return Status::Error(FLAGS_falloff + ": row " + std::to_string(row + 1) + ": frame is not a frame index");
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
  Skeleton skeleton;          // The subject's.
  ViewTransform transform;    // TakeViewTransform.
  double rms_mm = 0.0;        // The motion's marker residual over the take (TakeMarkerRmsMm).
  int samples = 0;
};

// --markers mapped onto the subject (axes, units, label prefix) with --motion drawn on the
// subject's skeleton and its marker residual; --compare markers mapped the same way.
Status AddSubjectTake(const Skeleton& motion_skeleton, Motion* motion, bool compare_markers, ViewScene* scene,
                      TakeWorld* world) {
  MarkerTake take;
  Status status = LoadMarkerTake(&take);
  if (!status.ok()) return status;
  const bool solved = !FLAGS_motion.empty();
  if (solved) {
    // The motion in the subject's frame: its file's skeleton may lack the subject's rest
    // rotations (a BVH written by solve from an ASF subject folds them into the angles),
    // so its rotations are re-expressed on the subject's skeleton before they are drawn
    // and compared with the markers.
    status = MotionOnSkeleton(motion_skeleton, *motion, take.skeleton, motion);
    if (!status.ok()) return Status::Error(FLAGS_motion + ": " + status.message());
  }
  TakeViewInputs inputs;
  inputs.skeleton = &take.skeleton;
  inputs.markers = &take.markers;
  inputs.observed = &take.observed;
  inputs.motion = solved ? motion : nullptr;
  inputs.frame_rate = take.trajectories.frame_rate > 0 ? take.trajectories.frame_rate : (solved ? motion->frame_rate : 0.0);
  status = MakeTakeViewScene(inputs, scene);
  if (status.ok()) status = TakeViewTransform(inputs, &world->transform);
  if (!status.ok()) return status;
  world->active = true;
  world->rms_mm = TakeMarkerRmsMm(inputs, &world->samples);
  if (compare_markers) {
    Subject subject;
    status = LoadSubjectFromFlags(&subject);
    MarkerTake other;
    if (status.ok()) status = LoadTakeForSubject(subject, FLAGS_compare, &other);
    if (!status.ok()) return status;
    std::vector<std::string> labels;
    for (int m = 0; m < take.markers.num_markers(); ++m) labels.push_back(take.markers.label(m));
    scene->markers.push_back(MakeViewMarkers(FileStem(FLAGS_compare) + " (compare)", labels, other.observed,
                                             world->transform));
  }
  world->skeleton = std::move(take.skeleton);
  return Status::Ok();
}

// Without a subject: --markers (and --compare markers) and --motion each in its own world.
Status AddFileWorlds(const Skeleton& skeleton, const Motion& motion, bool compare_markers, ViewScene* scene) {
  Status status = Status::Ok();
  if (!FLAGS_markers.empty()) {
    MarkerTrajectories trajectories;
    status = ReadMarkerFile(FLAGS_markers, &trajectories);
    if (status.ok()) status = RequireMarkerData(FLAGS_markers, trajectories);
    if (!status.ok()) return status;
    ViewTransform transform;
    status = MarkerTransform(FLAGS_markers, trajectories, &transform);
    if (!status.ok()) return status;
    scene->notes.push_back(transform.note);
    scene->frame_rate = trajectories.frame_rate;
    scene->markers.push_back(MakeViewMarkers("markers", trajectories, transform));
    if (compare_markers) {
      MarkerTrajectories other;
      status = ReadMarkerFile(FLAGS_compare, &other);
      if (status.ok()) status = RequireMarkerData(FLAGS_compare, other);
      if (!status.ok()) return status;
      ViewTransform other_transform;
      status = MarkerTransform(FLAGS_compare, other, &other_transform);
      if (!status.ok()) return status;
      scene->markers.push_back(MakeViewMarkers(FileStem(FLAGS_compare) + " (compare)", other, other_transform));
    }
  }
  if (!FLAGS_motion.empty()) {
    ViewTransform motion_transform;
    status = MotionTransform(FLAGS_motion, skeleton, motion, &motion_transform);
    if (!status.ok()) return status;
    scene->notes.push_back(motion_transform.note);
    scene->skeletons.push_back(MakeViewSkeleton(FileStem(FLAGS_motion), skeleton, motion, motion_transform));
    if (FLAGS_markers.empty()) scene->frame_rate = motion.frame_rate;
  }
  return Status::Ok();
}

// --compare=OTHER.bvh ghosted: in the take's world when it is a motion of the subject's
// skeleton (as --motion), else in its own.
Status AddCompareMotion(const TakeWorld& take, ViewScene* scene) {
  Skeleton other_skeleton;
  Motion other;
  Status status = LoadViewMotion(FLAGS_compare, &other_skeleton, &other);
  if (!status.ok()) return status;
  const std::string name = FileStem(FLAGS_compare) + " (compare)";
  Motion on_subject;
  ViewSkeleton ghost;
  if (take.active && MotionOnSkeleton(other_skeleton, other, take.skeleton, &on_subject).ok()) {
    ghost = MakeViewSkeleton(name, take.skeleton, on_subject, take.transform);
  } else {
    ViewTransform transform;
    status = MotionTransform(FLAGS_compare, other_skeleton, other, &transform);
    if (!status.ok()) return status;
    if (take.active) scene->notes.push_back(name + ": not the subject's skeleton; drawn in its own world");
    ghost = MakeViewSkeleton(name, other_skeleton, other, transform);
  }
  ghost.ghost = true;
  scene->skeletons.push_back(std::move(ghost));
  return Status::Ok();
}

Status RunView(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (FLAGS_out.empty()) return Status::Error("--out=PAGE.html is required");
  if (!IsTextOutputPath(FLAGS_out, ".html")) return Status::Error("--out=" + FLAGS_out + ": expected an .html page");
  if (FLAGS_markers.empty() && FLAGS_motion.empty() && FLAGS_character.empty()) {
    return Status::Error("nothing to show: give --markers, --motion and/or --character");
  }
  if (!FLAGS_repair_report.empty() && FLAGS_markers.empty()) return Status::Error("--repair_report needs --markers");
  if (!FLAGS_compare.empty() && FLAGS_markers.empty() && FLAGS_motion.empty()) {
    return Status::Error("--compare needs --markers or --motion to compare with");
  }
  const bool compare_markers = !FLAGS_compare.empty() && IsMarkerFile(FLAGS_compare);
  if (compare_markers && FLAGS_markers.empty()) return Status::Error("--compare=" + FLAGS_compare + ": a marker file needs --markers");
  if (!FLAGS_compare.empty() && !compare_markers && FLAGS_motion.empty()) {
    return Status::Error("--compare=" + FLAGS_compare + ": a motion needs --motion");
  }
  // The runtime first: a missing install is the first thing to say.
  std::string runtime_path;
  Status status = FindViewerRuntime(&runtime_path);
  if (!status.ok()) return status;

  ViewScene scene;
  std::vector<std::string> names;
  Skeleton skeleton;
  Motion motion;
  if (!FLAGS_motion.empty()) {
    status = LoadViewMotion(FLAGS_motion, &skeleton, &motion);
    if (!status.ok()) return status;
    names.push_back(FileStem(FLAGS_motion));
  }
  if (!FLAGS_markers.empty()) names.insert(names.begin(), FileStem(FLAGS_markers));
  TakeWorld take;
  status = !FLAGS_markers.empty() && HaveSubject() ? AddSubjectTake(skeleton, &motion, compare_markers, &scene, &take)
                                                   : AddFileWorlds(skeleton, motion, compare_markers, &scene);
  if (status.ok() && !FLAGS_compare.empty() && !compare_markers) status = AddCompareMotion(take, &scene);
  if (!status.ok()) return status;
  if (!FLAGS_repair_report.empty()) {
    ViewMarkers& markers = scene.markers[0];
    std::vector<ReportedInterval> detected, filled;
    status = ReadRepairReport(FLAGS_repair_report, markers.labels, markers.num_frames, &detected, &filled);
    if (!status.ok()) return status;
    scene.intervals = RepairedViewIntervals(detected, filled);
    MarkRepairedSamples(scene.intervals, &markers);
  }
  status = AddFalloff(&scene);
  if (status.ok()) status = AddCharacters(&scene);
  if (!status.ok()) return status;
  if (!(scene.frame_rate > 0.0)) scene.frame_rate = 30.0;
  if (!FLAGS_title.empty()) {
    scene.title = FLAGS_title;
  } else {
    for (const std::string& name : names) scene.title += (scene.title.empty() ? "" : " + ") + name;
    for (const ViewCharacter& c : scene.characters) scene.title += (scene.title.empty() ? "" : " + ") + c.name;
  }
  status = WriteViewPage(FLAGS_out, scene);
  if (!status.ok()) return status;
  if (!FLAGS_quiet) {
    char residual[96] = "";
    if (take.samples > 0) std::snprintf(residual, sizeof(residual), ", marker residual RMS %.4g mm", take.rms_mm);
    std::printf("view: %d frames, %zu marker sets, %zu skeletons, %zu characters%s; wrote %s\n", scene.num_frames(),
                scene.markers.size(), scene.skeletons.size(), scene.characters.size(), residual, FLAGS_out.c_str());
  }
  return Status::Ok();
}

}  // namespace

extern const Command kViewCommand = {
    "view", "write a self-contained browser page showing markers, motions, characters, repairs",
    "mocapsolve view [--markers=M.c3d|.trc] [--motion=X.bvh|.amc --skeleton=...] "
    "[--character=C.glb|.gltf[,C2.glb]] [--repair_report=r.json] [--falloff=w.csv] "
    "[--compare=OTHER.c3d|.bvh] --out=PAGE.html\n\n"
    "One HTML file that opens from disk, offline: three.js (installed by scripts/viewer_tools.sh)\n"
    "and the data (base64 binary arrays) inlined. One 3D view (orbit: drag; zoom: wheel),\n"
    "markers coloured by state (observed, missing, repaired by reason), hover or click names\n"
    "a marker; skeletons as bones, --compare ghosted; characters playing beside the source; a\n"
    "timeline with play/pause/step/scrub, the marker residual, repaired intervals and falloffs.\n"
    "With --subject (or --skeleton and --markerset) the markers are mapped onto the skeleton and\n"
    "the residual of --motion is drawn; otherwise each file is shown in its own unit, with its up\n"
    "axis from --up.",
    __FILE__, RunView,
    "subject,skeleton,skeleton_units,markerset,axes,marker_scale,markers,motion,character,out,amc_fps,animation,sample_fps,quiet"};

}  // namespace mocapsolve
