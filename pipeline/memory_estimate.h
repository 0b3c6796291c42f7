// The memory a whole-clip method needs, estimated from a take's frame and marker counts
// before any work, and the check of --memory_mb (settings/memory_settings.h) against it.
//
// Each estimate is a fixed base plus a cost per frame, both measured (peak RSS of the
// command, /usr/bin/time -v, MB = 1024 KB) on CMU 02_05 (41 markers, the CMU subject's
// 31 joints) at two or more lengths (BENCHMARKS.md, "Memory against the take's length"):
//
//   bytes(F, M) = base + F * (shared + per_marker * M)
//
// per_marker scales the part that holds marker samples (trajectories, observations,
// reconstructions, residuals) with the take's marker count M; shared is the part that
// holds poses and the writers' buffers. Measured on one subject and one character, so an
// estimate, not a bound: a character with many more joints than Xbot's 65, or several
// characters, need more.
#ifndef MOCAPSOLVE_PIPELINE_MEMORY_ESTIMATE_H_
#define MOCAPSOLVE_PIPELINE_MEMORY_ESTIMATE_H_

#include <string>

#include "kinematics/status.h"

namespace mocapsolve {

struct MemoryEstimate {
  std::string method;           // "the pipeline's per-frame stages", "the clip solve", ...
  int frames = 0, markers = 0;
  double base_mb = 0.0;         // Fixed: the program, the subject, the characters' files.
  double kb_per_frame = 0.0;    // At this take's marker count.

  double mb() const { return base_mb + frames * kb_per_frame / 1024.0; }
  // Adds another method's per-frame cost (it runs while the first's data is held).
  MemoryEstimate& Add(const MemoryEstimate& other);
};

// `pipeline` (pipeline/take_pipeline.h): repair, solve, retarget onto one character and
// the writers, every stage holding the whole take.
MemoryEstimate PipelineMemory(int frames, int markers);
// `pipeline` on a take longer than its window_frames (pipeline/take_windows.h): the
// stages of one window (PipelineMemory's per-frame cost over `window` frames, core and
// context) as the base, and per frame of the take what is kept for the outputs (the file's
// samples, the character's compact take, the writers' buffers).
MemoryEstimate WindowedPipelineMemory(int frames, int window, int markers);
// Adds `other`'s per-frame cost over `frames` frames to estimate's base (a method that runs
// on one window at a time).
void AddPerWindow(const MemoryEstimate& other, int frames, MemoryEstimate* estimate);
// The clip solve (solvers/, solve --mode=clip, pipeline --reference=clip): one sparse
// problem over every frame's pose and marker residuals.
MemoryEstimate ClipSolveMemory(int frames, int markers);
// The multiresolution filter of a solved motion (`filter`, pipeline --filter_levels): the
// motion read, its pyramid and the filtered copy.
MemoryEstimate PyramidFilterMemory(int frames);
// The filter inside `pipeline` (--filter_levels): what it adds to PipelineMemory.
MemoryEstimate PipelineFilterMemory(int frames);
// The pose-space Green's function of a motion (`propagate --method=green`): the pose
// graph and the Laplacian's eigenvectors over every frame.
MemoryEstimate GreenFunctionMemory(int frames);

// Ok without a limit (limit_mb <= 0) or when the estimate fits; else one line:
//   "--memory_mb=500: the pipeline's per-frame stages on TAKE (431,982 frames, 41 markers)
//    would need about 4,795 MB (28 MB + 11.3 KB per frame), over the limit; nothing was done"
Status CheckMemoryLimit(const MemoryEstimate& estimate, double limit_mb, const std::string& input);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_MEMORY_ESTIMATE_H_
