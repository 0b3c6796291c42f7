#include "pipeline/take_pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "io/atomic_file.h"
#include "io/bvh_writer.h"
#include "io/fbx_writer.h"
#include "io/gltf_writer.h"
#include "io/marker_file.h"
#include "io/motion_file.h"
#include "settings/repair_settings.h"
#include "pipeline/memory_estimate.h"
#include "pipeline/repair_report.h"
#include "pipeline/retarget_quality_report.h"
#include "pipeline/take_labelling.h"
#include "pipeline/take_view.h"
#include "problems/marker_solve/subject_checks.h"
#include "signal/motion_pyramid.h"
#include "viewer/view_page.h"

namespace mocapsolve {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string InFolder(const std::string& out_dir, const std::string& name) {
  if (out_dir.empty()) return name;
  return out_dir.back() == '/' ? out_dir + name : out_dir + "/" + name;
}

}  // namespace

bool TakePipelineOptions::IsValid(std::string* error) const {
  if (filter_levels < 0 || filter_levels > 30) {
    *error = "filter_levels: must be in [0, 30]";
    return false;
  }
  if (filter_levels > 0) {
    const Status status = filter.Validate();
    if (!status.ok()) {
      *error = "filter: " + status.message();
      return false;
    }
  }
  if (label != "auto" && label != "never" && label != "always") {
    *error = "label: unknown '" + label + "' (auto, never, always)";
    return false;
  }
  if (window_frames < 1 || window_context_frames < 0 || window_seam_blend_frames < 0) {
    *error = "window_frames: must be >= 1, window_context_frames and window_seam_blend_frames >= 0";
    return false;
  }
  if (num_threads < 1) {
    *error = "num_threads: must be >= 1";
    return false;
  }
  if (!(memory_mb >= 0.0) || !std::isfinite(memory_mb)) {
    *error = "memory_mb: must be >= 0 (0 = no limit)";
    return false;
  }
  return gate.IsValid(error) && retarget.IsValid(error);
}

std::string RepairedMarkersPath(const std::string& out_dir, const std::string& markers_path) {
  return InFolder(out_dir, "repaired" + FileExtension(markers_path));
}

std::string SolvedMotionPath(const std::string& out_dir) { return InFolder(out_dir, "solved.bvh"); }

std::string CharacterOutputPath(const std::string& out_dir, const std::string& character_name,
                                const std::string& character_path) {
  const std::string extension = FileExtension(character_path) == ".gltf" ? ".gltf" : ".glb";
  return InFolder(out_dir, character_name + extension);
}

Status CharacterFilesFromSettings(const DeliverySettings& delivery, bool animation_only,
                                  CharacterFileOptions* files) {
  files->animation_only = animation_only;
  files->fbx_key_tolerance_mm = delivery.fbx_key_tolerance;
  return DeliveryFormats(delivery, &files->formats);
}

std::string CharacterFormatPath(const std::string& out_dir, const std::string& character_path,
                                const std::string& format) {
  const std::string name = FileStem(character_path);
  if (format == "glb") return CharacterOutputPath(out_dir, name, character_path);
  return InFolder(out_dir, name + "." + format);
}

Status CheckCharacterFiles(const std::string& out_dir, const TakeInputs& inputs, const CharacterFileOptions& files) {
  for (const std::string& path : inputs.character_paths) {
    for (const std::string& format : files.formats) {
      if (CharacterFormatPath(out_dir, path, format) == SolvedMotionPath(out_dir)) {
        return Status::Error(path + ": --formats=" + format + " would write the character as " +
                             SolvedMotionPath(out_dir) + ", the take's solve (rename the character file)");
      }
    }
  }
  return Status::Ok();
}

