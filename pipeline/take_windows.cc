#include "pipeline/take_windows.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include "io/atomic_file.h"
#include "io/bvh_writer.h"
#include "io/marker_file.h"
#include "kinematics/forward_kinematics.h"
#include "pipeline/in_order_worker.h"
#include "pipeline/take_labelling.h"
#include "pipeline/window_seam_blend.h"

namespace mocapsolve {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A mean over windows weighted by their core frames; windows whose figure is not a number
// (not measured) are left out, and none measured gives NaN.
struct WeightedMean {
  double sum = 0.0, weight = 0.0;
  void Add(double value, double w) {
    if (!std::isfinite(value)) return;
    sum += value * w;
    weight += w;
  }
  double value() const { return weight > 0.0 ? sum / weight : std::nan(""); }
};

void AddMax(double value, double* max) {
  if (std::isfinite(value) && (!std::isfinite(*max) || value > *max)) *max = value;
}

// The combined figures of one character over the windows.
struct CharacterSums {
  WeightedMean position, normal, effector, cost, sigma, source_skate, result_skate, source_plant, result_plant;
  WeightedMean limb_mean, alignment, pelvis, chest, foot_skate, penetration_share, self_mean;
  std::vector<WeightedMean> limbs;
  bool started = false;
  double contact_samples = 0.0, plant_pairs = 0.0, contact_pairs = 0.0;
};

// Everything combined over the windows (see the header). `characters` is the character
// stages' (their thread's), the rest the repair stages'.
struct WindowSums {
  double naive_sq = 0.0, reference_sq = 0.0, repaired_sq = 0.0, frames = 0.0;
  double resolved = 0.0, unconverged = 0.0, trimmed = 0.0, removed = 0.0, polynomial = 0.0, rough = 0.0;
  std::vector<double> held, twist_held;
  WeightedMean torso;
  std::vector<CharacterSums> characters;
};

template <class T>
void KeepCore(const std::vector<T>& from, const FrameWindow& w, std::vector<T>* to) {
  for (T item : from) {
    item.first += w.first;
    item.last += w.first;
    if (item.first >= w.core_first && item.first <= w.core_last) to->push_back(item);
  }
}

template <class T>
void AddTime(const std::string& stage, double seconds, std::vector<T>* times) {
  for (T& t : *times) {
    if (t.stage == stage) {
      t.seconds += seconds;
      return;
    }
  }
  times->push_back({stage, seconds});
}

void ScaledSum(const std::vector<int>& from, double scale, std::vector<double>* to) {
  if (to->size() < from.size()) to->resize(from.size(), 0.0);
  for (size_t j = 0; j < from.size(); ++j) (*to)[j] += from[j] * scale;
}

std::vector<int> Rounded(const std::vector<double>& values) {
  std::vector<int> out;
  for (double v : values) out.push_back(static_cast<int>(std::lround(v)));
  return out;
}

// The repair's report, the gate's marker figures and the repair stage's timings of window
// `w` into *total and *sums.
void MergeRepair(const TakeResult& window, const FrameWindow& w, WindowSums* sums, TakeResult* total) {
  const RepairReport& r = window.repair;
  RepairReport& t = total->repair;
  const double core = w.core_last - w.core_first + 1;
  const double scale = core / (w.last - w.first + 1);  // Counts over the window, to its core.
  KeepCore(r.detected, w, &t.detected);
  KeepCore(r.filled, w, &t.filled);
  KeepCore(r.swaps, w, &t.swaps);
  KeepCore(r.unlabelled, w, &t.unlabelled);
  KeepCore(r.carried, w, &t.carried);
  for (const RepairStageTime& time : r.timings) AddTime(time.stage, time.seconds, &t.timings);
  sums->naive_sq += r.naive_rms * r.naive_rms * core;
  sums->reference_sq += r.reference_rms * r.reference_rms * core;
  sums->repaired_sq += r.repaired_rms * r.repaired_rms * core;
  sums->frames += core;
  sums->resolved += r.resolved_frames * scale;
  sums->unconverged += r.naive_unconverged_frames * scale;
  sums->trimmed += r.trimmed_samples * scale;
  sums->removed += r.removed_track_samples * scale;
  sums->polynomial += r.polynomial_samples * scale;
  sums->rough += r.rough_extension_samples * scale;
  ScaledSum(r.naive_held_frames, scale, &sums->held);
  ScaledSum(r.naive_twist_held_frames, scale, &sums->twist_held);
  sums->torso.Add(window.figures.torso_error_deg, core);
  if (window.figures.max_marker_offset_cm > total->figures.max_marker_offset_cm ||
      total->figures.farthest_marker.empty()) {
    total->figures.max_marker_offset_cm = window.figures.max_marker_offset_cm;
    total->figures.farthest_marker = window.figures.farthest_marker;
  }
  for (const StageTime& time : window.timings) AddTime(time.stage, time.seconds, &total->timings);
}

// The characters' retarget figures of one window into *total (the first window's result
// gives what does not change: setup, joint map, plants, root motion) and *sums.
void MergeCharacters(const TakeResult& window, const FrameWindow& w, WindowSums* sums, TakeResult* total) {
  const double core = w.core_last - w.core_first + 1;
  const double scale = core / (w.last - w.first + 1);
  sums->characters.resize(window.characters.size());
  for (size_t c = 0; c < window.characters.size(); ++c) {
    const CharacterRetargetResult& r = window.characters[c].result;
    CharacterRetargetResult& t = total->characters[c].result;
    CharacterSums& s = sums->characters[c];
    if (!s.started) {
      s.started = true;
      t = r;
      t.clip.frames.clear();
      t.clip.solve_seconds = 0.0;
      t.setup_seconds = 0.0;
      t.clip.max_position_error = -std::numeric_limits<double>::infinity();
      t.quality.limb_p95_deg = t.quality.pelvis_orientation_p95_deg = t.quality.chest_orientation_p95_deg = std::nan("");
      t.quality.penetration_cm = t.quality.self_joint_error_max_cm = std::nan("");
      for (LimbDirectionError& limb : t.quality.limbs) limb.p95_deg = std::nan("");
      s.limbs.resize(t.quality.limbs.size());
    }
    t.clip.solve_seconds += r.clip.solve_seconds;
    t.setup_seconds += r.setup_seconds;
    s.position.Add(r.clip.mean_position_error, core);
    AddMax(r.clip.max_position_error, &t.clip.max_position_error);
    s.normal.Add(r.clip.mean_normal_error_deg, core);
    s.effector.Add(r.clip.mean_effector_error, core);
    s.cost.Add(r.clip.mean_final_cost, core);
    s.sigma.Add(r.clip.sigma, core);
    s.source_skate.Add(r.clip.source_foot_skating, core);
    s.result_skate.Add(r.clip.result_foot_skating, core);
    s.source_plant.Add(r.source_plant_skating_cm_s, core);
    s.result_plant.Add(r.result_plant_skating_cm_s, core);
    s.contact_pairs += r.clip.contact_pairs * scale;
    s.contact_samples += r.contact_samples * scale;
    s.plant_pairs += r.plant_pairs * scale;
    const RetargetQuality& q = r.quality;
    s.limb_mean.Add(q.limb_mean_deg, core);
    AddMax(q.limb_p95_deg, &t.quality.limb_p95_deg);
    s.alignment.Add(q.alignment_deg, core);
    s.pelvis.Add(q.pelvis_orientation_mean_deg, core);
    AddMax(q.pelvis_orientation_p95_deg, &t.quality.pelvis_orientation_p95_deg);
    s.chest.Add(q.chest_orientation_mean_deg, core);
    AddMax(q.chest_orientation_p95_deg, &t.quality.chest_orientation_p95_deg);
    s.foot_skate.Add(q.foot_skate_cm_s, core);
    AddMax(q.penetration_cm, &t.quality.penetration_cm);
    s.penetration_share.Add(q.penetration_frame_share, core);
    s.self_mean.Add(q.self_joint_error_mean_cm, core);
    AddMax(q.self_joint_error_max_cm, &t.quality.self_joint_error_max_cm);
    for (size_t l = 0; l < t.quality.limbs.size(); ++l) {
      for (const LimbDirectionError& limb : q.limbs) {
        if (limb.limb != t.quality.limbs[l].limb) continue;
        s.limbs[l].Add(limb.mean_deg, core);
        AddMax(limb.p95_deg, &t.quality.limbs[l].p95_deg);
      }
    }
  }
}

// The combined figures and the gate's verdict, once every window is merged.
void FinishFigures(const TakePipelineOptions& options, const WindowSums& sums, TakeResult* total) {
  RepairReport& t = total->repair;
  const double n = std::max(sums.frames, 1.0);
  t.naive_rms = std::sqrt(sums.naive_sq / n);
  t.reference_rms = std::sqrt(sums.reference_sq / n);
  t.repaired_rms = std::sqrt(sums.repaired_sq / n);
  t.resolved_frames = static_cast<int>(std::lround(sums.resolved));
  t.naive_unconverged_frames = static_cast<int>(std::lround(sums.unconverged));
  t.trimmed_samples = static_cast<int>(std::lround(sums.trimmed));
  t.removed_track_samples = static_cast<int>(std::lround(sums.removed));
  t.polynomial_samples = static_cast<int>(std::lround(sums.polynomial));
  t.rough_extension_samples = static_cast<int>(std::lround(sums.rough));
  t.naive_held_frames = Rounded(sums.held);
  t.naive_twist_held_frames = Rounded(sums.twist_held);
  const double mm = total->take.skeleton.unit().metres_per_unit * 1000.0;
  SetRepairGateFigures(mm, total);
  QualityFigures& figures = total->figures;
  figures.torso_error_deg = sums.torso.value();
  total->verdict = CheckQuality(options.gate, figures);
  for (size_t c = 0; c < total->characters.size() && c < sums.characters.size(); ++c) {
    const CharacterSums& s = sums.characters[c];
    CharacterRetargetResult& r = total->characters[c].result;
    r.clip.mean_position_error = s.position.value();
    r.clip.mean_normal_error_deg = s.normal.value();
    r.clip.mean_effector_error = s.effector.value();
    r.clip.mean_final_cost = s.cost.value();
    r.clip.sigma = s.sigma.value();
    r.clip.source_foot_skating = s.source_skate.value();
    r.clip.result_foot_skating = s.result_skate.value();
    r.clip.contact_pairs = static_cast<int>(std::lround(s.contact_pairs));
    r.source_plant_skating_cm_s = s.source_plant.value();
    r.result_plant_skating_cm_s = s.result_plant.value();
    r.contact_samples = static_cast<int>(std::lround(s.contact_samples));
    r.plant_pairs = static_cast<int>(std::lround(s.plant_pairs));
    RetargetQuality& q = r.quality;
    q.limb_mean_deg = s.limb_mean.value();
    q.alignment_deg = s.alignment.value();
    q.pelvis_orientation_mean_deg = s.pelvis.value();
    q.chest_orientation_mean_deg = s.chest.value();
    q.foot_skate_cm_s = s.foot_skate.value();
    q.penetration_frame_share = s.penetration_share.value();
    q.self_joint_error_mean_cm = s.self_mean.value();
    for (size_t l = 0; l < q.limbs.size(); ++l) q.limbs[l].mean_deg = s.limbs[l].value();
    CheckRetargetQuality(options.gate, q, total->characters[c].name, &total->verdict);
  }
}

// The largest distance in mm between the joints and end sites of two solves of the same frames: frames
// [from, to] of the take, `a` holding frame f at f - a_first and `b` at f - b_first; at
// frame `at` into *at_mm.
double SeamDifference(const Skeleton& skeleton, const CompactMotion& a, int a_first, const CompactMotion& b,
                      int b_first, int from, int to, int at, double* at_mm) {
  const double mm = skeleton.unit().metres_per_unit * 1000.0;
  FkData fa(skeleton), fb(skeleton);
  Pose pa, pb;
  double largest = 0.0;
  *at_mm = 0.0;
  for (int f = from; f <= to; ++f) {
    a.Frame(f - a_first, &pa);
    b.Frame(f - b_first, &pb);
    ForwardKinematics(skeleton, pa, &fa);
    ForwardKinematics(skeleton, pb, &fb);
    double frame = 0.0;
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      frame = std::max(frame, (fa.world_positions[j] - fb.world_positions[j]).norm() * mm);
    }
    const Vector3dVector ea = EndSitePositions(skeleton, fa), eb = EndSitePositions(skeleton, fb);
    for (size_t e = 0; e < ea.size(); ++e) frame = std::max(frame, (ea[e] - eb[e]).norm() * mm);
    largest = std::max(largest, frame);
    if (f == at) *at_mm = frame;
  }
  return largest;
}

