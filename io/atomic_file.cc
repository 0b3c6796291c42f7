#include "io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <utility>

#include "io/file_transaction.h"

namespace mocapsolve {
namespace {

std::string Reason() { return std::strerror(errno); }

std::string FolderOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

// Where the outputs named "-" go: the standard output, or the copy of it kept by
// ReserveStandardOutputForData.
int data_stdout_fd = STDOUT_FILENO;

// Writes all of `bytes` to `fd`, retrying short writes and EINTR.
bool WriteAll(int fd, const std::string& bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

// A name no other writer of this process or another uses at the same time.
std::string TemporaryName(const std::string& path) {
  static std::atomic<int> counter{0};
  return path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
}

}  // namespace

Status StagedFile::Create(const std::string& path, const std::string& contents, StagedFile* staged) {
  staged->Discard();
  staged->path_ = path;
  if (path.empty() || path.back() == '/') return Status::Error("'" + path + "': expected a file name");
  if (IsStandardOutput(path)) {
    staged->stream_ = true;
    staged->stream_bytes_ = contents;
    return Status::Ok();
  }
  struct stat st;
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) return Status::Error(path + ": is a directory");
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) {
      staged->stream_ = true;
      staged->stream_bytes_ = contents;
      return Status::Ok();
    }
    if (!S_ISREG(st.st_mode)) return Status::Error(path + ": not a regular file");
  }
  const std::string folder = FolderOf(path);
  // The unnamed file can only be named later through /proc/self/fd.
  if (::access("/proc/self/fd", X_OK) == 0) {
    staged->fd_ = ::open(folder.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
    // A real refusal (no permission, read-only, full) is final; an unsupported O_TMPFILE
    // or a missing folder goes on to the named attempt, which says which.
    if (staged->fd_ < 0 && errno != EOPNOTSUPP && errno != EISDIR && errno != EINVAL && errno != ENOENT) {
      return Status::Error(path + ": cannot write (" + Reason() + ")");
    }
  }
  if (staged->fd_ < 0) {
    staged->named_temp_ = TemporaryName(path);
    staged->fd_ = ::open(staged->named_temp_.c_str(), O_CREAT | O_EXCL | O_WRONLY | O_CLOEXEC, 0666);
    if (staged->fd_ < 0) {
      const std::string reason = Reason();
      staged->named_temp_.clear();
      return Status::Error(path + ": cannot write (" + reason + ")");
    }
  }
  if (!WriteAll(staged->fd_, contents)) {
    const std::string reason = Reason();
    staged->Discard();
    return Status::Error(path + ": write failed (" + reason + ")");
  }
  return Status::Ok();
}

Status StagedFile::Publish() {
  if (stream_ && IsStandardOutput(path_)) {
    std::fflush(stdout);  // What was printed before comes first when stdout is not reserved.
    const bool written = WriteAll(data_stdout_fd, stream_bytes_);
    const std::string reason = Reason();
    stream_ = false;
    stream_bytes_.clear();
    if (!written) return Status::Error("standard output (-): write failed (" + reason + ")");
    return Status::Ok();
  }
  if (stream_) {
    const int fd = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) return Status::Error(path_ + ": cannot write (" + Reason() + ")");
    const bool written = WriteAll(fd, stream_bytes_);
    const std::string reason = Reason();
    const bool closed = ::close(fd) == 0;
    stream_ = false;
    stream_bytes_.clear();
    if (!written || !closed) return Status::Error(path_ + ": write failed (" + reason + ")");
    return Status::Ok();
  }
  if (fd_ < 0) return Status::Error(path_ + ": nothing staged");
  if (named_temp_.empty()) {
    // Name the unnamed file, then move the name over the target in one step.
    const std::string temp = TemporaryName(path_);
    const std::string proc = "/proc/self/fd/" + std::to_string(fd_);
    if (::linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, temp.c_str(), AT_SYMLINK_FOLLOW) != 0) {
      const std::string reason = Reason();
      Discard();
      return Status::Error(path_ + ": cannot write (" + reason + ")");
    }
    named_temp_ = temp;
  }
  if (::close(fd_) != 0) {
    fd_ = -1;
    const std::string reason = Reason();
    Discard();
    return Status::Error(path_ + ": write failed (" + reason + ")");
  }
  fd_ = -1;
  if (std::rename(named_temp_.c_str(), path_.c_str()) != 0) {
    const std::string reason = Reason();
    Discard();
    return Status::Error(path_ + ": cannot replace (" + reason + ")");
  }
  named_temp_.clear();
  return Status::Ok();
}

