// One take end to end (the thesis' pipeline: marker solving, cleanup, retargeting,
// delivery, with no person in between):
//
//   markers --(labelled first when they do not carry the subject's labels: take_labelling.h)
//           --(subject: skeleton, marker set, file mapping)--> observations
//     1. repair (thesis ch. 3): naive solve, robust reference, gap detection and refill,
//        re-solve; its re-solved motion is the take's solve;
//     2. filter (optional): multiresolution low-pass of the solved motion (Huang et al.);
//     3. retarget (thesis ch. 4) onto each character, the skeleton-only source bound to
//        the character's own mesh (problems/retarget/retarget_character.h);
//     4. the quality gate (quality_gate.h) on the figures of 1.
//
// Everything is computed in memory first; WriteTakeOutputs then writes
//   DIR/repaired.c3d (or .trc, as the input)  the input file with the repaired samples,
//   DIR/solved.bvh                            the (filtered) solve on the subject's skeleton,
//   DIR/<character>.glb                       each character's file plus the take as a new
//                                             animation named after the take (or, animation
//                                             only, its skeleton, skin and the take: io/gltf_writer.h),
//   DIR/<character>.fbx, .bvh                 when asked (CharacterFileOptions::formats,
//                                             settings/delivery_settings.h): the character
//                                             with the take as binary FBX, the take on its
//                                             skeleton as BVH,
//                                             every character file holding the take as
//                                             delivered (TakePipelineOptions::delivery: cut,
//                                             resampled; the other outputs keep the take's
//                                             frames and rate),
//   DIR/report.json                           every stage's timings and quality figures,
//   DIR/view.html                             the take's browser page (when asked; the
//                                             pipeline command's --view=auto default),
// each atomically (inside the command's FileTransaction, all together). Errors name the
// stage and the file. Knows nothing of flags or processes.
#ifndef MOCAPSOLVE_PIPELINE_TAKE_PIPELINE_H_
#define MOCAPSOLVE_PIPELINE_TAKE_PIPELINE_H_

#include <functional>
#include <string>
#include <vector>

#include "io/gltf_reader.h"
#include "io/gltf_writer.h"
#include "io/json_writer.h"
#include "kinematics/compact_motion.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/motion.h"
#include "kinematics/status.h"
#include "pipeline/gate_blame.h"
#include "pipeline/memory_estimate.h"
#include "pipeline/quality_gate.h"
#include "pipeline/subject.h"
#include "settings/delivery_settings.h"
#include "settings/label_settings.h"
#include "settings/solver_settings.h"
#include "problems/marker_repair/marker_repair.h"
#include "problems/retarget/retarget_character.h"
#include "signal/clip_delivery.h"
#include "signal/laplacian_pyramid.h"
#include "viewer/view_scene.h"

namespace mocapsolve {

struct TakePipelineOptions {
  RepairOptions repair;             // In the subject skeleton's units.
  int filter_levels = 0;            // 0 = no filtering; N drops the N finest bands.
  PyramidOptions filter;            // Kernel and tension of the filter.
  CharacterRetargetOptions retarget;
  QualityGate gate;
  // The character files' clip: cut and resampled (signal/clip_delivery.h); checked against
  // the take's frames as soon as it is read.
  ClipDelivery delivery;
  // Labelling the take's points first (TakeSettings::label: auto, never, always), how
  // (the labeller's options) and with which per-frame solve.
  std::string label = "auto";
  LabelSettings labelling;
  SolverSettings label_solver;
  // MB the take may need (settings/memory_settings.h; 0 = no limit): a take whose estimate
  // (pipeline/memory_estimate.h, from the file's frame and marker counts) is over it is
  // refused before any stage runs.
  double memory_mb = 0.0;
  // A take of more frames runs window by window (pipeline/take_windows.h), each window
  // with window_context_frames more on each side (settings/take_settings.h says why).
  int window_frames = 18000;
  int window_context_frames = 600;
  int window_seam_blend_frames = 60;  // Cross-fade at each seam (window_seam_blend.h).
  // SolverSettings::num_threads: with 2 or more, a windowed take's character stages
  // (RunTakeCharacterStage) run on a second thread beside the next windows' repairs; the
  // outputs are the same bytes as with 1.
  int num_threads = 1;

