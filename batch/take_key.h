// A take's key: what decides whether a finished take must be redone.
//
//   key = FNV-1a 64 over ("mocapsolve.batch_key 1", the program version, the resolved
//         options and the given ones (BatchTake::given) as their config-file JSON text,
//         and for each input in order its role and the FNV-1a 64 hash of its bytes)
// with the inputs: the marker file, the subject file, the subject's skeleton file when
// the subject names one (resolved against the subject's folder), and each character file.
// Paths do not enter the key, only contents, so moving the data does not redo a take.
// FNV-1a (64-bit: offset basis 14695981039346656037, prime 1099511628211) reads ~1 GB/s,
// needs no dependency, and a batch only compares a key with its own earlier value.
// A glTF's external buffers (.bin) are not hashed (GLB, the studio's format, has none).
#ifndef MOCAPSOLVE_BATCH_TAKE_KEY_H_
#define MOCAPSOLVE_BATCH_TAKE_KEY_H_

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "batch/manifest.h"
#include "kinematics/status.h"

namespace mocapsolve {

class Fnv1a64 {
 public:
  void Update(std::string_view bytes);
  uint64_t value() const { return hash_; }

 private:
  uint64_t hash_ = 14695981039346656037ull;
};

// 16 lower-case hex digits.
std::string HexHash(uint64_t hash);

// The file's bytes hashed in 1 MB reads (not recorded as a command input).
Status HashFile(const std::string& path, uint64_t* hash);

struct KeyInput {
  std::string role;   // "markers", "subject", "skeleton", "character".
  std::string path;
  uint64_t hash = 0;
};

struct TakeKey {
  std::vector<KeyInput> inputs;
  std::string options_json;  // OptionsJson(take.options).
  std::string given_json;    // OptionsJson(take.given): the worker's config.
  std::string version;
  uint64_t key = 0;
};

// `cache` (optional) maps a path to its hash for the length of one batch run: the
// subject and character files every take shares are read once.
Status ComputeTakeKey(const BatchTake& take, const std::string& version, TakeKey* key,
                      std::map<std::string, uint64_t>* cache = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_BATCH_TAKE_KEY_H_
