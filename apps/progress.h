// Progress on stderr for long work, silent with --quiet.
//
// On a terminal the line is rewritten in place (carriage return) at most ~10 times a
// second. When stderr is not a terminal (a log file, a pipe, a batch worker's capture) a
// carriage return would pile every update onto one line of the log, so a plain line is
// printed instead, at most every kPlainIntervalSeconds, and the last state once at the end.
//
// ProgressLine is that policy for any text (batch prints takes); Progress counts items:
// "label: 1200/2752 frames, 5400 frames/s, ETA 0.3 s" (`unit`: frames unless given).
#ifndef MOCAPSOLVE_APPS_PROGRESS_H_
#define MOCAPSOLVE_APPS_PROGRESS_H_

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <utility>

namespace mocapsolve {

class ProgressLine {
 public:
  static constexpr double kTerminalIntervalSeconds = 0.1;
  static constexpr double kPlainIntervalSeconds = 5.0;

  explicit ProgressLine(bool quiet)
      : quiet_(quiet), terminal_(isatty(fileno(stderr)) != 0), last_shown_(std::chrono::steady_clock::now()) {}
  // Ends a line left open in place (the work failed before its last state), so what is
  // printed next starts on a line of its own.
  ~ProgressLine() {
    if (open_) std::fprintf(stderr, "\n");
  }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // True when a Show now would print (not quiet, not finished, the interval has passed or
  // this is the last state): callers build the text only then.
  bool Due(bool last) const {
    if (quiet_ || finished_) return false;
    const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_shown_).count();
    return last || since >= (terminal_ ? kTerminalIntervalSeconds : kPlainIntervalSeconds);
  }

  // Prints `text` if Due(last); the last state ends the line and nothing follows it.
  void Show(const std::string& text, bool last) {
    if (!Due(last)) return;
    last_shown_ = std::chrono::steady_clock::now();
    if (terminal_) {
      std::fprintf(stderr, "\r%s   %s", text.c_str(), last ? "\n" : "");
    } else {
      std::fprintf(stderr, "%s\n", text.c_str());
    }
    std::fflush(stderr);
    finished_ = last;
    open_ = terminal_ && !last;
  }

 private:
  bool quiet_;
  bool terminal_;
  bool finished_ = false;
  bool open_ = false;  // A terminal line printed without its newline.
  std::chrono::steady_clock::time_point last_shown_;
};

class Progress {
 public:
  Progress(std::string label, int total, bool quiet, std::string unit = "frames")
      : label_(std::move(label)), unit_(std::move(unit)), total_(total), line_(quiet),
        start_(std::chrono::steady_clock::now()) {}

  void Update(int done) {
    const bool last = done >= total_;
    if (!line_.Due(last)) return;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double rate = seconds > 0 ? done / seconds : 0.0;
    const double eta = rate > 0 ? (total_ - done) / rate : 0.0;
    char text[512];
    std::snprintf(text, sizeof(text), "%s: %d/%d %s, %.*f %s/s, ETA %.1f s", label_.c_str(), done, total_,
                  unit_.c_str(), rate < 10.0 ? 2 : 0, rate, unit_.c_str(), eta);
    line_.Show(text, last);
  }

 private:
  std::string label_;
  std::string unit_;
  int total_;
  ProgressLine line_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_PROGRESS_H_
