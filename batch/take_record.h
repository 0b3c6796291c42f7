// A take's record, DIR/<take>/record.json: the last file a batch writes for a take, so
// its presence with a matching key means the take's outputs are complete.
//
//   {"format": "mocapsolve.batch_record", "version": 1, "take": "02_05",
//    "key": "<16 hex>", "program_version": "0.1.0",
//    "inputs": [{"role": "markers", "path": "...", "hash": "<16 hex>"}, ...],
//    "options": {...the resolved pipeline options...}, "given_options": {...the worker's config...},
//    "status": "done" | "failed", "exit": "0" | "1" | "3" | "SIGABRT" | "timeout" | ...,
//    "exit_code": 0, "error": "the worker's last stderr line",
//    "frames": 60, "wall_seconds": 1.2, "timings": [{"stage": "...", "seconds": 0.1}, ...],
//    "naive_rms_mm": .., "repaired_rms_mm": .., "repaired_share": .., "gate_pass": true,
//    "vertex_error": .., "foot_skating_cm_per_s": .., "limb_mean_deg": .., "limb_p95_deg": ..,
//    "penetration_cm": .., "min_limb_vertices": .., "outputs": ["report.json", ...]}
// The figures come from the pipeline's report.json (TakeFiguresFromReport); a take that
// produced no report has null figures. vertex_error and foot skating are the mean over the
// take's characters (mean vertex error as a fraction of the character's height; the
// retargeted result's planted-foot skating in cm/s); the retarget quality figures
// (pipeline/quality_gate.h) are the worst character's: the largest limb direction errors
// (mean, 95th percentile, degrees) and penetration (cm), the fewest tracked vertices on a limb.
#ifndef MOCAPSOLVE_BATCH_TAKE_RECORD_H_
#define MOCAPSOLVE_BATCH_TAKE_RECORD_H_

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "batch/take_key.h"
#include "kinematics/status.h"
#include "pipeline/take_pipeline.h"

namespace mocapsolve {

struct TakeFigures {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  int frames = 0;
  std::vector<StageTime> timings;
  double naive_rms_mm = kNone;
  double repaired_rms_mm = kNone;
  double repaired_share = kNone;
  int gate_pass = -1;  // -1 unknown, 0 failed, 1 passed.
  double vertex_error = kNone;
  double foot_skating_cm_s = kNone;
  double limb_mean_deg = kNone;
  double limb_p95_deg = kNone;
  double penetration_cm = kNone;
  double min_limb_vertices = kNone;
  std::string view;    // The take's page, relative to its folder ("view.html"); "" = none.
};

struct TakeRecord {
  std::string take;
  std::string key;                   // HexHash of TakeKey::key.
  std::string program_version;
  std::vector<KeyInput> inputs;
  std::string options_json;
  std::string given_json;
  std::string status;                // "done" or "failed".
  std::string exit;                  // "0", "3", "1", a signal name, "timeout".
  int exit_code = 0;                 // The worker's exit code; 128 + signal for a signal; -1 not run.
  std::string error;                 // One line; empty when done.
  double wall_seconds = 0.0;
  TakeFigures figures;
  std::vector<std::string> outputs;  // File names in the take's folder besides record.json.
};

// Reads the figures of a pipeline report.json.
Status TakeFiguresFromReport(const std::string& report_path, TakeFigures* figures);

std::string RecordPath(const std::string& take_dir);
std::string FormatTakeRecord(const TakeRecord& record);
// Written at once (not staged in a command's FileTransaction): the record is the batch's
// progress and must survive the batch being killed.
Status WriteTakeRecord(const std::string& take_dir, const TakeRecord& record);
Status ReadTakeRecord(const std::string& path, TakeRecord* record);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_BATCH_TAKE_RECORD_H_