// The window's repaired samples of its core back into the take's file; the samples of the
// subject's markers that changed are counted into total->repaired_samples.
void KeepRepairedCore(const TakeResult& window, const FrameWindow& w, MarkerTrajectories* file, TakeResult* total) {
  const MarkerTrajectories& from = window.repaired_file;
  std::vector<bool> subject(from.num_markers(), false);
  for (int m = 0; m < window.take.markers.num_markers(); ++m) {
    const int column = from.FindMarker(window.take.markers.label(m));
    if (column >= 0) subject[column] = true;
  }
  for (int f = w.core_first; f <= w.core_last; ++f) {
    const int local = f - w.first;
    for (int m = 0; m < from.num_markers(); ++m) {
      const bool valid = from.valid(local, m);
      const bool same = valid == file->valid(f, m) &&
                        (!valid || (from.position(local, m) == file->position(f, m) &&
                                    from.residual(local, m) == file->residual(f, m)));
      if (same) continue;
      if (subject[m]) ++total->repaired_samples;
      if (valid) {
        file->SetSample(f, m, from.position(local, m), from.residual(local, m), from.camera_mask(local, m));
      } else {
        file->SetMissing(f, m);
      }
    }
  }
}

// What a windowed take cannot do yet; one line each.
Status CheckWindowedTake(const TakeInputs& inputs, const TakePipelineOptions& options,
                         const MarkerTrajectories& file) {
  const std::string take = inputs.markers_path + " (" + std::to_string(file.num_frames()) + " frames, over --window_frames=" +
                           std::to_string(options.window_frames) + ")";
  if (!options.delivery.keeps_clip()) {
    return Status::Error(take + ": a windowed take is delivered whole (no --frames, --seconds or --out_fps)");
  }
  const std::vector<std::string> missing = SubjectLabelsMissing(*inputs.subject, file);
  if (options.label == "always" || (options.label == "auto" && !missing.empty())) {
    return Status::Error(take + ": a windowed take is not labelled first; label it with `mocapsolve label` " +
                         (missing.empty() ? std::string("(--label=always)") : "(" + missing.front() + " missing)"));
  }
  return Status::Ok();
}

