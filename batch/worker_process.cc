#include "batch/worker_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <string>

namespace mocapsolve {
namespace {

using Clock = std::chrono::steady_clock;

constexpr size_t kTailBytes = 8192;

std::string SignalName(int signal) {
  switch (signal) {
    case SIGABRT: return "SIGABRT";
    case SIGSEGV: return "SIGSEGV";
    case SIGKILL: return "SIGKILL";
    case SIGTERM: return "SIGTERM";
    case SIGINT: return "SIGINT";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGPIPE: return "SIGPIPE";
    case SIGXCPU: return "SIGXCPU";
    default: return "signal " + std::to_string(signal);
  }
}

// The last non-empty, non-indented line of `text`, a progress line rewritten with '\r' reduced to its
// last state.
std::string LastLine(const std::string& text) {
  size_t end = text.size();
  while (end > 0) {
    size_t begin = text.find_last_of('\n', end - 1);
    begin = begin == std::string::npos ? 0 : begin + 1;
    std::string line = text.substr(begin, end - begin);
    const size_t cr = line.find_last_of('\r', line.size() >= 1 ? line.size() - 1 : 0);
    if (cr != std::string::npos) line = line.substr(cr + 1);
    while (!line.empty() && (line.back() == ' ' || line.back() == '\r' || line.back() == '\t')) line.pop_back();
    // An indented line continues the one above it (the quality gate's advice under its
    // failures): the error is the line it continues.
    if (!line.empty() && line[0] != ' ' && line[0] != '\t') return line;
    if (begin == 0) break;
    end = begin - 1;
  }
  return "";
}

struct Running {
  int index = 0;
  pid_t pid = -1;
  int fd = -1;
  std::string tail;
  Clock::time_point start;
  bool timed_out = false;
};

void ReadAvailable(Running* r) {
  char buffer[4096];
  while (r->fd >= 0) {
    const ssize_t n = ::read(r->fd, buffer, sizeof(buffer));
    if (n > 0) {
      r->tail.append(buffer, static_cast<size_t>(n));
      if (r->tail.size() > 2 * kTailBytes) r->tail.erase(0, r->tail.size() - kTailBytes);
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) return;
    ::close(r->fd);  // EOF or error.
    r->fd = -1;
  }
}

// Forks and execs; the child's stderr goes to *fd. Returns the pid or -1.
pid_t Spawn(const WorkerJob& job, const WorkerLimits& limits, int crash_signal, int* fd, int stdout_fd) {
  std::vector<char*> argv;
  for (const std::string& a : job.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) return -1;
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    return -1;
  }
  if (pid == 0) {
    // The child: async-signal-safe calls only until exec.
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);
    const int null_fd = ::open("/dev/null", O_RDWR);  // stdin, and stdout when not kept: written to.
    if (null_fd >= 0) ::dup2(null_fd, 0);
    ::dup2(stdout_fd >= 0 ? stdout_fd : null_fd, 1);
    ::dup2(pipe_fds[1], 2);
    if (limits.memory_mb > 0) {
      struct rlimit limit;
      limit.rlim_cur = limit.rlim_max = static_cast<rlim_t>(limits.memory_mb) * 1024 * 1024;
      ::setrlimit(RLIMIT_AS, &limit);
    }
    if (crash_signal != 0) {
      static const char kMessage[] = "MOCAPSOLVE_TEST_CRASH_TAKE: crashing the worker\n";
      (void)!::write(2, kMessage, sizeof(kMessage) - 1);
      ::raise(crash_signal);
      ::_exit(127);
    }
    ::execv(argv[0], argv.data());
    static const char kMessage[] = "cannot execute the mocapsolve binary\n";
    (void)!::write(2, kMessage, sizeof(kMessage) - 1);
    ::_exit(127);
  }
  ::setpgid(pid, pid);  // Also here, so the group exists before any kill.
  ::close(pipe_fds[1]);
  ::fcntl(pipe_fds[0], F_SETFL, O_NONBLOCK);
  *fd = pipe_fds[0];
  return pid;
}

}  // namespace

std::string WorkerResult::ExitName() const {
  if (!started) return "not started";
  if (timed_out) return "timeout";
  if (signal != 0) return SignalName(signal);
  return std::to_string(exit_code);
}