namespace {

// The take's markers onto its subject, their points labelled first when options.label
// says so (auto: the file lacks some of the subject's labels); *label_seconds the
// labelling's time (0 when not labelled).
Status ReadTakeMarkers(const TakeInputs& inputs, const TakePipelineOptions& options, TakeResult* result,
                       const PipelineProgress& progress, double* label_seconds) {
  MarkerTrajectories file;
  Status status = ReadMarkerFileForSubject(*inputs.subject, inputs.markers_path, &file);
  if (!status.ok()) return Status::Error("read: " + status.message());
  return MapTakeMarkers(inputs, options, std::move(file), result, progress, label_seconds);
}

// Error when options.memory_mb is set and the take's estimate (its file's frame and marker
// counts, the samples not read) is over it: the per-frame stages (of one window for a
// windowed take), plus the clip reference's problem and the filter when asked.
Status CheckTakeMemory(const TakeInputs& inputs, const TakePipelineOptions& options) {
  if (!(options.memory_mb > 0.0)) return Status::Ok();
  MarkerFileShape shape;
  const Status status = ReadMarkerFileShape(inputs.markers_path, &shape);
  if (!status.ok()) return Status::Error("read: " + status.message());
  return CheckMemoryLimit(TakeMemory(shape.frames, shape.markers, options), options.memory_mb, inputs.markers_path);
}

}  // namespace

MemoryEstimate TakeMemory(int frames, int markers, const TakePipelineOptions& options) {
  const bool windowed = frames > options.window_frames;
  const int window = windowed ? std::min(frames, options.window_frames + 2 * options.window_context_frames) : frames;
  MemoryEstimate estimate = windowed ? WindowedPipelineMemory(frames, window, markers) : PipelineMemory(frames, markers);
  std::vector<MemoryEstimate> more;
  if (options.repair.reference_kind == ReferenceKind::kClip) more.push_back(ClipSolveMemory(window, markers));
  if (options.filter_levels > 0) more.push_back(PipelineFilterMemory(window));
  for (const MemoryEstimate& m : more) {
    if (windowed) {
      AddPerWindow(m, window, &estimate);
    } else {
      estimate.Add(m);
    }
  }
  return estimate;
}

Status MapTakeMarkers(const TakeInputs& inputs, const TakePipelineOptions& options, MarkerTrajectories file,
                      TakeResult* result, const PipelineProgress& progress, double* label_seconds) {
  *label_seconds = 0.0;
  const Subject& subject = *inputs.subject;
  const std::vector<std::string> missing = SubjectLabelsMissing(subject, file);
  if (options.label == "always" || (options.label == "auto" && !missing.empty())) {
    const Clock::time_point start = Clock::now();
    TakeLabelling labelling;
    Status status = LabelTakeForSubject(subject, file, inputs.markers_path, options.labelling, options.label_solver,
                                        [&](int done, int total) {
                                          if (progress) progress("label", done, total);
                                        },
                                        &labelling);
    if (!status.ok()) return Status::Error("label: " + status.message());
    std::string reason = "always";
    if (options.label == "auto") {
      reason = std::to_string(missing.size()) + " of the subject's " + std::to_string(subject.markers.num_markers()) +
               " labels missing from the file (" + missing.front() + (missing.size() > 1 ? ", ...)" : ")");
    }
    result->labelling = LabellingReport(subject, labelling).Add("reason", reason);
    result->labelled_points = labelling.points;
    for (const MarkerLabelStats& s : labelling.details.per_marker) result->labelled_samples += s.labelled;
    file = std::move(labelling.markers);
    *label_seconds = SecondsSince(start);
  }
  Status status = TakeForSubject(subject, std::move(file), inputs.markers_path, &result->take);
  if (status.ok()) status = RequireTakeData(inputs.markers_path, result->take);
  if (status.ok()) return status;
  const bool raw = options.label == "never" && !missing.empty();
  return Status::Error("read: " + status.message() + (raw ? " (a raw capture? --label=auto labels its points first)" : ""));
}

Status ReadTakeCharacters(const TakeInputs& inputs, std::vector<CharacterOutput>* characters) {
  for (const std::string& path : inputs.character_paths) {
    CharacterOutput output;
    output.path = path;
    output.name = FileStem(path);
    Status status = GltfDocument::Read(path, &output.document);
    if (status.ok()) status = ReadGltfCharacter(output.document, GltfReadOptions(), &output.character);
    if (!status.ok()) return Status::Error("read: " + status.message());
    for (const std::string& existing : output.character.animation_names) {
      if (existing == inputs.name) {
        return Status::Error("read: " + path + ": already has an animation named '" + inputs.name +
                             "' (the take's name)");
      }
    }
    for (const CharacterOutput& other : *characters) {
      if (other.name == output.name) {
        return Status::Error("read: " + path + ": two characters named '" + output.name + "'");
      }
    }
    characters->push_back(std::move(output));
  }
  return Status::Ok();
}

