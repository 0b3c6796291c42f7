// Atomic output: every writer in io/ builds its file in memory and hands it to
// WriteFileAtomically. The bytes go to a temporary file beside the target, which is then
// renamed over it, so a reader never sees a partial file and a failed write leaves no
// output behind. Inside a FileTransaction (io/file_transaction.h; apps/main.cc opens one
// per command) the rename waits for the transaction's Commit, which also refuses outputs
// that would overwrite an input or each other.
//
// An existing character device or FIFO (/dev/null, /dev/full, a pipe) is written into,
// never replaced by a regular file; a directory or another special file is an error.
// The path "-" names the standard output: written into like a stream, when the
// transaction commits (text outputs only: the commands check which outputs may be "-").
#ifndef MOCAPSOLVE_IO_ATOMIC_FILE_H_
#define MOCAPSOLVE_IO_ATOMIC_FILE_H_

#include <sys/stat.h>

#include <string>

#include "kinematics/status.h"

namespace mocapsolve {

Status WriteFileAtomically(const std::string& path, const std::string& contents);

// Like WriteFileAtomically, but published at once even inside a FileTransaction (not at
// its Commit, and not checked against its inputs): for files that record a command's
// progress and must survive it being killed (a batch's take records and summaries). The
// caller checks that the path is none of its inputs.
Status WriteFileAtomicallyNow(const std::string& path, const std::string& contents);

// True for "-", the output path that means the standard output.
bool IsStandardOutput(const std::string& path);
// Keeps the process's standard output for the outputs named "-" and sends everything
// else printed there (progress, "wrote ...") to standard error, so the data on stdout is
// the output alone. apps/main.cc calls it when a flag of the command is "-"; idempotent.
void ReserveStandardOutputForData();
// The descriptor outputs named "-" are written to (STDOUT_FILENO unless reserved): for a
// writer that streams its output (mocapsolve live) rather than writing it once.
int StandardOutputDataFd();

// Opens an input file to read: with O_NONBLOCK, so that a FIFO without a writer cannot
// block, then fstat; anything but a regular file (a folder, FIFO, socket or device) is an
// error naming the path ("is not a regular file (a FIFO)"), as is a missing or unreadable
// one. On success *fd is open (blocking again, close-on-exec) and *st describes it. The
// one way io/ opens what it reads (ReadFileToString, HashFile), so no reader can hang
// on a pipe.
Status OpenRegularFile(const std::string& path, int* fd, struct stat* st);

// Reads a whole file (OpenRegularFile); the error names the path. Inside a FileTransaction the file is
// recorded as an input. A regular file that changes while it is read (its size or
// modification time differs after the read, or fewer bytes came than it had: another
// program writing or truncating it) is an error, not a silently shorter file.
Status ReadFileToString(const std::string& path, std::string* contents);
// Test seam: called after each chunk ReadFileToString reads (nullptr: none), so a test
// can change the file in the middle of a read.
void SetReadChunkObserverForTesting(void (*observer)(const std::string& path, size_t bytes_so_far));

// Records a file that a third-party library reads by itself (a glTF's external buffers)
// as an input of the open FileTransaction, if any.
void NoteInputFile(const std::string& path);

// mkdir -p: creates the folder and its missing parents; an error names a part that is
// not a folder or cannot be created. Inside a FileTransaction the folders it made are
// removed again, if still empty, when the command fails (file_transaction.h).
Status MakeFolders(const std::string& path);

// True if both paths name the same existing file (used to refuse overwriting an input).
bool SameFile(const std::string& a, const std::string& b);

// An output path must not name one of the inputs ("" names none): the one-line error
// "OUT: output would overwrite the input IN".
Status CheckNotAnInput(const std::string& output, const std::string& input);

// An output written but not yet visible: an unnamed temporary file in the target's
// folder (O_TMPFILE; a named "<target>.tmp.<pid>.<n>" where the file system lacks it),
// or, for a target that is a character device or FIFO, the bytes held for writing into
// it. Publish() gives the file its name (or writes the stream); the destructor drops an
// unpublished file.
class StagedFile {
 public:
  // Errors (one line, naming `path`): a missing or unwritable folder, a full disk, a
  // directory or special file as the target.
  static Status Create(const std::string& path, const std::string& contents, StagedFile* staged);

  StagedFile() = default;
  ~StagedFile();
  StagedFile(StagedFile&& other) noexcept;
  StagedFile& operator=(StagedFile&& other) noexcept;
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;

  Status Publish();
  // Appends bytes to the staged file (a long output written in pieces; AtomicFileWriter).
  Status Append(const void* data, size_t size);
  const std::string& path() const { return path_; }
  bool is_stream() const { return stream_; }

 private:
  void Discard();

  std::string path_;
  int fd_ = -1;                // The unnamed (or named) temporary file.
  std::string named_temp_;     // Non-empty when the temporary file has a name.
  bool stream_ = false;        // The target is a character device or FIFO.
  std::string stream_bytes_;   // What a stream target receives.
};

// An output written in pieces (a long take's files, pipeline/take_windows.h), atomic as
// WriteFileAtomically: Open stages an empty temporary file beside `path` (the errors of
// StagedFile::Create), Append adds bytes to it, Close publishes it: at once, or, inside a
// FileTransaction, at its Commit (checked then as a staged output). Dropped unclosed, it
// leaves nothing behind.
class AtomicFileWriter {
 public:
  Status Open(const std::string& path);
  Status Append(const std::string& bytes);
  Status Append(const void* data, size_t size);
  Status Close();
  bool is_open() const { return open_; }

 private:
  StagedFile staged_;
  bool open_ = false;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_ATOMIC_FILE_H_