void RunWorkers(const std::vector<WorkerJob>& work, int jobs, const WorkerLimits& limits,
                const WorkerCallbacks& callbacks) {
  // Tests crash chosen takes' workers: MOCAPSOLVE_TEST_CRASH_TAKE=label[:KILL],... (SIGABRT
  // unless :KILL, as the kernel's out-of-memory killer or an operator would).
  std::map<std::string, int> crash_signals;
  if (const char* crash_env = std::getenv("MOCAPSOLVE_TEST_CRASH_TAKE")) {
    std::stringstream list(crash_env);
    for (std::string item; std::getline(list, item, ',');) {
      const size_t colon = item.find(':');
      crash_signals[item.substr(0, colon)] =
          colon != std::string::npos && item.substr(colon + 1) == "KILL" ? SIGKILL : SIGABRT;
    }
  }
  if (jobs < 1) jobs = 1;
  std::vector<Running> running;
  size_t next = 0;
  auto last_tick = Clock::now();
  while (next < work.size() || !running.empty()) {
    while (static_cast<int>(running.size()) < jobs && next < work.size()) {
      const int index = static_cast<int>(next++);
      if (callbacks.on_start && !callbacks.on_start(index)) continue;
      Running r;
      r.index = index;
      r.start = Clock::now();
      const auto crash = crash_signals.find(work[index].label);
      r.pid = Spawn(work[index], limits, crash == crash_signals.end() ? 0 : crash->second, &r.fd, -1);
      if (r.pid < 0) {
        WorkerResult result;
        result.last_line = "cannot start a worker process: " + std::string(std::strerror(errno));
        if (callbacks.on_done) callbacks.on_done(index, result);
        continue;
      }
      running.push_back(std::move(r));
    }
    if (running.empty()) continue;
    std::vector<pollfd> fds;
    for (const Running& r : running) {
      if (r.fd >= 0) fds.push_back({r.fd, POLLIN, 0});
    }
    if (!fds.empty()) {
      ::poll(fds.data(), fds.size(), 20);
    } else {
      ::usleep(20000);
    }
    const auto now = Clock::now();
    for (size_t i = 0; i < running.size();) {
      Running& r = running[i];
      ReadAvailable(&r);
      const double seconds = std::chrono::duration<double>(now - r.start).count();
      if (!r.timed_out && limits.timeout_seconds > 0 && seconds > limits.timeout_seconds) {
        r.timed_out = true;
        ::kill(-r.pid, SIGKILL);
        ::kill(r.pid, SIGKILL);
      }
      int wait_status = 0;
      const pid_t done = ::waitpid(r.pid, &wait_status, WNOHANG);
      if (done != r.pid) {
        ++i;
        continue;
      }
      ReadAvailable(&r);
      if (r.fd >= 0) ::close(r.fd);
      WorkerResult result;
      result.started = true;
      result.timed_out = r.timed_out;
      if (WIFEXITED(wait_status)) result.exit_code = WEXITSTATUS(wait_status);
      if (WIFSIGNALED(wait_status)) {
        result.signal = WTERMSIG(wait_status);
        result.exit_code = 128 + result.signal;
      }
      result.last_line = LastLine(r.tail);
      result.seconds = std::chrono::duration<double>(Clock::now() - r.start).count();
      const int index = r.index;
      running.erase(running.begin() + static_cast<long>(i));
      if (callbacks.on_done) callbacks.on_done(index, result);
    }
    if (callbacks.on_tick && Clock::now() - last_tick > std::chrono::milliseconds(100)) {
      last_tick = Clock::now();
      callbacks.on_tick();
    }
  }
}

Status RunAndCapture(const std::vector<std::string>& argv, std::string* output) {
  int out_pipe[2];
  if (::pipe2(out_pipe, O_CLOEXEC) != 0) return Status::Error("cannot create a pipe");
  WorkerJob job{"", argv};
  int err_fd = -1;
  const pid_t pid = Spawn(job, WorkerLimits(), 0, &err_fd, out_pipe[1]);
  ::close(out_pipe[1]);
  if (pid < 0) {
    ::close(out_pipe[0]);
    return Status::Error("cannot start " + argv[0]);
  }
  std::string text;
  char buffer[4096];
  ssize_t n;
  while ((n = ::read(out_pipe[0], buffer, sizeof(buffer))) > 0 || (n < 0 && errno == EINTR)) {
    if (n > 0) text.append(buffer, static_cast<size_t>(n));
  }
  ::close(out_pipe[0]);
  Running r;
  r.fd = err_fd;
  ::fcntl(err_fd, F_SETFL, 0);  // Blocking: read the rest.
  ReadAvailable(&r);
  int wait_status = 0;
  ::waitpid(pid, &wait_status, 0);
  if (!WIFEXITED(wait_status) || WEXITSTATUS(wait_status) != 0) {
    return Status::Error(argv[0] + " " + (argv.size() > 1 ? argv[1] : "") + ": failed: " + LastLine(r.tail));
  }
  *output = std::move(text);
  return Status::Ok();
}

std::string SelfExecutable() {
  char buffer[4096];
  const ssize_t n = ::readlink("/proc/self/exe", buffer, sizeof(buffer) - 1);
  if (n <= 0) return "/proc/self/exe";
  return std::string(buffer, static_cast<size_t>(n));
}

}  // namespace mocapsolve