void SetRepairGateFigures(double mm, TakeResult* result) {
  QualityFigures& figures = result->figures;
  figures.naive_rms_mm = result->repair.naive_rms * mm;
  figures.repaired_rms_mm = result->repair.repaired_rms * mm;
  figures.repaired_share = result->samples > 0 ? double(result->repaired_samples) / result->samples : 0.0;
  figures.iteration_limit_share = double(result->repair.naive_unconverged_frames) / result->frames;
}

Status RunTakePipeline(const TakeInputs& inputs, const TakePipelineOptions& options, TakeResult* result,
                       const PipelineProgress& progress) {
  if (inputs.subject == nullptr) return Status::Error("pipeline: no subject");
  std::string error;
  if (!options.IsValid(&error)) return Status::Error("pipeline options: " + error);
  const Clock::time_point start = Clock::now();
  Status status = CheckTakeMemory(inputs, options);
  if (!status.ok()) return status;

  // Read: the markers through the subject's mapping; the characters.
  Clock::time_point stage_start = Clock::now();
  double label_seconds = 0.0;
  status = ReadTakeMarkers(inputs, options, result, progress, &label_seconds);
  if (!status.ok()) return status;
  const int frames = static_cast<int>(result->take.observed.size());
  if (frames == 0) return Status::Error("read: " + inputs.markers_path + ": the take has no frames");
  int first = 0, last = 0;  // The delivered range, checked before any work.
  status = ResolveClipRange(options.delivery.range, frames, result->take.trajectories.frame_rate, &first, &last);
  if (!status.ok()) return Status::Error("deliver: " + inputs.markers_path + ": " + status.message());
  status = ReadTakeCharacters(inputs, &result->characters);
  if (!status.ok()) return status;
  result->timings.push_back({"read", SecondsSince(stage_start) - label_seconds});
  if (label_seconds > 0.0) result->timings.push_back({"label", label_seconds});
  status = RunTakeStages(inputs, options, result, progress);
  result->seconds = SecondsSince(start);
  return status;
}

Status RunTakeStages(const TakeInputs& inputs, const TakePipelineOptions& options, TakeResult* result,
                     const PipelineProgress& progress) {
  Motion solved;
  Status status = RunTakeRepairStage(inputs, options, result, &solved, progress);
  if (status.ok()) status = RunTakeCharacterStage(inputs, options, std::move(solved), result, progress);
  return status;
}

