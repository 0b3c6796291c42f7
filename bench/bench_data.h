// Where the benchmarks find ../shared/data: $MOCAPSOLVE_DATA, else the folder beside the
// source tree (as the tests do).
#ifndef MOCAPSOLVE_BENCH_BENCH_DATA_H_
#define MOCAPSOLVE_BENCH_BENCH_DATA_H_

#include <cstdlib>
#include <string>

namespace mocapsolve {

inline std::string DataFile(const std::string& relative) {
  const char* env = std::getenv("MOCAPSOLVE_DATA");
  const std::string root = env != nullptr && *env ? env : MOCAPSOLVE_SOURCE_DIR "/../shared/data";
  return root + "/" + relative;
}

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_BENCH_BENCH_DATA_H_
