// A long take through the pipeline window by window (issue 35), so that its memory is
// bounded by a window, not by the take: the take of F frames is cut into n = ceil(F / W)
// windows (W = TakePipelineOptions::window_frames) whose cores, as equal as can be, cover
// every frame once, in order; each window reads its core plus C context frames on each
// side (C = window_context_frames, clamped to the take) and runs the stages of
// RunTakePipeline on them alone (repair with its reference, gap detection and fills, the
// filter, the retarget onto each character, the gate's figures). The windows' repairs run in
// order, each one's frame-by-frame solves starting from the previous window's solve of the
// frame before it (RepairOptions::start_pose), and reading the file's samples with the
// earlier windows' cores repaired: a joint the markers leave free (CMU's thumbs and fingers,
// leaves with no marker) is held near its warm start, so a cold start holds it elsewhere for
// the whole window (10 cm at the thumb's tip on cmu_02_05). A window's character stage
// (RunTakeCharacterStage: the retargets from the character's own bind pose, their figures)
// depends on its own repair only: with TakePipelineOptions::num_threads >= 2 the character
// stages run on a second thread (pipeline/in_order_worker.h) while this one repairs the
// next windows, in window order, at most one window waiting (one more window's solve and
// retarget in memory: measured in BENCHMARKS.md); when the second thread is still busy as
// the next window is given, and once the repairs are done, this thread runs the waiting
// window's character stage beside the second thread's, their results kept in window order;
// every file is the same bytes as with one thread. Each window keeps its core frames only
// (the solve's and the characters' cross-faded over window_seam_blend_frames on each side of
// a seam, pipeline/window_seam_blend.h):
//   repaired.c3d/.trc  the file's samples of the core, as the window repaired them, put
//                      back into the file (read whole once: 1.2 KB per frame at 41
//                      markers), written when the last window is done;
//   solved.bvh         its header after the first window (the first window's solve fixes
//                      the channels), then each core's MOTION lines as it is done (the
//                      Euler angles continued across windows, io/bvh_writer.h);
//   <character>.glb    each core's retargeted frames appended to the character's compact
//   (.fbx, .bvh)       take (kinematics/compact_motion.h: Xbot 1.05 KB per frame), the files
//                      written from it after the last window, one joint of one frame at a
//                      time (io/motion_samples.h);
//   report.json        (WriteTakeOutputs) the windows' figures combined: RMS from the
//                      windows' mean squares weighted by their core frames, shares and
//                      counts from sums (the counts a window reports over its context too,
//                      such as re-solved frames, scaled to its core), intervals with the
//                      take's frame numbers (each interval by the window whose core holds
//                      its first frame), maxima as maxima (a 95th percentile as the
//                      windows' largest), the other means weighted by core frames; the gate
//                      on the combined figures (no blame list: the marker blame reads the
//                      whole take); "windows": count, frames, context, threads (1 or 2)
//                      and the seam check.
// Every file is atomic (io/atomic_file.h: AtomicFileWriter, inside the command's
// FileTransaction). Refused for a windowed take, with one line: labelling its points first
// (label the file with `mocapsolve label`), a cut or resampled delivery, and the take's
// page (view.html).
#ifndef MOCAPSOLVE_PIPELINE_TAKE_WINDOWS_H_
#define MOCAPSOLVE_PIPELINE_TAKE_WINDOWS_H_

#include <string>
#include <vector>

#include "pipeline/take_pipeline.h"

namespace mocapsolve {

struct FrameWindow {
  int first = 0, last = 0;            // Frames read and solved (inclusive): core and context.
  int core_first = 0, core_last = 0;  // Frames kept (inclusive).
};

// The windows of a take of `frames` frames (see above); one window, the whole take, when
// frames <= window_frames.
std::vector<FrameWindow> TakeWindows(int frames, int window_frames, int context_frames);

// True when the take's file has more frames than options.window_frames (its header and
// parameters read, not its samples); an error reading it goes to *status.
bool TakeRunsInWindows(const TakeInputs& inputs, const TakePipelineOptions& options, Status* status);

// Runs the take window by window and writes its files but report.json into out_dir (made
// when missing); *result holds the combined figures (TakeReport, TakeSummary) and
// result->windows. WriteTakeOutputs then writes report.json.
Status RunTakeInWindows(const std::string& out_dir, const TakeInputs& inputs, const TakePipelineOptions& options,
                        const CharacterFileOptions& files, TakeResult* result,
                        const PipelineProgress& progress = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_TAKE_WINDOWS_H_