Status RunTakeRepairStage(const TakeInputs& inputs, const TakePipelineOptions& options, TakeResult* result,
                          Motion* solved_out, const PipelineProgress& progress) {
  auto lap = [&](const std::string& stage, Clock::time_point since) {
    result->timings.push_back({stage, SecondsSince(since)});
  };
  const MarkerTake& take = result->take;
  const int frames = result->frames = static_cast<int>(take.observed.size());
  int first = 0, last = 0;  // The delivered range (checked by the caller).
  Status status = ResolveClipRange(options.delivery.range, frames, take.trajectories.frame_rate, &first, &last);
  if (!status.ok()) return Status::Error("deliver: " + inputs.markers_path + ": " + status.message());

  // 1. Repair, whose re-solve is the take's solve.
  Clock::time_point stage_start = Clock::now();
  if (progress) progress("repair", 0, frames);
  std::vector<std::vector<Eigen::Vector3d>> repaired;
  RepairOptions repair_options = options.repair;
  SetRepairRestRotations(take.mean_pose, &repair_options);
  Motion& solved = *solved_out;  // Until the retarget takes it over; result->solved keeps it compact.
  solved = Motion();
  status = RepairMarkers(take.skeleton, take.markers, take.observed, take.unlabelled, repair_options, &repaired,
                         &solved, &result->repair);
  if (!status.ok()) return Status::Error("repair: " + inputs.markers_path + ": " + status.message());
  solved.frame_rate = take.trajectories.frame_rate;
  if (progress) progress("repair", frames, frames);
  result->repaired_file = WithRepairedSamples(take, repaired, &result->repaired_samples, result->repair.unlabelled);
  result->repaired = std::move(repaired);
  // The file's samples live on in repaired_file: the take keeps the file's metadata only
  // (frame rate, unit, labels), not a second copy of a long take (1.2 KB per frame).
  result->take.trajectories = TrajectoryFrames(take.trajectories, 0, 0);
  result->samples = frames * take.markers.num_markers();
  lap("repair and solve", stage_start);

  // 2. Filter.
  if (options.filter_levels > 0) {
    stage_start = Clock::now();
    PyramidOptions pyramid = options.filter;
    pyramid.levels = options.filter_levels;
    Motion filtered;
    status = FilterMotion(solved, pyramid, DropFinestBands(pyramid.levels, pyramid.levels), &filtered);
    if (!status.ok()) return Status::Error("filter: " + status.message());
    solved = std::move(filtered);
    lap("filter", stage_start);
  }
  result->solved = CompactMotion(solved);

  // The quality gate's marker checks (its retarget checks follow the retargets), on the
  // solve in double before the retarget takes it over.
  const double mm = take.skeleton.unit().metres_per_unit * 1000.0;
  QualityFigures& figures = result->figures;
  SetRepairGateFigures(mm, result);
  // The checks of a fitted subject, on this take: skin distance and torso direction.
  const SubjectChecks checks = CheckSubjectFit(take.skeleton, take.markers, take.observed, solved);
  figures.max_marker_offset_cm = checks.max_bone_distance_cm;
  figures.farthest_marker = checks.farthest_marker;
  figures.torso_error_deg = checks.torso_frames > 0 ? checks.torso_error_mean_deg : std::nan("");
  result->verdict = CheckQuality(options.gate, figures);
  if (!result->verdict.pass) {  // Only the marker checks so far: which markers and frames carry them.
    result->blame = BlameMarkers(take.skeleton, take.markers, take.observed, solved, mm);
    result->gate_advice = GateAdvice(result->blame, inputs.markers_path, inputs.subject_from_take);
  }
  // Nothing reads the samples as observed from here (the page shows the repaired ones).
  result->take.observed = std::vector<std::vector<Eigen::Vector3d>>();
  return Status::Ok();
}

Status RunTakeCharacterStage(const TakeInputs& inputs, const TakePipelineOptions& options, Motion solved,
                             TakeResult* result, const PipelineProgress& progress) {
  const MarkerTake& take = result->take;
  const int frames = result->frames;
  int first = 0, last = 0;  // The delivered range (checked before the repair stage).
  Status status = ResolveClipRange(options.delivery.range, frames, take.trajectories.frame_rate, &first, &last);
  if (!status.ok()) return Status::Error("deliver: " + inputs.markers_path + ": " + status.message());

  // 3. Retarget onto each character; the last one takes the solve over (its working copy
  // is made in place: one whole-take copy of the solve less while it runs).
  for (size_t k = 0; k < result->characters.size(); ++k) {
    CharacterOutput& output = result->characters[k];
    const Clock::time_point stage_start = Clock::now();
    const std::string stage = "retarget onto " + output.name;
    const GltfCharacter& character = output.rig();
    RetargetCharacter source;  // Skeleton only: the character's mesh is bound to it.
    source.skeleton = &take.skeleton;
    RetargetCharacter target;
    target.skeleton = &character.skeleton;
    target.mesh = &character.mesh;
    target.bind_pose = character.bind_pose;
    target.rest_pose = character.rest_pose;
    Motion source_motion = k + 1 == result->characters.size() ? std::move(solved) : solved;
    status = RetargetMotionOntoCharacter(source, std::move(source_motion), target, options.retarget, &output.result,
                                         [&](int done, int total) {
                                           if (progress) progress(stage, done, total);
                                         });
    if (!status.ok()) return Status::Error("retarget: " + output.path + ": " + status.message());
    output.delivered_is_clip = first == 0 && last == frames - 1 && options.delivery.out_fps == 0.0;
    if (!output.delivered_is_clip) {
      status = DeliverClip(output.result.clip.motion, options.delivery, &output.delivered);
      if (!status.ok()) return Status::Error("deliver: " + output.path + ": " + status.message());
    }
    output.take = CompactMotion(output.result.clip.motion);
    output.result.clip.motion = Motion();
    result->timings.push_back({stage, SecondsSince(stage_start)});
  }

  // 4. The quality gate's retarget checks.
  for (const CharacterOutput& output : result->characters) {
    CheckRetargetQuality(options.gate, output.result.quality, output.name, &result->verdict);
  }
  return Status::Ok();
}