  bool IsValid(std::string* error) const;
};

struct TakeInputs {
  std::string name;             // The take's name: the characters' new animation.
  const Subject* subject = nullptr;
  std::string markers_path;     // .c3d or .trc.
  std::vector<std::string> character_paths;  // .glb / .gltf; empty: stop after the solve.
  // The subject was fitted on this take (--subject=auto): a failed gate's advice does not
  // suggest fitting one on it (GateAdvice).
  bool subject_from_take = false;
};

struct StageTime {
  std::string stage;
  double seconds = 0.0;
};

struct CharacterOutput {
  std::string name;             // File name without folder and extension.
  std::string path;             // The character file read.
  GltfDocument document;
  GltfCharacter character;
  // A window's retarget (pipeline/take_windows.h): the character read once for every
  // window, `document` and `character` above left empty.
  const GltfCharacter* shared = nullptr;
  const GltfCharacter& rig() const { return shared != nullptr ? *shared : character; }
  // result.clip.motion is emptied into `take` once the retarget and its figures are done.
  CharacterRetargetResult result;
  // The retargeted take at the take's frames and rate, compact (float rotations and moving
  // translations, kinematics/compact_motion.h: Xbot's 65 joints 1.0 instead of 3.7 KB per
  // frame), expanded where it is read.
  CompactMotion take;
  // The take cut and resampled as the options say; left empty when the options keep every
  // frame at the take's rate (the delivered clip is then `take` itself, not a second copy
  // of a long take).
  Motion delivered;
  bool delivered_is_clip = false;
  // The delivered clip, expanded (a copy).
  Motion delivered_motion() const { return delivered_is_clip ? take.ToMotion() : delivered; }
  int delivered_frames() const { return delivered_is_clip ? take.num_frames() : delivered.num_frames(); }
  double delivered_frame_rate() const { return delivered_is_clip ? take.frame_rate() : delivered.frame_rate; }
};

// How a windowed take ran (pipeline/take_windows.h); count 0: whole.
struct TakeWindowsSummary {
  int count = 0;
  int frames = 0;          // The frames each window keeps (its core; the last may keep fewer).
  int context_frames = 0;  // Solved on each side of a core and dropped.
  int seam_blend_frames = 0;  // The solve and characters cross-fade over these each side of a seam.
  // 2 when the windows' character stages ran on a second thread beside the repairs
  // (TakePipelineOptions::num_threads), else 1.
  int threads = 1;
  // The seams: the largest difference, in mm of joint position of the solve, between the two
  // windows that solved the same context frames (each seam's largest), and at the seam's
  // first frame (the later window's first kept frame, which the earlier one solved too).
  std::vector<double> seam_max_mm, seam_first_frame_mm;
};

struct TakeResult {
  // The markers as read (labelled, when they were), with their mapping; take.trajectories
  // keeps the file's metadata but no frames once repaired_file holds them, and
  // take.observed is freed once the gate's marker checks have read it (1 KB per frame of a
  // long take through the retarget and the writers).
  MarkerTake take;
  int frames = 0;                     // The take's.
  // When the points were labelled first: LabellingReport (pipeline/take_labelling.h) with
  // "reason" (why: "always", or the subject's labels the file lacks); else empty.
  JsonObject labelling;
  int labelled_samples = 0, labelled_points = 0;  // For the console line.
  MarkerTrajectories repaired_file;   // The input file with the repaired samples.
  std::vector<std::vector<Eigen::Vector3d>> repaired;  // [frame][marker], skeleton frame (NaN = missing).
  // On the subject's skeleton (filtered if asked), compact (kinematics/compact_motion.h:
  // 0.5 instead of 1.8 KB per frame of the CMU subject's 31 joints).
  CompactMotion solved;
  RepairReport repair;
  int repaired_samples = 0;           // Samples of the subject's markers that were rewritten.
  int samples = 0;                    // All samples of the subject's markers.
  std::vector<CharacterOutput> characters;
  QualityFigures figures;
  QualityVerdict verdict;
  // When a marker check of the gate failed: the markers to blame and what to try
  // (pipeline/gate_blame.h); else empty.
  std::vector<MarkerBlame> blame;
  std::string gate_advice;
  std::vector<StageTime> timings;
  double seconds = 0.0;               // The whole take (reading included, writing not).
  // A windowed take: its files were written as its windows finished (all but report.json,
  // which WriteTakeOutputs writes), and the whole-take arrays above (repaired_file,
  // repaired, solved, each character's take) are empty; the figures are the windows'.
  TakeWindowsSummary windows;
};

// (stage, done, total) while a stage runs, for progress display.
using PipelineProgress = std::function<void(const std::string& stage, int done, int total)>;

Status RunTakePipeline(const TakeInputs& inputs, const TakePipelineOptions& options, TakeResult* result,
                       const PipelineProgress& progress = nullptr);

// The stages of RunTakePipeline, for a take read in pieces (pipeline/take_windows.h):
// the file's samples onto the subject, labelled first as options.label says, into
// result->take (*label_seconds the labelling's; errors name inputs.markers_path) ...
Status MapTakeMarkers(const TakeInputs& inputs, const TakePipelineOptions& options, MarkerTrajectories file,
                      TakeResult* result, const PipelineProgress& progress, double* label_seconds);
// ... the characters read (inputs.character_paths) ...
Status ReadTakeCharacters(const TakeInputs& inputs, std::vector<CharacterOutput>* characters);
// ... and stages 1-4 on result->take, onto result->characters (read): RunTakeRepairStage,
// then RunTakeCharacterStage.
Status RunTakeStages(const TakeInputs& inputs, const TakePipelineOptions& options, TakeResult* result,
                     const PipelineProgress& progress = nullptr);
// Stages 1-2 and the gate's marker checks: the repair of result->take (repaired, repaired_file,
// the report, the figures and the verdict so far), its re-solve filtered as asked into
// result->solved (compact) and *solved (double: the character stage's input); frees
// result->take's observed samples.
Status RunTakeRepairStage(const TakeInputs& inputs, const TakePipelineOptions& options, TakeResult* result,
                          Motion* solved, const PipelineProgress& progress = nullptr);
// Stages 3-4: `solved` (from RunTakeRepairStage) retargeted onto each of result->characters,
// their timings and the gate's retarget checks added to result->timings and verdict. Reads
// nothing else of *result but take.skeleton, take.trajectories' frame rate and frames, so a
// windowed take runs it apart from the repair stage, on another thread
// (pipeline/take_windows.h).
Status RunTakeCharacterStage(const TakeInputs& inputs, const TakePipelineOptions& options, Motion solved,
                             TakeResult* result, const PipelineProgress& progress = nullptr);
// The gate's figures from the repair's report (result->repair, samples, repaired_samples,
// frames): naive and repaired RMS in mm (`mm` per skeleton unit), repaired and
// iteration-limit shares.
void SetRepairGateFigures(double mm, TakeResult* result);
// The memory the take needs (pipeline/memory_estimate.h): whole, or windowed when it has
// more than options.window_frames frames; with the clip reference and the filter as asked.
MemoryEstimate TakeMemory(int frames, int markers, const TakePipelineOptions& options);

// Output file names in `out_dir` ("" for the working directory).
std::string RepairedMarkersPath(const std::string& out_dir, const std::string& markers_path);
std::string SolvedMotionPath(const std::string& out_dir);
std::string CharacterOutputPath(const std::string& out_dir, const std::string& character_name,
                                const std::string& character_path);

// How WriteTakeOutputs writes each character.
struct CharacterFileOptions {
  // Each of glb (the character's glTF form: .glb, or .gltf for a .gltf character), fbx
  // (io/fbx_writer.h: WriteFbxCharacter) and bvh (the take on the character's skeleton).
  std::vector<std::string> formats = {"glb"};
  bool animation_only = false;  // glb and fbx: skeleton, skin and the take, no meshes.
  double fbx_key_tolerance_mm = 0.0;  // FbxWriteOptions::key_tolerance_mm.
};

// The delivery settings (--formats) and --animation_only as CharacterFileOptions; an error
// naming --formats for a bad list.
Status CharacterFilesFromSettings(const DeliverySettings& delivery, bool animation_only,
                                  CharacterFileOptions* files);

// DIR/<character>.<format> for one of CharacterFileOptions::formats, the character read
// from `character_path` ("glb" keeps a .gltf character's .gltf).
std::string CharacterFormatPath(const std::string& out_dir, const std::string& character_path,
                                const std::string& format);

// Character `c`'s files, each of files.formats, into `out_dir` (CharacterFormatPath): from
// its compact take when that is what is delivered (c.delivered_is_clip; read one joint of
// one frame at a time, io/motion_samples.h), else from its delivered clip.
Status WriteCharacterFiles(const std::string& out_dir, const std::string& take_name, const CharacterOutput& c,
                           const CharacterFileOptions& files);

// An error naming the character when one of its files would be another output (a
// character named "solved" with bvh: DIR/solved.bvh); before any work, and again by
// WriteTakeOutputs.
Status CheckCharacterFiles(const std::string& out_dir, const TakeInputs& inputs, const CharacterFileOptions& files);

// The take's report (stage timings, quality figures, gate verdict, per character the
// retarget's vertex/normal error and foot skating).
JsonObject TakeReport(const TakeInputs& inputs, const TakeResult& result);

// Writes the outputs above, and `report` (TakeReport plus what the caller adds) as
// DIR/report.json; with a view_path (usually ViewPagePath(out_dir); "" = none) also the
// take's page there (pipeline/take_view.h: the repaired markers coloured by reason, the
// solve, the residual curve, each character playing the take beside it), which needs the
// viewer's runtime (viewer/view_page.h): without it, an error and nothing written.
// character_files: which files of each character are written and how (animation_only:
// without the character's meshes; the page always embeds whole characters);
// CheckCharacterFiles first, before anything is written.
Status WriteTakeOutputs(const std::string& out_dir, const TakeInputs& inputs, const TakeResult& result,
                        const JsonObject& report, const std::string& view_path = "",
                        const CharacterFileOptions& character_files = {});
// DIR/view.html.
std::string ViewPagePath(const std::string& out_dir);
// The take's page as `view` asks (pipeline --view, Python's view=): "auto" = DIR/view.html
// when the viewer's runtime is installed, else none and *warning says why (a batch on a
// machine without it still delivers its takes); "off" = none; a path = that page, asked
// for, so a missing runtime is an error. *path: "" for none.
Status TakeViewPath(const std::string& view, const std::string& out_dir, std::string* path, std::string* warning);
// The page WriteTakeOutputs writes.
Status MakeTakeResultView(const TakeInputs& inputs, const TakeResult& result, ViewScene* scene);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_TAKE_PIPELINE_H_