Status StagedFile::Append(const void* data, size_t size) {
  const char* bytes = static_cast<const char*>(data);
  if (stream_) {
    stream_bytes_.append(bytes, size);
    return Status::Ok();
  }
  if (fd_ < 0) return Status::Error(path_ + ": nothing staged");
  size_t done = 0;
  while (done < size) {
    const ssize_t n = ::write(fd_, bytes + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return Status::Error(path_ + ": write failed (" + Reason() + ")");
    done += static_cast<size_t>(n);
  }
  return Status::Ok();
}

Status AtomicFileWriter::Open(const std::string& path) {
  open_ = false;
  Status status = StagedFile::Create(path, "", &staged_);
  if (status.ok()) open_ = true;
  return status;
}

Status AtomicFileWriter::Append(const std::string& bytes) { return Append(bytes.data(), bytes.size()); }

Status AtomicFileWriter::Append(const void* data, size_t size) {
  if (!open_) return Status::Error("AtomicFileWriter: not open");
  return staged_.Append(data, size);
}

Status AtomicFileWriter::Close() {
  if (!open_) return Status::Error("AtomicFileWriter: not open");
  open_ = false;
  if (FileTransaction* transaction = FileTransaction::Current()) return transaction->Adopt(std::move(staged_));
  return staged_.Publish();
}

void StagedFile::Discard() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!named_temp_.empty()) ::unlink(named_temp_.c_str());
  named_temp_.clear();
  stream_ = false;
  stream_bytes_.clear();
}

StagedFile::~StagedFile() { Discard(); }

StagedFile::StagedFile(StagedFile&& other) noexcept { *this = std::move(other); }

StagedFile& StagedFile::operator=(StagedFile&& other) noexcept {
  if (this == &other) return *this;
  Discard();
  path_ = std::move(other.path_);
  fd_ = std::exchange(other.fd_, -1);
  named_temp_ = std::move(other.named_temp_);
  other.named_temp_.clear();
  stream_ = std::exchange(other.stream_, false);
  stream_bytes_ = std::move(other.stream_bytes_);
  return *this;
}

bool IsStandardOutput(const std::string& path) { return path == "-"; }

int StandardOutputDataFd() { return data_stdout_fd; }

void ReserveStandardOutputForData() {
  if (data_stdout_fd != STDOUT_FILENO) return;
  std::fflush(stdout);
  const int kept = ::fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, 3);
  if (kept < 0) return;  // No descriptor left: "-" then shares stdout with the messages.
  if (::dup2(STDERR_FILENO, STDOUT_FILENO) < 0) {
    ::close(kept);
    return;
  }
  data_stdout_fd = kept;
}

Status WriteFileAtomically(const std::string& path, const std::string& contents) {
  if (FileTransaction* transaction = FileTransaction::Current()) return transaction->Stage(path, contents);
  return WriteFileAtomicallyNow(path, contents);
}

namespace {
void (*read_chunk_observer)(const std::string&, size_t) = nullptr;
}  // namespace

void SetReadChunkObserverForTesting(void (*observer)(const std::string& path, size_t bytes_so_far)) {
  read_chunk_observer = observer;
}

