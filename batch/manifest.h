// Batch manifests: the takes of a batch and the pipeline options of each.
//
//   {
//     "defaults": {"subject": "S.json", "characters": ["Xbot.glb"], "gate_repaired_rms_mm": 15, ...},
//     "takes": [
//       {"name": "02_05", "markers": "c3d/02_05.c3d", "subject": "S.json",
//        "characters": ["Xbot.glb"], "filter_levels": 1},
//       ...
//     ]
//   }
// "defaults" and each take may hold "subject", "characters" and any pipeline option (the
// keys of `mocapsolve pipeline --print_config`, of the same JSON type as there); a take's
// own values override the defaults, which override the pipeline's. A take needs "markers"
// and (itself or in defaults) "subject" (a file, or "auto": fitted from each take by its own
// pipeline, pipeline/subject.h kAutoSubject); "name" defaults to the marker file's name without
// extension and must be unique and a plain folder name (it is the take's output folder):
// not empty, at most 255 bytes, no '/', no control character (NUL included), not starting
// with '.', and none of the batch's own files (summary.json/.csv/.html, summary.shard*,
// the manifest's own file name). Relative paths are relative to the manifest's folder.
// Unknown keys, wrong types and bad names are errors naming the file, line:column and
// field (a name escaped by QuoteToken), e.g.
//   M.json:7:22: takes[1]: unknown key 'filter_level' (expected: ...)
// Only the manifest's form is checked here: whether a take's files exist and can be read
// is the batch's business (such a take fails alone).
// Memory: a take holds its name, paths and own overrides only (a few hundred bytes); the
// options every take shares are kept once in the manifest and the per-take option sets
// are made on demand (GivenOptionsJson, ResolvedOptionsJson).
// Nothing here knows of flags or processes.
#ifndef MOCAPSOLVE_BATCH_MANIFEST_H_
#define MOCAPSOLVE_BATCH_MANIFEST_H_

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/json_reader.h"
#include "kinematics/status.h"
#include "pipeline/subject.h"

namespace mocapsolve {

// Pipeline options in order, each a JSON value (number, string or boolean).
using BatchOptions = std::vector<std::pair<std::string, JsonNode>>;

struct BatchTake {
  std::string name;
  std::string markers;                  // Resolved paths (relative to the working folder or absolute).
  std::string subject;
  std::vector<std::string> characters;
  BatchOptions overrides;               // The options the take itself gives (usually none).
};

struct BatchManifest {
  std::string path;                     // "" for a manifest built in memory.
  BatchOptions pipeline;                // The pipeline's options and defaults.
  BatchOptions defaults;                // The manifest's "defaults" options only (not the pipeline's).
  std::string default_subject;
  std::vector<std::string> default_characters;
  bool has_default_characters = false;
  std::vector<BatchTake> takes;
};

// The manifest's defaults with the take's overrides, as a one-line JSON object: what the
// worker's --config holds. (A config file sets flags, and the pipeline treats some set
// flags unlike their defaults: --solver given means that solver for repair and retarget,
// not given means DLS; so only given options are passed on.)
std::string GivenOptionsJson(const BatchManifest& manifest, const BatchTake& take);
// Every pipeline option, resolved (the pipeline's defaults under the given ones), for the
// record and the key.
std::string ResolvedOptionsJson(const BatchManifest& manifest, const BatchTake& take);
// Sets `options` (pipeline options every take gets: the batch command's own --formats)
// as defaults of the manifest, replacing its "defaults" for those keys; a take's own value
// still wins. A key that is not a pipeline option, or a value of another JSON type than
// its default, is an error naming the option.
Status SetDefaultOptions(const BatchOptions& options, BatchManifest* manifest);
// True if the take's given options (defaults or overrides) hold `key`.
bool TakeGivesOption(const BatchManifest& manifest, const BatchTake& take, const std::string& key);

// Checks a take name (see above); `reserved` are further names the batch writes itself.
// The error names the take (QuoteToken) and why, without a location.
Status CheckTakeName(const std::string& name, const std::vector<std::string>& reserved = {});

// The pipeline's options with their defaults, from the text of `pipeline --print_config`.
Status ParsePipelineOptions(const std::string& config_json, BatchOptions* options);

// Reads and validates a manifest; `pipeline_options` are the pipeline's keys and defaults.
Status ReadManifest(const std::string& path, const BatchOptions& pipeline_options, BatchManifest* manifest);
// The same on the manifest's text; `path` names it in messages and anchors relative paths.
Status ParseManifest(std::string_view text, const std::string& path, const BatchOptions& pipeline_options,
                     BatchManifest* manifest);

// One take per file matching `markers_glob` (glob(3), sorted), all with `subject` and
// `characters`: the common case. A take is named after its file without extension; files
// of the same name in different folders are named "<folder>_<name>" (the folder's own
// name) instead, all of them. An error if nothing matches, a name is not usable or two
// names still collide.
Status ManifestFromGlob(const std::string& markers_glob, const std::string& subject,
                        const std::vector<std::string>& characters, const BatchOptions& pipeline_options,
                        BatchManifest* manifest);

// The manifest as a file (absolute paths; defaults and per-take options as they were
// given), for --write_manifest.
std::string FormatManifest(const BatchManifest& manifest, const BatchOptions& pipeline_options);

// The options as a one-line JSON object (a pipeline --config file).
std::string OptionsJson(const BatchOptions& options);

// `path` made absolute against the working folder (not resolving symlinks).
std::string AbsolutePath(const std::string& path);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_BATCH_MANIFEST_H_