// The windows' outputs written as they finish (see the header).
struct WindowWriters {
  AtomicFileWriter bvh;
  BvhPieceWriter bvh_frames;
  CompactMotion previous_solve;  // The last window's, for the seam check.
  FrameWindow previous;
  WindowSeamBlend solve_seams{0};  // solved.bvh's frames, cross-faded at the seams.
};

// Window `w`'s repaired core into the outputs (the file's samples, solved.bvh), the repair's
// figures and the seam check; the window's repair stage done.
Status KeepRepairedWindow(const TakeResult& window, const FrameWindow& w, int frames, bool first_window,
                          bool last_window, WindowWriters* writers, MarkerTrajectories* file, WindowSums* sums,
                          TakeResult* total) {
  KeepRepairedCore(window, w, file, total);
  const Motion solve = window.solved.ToMotion();  // One window's.
  std::string lines;
  Status status = Status::Ok();
  if (first_window) {
    status = writers->bvh_frames.Start(total->take.skeleton, solve);  // Kept: the writer holds it.
    if (status.ok()) lines = writers->bvh_frames.Header(frames, window.solved.frame_rate());
  }
  if (status.ok()) {
    status = writers->solve_seams.Add(solve, w, last_window, [&](const Motion& motion, int first, int count) {
      return writers->bvh_frames.AppendFrames(motion, first, count, &lines);
    });
  }
  if (status.ok()) status = writers->bvh.Append(lines);
  if (!status.ok()) return status;
  if (!first_window) {
    double at = 0.0;
    const int to = std::min(writers->previous.last, w.last);
    total->windows.seam_max_mm.push_back(SeamDifference(window.take.skeleton, writers->previous_solve,
                                                        writers->previous.first, window.solved, w.first, w.first, to,
                                                        w.core_first, &at));
    total->windows.seam_first_frame_mm.push_back(at);
  }
  writers->previous_solve = window.solved;
  writers->previous = w;
  MergeRepair(window, w, sums, total);
  return Status::Ok();
}