Status WriteFileAtomicallyNow(const std::string& path, const std::string& contents) {
  StagedFile staged;
  Status status = StagedFile::Create(path, contents, &staged);
  return status.ok() ? staged.Publish() : status;
}

namespace {

const char* FileKind(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  return "a special file";
}

}  // namespace

Status OpenRegularFile(const std::string& path, int* fd, struct stat* st) {
  const int file = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (file < 0) return Status::Error(path + ": cannot open (" + std::strerror(errno) + ")");
  if (::fstat(file, st) != 0) {
    const std::string reason = std::strerror(errno);
    ::close(file);
    return Status::Error(path + ": cannot open (" + reason + ")");
  }
  if (!S_ISREG(st->st_mode)) {
    ::close(file);
    return Status::Error(path + ": is not a regular file (" + FileKind(st->st_mode) + ")");
  }
  ::fcntl(file, F_SETFL, ::fcntl(file, F_GETFL) & ~O_NONBLOCK);
  *fd = file;
  return Status::Ok();
}

Status ReadFileToString(const std::string& path, std::string* contents) {
  struct stat before;
  int fd = -1;
  Status status = OpenRegularFile(path, &fd, &before);
  if (!status.ok()) return status;
  NoteInputFile(path);
  std::string text;
  text.reserve(static_cast<size_t>(before.st_size));
  char buffer[1 << 16];
  while (true) {
    const ssize_t n = ::read(fd, buffer, sizeof(buffer));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::string reason = std::strerror(errno);
      ::close(fd);
      return Status::Error(path + ": read failed (" + reason + ")");
    }
    if (n == 0) break;
    text.append(buffer, static_cast<size_t>(n));
    if (read_chunk_observer != nullptr) read_chunk_observer(path, text.size());
  }
  struct stat after;
  const bool changed = ::fstat(fd, &after) != 0 || after.st_size != before.st_size ||
                       after.st_mtim.tv_sec != before.st_mtim.tv_sec ||
                       after.st_mtim.tv_nsec != before.st_mtim.tv_nsec ||
                       // (/proc files say 0 bytes and have more.)
                       (before.st_size > 0 && text.size() != static_cast<size_t>(before.st_size));
  ::close(fd);
  if (changed) {
    return Status::Error(path + ": the file changed while it was read (" + std::to_string(before.st_size) +
                         " bytes, then " + std::to_string(text.size()) + " read); read it again once it is complete");
  }
  if (FileTransaction* transaction = FileTransaction::Current()) transaction->RecordInputContents(path, text);
  *contents = std::move(text);
  return Status::Ok();
}

void NoteInputFile(const std::string& path) {
  if (FileTransaction* transaction = FileTransaction::Current()) transaction->RecordInput(path);
}

Status MakeFolders(const std::string& path) {
  for (size_t i = 1; i <= path.size(); ++i) {
    if (i < path.size() && path[i] != '/') continue;
    const std::string prefix = path.substr(0, i);
    struct stat st;
    if (::stat(prefix.c_str(), &st) == 0) {
      if (!S_ISDIR(st.st_mode)) return Status::Error(path + ": " + prefix + " is not a folder");
      continue;
    }
    if (::mkdir(prefix.c_str(), 0777) == 0) {
      if (FileTransaction* transaction = FileTransaction::Current()) transaction->RecordCreatedFolder(prefix);
    } else if (errno != EEXIST) {
      return Status::Error(path + ": cannot create the folder");
    }
  }
  return Status::Ok();
}

bool SameFile(const std::string& a, const std::string& b) {
  struct stat sa, sb;
  if (::stat(a.c_str(), &sa) != 0 || ::stat(b.c_str(), &sb) != 0) return false;
  return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

Status CheckNotAnInput(const std::string& output, const std::string& input) {
  if (input.empty() || (output != input && !SameFile(output, input))) return Status::Ok();
  return Status::Error(output + ": output would overwrite the input " + input);
}

}  // namespace mocapsolve
