// Content hashes of files: FNV-1a 64 (offset basis 14695981039346656037, prime
// 1099511628211), ~1 GB/s and no dependency. Not cryptographic: it tells whether bytes
// changed (a batch take's key, batch/take_key.h) and which bytes a report's inputs had
// (every command's --report), not whether someone forged them.
#ifndef MOCAPSOLVE_IO_CONTENT_HASH_H_
#define MOCAPSOLVE_IO_CONTENT_HASH_H_

#include <cstdint>
#include <string>
#include <string_view>

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

// The file's bytes hashed in 1 MB reads (not recorded as a command input); a missing,
// unreadable or non-regular file (OpenRegularFile, io/atomic_file.h) is an error.
Status HashFile(const std::string& path, uint64_t* hash);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_CONTENT_HASH_H_
