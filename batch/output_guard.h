// A batch must never replace or remove one of its own inputs. Before anything is written,
// CheckBatchOutputs compares every output of the batch with every input, by file identity
// (device and inode, following symlinks: a link or another path to an input counts as the
// input), not by name:
//   inputs   the manifest file, and each take's markers, subject, the subject's skeleton
//            file and characters (the ones that exist: a missing one fails its take alone);
//   outputs  files the batch writes (the summaries, --write_manifest) and folders it
//            creates or whose files it replaces (--out_dir, each take's folder, the work
//            folder). An output may not be an input, and a take's folder or the work folder
//            may not hold an input (their files are removed and rewritten); a file output
//            may not be a take's folder either.
// The error is one line naming the output (by its flag or role) and the input (its role
// and take), e.g.
//   --write_manifest=takes/t1.c3d is the markers file of take 't1' (refusing to overwrite an input)
#ifndef MOCAPSOLVE_BATCH_OUTPUT_GUARD_H_
#define MOCAPSOLVE_BATCH_OUTPUT_GUARD_H_

#include <string>
#include <vector>

#include "batch/manifest.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct BatchOutput {
  std::string what;   // For the message: "--write_manifest", "the summary", ...
  std::string path;
  bool folder = false;  // A folder whose files the batch replaces or removes.
};

// The batch's own outputs when it writes into `out_dir` (none when ""): --out_dir itself,
// the summaries "<summary_base>.json/.csv/.html", the work folder (when not ""), and
// `write_manifest` when not "".
std::vector<BatchOutput> BatchOutputs(const std::string& out_dir, const std::string& summary_base,
                                      const std::string& work_dir, const std::string& write_manifest);

// Checks `outputs` and, when `out_dir` is not "", each take's folder OUT_DIR/<name> (made
// one at a time: a batch of 10^6 takes holds no list of them).
Status CheckBatchOutputs(const BatchManifest& manifest, const std::string& out_dir,
                         const std::vector<BatchOutput>& outputs);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_BATCH_OUTPUT_GUARD_H_
