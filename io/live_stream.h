// Byte streams for `mocapsolve live`: a localhost TCP listener (one client), a buffered
// reader over a file descriptor (stdin or a socket) and a writer, all on POSIX sockets
// and poll() with timeouts, so that nothing waits forever: a read that sees no byte for
// its timeout reports kStalled, a write that cannot proceed for its timeout fails.
//
// Errors are one line naming the endpoint ("tcp:9000: port in use", "tcp:9000: the
// client disconnected"). SIGPIPE must be ignored by the process (the live command does
// so) for a closed standard output to be an error rather than a signal; sockets are
// written with MSG_NOSIGNAL.
#ifndef MOCAPSOLVE_IO_LIVE_STREAM_H_
#define MOCAPSOLVE_IO_LIVE_STREAM_H_

#include <string>
#include <string_view>

#include "kinematics/status.h"

namespace mocapsolve {

// "-" (the standard stream) or "tcp:PORT" (a listener on 127.0.0.1, PORT in 0..65535;
// 0: a free port the system picks). *port = -1 for "-". Errors name `flag`.
Status ParseStreamEndpoint(const std::string& text, const std::string& flag, int* port);

// A socket listening on 127.0.0.1:port (0: any free port; *bound_port the one bound).
// Errors: "tcp:PORT: port in use", ...
Status ListenLocalhost(int port, int* listen_fd, int* bound_port);
// Waits up to timeout_seconds for one client on listen_fd; *fd its connection.
Status AcceptClient(int listen_fd, const std::string& name, double timeout_seconds, int* fd);
// Closes fd if >= 0 and sets it to -1.
void CloseFd(int* fd);

// Buffered reads from a descriptor it does not own.
class StreamReader {
 public:
  enum class Result { kData, kEnd, kStalled, kError };

  StreamReader(int fd, std::string name) : fd_(fd), name_(std::move(name)) {}

  // The next line without its '\n' (a final line without one counts at the end). kEnd at
  // the end of the stream with nothing pending; kStalled when no byte came for
  // timeout_seconds; kError with *error (an I/O error, or a line over max_line bytes).
  Result ReadLine(double timeout_seconds, size_t max_line, std::string_view* line, std::string* error);
  // Exactly n bytes. kEnd when the stream ended before the first of them; kError (with
  // "truncated") when it ended inside them.
  Result ReadBytes(size_t n, double timeout_seconds, std::string_view* bytes, std::string* error);
  // The first n bytes without consuming them (fewer if the stream ends first).
  Result Peek(size_t n, double timeout_seconds, std::string_view* bytes, std::string* error);

  const std::string& name() const { return name_; }

 private:
  // Appends what is available (waits up to timeout_seconds): kData, kEnd, kStalled, kError.
  Result Fill(double timeout_seconds, std::string* error);
  void Compact();

  int fd_;
  std::string name_;
  std::string buffer_;
  size_t start_ = 0;  // Consumed bytes at the front of buffer_.
  bool ended_ = false;
};

// Writes all of `bytes` to fd (a socket when is_socket: MSG_NOSIGNAL), waiting up to
// timeout_seconds for the peer to take them. Errors name `name`: "the client disconnected"
// (a socket's EPIPE, ECONNRESET), "the reader closed the pipe" (stdout), "stalled"
// (timeout) or the system's message.
Status WriteAll(int fd, bool is_socket, std::string_view bytes, double timeout_seconds, const std::string& name);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_LIVE_STREAM_H_
