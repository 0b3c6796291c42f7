// Atomic output: every writer in io/ builds its file in memory and hands it here. The
// bytes go to a temporary file beside the target, which is then renamed over it, so a
// reader never sees a partial file and a failed write leaves no output behind.
#ifndef MOCAPSOLVE_IO_ATOMIC_FILE_H_
#define MOCAPSOLVE_IO_ATOMIC_FILE_H_

#include <string>

#include "kinematics/status.h"

namespace mocapsolve {

Status WriteFileAtomically(const std::string& path, const std::string& contents);

// Reads a whole file; the error names the path.
Status ReadFileToString(const std::string& path, std::string* contents);

// True if both paths name the same existing file (used to refuse overwriting an input).
bool SameFile(const std::string& a, const std::string& b);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_ATOMIC_FILE_H_