JsonObject TakeReport(const TakeInputs& inputs, const TakeResult& result) {
  const MarkerTake& take = result.take;
  const int frames = result.frames;
  const double mm = take.skeleton.unit().metres_per_unit * 1000.0;
  std::vector<JsonObject> timings;
  for (const StageTime& t : result.timings) {
    JsonObject o;
    o.Add("stage", t.stage).Add("seconds", t.seconds);
    timings.push_back(o);
  }
  std::vector<JsonObject> repair_timings;
  for (const RepairStageTime& t : result.repair.timings) {
    JsonObject o;
    o.Add("stage", t.stage).Add("seconds", t.seconds);
    repair_timings.push_back(o);
  }
  std::vector<JsonObject> filled;
  for (const RepairInterval& i : result.repair.filled) {
    JsonObject o;
    o.Add("marker", take.markers.label(i.marker)).Add("first_frame", i.first).Add("last_frame", i.last)
        .Add("what", i.what);
    filled.push_back(o);
  }
  JsonObject repair;
  repair.Add("detected_intervals", static_cast<int>(result.repair.detected.size()))
      .Add("filled_intervals", filled)
      .Add("repaired_samples", result.repaired_samples)
      .Add("samples", result.samples)
      .Add("rms_naive_mm", result.repair.naive_rms * mm)
      .Add("rms_reference_mm", result.repair.reference_rms * mm)
      .Add("rms_repaired_mm", result.repair.repaired_rms * mm)
      .Add("naive_frames_at_iteration_limit", result.repair.naive_unconverged_frames)
      .Add("resolved_frames", result.repair.resolved_frames)
      .Add("carried_joints", CarriedJointsJson(take.skeleton, result.repair.carried))
      .Add("naive_hidden_joints_held_frames", HeldJointsJson(take.skeleton, result.repair.naive_held_frames))
      .Add("naive_twist_held_frames", HeldJointsJson(take.skeleton, result.repair.naive_twist_held_frames))
      .Add("timings", repair_timings);
  std::vector<JsonObject> characters;
  for (const CharacterOutput& c : result.characters) {
    const RetargetClipResult& r = c.result.clip;
    std::vector<std::string> failures;  // The gate's lines about this character.
    for (const std::string& f : result.verdict.failures) {
      if (f.rfind(c.name + ": ", 0) == 0) failures.push_back(f);
    }
    JsonObject o;
    o.Add("character", c.name)
        .Add("file", c.path)
        .Add("joints", c.character.skeleton.num_joints())
        .Add("mean_vertex_error_fraction_of_height", r.mean_position_error)
        .Add("max_vertex_error_fraction_of_height", r.max_position_error)
        .Add("mean_normal_error_deg", r.mean_normal_error_deg)
        .Add("planted_joints", static_cast<int>(c.result.plant_joints.size()))
        .Add("contact_samples", c.result.contact_samples)
        .Add("source_foot_skating_cm_per_s", c.result.source_plant_skating_cm_s)
        .Add("result_foot_skating_cm_per_s", c.result.result_plant_skating_cm_s)
        .Add("mean_bone_angle_deg", c.result.mean_bone_angle_deg)
        .Add("root_motion", c.result.root_motion.note.empty() ? std::string("keep") : c.result.root_motion.note)
        .Add("delivered_frames", c.delivered_frames())
        .Add("delivered_frame_rate", c.delivered_frame_rate())
        .Add("setup_seconds", c.result.setup_seconds)
        .Add("solve_seconds", r.solve_seconds)
        .Add("quality", RetargetQualityJson(c.result.quality, failures));
    characters.push_back(o);
  }
  std::vector<JsonValue> failures;
  for (const std::string& f : result.verdict.failures) failures.push_back(f);
  JsonObject gate;
  gate.Add("pass", result.verdict.pass)
      .Add("failures", failures)
      .Add("naive_rms_mm", result.figures.naive_rms_mm)
      .Add("repaired_rms_mm", result.figures.repaired_rms_mm)
      .Add("repaired_share", result.figures.repaired_share)
      .Add("iteration_limit_share", result.figures.iteration_limit_share)
      .Add("max_marker_bone_distance_cm", result.figures.max_marker_offset_cm)
      .Add("farthest_marker", result.figures.farthest_marker)
      .Add("torso_error_deg", result.figures.torso_error_deg);
  if (!result.gate_advice.empty()) {
    std::vector<JsonObject> blame;
    for (size_t k = 0; k < result.blame.size() && k < 10; ++k) {
      const MarkerBlame& b = result.blame[k];
      JsonObject o;
      o.Add("marker", b.label).Add("rms_mm", b.rms_mm).Add("share", b.share)
          .Add("worst_frames", std::vector<JsonValue>{JsonValue(b.worst_first), JsonValue(b.worst_last)});
      blame.push_back(o);
    }
    gate.Add("blame", blame).Add("advice", result.gate_advice);
  }
  JsonObject report;
  report.Add("take", inputs.name)
      .Add("markers", inputs.markers_path)
      .Add("frames", frames)
      .Add("frame_rate", take.trajectories.frame_rate)
      .Add("subject_markers", take.markers.num_markers())
      .Add("seconds", result.seconds)
      .Add("frames_per_second", result.seconds > 0 ? frames / result.seconds : 0.0)
      .Add("timings", timings);
  // The labelling when the points were labelled first, else null.
  if (result.labelling.Has("reason")) {
    report.Add("labelling", result.labelling);
  } else {
    report.Add("labelling", JsonValue());
  }
  report.Add("quality_gate", gate)
      .Add("repair", repair)
      .Add("characters", characters);
  if (result.windows.count > 0) {
    const TakeWindowsSummary& w = result.windows;
    std::vector<JsonValue> seam_max, seam_first;
    for (double d : w.seam_max_mm) seam_max.push_back(d);
    for (double d : w.seam_first_frame_mm) seam_first.push_back(d);
    JsonObject windows;
    windows.Add("count", w.count)
        .Add("frames", w.frames)
        .Add("context_frames", w.context_frames)
        .Add("seam_blend_frames", w.seam_blend_frames)
        .Add("threads", w.threads)
        .Add("seam_max_mm", seam_max.empty() ? 0.0 : *std::max_element(w.seam_max_mm.begin(), w.seam_max_mm.end()))
        .Add("seam_first_frame_max_mm",
             seam_first.empty() ? 0.0 : *std::max_element(w.seam_first_frame_mm.begin(), w.seam_first_frame_mm.end()))
        .Add("seams_mm", seam_max)
        .Add("seams_first_frame_mm", seam_first);
    report.Add("windows", windows);
  }
  return report;
}