// Window `w`'s character stage done (`part`): its cores appended to the characters' takes
// (cross-faded at the seams: window_seam_blend.h),
// its figures into sums->characters and total's characters, its timings into *timings.
// Touches nothing the repair stages do, so it runs on the character stages' thread.
Status KeepCharacters(const TakeResult& part, const FrameWindow& w, bool last_window,
                      std::vector<WindowSeamBlend>* seams, WindowSums* sums, std::vector<StageTime>* timings,
                      TakeResult* total) {
  for (size_t c = 0; c < part.characters.size(); ++c) {
    const Motion take = part.characters[c].take.ToMotion();
    CompactMotion& kept = total->characters[c].take;
    const Status status = (*seams)[c].Add(take, w, last_window, [&kept](const Motion& motion, int first, int count) {
      kept.Append(motion, first, count);
      return Status::Ok();
    });
    if (!status.ok()) return status;
  }
  MergeCharacters(part, w, sums, total);
  for (const StageTime& time : part.timings) AddTime(time.stage, time.seconds, timings);
  return Status::Ok();
}

// One window read from the file and run through the repair stage into *window and *solved
// (the character stage's input).
Status RunWindowRepair(const TakeInputs& inputs, const TakePipelineOptions& options, const MarkerTrajectories& file,
                       const FrameWindow& w, const Pose& start, const std::string& label,
                       const PipelineProgress& progress, TakeResult* window, Motion* solved) {
  double label_seconds = 0.0;
  TakePipelineOptions window_options = options;
  window_options.label = "never";  // CheckWindowedTake refused the others.
  window_options.repair.start_pose = start;
  Status status = MapTakeMarkers(inputs, window_options, TrajectoryFrames(file, w.first, w.last - w.first + 1),
                                 window, nullptr, &label_seconds);
  if (!status.ok()) return status;
  return RunTakeRepairStage(inputs, window_options, window, solved, [&](const std::string& stage, int done, int total) {
    if (progress) progress(label + stage, done, total);
  });
}

