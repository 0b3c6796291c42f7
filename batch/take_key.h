// A take's key: what decides whether a finished take must be redone.
//
//   key = FNV-1a 64 over ("mocapsolve.batch_key 1", the program version, the resolved
//         options and the given ones (ResolvedOptionsJson, GivenOptionsJson) as their
//         config-file JSON text,
//         and for each input in order its role and the FNV-1a 64 hash of its bytes)
// with the inputs: the marker file, the subject file, the subject's skeleton file when
// the subject names one (resolved against the subject's folder), and each character file.
// Paths do not enter the key, only contents, so moving the data does not redo a take.
// FNV-1a (io/content_hash.h) needs no dependency, and a batch only compares a key with
// its own earlier value.
// A glTF's external buffers (.bin) are not hashed (GLB, the studio's format, has none).
#ifndef MOCAPSOLVE_BATCH_TAKE_KEY_H_
#define MOCAPSOLVE_BATCH_TAKE_KEY_H_

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "batch/manifest.h"
#include "io/content_hash.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct KeyInput {
  std::string role;   // "markers", "subject", "skeleton", "character".
  std::string path;
  uint64_t hash = 0;
};

struct TakeKey {
  std::vector<KeyInput> inputs;
  std::string options_json;  // ResolvedOptionsJson(manifest, take).
  std::string given_json;    // GivenOptionsJson(manifest, take): the worker's config.
  std::string version;
  uint64_t key = 0;
};

// The skeleton file a subject names ("skeleton": "path"), resolved against the subject's
// folder; "" when the subject holds its skeleton or cannot be read (the pipeline says why).
std::string SubjectSkeletonPath(const std::string& subject_path);

// For the length of one batch run: the subject and character files every take shares are
// read (hashed, and the subject's skeleton path found) once.
struct TakeKeyCache {
  std::map<std::string, uint64_t> hashes;       // Path -> content hash.
  std::map<std::string, std::string> skeletons; // Subject path -> its skeleton path ("" none).
  std::string given_json, options_json;         // Of the takes without overrides ("" = not yet).
};

// An input that cannot be read (missing, unreadable, not a regular file) is an error
// naming its role and path. `cache` is optional.
Status ComputeTakeKey(const BatchManifest& manifest, const BatchTake& take, const std::string& version,
                      TakeKey* key, TakeKeyCache* cache = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_BATCH_TAKE_KEY_H_
