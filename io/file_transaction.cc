#include "io/file_transaction.h"

#include <limits.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <mutex>
#include <vector>

#include <cstdio>
#include <cstdlib>

#include "io/atomic_file.h"
#include "io/content_hash.h"

namespace mocapsolve {
namespace {

FileTransaction* current_transaction = nullptr;
thread_local int untracked_reads = 0;  // Live UntrackedReads scopes of this thread.

// The file a path names, as far as it can be told before it exists: the folder's real
// path plus the file name ("" when the folder does not exist).
std::string CanonicalName(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  char resolved[PATH_MAX];
  if (::realpath(folder.c_str(), resolved) == nullptr) return "";
  return std::string(resolved) + "/" + name;
}

struct FileIdentity {
  std::string path;       // As the command named it (for messages).
  std::string canonical;  // CanonicalName(path).
  bool exists = false;
  dev_t device = 0;
  ino_t inode = 0;
};

FileIdentity Identify(const std::string& path) {
  FileIdentity id;
  id.path = path;
  id.canonical = CanonicalName(path);
  struct stat st;
  if (::stat(path.c_str(), &st) == 0) {
    id.exists = true;
    id.device = st.st_dev;
    id.inode = st.st_ino;
  }
  return id;
}

bool Same(const FileIdentity& a, const FileIdentity& b) {
  if (!a.canonical.empty() && a.canonical == b.canonical) return true;
  return a.exists && b.exists && a.device == b.device && a.inode == b.inode;
}

}  // namespace

struct FileTransaction::State {
  std::mutex mutex;
  std::vector<FileIdentity> inputs;
  std::vector<InputFile> input_files;
  std::vector<FileIdentity> outputs;  // Parallel to staged.
  std::vector<StagedFile> staged;
  std::vector<std::string> created_folders;  // In the order made.

  // Refuses `output` if it names an input. Called with the mutex held.
  Status CheckNotAnInput(const FileIdentity& output) const {
    for (const FileIdentity& input : inputs) {
      if (Same(output, input)) {
        return Status::Error(output.path + ": output would overwrite the input " + input.path);
      }
    }
    return Status::Ok();
  }
};

FileTransaction::FileTransaction() : state_(new State) {
  if (current_transaction != nullptr) {  // A programmer error: transactions do not nest.
    std::fprintf(stderr, "FileTransaction: one at a time\n");
    std::abort();
  }
  current_transaction = this;
}

FileTransaction::~FileTransaction() {
  if (current_transaction == this) current_transaction = nullptr;
  // Unpublished staged files are dropped by their destructors; then the folders made for
  // them, innermost first (rmdir refuses a folder that is not empty).
  state_->staged.clear();
  for (auto folder = state_->created_folders.rbegin(); folder != state_->created_folders.rend(); ++folder) {
    ::rmdir(folder->c_str());
  }
}

void FileTransaction::RecordCreatedFolder(const std::string& path) {
  std::lock_guard<std::mutex> lock(state_->mutex);
  state_->created_folders.push_back(path);
}

FileTransaction* FileTransaction::Current() { return current_transaction; }

FileTransaction::UntrackedReads::UntrackedReads() { ++untracked_reads; }
FileTransaction::UntrackedReads::~UntrackedReads() { --untracked_reads; }

void FileTransaction::RecordInput(const std::string& path) {
  if (untracked_reads > 0) return;
  FileIdentity id = Identify(path);
  std::lock_guard<std::mutex> lock(state_->mutex);
  state_->inputs.push_back(std::move(id));
}

void FileTransaction::RecordInputContents(const std::string& path, const std::string& contents) {
  if (untracked_reads > 0) return;
  Fnv1a64 hash;
  hash.Update(contents);
  InputFile file{path, contents.size(), HexHash(hash.value())};
  std::lock_guard<std::mutex> lock(state_->mutex);
  for (InputFile& known : state_->input_files) {
    if (known.path == path) {
      known = std::move(file);
      return;
    }
  }
  state_->input_files.push_back(std::move(file));
}

std::vector<FileTransaction::InputFile> FileTransaction::InputFiles() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->input_files;
}

Status FileTransaction::Stage(const std::string& path, const std::string& contents) {
  const FileIdentity output = Identify(path);
  {
    std::lock_guard<std::mutex> lock(state_->mutex);
    Status status = state_->CheckNotAnInput(output);
    if (!status.ok()) return status;
    for (const FileIdentity& other : state_->outputs) {
      if (Same(output, other)) {
        return Status::Error(path + ": named twice as an output" +
                             (other.path == path ? std::string() : " (also as " + other.path + ")"));
      }
    }
  }
  StagedFile staged;
  Status status = StagedFile::Create(path, contents, &staged);
  if (!status.ok()) return status;
  std::lock_guard<std::mutex> lock(state_->mutex);
  state_->outputs.push_back(output);
  state_->staged.push_back(std::move(staged));
  return Status::Ok();
}

Status FileTransaction::Adopt(StagedFile staged) {
  const FileIdentity output = Identify(staged.path());
  std::lock_guard<std::mutex> lock(state_->mutex);
  Status status = state_->CheckNotAnInput(output);
  if (!status.ok()) return status;
  for (const FileIdentity& other : state_->outputs) {
    if (Same(output, other)) return Status::Error(staged.path() + ": named twice as an output");
  }
  state_->outputs.push_back(output);
  state_->staged.push_back(std::move(staged));
  return Status::Ok();
}

int FileTransaction::num_staged() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return static_cast<int>(state_->staged.size());
}

bool FileTransaction::NamesAnInput(const std::string& path) const {
  const FileIdentity id = Identify(path);
  std::lock_guard<std::mutex> lock(state_->mutex);
  return !state_->CheckNotAnInput(id).ok();
}

Status FileTransaction::Commit() {
  std::lock_guard<std::mutex> lock(state_->mutex);
  // Inputs read after an output was staged count too.
  for (const FileIdentity& output : state_->outputs) {
    Status status = state_->CheckNotAnInput(output);
    if (!status.ok()) {
      state_->staged.clear();
      return status;
    }
  }
  // Streams first: they cannot be taken back, so a failing one stops the renames.
  std::vector<StagedFile*> order;
  for (StagedFile& file : state_->staged) {
    if (file.is_stream()) order.push_back(&file);
  }
  for (StagedFile& file : state_->staged) {
    if (!file.is_stream()) order.push_back(&file);
  }
  for (StagedFile* file : order) {
    Status status = file->Publish();
    if (!status.ok()) {
      state_->staged.clear();
      return status;
    }
  }
  state_->staged.clear();
  state_->outputs.clear();
  state_->created_folders.clear();  // Published: they stay.
  return Status::Ok();
}

}  // namespace mocapsolve