// A window's character stage: what it reads (CharacterPart) and its repaired solve, then
// what it made, kept in window order (KeepCharacters).
struct CharacterJob {
  TakeResult part;
  Motion solved;
};

// What a window's character stage reads (RunTakeCharacterStage): the repaired window's
// skeleton, frame rate and frames, and the characters read once for every window.
TakeResult CharacterPart(const TakeResult& window, const std::vector<CharacterOutput>& characters) {
  TakeResult part;
  part.take.skeleton = window.take.skeleton;
  part.take.trajectories = window.take.trajectories;  // Metadata only (RunTakeRepairStage).
  part.frames = window.frames;
  for (const CharacterOutput& c : characters) {
    CharacterOutput output;
    output.name = c.name;
    output.path = c.path;
    output.shared = &c.character;
    part.characters.push_back(std::move(output));
  }
  return part;
}

}  // namespace

std::vector<FrameWindow> TakeWindows(int frames, int window_frames, int context_frames) {
  std::vector<FrameWindow> windows;
  if (frames <= 0) return windows;
  const int n = frames <= window_frames ? 1 : (frames + window_frames - 1) / window_frames;
  for (int k = 0; k < n; ++k) {
    FrameWindow w;
    w.core_first = static_cast<int>(static_cast<long long>(frames) * k / n);
    w.core_last = static_cast<int>(static_cast<long long>(frames) * (k + 1) / n) - 1;
    w.first = std::max(0, w.core_first - context_frames);
    w.last = std::min(frames - 1, w.core_last + context_frames);
    windows.push_back(w);
  }
  return windows;
}

