// mocapsolve fit_skeleton: a subject (bone lengths, marker attachments and offsets) from
// its markers alone, starting from a template subject (problems/marker_solve/skeleton_fit.h),
// checked by measures that do not trust the residual (subject_checks.h).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/solver_flags.h"
#include "io/bvh_writer.h"
#include "io/marker_file.h"
#include "io/marker_set_file.h"
#include "io/motion_file.h"
#include "pipeline/subject.h"
#include "problems/marker_solve/calibration.h"
#include "problems/marker_solve/skeleton_fit.h"
#include "problems/marker_solve/subject_checks.h"

DECLARE_string(out_subject);
DEFINE_string(template_subject, "", "Template subject (.json): skeleton and marker set to start from "
              "(e.g. CMU subject 2 calibrated on 02_01); replaces --skeleton/--markerset. --axes and "
              "--marker_scale then describe the take's marker file.");
DEFINE_string(out_markerset, "", "The fitted marker set (.json), in the skeleton's units.");
DEFINE_int32(fit_iterations, -1, "Alternations of pose solve and length/offset fit on the template's markers; "
             "-1: 15 with --template_subject, else 6.");
DEFINE_int32(attach_rounds, -1, "Rounds of attaching every marker of the take to the fitted skeleton (auto: "
             "the joint it moves least with, among joints whose bone is within --max_skin_cm) and fitting "
             "again (stopping early when a round does not improve); -1: 6 with --template_subject, else 0.");
DEFINE_int32(attach_iterations, 6, "Fit iterations in each attach round.");
DEFINE_int32(fit_frame_step, 4, "Use every N-th frame in the length/offset fit.");
DEFINE_int32(fit_max_frames, 0, "Fit on the first N frames only (0 = all).");
DEFINE_double(max_skin_cm, 12.0, "Markers stay within this distance of their bone (fit and attach); 0: off.");
DEFINE_double(min_bone_scale, 0.8, "Bone lengths no shorter than this times the template's.");
DEFINE_double(max_bone_scale, 1.25, "Bone lengths no longer than this times the template's.");
DEFINE_double(offset_prior, 0.0, "Weight of the prior that keeps marker offsets near the template's in the "
              "first fit, per frame, relative to a marker residual; 0: off.");
DEFINE_string(check, "fail", "The subject checks (marker within 15 cm of its bone, torso direction within "
              "15 degrees of the markers', left/right within 5 %, marker RMS within 25 mm): fail (exit 1, "
              "nothing written but the report), warn, off.");

