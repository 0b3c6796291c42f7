// mocapsolve fit_skeleton: bone lengths and marker offsets of a subject from its markers,
// starting from a template skeleton and marker set (problems/marker_solve/skeleton_fit.h).
#include <cstdio>
#include <string>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/solver_flags.h"
#include "io/bvh_writer.h"
#include "io/marker_file.h"
#include "io/marker_set_file.h"
#include "io/motion_file.h"
#include "problems/marker_solve/skeleton_fit.h"

DEFINE_string(out_markerset, "", "The fitted marker set (.json), in the skeleton's units.");
DEFINE_int32(fit_iterations, 6, "Alternations of pose solve and length/offset fit.");
DEFINE_int32(fit_frame_step, 4, "Use every N-th frame in the length/offset fit.");

namespace mocapsolve {
namespace {

Status RunFitSkeleton(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (FLAGS_skeleton.empty() || FLAGS_markers.empty() || FLAGS_markerset.empty() || FLAGS_out.empty() ||
      FLAGS_out_markerset.empty()) {
    return Status::Error("--skeleton, --markers, --markerset, --out and --out_markerset are required");
  }
  if (FileExtension(FLAGS_out) != ".bvh") return Status::Error(FLAGS_out + ": expected a .bvh");
  if (FileExtension(FLAGS_out_markerset) != ".json") return Status::Error(FLAGS_out_markerset + ": expected a .json");
  for (const std::string& out : {FLAGS_out, FLAGS_out_markerset}) {
    for (const std::string& in : {FLAGS_skeleton, FLAGS_markers, FLAGS_markerset}) {
      Status status = CheckNotAnInput(out, in);
      if (!status.ok()) return status;
    }
  }
  if (FLAGS_out == FLAGS_out_markerset) return Status::Error("--out and --out_markerset name the same file");
  if (FLAGS_fit_iterations < 0 || FLAGS_fit_iterations > 100) return Status::Error("--fit_iterations: 0..100");
  if (FLAGS_fit_frame_step < 1) return Status::Error("--fit_frame_step: >= 1");
  Skeleton skeleton;
  Status status = LoadSkeleton(FLAGS_skeleton, &skeleton);
  if (!status.ok()) return status;
  MarkerSet markers;
  status = ReadMarkerSet(FLAGS_markerset, skeleton, &markers);
  if (!status.ok()) return status;
  // A template set may name markers this subject's file lacks: fit the ones it has.
  MarkerTrajectories file;
  status = ReadMarkerFile(FLAGS_markers, &file);
  if (!status.ok()) return status;
  std::vector<MarkerSpec> present;
  std::string absent;
  for (int m = 0; m < markers.num_markers(); ++m) {
    if (file.FindMarker(markers.label(m)) >= 0) {
      present.push_back(markers.marker(m));
    } else {
      absent += (absent.empty() ? "" : ", ") + markers.label(m);
    }
  }
  if (present.size() < 3) return Status::Error(FLAGS_markers + ": fewer than 3 of the marker set's labels");
  if (!absent.empty() && !FLAGS_quiet) std::fprintf(stderr, "fit_skeleton: not in the file, left out: %s\n", absent.c_str());
  status = MarkerSet::Create(skeleton, std::move(present), &markers);
  if (!status.ok()) return status;
  MarkerTrajectories trajectories;
  MarkerFileToModel transform;
  std::vector<std::vector<Eigen::Vector3d>> observed;
  status = LoadObservations(FLAGS_markers, skeleton, markers, &trajectories, &transform, &observed);
  if (!status.ok()) return status;
  MarkerSolveOptions solve_options;
  status = MarkerSolveOptionsFromFlags(skeleton.unit(), &solve_options);
  if (!status.ok()) return status;
  SkeletonFitOptions options;
  options.iterations = FLAGS_fit_iterations;
  options.frame_step = FLAGS_fit_frame_step;
  Skeleton fitted;
  MarkerSet fitted_markers;
  Motion motion;
  SkeletonFitReport report;
  status = FitSkeletonToMarkers(skeleton, markers, observed, solve_options, options, &fitted, &fitted_markers,
                                &motion, &report);
  if (!status.ok()) return Status::Error(FLAGS_markers + ": " + status.message());
  motion.frame_rate = trajectories.frame_rate;
  status = WriteBvh(FLAGS_out, fitted, motion, BvhWriteOptions());
  if (status.ok()) status = WriteMarkerSet(FLAGS_out_markerset, fitted, fitted_markers);
  if (!status.ok()) return status;
  const bool mm_known = skeleton.unit().known();
  const double mm = mm_known ? skeleton.unit().metres_per_unit * 1000.0 : 1.0;
  std::printf("fit_skeleton: marker RMS %s by iteration:", mm_known ? "(mm)" : "(skeleton units)");
  std::vector<JsonValue> rms;
  for (double r : report.rms) {
    std::printf(" %.2f", r * mm);
    rms.push_back(JsonValue(r * mm));
  }
  std::printf("\nbone scales:");
  std::vector<JsonObject> scales;
  for (int j = 1; j < fitted.num_joints(); ++j) {
    if (report.bone_scales[j] != 1.0) std::printf(" %s %.3f", fitted.name(j).c_str(), report.bone_scales[j]);
    JsonObject o;
    o.Add("joint", fitted.name(j)).Add("scale", report.bone_scales[j]);
    scales.push_back(o);
  }
  std::printf("\nwrote %s (fitted skeleton and its solved motion) and %s\n", FLAGS_out.c_str(),
              FLAGS_out_markerset.c_str());
  JsonObject json;
  json.Add("markers", FLAGS_markers).Add("out", FLAGS_out).Add("out_markerset", FLAGS_out_markerset)
      .Add(mm_known ? "rms_mm_by_iteration" : "rms_by_iteration", rms).Add("bone_scales", scales);
  return WriteReport(json);
}

const std::string kFitFlags =
    std::string("skeleton,skeleton_units,markers,markerset,axes,marker_scale,out,report,quiet,") + kSolverFlagNames;

}  // namespace

extern const Command kFitSkeletonCommand = {
    "fit_skeleton", "fit bone lengths and marker offsets of a subject to its markers",
    "mocapsolve fit_skeleton --skeleton=TEMPLATE.bvh|.asf --markers=IN.c3d|.trc --markerset=J.json "
    "--out=FITTED.bvh --out_markerset=FITTED.json [--fit_iterations=6] [--report=r.json]\n\n"
    "For captures without a skeleton: start from a template skeleton and a marker set whose\n"
    "labels the file has (attachments and rough offsets; labels it lacks are left out), then alternate per-frame pose\n"
    "solves with a linear least-squares fit of bone-length scales and marker offsets (the\n"
    "root translation eliminated per frame). Writes the fitted skeleton with the motion\n"
    "solved on it, and the fitted marker set; prints the marker RMS after each pose solve.",
    __FILE__, RunFitSkeleton, kFitFlags.c_str()};

}  // namespace mocapsolve
