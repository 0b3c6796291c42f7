// mocapsolve live: a subject's markers solved frame by frame as they stream in.
#include <csignal>
#include <cstdio>
#include <memory>
#include <unistd.h>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "apps/solver_flags.h"
#include "io/atomic_file.h"
#include "kinematics/quote_token.h"
#include "io/live_source.h"
#include "io/live_stream.h"
#include "settings/live_settings.h"
#include "tasks/live_task.h"

namespace mocapsolve {
namespace {

// A stream endpoint: "-" (fd given) or a TCP listener whose one client becomes fd.
struct Endpoint {
  std::string name;
  int port = -1;
  int listen_fd = -1;
  int fd = -1;
  bool owned = false;
  ~Endpoint() {
    if (owned) CloseFd(&fd);
    CloseFd(&listen_fd);
  }
};

Status Listen(const std::string& text, const std::string& flag, int standard_fd, Endpoint* endpoint) {
  Status status = ParseStreamEndpoint(text, flag, &endpoint->port);
  if (!status.ok()) return status;
  endpoint->name = text == "-" ? (standard_fd == 0 ? "stdin" : "stdout") : text;
  if (endpoint->port < 0) {
    endpoint->fd = standard_fd;
    return Status::Ok();
  }
  int bound = 0;
  status = ListenLocalhost(endpoint->port, &endpoint->listen_fd, &bound);
  if (status.ok() && endpoint->port == 0) std::fprintf(stderr, "live: %s listening on tcp:%d\n", flag.c_str(), bound);
  return status;
}

Status Accept(double timeout, Endpoint* endpoint) {
  if (endpoint->listen_fd < 0) return Status::Ok();
  endpoint->owned = true;
  return AcceptClient(endpoint->listen_fd, endpoint->name, timeout, &endpoint->fd);
}

Status LiveMain(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  LiveConfig config;
  ReadOptionFlags(LiveSettingOptions(), &config.live);
  config.solver = SolverSettingsFromFlags();  // Reads only the options live declares.
  const LiveSettings& live = config.live;
  if (Files().subject.empty() || live.input.empty()) return Status::Error("--subject and --input are required");
  std::signal(SIGPIPE, SIG_IGN);  // A reader gone is a write error, not a signal.
  Subject subject;
  SetStage("inputs");
  Status status = LoadSubjectFromFlags(&subject);
  if (!status.ok()) return status;
  Endpoint input, output;
  std::unique_ptr<LiveFrameSource> source;
  if (live.input.rfind("replay:", 0) == 0) {
    status = MakeReplayFrameSource(live.input.substr(7), live.replay_speed, &source);
  } else {
    status = Listen(live.input, "input", STDIN_FILENO, &input);
  }
  if (status.ok()) status = Listen(live.output, "output", StandardOutputDataFd(), &output);
  if (status.ok()) status = Accept(live.stall_seconds, &output);
  if (status.ok()) status = Accept(live.stall_seconds, &input);
  if (!status.ok()) return status;
  if (!source) source = MakeStreamFrameSource(input.fd, input.name, live.stall_seconds);
  LiveIo io;
  io.source = source.get();
  const bool socket = output.port >= 0;
  io.write = [&](std::string_view bytes) {
    return WriteAll(output.fd, socket, bytes, live.stall_seconds, output.name);
  };
  io.warning = [](const std::string& message) {
    std::fprintf(stderr, "warning: %s\n", TerminalText(message).c_str());
  };
  SetStage("live");
  LiveResult result;
  status = RunLive(subject, config, io, &result);
  if (!status.ok()) return status;
  if (!Console().quiet) {
    std::fprintf(stderr, "live: %ld frames in, %ld out, %ld dropped (input %s)\n", result.frames_in,
                 result.frames_out, result.frames_dropped, result.end.c_str());
  }
  JsonObject report;
  report.Add("subject", Files().subject).Merge(result.report);
  return WriteReport(report);
}

}  // namespace

extern const Command kLiveCommand = {
    "live", "solves a subject's markers frame by frame as they stream in (stdin, TCP or a replayed take)",
    "mocapsolve live --subject=S.json --input=-|tcp:PORT|replay:TAKE.c3d [--output=-|tcp:PORT]\n"
    "    [--output_format=json|bvh] [--replay_speed=1] [--on_bad_frame=stop|skip] [--report=r.json]\n\n"
    "Reads marker frames as a capture system streams them (JSON lines or a binary float32\n"
    "framing, docs/live.md), solves each as it arrives (warm-started from the previous pose,\n"
    "no look-ahead; a marker gone missing is predicted for --predict_frames) and writes its\n"
    "pose at once, as a JSON line or a BVH MOTION line. The run ends when the input closes or\n"
    "stays silent for --stall_seconds; --report gives frames in, out and dropped and the\n"
    "per-frame latency (frame in to pose out: median, 99th percentile, max).",
    __FILE__, LiveMain,
    {SharedOptions("subject,report"), LiveSettingOptions().options(), LiveSolverOptions().options()}};

}  // namespace mocapsolve
