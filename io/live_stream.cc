#include "io/live_stream.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace mocapsolve {
namespace {

int TimeoutMs(double seconds) {
  if (!(seconds > 0)) return 0;
  return seconds > 2.0e6 ? 2000000000 : static_cast<int>(std::ceil(seconds * 1000.0));
}

std::string SecondsText(double seconds) {  // 5, 0.5, not 5.000000.
  char text[32];
  std::snprintf(text, sizeof(text), "%g", seconds);
  return text;
}

double Now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

Status ParseStreamEndpoint(const std::string& text, const std::string& flag, int* port) {
  if (text == "-") {
    *port = -1;
    return Status::Ok();
  }
  if (text.rfind("tcp:", 0) == 0) {
    const std::string digits = text.substr(4);
    if (!digits.empty() && digits.size() <= 5 && digits.find_first_not_of("0123456789") == std::string::npos &&
        std::stoi(digits) <= 65535) {
      *port = std::stoi(digits);
      return Status::Ok();
    }
    return Status::Error("--" + flag + "=" + text + ": expected tcp:PORT with PORT in 0..65535");
  }
  return Status::Error("--" + flag + "=" + text + ": expected - or tcp:PORT");
}

void CloseFd(int* fd) {
  if (*fd >= 0) ::close(*fd);
  *fd = -1;
}

Status ListenLocalhost(int port, int* listen_fd, int* bound_port) {
  const std::string name = "tcp:" + std::to_string(port);
  int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return Status::Error(name + ": cannot open a socket (" + std::strerror(errno) + ")");
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {
    const int error = errno;
    ::close(fd);
    return Status::Error(name + (error == EADDRINUSE ? std::string(": port in use")
                                                     : ": cannot bind (" + std::string(std::strerror(error)) + ")"));
  }
  if (::listen(fd, 1) != 0) {
    const int error = errno;
    ::close(fd);
    return Status::Error(name + ": cannot listen (" + std::strerror(error) + ")");
  }
  socklen_t size = sizeof(address);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size);
  *bound_port = ntohs(address.sin_port);
  *listen_fd = fd;
  return Status::Ok();
}

Status AcceptClient(int listen_fd, const std::string& name, double timeout_seconds, int* fd) {
  pollfd wait{listen_fd, POLLIN, 0};
  int ready;
  do {
    ready = ::poll(&wait, 1, TimeoutMs(timeout_seconds));
  } while (ready < 0 && errno == EINTR);
  if (ready == 0) return Status::Error(name + ": no client connected within " + SecondsText(timeout_seconds) + " s");
  if (ready < 0) return Status::Error(name + ": " + std::strerror(errno));
  const int client = ::accept4(listen_fd, nullptr, nullptr, SOCK_CLOEXEC);
  if (client < 0) return Status::Error(name + ": accept failed (" + std::strerror(errno) + ")");
  const int one = 1;  // Poses go out as they are made, not batched by Nagle.
  ::setsockopt(client, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));
  *fd = client;
  return Status::Ok();
}

void StreamReader::Compact() {
  if (start_ > 0 && start_ * 2 >= buffer_.size()) {
    buffer_.erase(0, start_);
    start_ = 0;
  }
}

StreamReader::Result StreamReader::Fill(double timeout_seconds, std::string* error) {
  if (ended_) return Result::kEnd;
  Compact();
  pollfd wait{fd_, POLLIN, 0};
  int ready;
  do {
    ready = ::poll(&wait, 1, TimeoutMs(timeout_seconds));
  } while (ready < 0 && errno == EINTR);
  if (ready == 0) return Result::kStalled;
  if (ready < 0) {
    *error = name_ + ": " + std::strerror(errno);
    return Result::kError;
  }
  char chunk[65536];
  ssize_t got;
  do {
    got = ::read(fd_, chunk, sizeof(chunk));
  } while (got < 0 && errno == EINTR);
  if (got < 0) {
    if (errno == ECONNRESET) {  // The peer went away: the stream ends there.
      ended_ = true;
      return Result::kEnd;
    }
    *error = name_ + ": " + std::strerror(errno);
    return Result::kError;
  }
  if (got == 0) {
    ended_ = true;
    return Result::kEnd;
  }
  buffer_.append(chunk, static_cast<size_t>(got));
  return Result::kData;
}

StreamReader::Result StreamReader::ReadLine(double timeout_seconds, size_t max_line, std::string_view* line,
                                            std::string* error) {
  const double deadline = Now() + timeout_seconds;
  size_t searched = start_;
  while (true) {
    const size_t end = buffer_.find('\n', searched);
    if (end != std::string::npos) {
      *line = std::string_view(buffer_).substr(start_, end - start_);
      start_ = end + 1;
      return Result::kData;
    }
    if (buffer_.size() - start_ > max_line) {
      *error = name_ + ": a line longer than " + std::to_string(max_line) + " bytes";
      return Result::kError;
    }
    const size_t pending = buffer_.size() - start_;
    const Result filled = Fill(deadline - Now(), error);
    searched = start_ + pending;  // Fill may have moved the data to the front.
    if (filled == Result::kData) continue;
    if (filled == Result::kEnd && buffer_.size() > start_) {  // A last line without '\n'.
      *line = std::string_view(buffer_).substr(start_);
      start_ = buffer_.size();
      return Result::kData;
    }
    return filled;
  }
}

StreamReader::Result StreamReader::Peek(size_t n, double timeout_seconds, std::string_view* bytes,
                                        std::string* error) {
  const double deadline = Now() + timeout_seconds;
  while (buffer_.size() - start_ < n) {
    const Result filled = Fill(deadline - Now(), error);
    if (filled == Result::kEnd) break;
    if (filled != Result::kData) return filled;
  }
  *bytes = std::string_view(buffer_).substr(start_, std::min(n, buffer_.size() - start_));
  return bytes->empty() ? Result::kEnd : Result::kData;
}

StreamReader::Result StreamReader::ReadBytes(size_t n, double timeout_seconds, std::string_view* bytes,
                                             std::string* error) {
  const Result peeked = Peek(n, timeout_seconds, bytes, error);
  if (peeked != Result::kData) return peeked;
  if (bytes->size() < n) {
    *error = name_ + ": truncated (the stream ended inside a frame)";
    start_ = buffer_.size();
    return Result::kError;
  }
  start_ += n;
  return Result::kData;
}

Status WriteAll(int fd, bool is_socket, std::string_view bytes, double timeout_seconds, const std::string& name) {
  size_t done = 0;
  while (done < bytes.size()) {
    ssize_t wrote = is_socket ? ::send(fd, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL | MSG_DONTWAIT)
                              : ::write(fd, bytes.data() + done, bytes.size() - done);
    if (wrote >= 0) {
      done += static_cast<size_t>(wrote);
      continue;
    }
    if (errno == EINTR) continue;
    if (errno == EPIPE || errno == ECONNRESET) {
      return Status::Error(name + (is_socket ? ": the client disconnected" : ": the reader closed the pipe"));
    }
    if (errno != EAGAIN && errno != EWOULDBLOCK) return Status::Error(name + ": " + std::strerror(errno));
    pollfd wait{fd, POLLOUT, 0};
    const int ready = ::poll(&wait, 1, TimeoutMs(timeout_seconds));
    if (ready == 0) return Status::Error(name + ": stalled (the reader took nothing for " +
                                         SecondsText(timeout_seconds) + " s)");
  }
  return Status::Ok();
}

}  // namespace mocapsolve