bool TakeRunsInWindows(const TakeInputs& inputs, const TakePipelineOptions& options, Status* status) {
  MarkerFileShape shape;
  *status = ReadMarkerFileShape(inputs.markers_path, &shape);
  if (!status->ok()) *status = Status::Error("read: " + status->message());
  // A file without points runs whole, which refuses it in one line (its header's frame
  // count can be anything).
  return status->ok() && shape.markers > 0 && shape.frames > options.window_frames;
}

Status RunTakeInWindows(const std::string& out_dir, const TakeInputs& inputs, const TakePipelineOptions& options,
                        const CharacterFileOptions& files, TakeResult* result, const PipelineProgress& progress) {
  if (inputs.subject == nullptr) return Status::Error("pipeline: no subject");
  std::string error;
  if (!options.IsValid(&error)) return Status::Error("pipeline options: " + error);
  const Clock::time_point start = Clock::now();
  MarkerFileShape shape;
  Status status = ReadMarkerFileShape(inputs.markers_path, &shape);
  if (!status.ok()) return Status::Error("read: " + status.message());
  status = CheckMemoryLimit(TakeMemory(shape.frames, shape.markers, options), options.memory_mb, inputs.markers_path);
  if (!status.ok()) return status;
  MarkerTrajectories file;  // Read whole once; each window's repaired core goes back into it.
  status = ReadMarkerFileForSubject(*inputs.subject, inputs.markers_path, &file);
  if (!status.ok()) return Status::Error("read: " + status.message());
  status = CheckWindowedTake(inputs, options, file);
  if (status.ok()) status = ReadTakeCharacters(inputs, &result->characters);
  if (!status.ok()) return status;
  const int frames = result->frames = file.num_frames();
  result->timings.push_back({"read", SecondsSince(start)});
  const std::vector<FrameWindow> windows = TakeWindows(frames, options.window_frames, options.window_context_frames);
  result->windows.count = static_cast<int>(windows.size());
  result->windows.frames = windows.front().core_last - windows.front().core_first + 1;
  result->windows.context_frames = options.window_context_frames;
  result->windows.seam_blend_frames = std::min(options.window_seam_blend_frames, options.window_context_frames);
  const bool second_thread = options.num_threads >= 2;  // For the windows' character stages.
  result->windows.threads = second_thread ? 2 : 1;
  for (CharacterOutput& c : result->characters) c.take.Reserve(frames);
  WindowWriters writers;
  writers.solve_seams = WindowSeamBlend(options.window_seam_blend_frames);
  std::vector<WindowSeamBlend> character_seams(result->characters.size(),
                                               WindowSeamBlend(options.window_seam_blend_frames));
  status = MakeFolders(out_dir);  // After every check: a refused take leaves nothing.
  if (status.ok()) status = writers.bvh.Open(SolvedMotionPath(out_dir));
  WindowSums sums;
  std::vector<StageTime> character_timings;
  // The repairs in order on this thread, each window starting from the previous one's solve
  // of the frame before it (RepairOptions::start_pose) and reading the file's samples with
  // the previous cores repaired; the character stages, which start from their own bind
  // pose, on a second thread with --num_threads >= 2 (pipeline/in_order_worker.h), at most
  // one window waiting, kept in window order; when the second thread is still busy as the
  // next window is given, and after the last, this thread runs the waiting one itself.
  InOrderWorker characters(second_thread);
  for (size_t k = 0; k < windows.size() && status.ok(); ++k) {
    Pose start;  // None for a window whose context reaches frame 0: it starts as the first.
    if (windows[k].first > 0) writers.previous_solve.Frame(windows[k].first - 1 - writers.previous.first, &start);
    const std::string label = "window " + std::to_string(k + 1) + "/" + std::to_string(windows.size()) + ": ";
    TakeResult window;
    Motion solved;
    status = RunWindowRepair(inputs, options, file, windows[k], start, label, progress, &window, &solved);
    if (k == 0 && status.ok()) {
      result->take.skeleton = window.take.skeleton;
      result->take.markers = window.take.markers;
      result->take.trajectories = window.take.trajectories;  // Metadata only (RunTakeRepairStage).
      result->samples = frames * window.take.markers.num_markers();
    }
    const bool last_window = k + 1 == windows.size();
    if (status.ok()) {
      status = KeepRepairedWindow(window, windows[k], frames, k == 0, last_window, &writers, &file, &sums, result);
    }
    if (!status.ok()) break;
    TakeResult part = CharacterPart(window, result->characters);
    window = TakeResult();  // Freed before a waiting window's character stage may run here.
    // The progress display is the repairs' when the character stages run beside them.
    PipelineProgress part_progress = nullptr;
    if (!second_thread && progress) {
      part_progress = [&progress, label](const std::string& stage, int done, int total) {
        progress(label + stage, done, total);
      };
    }
    const FrameWindow w = windows[k];
    auto job = std::make_shared<CharacterJob>(CharacterJob{std::move(part), std::move(solved)});
    const bool submitted = characters.Submit(
        [&inputs, &options, job, part_progress] {
          return RunTakeCharacterStage(inputs, options, std::move(job->solved), &job->part, part_progress);
        },
        [&, job, w, last_window] {
          return KeepCharacters(job->part, w, last_window, &character_seams, &sums, &character_timings, result);
        });
    if (!submitted) break;  // A window's character stage failed: Finish says which.
  }
  // solved.bvh and repaired.c3d are whole once the last window's repair is kept: finished
  // here while the last character stages may still run.
  if (status.ok()) status = writers.bvh.Close();
  Clock::time_point write_start = Clock::now();
  if (status.ok()) {
    status = WriteMarkerFile(RepairedMarkersPath(out_dir, inputs.markers_path), file);
    if (!status.ok()) status = Status::Error("write: " + status.message());
  }
  file = MarkerTrajectories();
  double write_seconds = SecondsSince(write_start);
  // A character stage's error first: it is an earlier window's than this thread's.
  const Status character_status = characters.Finish();
  if (!character_status.ok()) status = character_status;
  for (const StageTime& time : character_timings) AddTime(time.stage, time.seconds, &result->timings);
  if (!status.ok()) return status;
  FinishFigures(options, sums, result);
  write_start = Clock::now();
  for (CharacterOutput& c : result->characters) {
    c.delivered_is_clip = true;  // The report's delivered frames and the files: the compact take.
    if (status.ok()) status = WriteCharacterFiles(out_dir, inputs.name, c, files);
  }
  result->timings.push_back({"write", write_seconds + SecondsSince(write_start)});
  result->seconds = SecondsSince(start);
  return status.ok() ? status : Status::Error("write: " + status.message());
}

}  // namespace mocapsolve