std::string ViewPagePath(const std::string& out_dir) { return InFolder(out_dir, "view.html"); }

Status TakeViewPath(const std::string& view, const std::string& out_dir, std::string* path, std::string* warning) {
  path->clear();
  warning->clear();
  if (view == "off") return Status::Ok();
  std::string runtime;
  const Status found = FindViewerRuntime(&runtime);
  if (view == "auto") {
    if (found.ok()) {
      *path = ViewPagePath(out_dir);
    } else {
      *warning = "no view.html (--view=auto): " + found.message();
    }
    return Status::Ok();
  }
  if (!found.ok()) return Status::Error("--view=" + view + ": " + found.message());
  *path = view;
  return Status::Ok();
}

Status MakeTakeResultView(const TakeInputs& inputs, const TakeResult& result, ViewScene* scene) {
  TakeViewInputs view;
  view.title = inputs.name;
  view.skeleton = &result.take.skeleton;
  view.markers = &result.take.markers;
  view.repaired = &result.repaired;
  view.intervals = RepairViewIntervals(result.repair);
  const Motion solved = result.solved.ToMotion();  // The page's copy.
  view.motion = &solved;
  view.frame_rate = solved.frame_rate > 0 ? solved.frame_rate : 30.0;
  for (const CharacterOutput& c : result.characters) {
    ViewCharacter character;
    character.name = c.name;
    character.animation = inputs.name;
    GltfWriteOptions page_copy;
    page_copy.compact = true;  // Int16 rotations, still joints as one key: the page only plays it.
    Status status = SerializeGltfWithAnimation(c.document, c.character, c.take, inputs.name,
                                               /*binary=*/true, &character.glb, page_copy);
    if (!status.ok()) return status;
    view.characters.push_back(std::move(character));
  }
  return MakeTakeViewScene(view, scene);
}

