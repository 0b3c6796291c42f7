// A command's files as one transaction: its inputs are never overwritten, and its
// outputs appear together or not at all.
//
// While a FileTransaction is open (apps/main.cc opens one around every command):
//   - every file read through ReadFileToString (io/atomic_file.h), which every reader in
//     io/ uses, is recorded as an input (by path and by device/inode, so a symlink or a
//     hard link to an input counts as the input);
//   - every WriteFileAtomically is staged: its bytes go at once to an unnamed temporary
//     file in the target's folder (Linux O_TMPFILE; a named ".tmp" file where the file
//     system lacks it), so a full disk or an unwritable folder is reported at once and a
//     process killed while writing leaves nothing behind. Staging an output that names an
//     input, or the same file as an earlier output, is an error.
//   - Commit() checks the whole set again (an input read after an output was staged
//     counts too), then writes the outputs that are streams (an existing character device
//     or FIFO such as /dev/null: written into, never replaced by a regular file), then
//     gives each staged file its name (link to a temporary name, rename over the target).
//     Only that last loop of renames can be cut short by a SIGKILL.
//   - Without Commit (the command failed), the destructor drops every staged file and
//     removes the folders MakeFolders created for it that are still empty, newest first:
//     a command that fails leaves no empty output folder behind.
// With no transaction open (library use, tests), WriteFileAtomically writes and renames
// at once, as before.
#ifndef MOCAPSOLVE_IO_FILE_TRANSACTION_H_
#define MOCAPSOLVE_IO_FILE_TRANSACTION_H_

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/atomic_file.h"
#include "kinematics/status.h"

namespace mocapsolve {

class FileTransaction {
 public:
  // Becomes the process's current transaction; one at a time (CHECKed).
  FileTransaction();
  ~FileTransaction();
  FileTransaction(const FileTransaction&) = delete;
  FileTransaction& operator=(const FileTransaction&) = delete;

  // Publishes every staged output (see above). Errors name the file; on an error before
  // the renames begin nothing has been published.
  Status Commit();

  // The open transaction, or nullptr. Used by io/atomic_file.cc.
  static FileTransaction* Current();

  // Hooks for io/atomic_file.cc: a file about to be read, and the bytes read from it.
  void RecordInput(const std::string& path);
  void RecordInputContents(const std::string& path, const std::string& contents);

  // The inputs read whole (ReadFileToString), in first-read order, each once: what a
  // report names as the bytes the command saw (FNV-1a 64, io/content_hash.h).
  struct InputFile {
    std::string path;
    uint64_t bytes = 0;
    std::string hash;  // 16 hex digits.
  };
  std::vector<InputFile> InputFiles() const;
  Status Stage(const std::string& path, const std::string& contents);
  // A file staged and written already (AtomicFileWriter): checked as Stage checks its path.
  Status Adopt(StagedFile staged);
  // A folder MakeFolders created (it did not exist): removed again if the transaction is
  // dropped and the folder is still empty.
  void RecordCreatedFolder(const std::string& path);

  int num_staged() const;
  // True if `path` names a file recorded as an input (by name or device/inode).
  bool NamesAnInput(const std::string& path) const;

  // While one exists, reads are not recorded: for a command reading back what its own
  // workers wrote (the batch and its takes' reports and records), files that are neither
  // its inputs nor its outputs; a batch of thousands of takes then stays flat in memory.
  class UntrackedReads {
   public:
    UntrackedReads();
    ~UntrackedReads();
    UntrackedReads(const UntrackedReads&) = delete;
    UntrackedReads& operator=(const UntrackedReads&) = delete;
  };

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_FILE_TRANSACTION_H_