namespace mocapsolve {
namespace {

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

JsonObject ChecksJson(const SubjectChecks& checks) {
  std::vector<JsonValue> failures(checks.failures.begin(), checks.failures.end());
  std::vector<JsonObject> markers;
  for (const MarkerDistance& d : checks.markers) {
    JsonObject o;
    o.Add("label", d.label).Add("joint", d.joint).Add("to_bone_cm", d.to_bone_cm).Add("to_joint_cm", d.to_joint_cm);
    markers.push_back(o);
  }
  JsonObject json;
  json.Add("passed", checks.ok()).Add("failures", failures).Add("rms_mm", checks.rms_mm)
      .Add("max_marker_bone_distance_cm", checks.max_bone_distance_cm)
      .Add("max_marker_joint_distance_cm", checks.max_joint_distance_cm)
      .Add("farthest_marker", checks.farthest_marker)
      .Add("torso_frames", checks.torso_frames)
      .Add("torso_error_mean_deg", checks.torso_error_mean_deg)
      .Add("torso_error_max_deg", checks.torso_error_max_deg)
      .Add("max_left_right_asymmetry", checks.max_asymmetry)
      .Add("least_symmetric_pair", checks.least_symmetric_pair)
      .Add("markers", markers);
  return json;
}

Status RunFitSkeleton(const std::vector<std::string>& arguments) {
  const auto start = std::chrono::steady_clock::now();
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  const bool from_subject = !FLAGS_template_subject.empty();
  if (from_subject && (!FLAGS_skeleton.empty() || !FLAGS_markerset.empty() || !FLAGS_skeleton_units.empty())) {
    return Status::Error(std::string("--template_subject and --") +
                         (!FLAGS_skeleton.empty() ? "skeleton" : !FLAGS_markerset.empty() ? "markerset" : "skeleton_units") +
                         " both given: the template subject holds the skeleton and marker set");
  }
  if (FLAGS_markers.empty() || (!from_subject && (FLAGS_skeleton.empty() || FLAGS_markerset.empty()))) {
    return Status::Error("--markers and either --template_subject or --skeleton and --markerset are required");
  }
  if (FLAGS_out.empty() && FLAGS_out_subject.empty()) return Status::Error("--out or --out_subject is required");
  if (!FLAGS_out.empty() && FileExtension(FLAGS_out) != ".bvh") return Status::Error(FLAGS_out + ": expected a .bvh");
  for (const std::string& json : {FLAGS_out_markerset, FLAGS_out_subject}) {
    if (!json.empty() && FileExtension(json) != ".json") return Status::Error(json + ": expected a .json");
  }
  const std::vector<std::string> outputs = {FLAGS_out, FLAGS_out_markerset, FLAGS_out_subject};
  for (size_t a = 0; a < outputs.size(); ++a) {
    if (outputs[a].empty()) continue;
    for (const std::string& in : {FLAGS_template_subject, FLAGS_skeleton, FLAGS_markers, FLAGS_markerset}) {
      if (in.empty()) continue;
      Status status = CheckNotAnInput(outputs[a], in);
      if (!status.ok()) return status;
    }
    for (size_t b = a + 1; b < outputs.size(); ++b) {
      if (outputs[a] == outputs[b]) return Status::Error(outputs[a] + ": named by two output flags");
    }
  }
  if (FLAGS_fit_iterations < -1 || FLAGS_fit_iterations > 100) return Status::Error("--fit_iterations: -1..100");
  if (FLAGS_attach_iterations < 0 || FLAGS_attach_iterations > 100) return Status::Error("--attach_iterations: 0..100");
  if (FLAGS_attach_rounds < -1 || FLAGS_attach_rounds > 20) return Status::Error("--attach_rounds: -1..20");
  if (FLAGS_fit_frame_step < 1) return Status::Error("--fit_frame_step: >= 1");
  if (FLAGS_fit_max_frames < 0) return Status::Error("--fit_max_frames: >= 0");
  if (!(FLAGS_offset_prior >= 0.0)) return Status::Error("--offset_prior: >= 0");
  if (!(FLAGS_max_skin_cm >= 0.0)) return Status::Error("--max_skin_cm: >= 0");
  if (!(FLAGS_min_bone_scale > 0.0 && FLAGS_min_bone_scale <= 1.0 && FLAGS_max_bone_scale >= 1.0)) {
    return Status::Error("--min_bone_scale in (0, 1] and --max_bone_scale >= 1");
  }
  if (FLAGS_check != "fail" && FLAGS_check != "warn" && FLAGS_check != "off") {
    return Status::Error("--check: expected fail, warn or off");
  }
  const int rounds = FLAGS_attach_rounds >= 0 ? FLAGS_attach_rounds : (from_subject ? 6 : 0);

  // The template.
  Subject templ;
  Status status = Status::Ok();
  if (from_subject) {
    status = ReadSubject(FLAGS_template_subject, &templ);
  } else {
    status = LoadSkeleton(FLAGS_skeleton, &templ.skeleton);
    if (status.ok()) status = ReadMarkerSet(FLAGS_markerset, templ.skeleton, &templ.markers);
  }
  if (!status.ok()) return status;
  const Skeleton& skeleton = templ.skeleton;
  if (FLAGS_max_skin_cm > 0.0 && !skeleton.unit().known()) {
    return Status::Error("the template skeleton's unit is unknown: give --skeleton_units (or --max_skin_cm=0)");
  }
  const double units_per_cm = skeleton.unit().known() ? 0.01 / skeleton.unit().metres_per_unit : 1.0;

  // The take, in the skeleton's frame and units (--axes, --marker_scale describe it).
  Subject take_mapping = templ;
  take_mapping.axes = FLAGS_axes;
  take_mapping.marker_scale = FLAGS_marker_scale;
  take_mapping.label_prefix.clear();
  MarkerTrajectories file;
  status = ReadMarkerFile(FLAGS_markers, &file);
  if (!status.ok()) return status;
  // A template set may name markers this take lacks: fit the ones it has.
  std::vector<MarkerSpec> present;
  std::string absent;
  for (int m = 0; m < templ.markers.num_markers(); ++m) {
    if (file.FindMarker(templ.markers.label(m)) >= 0) {
      present.push_back(templ.markers.marker(m));
    } else {
      absent += (absent.empty() ? "" : ", ") + templ.markers.label(m);
    }
  }
  if (present.size() < 3) return Status::Error(FLAGS_markers + ": fewer than 3 of the template marker set's labels");
  if (!absent.empty() && !FLAGS_quiet) std::fprintf(stderr, "fit_skeleton: not in the file, left out: %s\n", absent.c_str());
  status = MarkerSet::Create(skeleton, std::move(present), &take_mapping.markers);
  if (!status.ok()) return status;
  MarkerTake take;
  status = LoadTakeForSubject(take_mapping, FLAGS_markers, &take);
  if (!status.ok()) return status;
  const int frames = FLAGS_fit_max_frames > 0 ? std::min<int>(FLAGS_fit_max_frames, take.observed.size())
                                              : static_cast<int>(take.observed.size());
  take.observed.resize(frames);
  MarkerTrajectories model_frame = take.trajectories;  // For auto attach.
  TransformMarkers(take.transform, skeleton.unit(), &model_frame);

  MarkerSolveOptions solve_options;
  status = MarkerSolveOptionsFromFlags(skeleton.unit(), &solve_options);
  if (!status.ok()) return status;
  SkeletonFitOptions options;
  options.frame_step = FLAGS_fit_frame_step;
  options.min_scale = FLAGS_min_bone_scale;
  options.max_scale = FLAGS_max_bone_scale;
  options.max_bone_distance = FLAGS_max_skin_cm * units_per_cm;
  options.root_from_markers = true;
  const double mm = skeleton.unit().known() ? skeleton.unit().metres_per_unit * 1000.0 : 1.0;
  const char* unit = skeleton.unit().known() ? "mm" : "skeleton units";

  Skeleton fitted = skeleton;
  MarkerSet fitted_markers = take_mapping.markers;
  Motion motion;
  SkeletonFitReport report;
  std::vector<JsonObject> round_json;
  std::vector<double> scales(skeleton.num_joints(), 1.0);
  // The best round with every marker attached (rounds >= 1), by marker RMS: re-attaching
  // can also make a round worse.
  struct Best {
    int round = -1;
    double rms = 0.0;
    Skeleton skeleton;
    MarkerSet markers;
    Motion motion;
    SkeletonFitReport report;
    std::vector<std::vector<Eigen::Vector3d>> observed;
  } best;
  for (int round = 0; round <= rounds; ++round) {
    std::vector<std::vector<Eigen::Vector3d>> observed = take.observed;
    MarkerSet round_markers = fitted_markers;
    if (round >= 2 && best.round >= 1) {
      // Each round starts from the best so far: a worse round must not feed the next.
      fitted = best.skeleton;
      fitted_markers = best.markers;
      motion = best.motion;
      scales = best.report.bone_scales;
    }
    if (round > 0) {
      // Attach every marker of the take to the skeleton as fitted; markers the template
      // knows keep its joints (and their fitted offsets): they anchor the skeleton.
      CalibrationOptions calibration;
      calibration.max_bone_distance = options.max_bone_distance;
      CalibrationResult attached;
      status = CalibrateMarkers(fitted, motion, model_frame, calibration, nullptr, &attached);
      if (!status.ok()) return Status::Error(FLAGS_markers + ": attach round " + std::to_string(round) + ": " + status.message());
      std::vector<MarkerSpec> specs;
      for (int m = 0; m < attached.marker_set.num_markers(); ++m) {
        MarkerSpec spec = attached.marker_set.marker(m);
        const int known = fitted_markers.FindMarker(spec.label);
        if (known >= 0 && take_mapping.markers.FindMarker(spec.label) >= 0) spec = fitted_markers.marker(known);
        for (MarkerAttachment& a : spec.attachments) {
          if (options.max_bone_distance > 0.0) a.offset = ClampToBone(fitted, a.joint, a.offset, options.max_bone_distance);
        }
        specs.push_back(spec);
      }
      status = MarkerSet::Create(fitted, std::move(specs), &round_markers);
      if (!status.ok()) return status;
      status = GatherObservations(round_markers, take.trajectories, take.transform, &observed);
      if (!status.ok()) return Status::Error(FLAGS_markers + ": " + status.message());
      observed.resize(frames);
    }
    options.iterations = round > 0 ? FLAGS_attach_iterations
                                   : FLAGS_fit_iterations >= 0 ? FLAGS_fit_iterations : (from_subject ? 15 : 6);
    // The template's offsets are a prior worth keeping; an attach round's are estimates
    // from a motion that is itself being fitted.
    options.offset_prior_weight = round == 0 ? FLAGS_offset_prior : 0.0;
    options.initial_scales = scales;
    if (!FLAGS_quiet) {
      std::fprintf(stderr, "fit_skeleton: round %d/%d: %d markers, %d frames, %d iterations (%.0f s so far)\n", round,
                   rounds, round_markers.num_markers(), frames, options.iterations, Seconds(start));
    }
    const SkeletonFitProgress progress = [&](int iteration, double rms) {
      if (!FLAGS_quiet) std::fprintf(stderr, "  iteration %d: marker RMS %.2f %s (%.0f s)\n", iteration, rms * mm, unit, Seconds(start));
    };
    Skeleton next;
    MarkerSet next_markers;
    status = FitSkeletonToMarkers(fitted, round_markers, observed, solve_options, options, &next, &next_markers,
                                  &motion, &report, progress);
    if (!status.ok()) return Status::Error(FLAGS_markers + ": " + status.message());
    motion.frame_rate = take.trajectories.frame_rate > 0.0 ? take.trajectories.frame_rate : 120.0;
    fitted = std::move(next);
    fitted_markers = std::move(next_markers);
    scales = report.bone_scales;
    std::vector<JsonValue> rms;
    for (double r : report.rms) rms.push_back(JsonValue(r * mm));
    JsonObject o;
    o.Add("round", round).Add("markers", fitted_markers.num_markers()).Add("rms_by_iteration", rms);
    round_json.push_back(o);
    std::printf("round %d: %d markers, marker RMS %.2f -> %.2f %s\n", round, fitted_markers.num_markers(),
                report.rms.front() * mm, report.rms.back() * mm, unit);
    if (round <= 1 || report.rms.back() < best.rms) {
      best = {round, report.rms.back(), fitted, fitted_markers, motion, report, observed};
    } else if (round >= 2) {
      // The next round would start from the same best state and attach alike.
      if (!FLAGS_quiet) std::fprintf(stderr, "fit_skeleton: round %d did not improve; stopping\n", round);
      break;
    }
  }
  if (rounds > 0 && best.round != rounds && !FLAGS_quiet) {
    std::fprintf(stderr, "fit_skeleton: keeping round %d (marker RMS %.2f %s)\n", best.round, best.rms * mm, unit);
  }
  // The checks see the kept model against the observations it was fitted to.
  fitted = std::move(best.skeleton);
  fitted_markers = std::move(best.markers);
  motion = std::move(best.motion);
  report = std::move(best.report);
  take.observed = std::move(best.observed);
  motion.frame_rate = take.trajectories.frame_rate;
  const SubjectChecks checks = CheckSubjectFit(fitted, fitted_markers, take.observed, motion);
  const double seconds = Seconds(start);
  std::printf("checks: marker RMS %.1f mm, max marker-to-bone %.1f cm (%s), max marker-to-joint %.1f cm, torso direction error "
              "mean %.1f max %.1f deg over %d frames, left/right asymmetry %.1f %%%s%s\n",
              checks.rms_mm, checks.max_bone_distance_cm, checks.farthest_marker.c_str(), checks.max_joint_distance_cm,
              checks.torso_error_mean_deg, checks.torso_error_max_deg, checks.torso_frames, 100.0 * checks.max_asymmetry,
              checks.least_symmetric_pair.empty() ? "" : (" (" + checks.least_symmetric_pair + ")").c_str(),
              checks.ok() ? ", passed" : "");
  std::printf("bone scales:");
  std::vector<JsonObject> scale_json;
  for (int j = 1; j < fitted.num_joints(); ++j) {
    if (std::abs(report.bone_scales[j] - 1.0) > 1e-9) std::printf(" %s %.3f", fitted.name(j).c_str(), report.bone_scales[j]);
    JsonObject o;
    o.Add("joint", fitted.name(j)).Add("scale", report.bone_scales[j]);
    scale_json.push_back(o);
  }
  std::printf("\nfit: %d markers, marker RMS %.2f %s, %.1f s\n", fitted_markers.num_markers(), report.rms.back() * mm,
              unit, seconds);
  JsonObject json;
  json.Add("markers", FLAGS_markers).Add("template", from_subject ? FLAGS_template_subject : FLAGS_skeleton)
      .Add("frames", frames).Add("attach_rounds", rounds).Add("kept_round", best.round).Add("seconds", seconds)
      .Add(skeleton.unit().known() ? "rms_mm" : "rms", report.rms.back() * mm)
      .Add("rounds", round_json).Add("bone_scales", scale_json).Add("checks", ChecksJson(checks));
  if (!checks.ok() && FLAGS_check != "off") {
    for (const std::string& failure : checks.failures) std::fprintf(stderr, "fit_skeleton: check failed: %s\n", failure.c_str());
    if (FLAGS_check == "fail") {
      Status written = WriteReport(json);
      if (!written.ok()) return written;
      return Status::Error(FLAGS_markers + ": the fitted subject fails its checks (" + checks.failures[0] +
                           "); nothing written but the report (--check=warn writes it anyway)");
    }
  }
  if (!FLAGS_out.empty()) {
    status = WriteBvh(FLAGS_out, fitted, motion, BvhWriteOptions());
    if (!status.ok()) return status;
  }
  if (!FLAGS_out_markerset.empty()) {
    status = WriteMarkerSet(FLAGS_out_markerset, fitted, fitted_markers);
    if (!status.ok()) return status;
  }
  if (!FLAGS_out_subject.empty()) {
    Subject subject;
    subject.name = templ.name.empty() ? "fitted" : "fitted from " + templ.name;
    subject.skeleton = fitted;  // Inline: the fitted skeleton exists nowhere else.
    subject.markers = fitted_markers;
    subject.axes = FLAGS_axes;
    subject.marker_scale = FLAGS_marker_scale;
    subject.amc_fps = FLAGS_amc_fps;
    status = WriteSubject(FLAGS_out_subject, subject);
    if (!status.ok()) return status;
  }
  for (const std::string& out : outputs) {
    if (!out.empty()) std::printf("wrote %s\n", out.c_str());
  }
  return WriteReport(json);
}

const std::string kFitFlags =
    std::string("template_subject,skeleton,skeleton_units,amc_fps,markers,markerset,axes,marker_scale,out,out_subject,report,quiet,") +
    kSolverFlagNames;

}  // namespace

extern const Command kFitSkeletonCommand = {
    "fit_skeleton", "fit a subject (bone lengths, marker attachments and offsets) to a take's markers",
    "mocapsolve fit_skeleton --template_subject=T.json --markers=IN.c3d|.trc --out_subject=S.json\n"
    "          [--out=FITTED.bvh] [--out_markerset=S.json] [--axes=x,y,z] [--attach_rounds=6]\n"
    "          [--check=fail|warn|off] [--report=r.json]\n"
    "   or: --skeleton=TEMPLATE.bvh|.asf --markerset=J.json instead of --template_subject\n\n"
    "For captures without a skeleton. Starts from a template subject (skeleton + marker set;\n"
    "--axes/--marker_scale describe the take's file) and fits on the markers the take shares\n"
    "with it by label: per-frame pose solves (the first frame's root from the markers' own\n"
    "geometry) alternate with a Gauss-Newton fit of bone-length scales and marker offsets.\n"
    "Then --attach_rounds times: every marker of the take is attached to the joint it moves\n"
    "least with (among joints whose bone it is within --max_skin_cm of) and the fit runs\n"
    "again with all of them. Constraints: bone scales within [--min_bone_scale,\n"
    "--max_bone_scale] of the template, left = right, offsets within --max_skin_cm of their\n"
    "bone. Then the checks, which do not trust the residual: every marker within 15 cm of\n"
    "its bone, the solved pelvis-to-head direction within 15 degrees (mean) of the markers'\n"
    "own, left/right bone lengths within 5 %, and the marker RMS within 25 mm;\n"
    "--check=fail (default) exits 1 when one fails.\n"
    "Writes the subject (skeleton inline), and optionally the solved motion and marker set.",
    __FILE__, RunFitSkeleton, kFitFlags.c_str()};

}  // namespace mocapsolve