Status WriteCharacterFiles(const std::string& out_dir, const std::string& take_name, const CharacterOutput& c,
                           const CharacterFileOptions& files) {
  GltfWriteOptions gltf;
  gltf.animation_only = files.animation_only;
  Status status = Status::Ok();
  for (const std::string& format : files.formats) {
    if (!status.ok()) break;
    const std::string path = CharacterFormatPath(out_dir, c.path, format);
    const bool compact = c.delivered_is_clip;
    if (format == "glb") {
      status = compact ? WriteGltfWithAnimation(c.document, c.character, c.take, take_name, path, gltf)
                       : WriteGltfWithAnimation(c.document, c.character, c.delivered, take_name, path, gltf);
    } else if (format == "fbx") {
      status = compact ? WriteFbxCharacter(path, c.character, c.take, take_name, files.animation_only,
                                           files.fbx_key_tolerance_mm)
                       : WriteFbxCharacter(path, c.character, c.delivered, take_name, files.animation_only,
                                           files.fbx_key_tolerance_mm);
    } else if (format == "bvh") {
      status = compact ? WriteBvh(path, c.character.skeleton, c.take, BvhWriteOptions())
                       : WriteBvh(path, c.character.skeleton, c.delivered, BvhWriteOptions());
    } else {
      status = Status::Error("--formats: unknown '" + format + "' (glb, fbx, bvh)");
    }
  }
  return status;
}

Status WriteTakeOutputs(const std::string& out_dir, const TakeInputs& inputs, const TakeResult& result,
                        const JsonObject& report, const std::string& view_path,
                        const CharacterFileOptions& character_files) {
  Status status = CheckCharacterFiles(out_dir, inputs, character_files);
  if (!status.ok()) return Status::Error("write: " + status.message());
  if (result.windows.count > 0) {  // Its other files are written (pipeline/take_windows.h).
    if (!view_path.empty()) return Status::Error("write: " + view_path + ": no page for a windowed take");
    status = WriteFileAtomically(InFolder(out_dir, "report.json"), report.ToString() + "\n");
    return status.ok() ? status : Status::Error("write: " + status.message());
  }
  status = WriteMarkerFile(RepairedMarkersPath(out_dir, inputs.markers_path), result.repaired_file);
  if (status.ok()) {  // From the compact solve, a piece at a time.
    status = WriteBvh(SolvedMotionPath(out_dir), result.take.skeleton, result.solved, BvhWriteOptions());
  }
  for (const CharacterOutput& c : result.characters) {
    if (status.ok()) status = WriteCharacterFiles(out_dir, inputs.name, c, character_files);
  }
  if (status.ok()) status = WriteFileAtomically(InFolder(out_dir, "report.json"), report.ToString() + "\n");
  if (status.ok() && !view_path.empty()) {
    ViewScene scene;
    status = MakeTakeResultView(inputs, result, &scene);
    if (status.ok()) status = WriteViewPage(view_path, scene);
  }
  return status.ok() ? status : Status::Error("write: " + status.message());
}

}  // namespace mocapsolve
