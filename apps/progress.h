// Progress on stderr for long work: "label: 1200/2752 frames, 5400 frames/s, ETA 0.3 s",
// rewritten in place at most ~10 times a second, silent with --quiet. `unit` names what is
// counted (frames unless given: "trials").
#ifndef MOCAPSOLVE_APPS_PROGRESS_H_
#define MOCAPSOLVE_APPS_PROGRESS_H_

#include <chrono>
#include <cstdio>
#include <string>
#include <utility>

namespace mocapsolve {

class Progress {
 public:
  Progress(std::string label, int total, bool quiet, std::string unit = "frames")
      : label_(std::move(label)), unit_(std::move(unit)), total_(total), quiet_(quiet),
        start_(std::chrono::steady_clock::now()), last_(start_) {}

  void Update(int done) {
    if (quiet_) return;
    const auto now = std::chrono::steady_clock::now();
    if (done < total_ && now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    const double seconds = std::chrono::duration<double>(now - start_).count();
    const double rate = seconds > 0 ? done / seconds : 0.0;
    const double eta = rate > 0 ? (total_ - done) / rate : 0.0;
    std::fprintf(stderr, "\r%s: %d/%d %s, %.*f %s/s, ETA %.1f s   ", label_.c_str(), done, total_,
                 unit_.c_str(), rate < 10.0 ? 2 : 0, rate, unit_.c_str(), eta);
    if (done >= total_) std::fprintf(stderr, "\n");
  }

 private:
  std::string label_;
  std::string unit_;
  int total_;
  bool quiet_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_PROGRESS_H_
