#include "batch/output_guard.h"

#include <sys/stat.h>

#include <functional>
#include <unordered_map>
#include <unordered_set>

#include "batch/take_key.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {
namespace {

struct FileId {
  dev_t dev = 0;
  ino_t ino = 0;
  bool operator==(const FileId& other) const { return dev == other.dev && ino == other.ino; }
};

struct FileIdHash {
  size_t operator()(const FileId& id) const {
    return std::hash<unsigned long long>()(static_cast<unsigned long long>(id.ino) * 1000003ull ^ id.dev);
  }
};

struct InputRef {
  int take = -1;        // -1: the manifest file.
  const char* role = "";
};

using InputMap = std::unordered_map<FileId, InputRef, FileIdHash>;

bool Identify(const std::string& path, FileId* id) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) return false;
  *id = {st.st_dev, st.st_ino};
  return true;
}

std::string ParentOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string BaseName(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string Describe(const BatchManifest& manifest, const InputRef& ref) {
  if (ref.take < 0) return "the manifest";
  return std::string("the ") + ref.role + " file of take " + QuoteToken(manifest.takes[ref.take].name);
}

// Every existing input by its identity, and the folders holding them.
void CollectInputs(const BatchManifest& manifest, InputMap* files, InputMap* folders) {
  std::unordered_set<std::string> seen;  // Shared files (subject, characters) once.
  auto add = [&](const std::string& path, int take, const char* role) {
    if (path.empty() || (take >= 0 && std::string(role) != "markers" && !seen.insert(path).second)) return;
    FileId id;
    if (Identify(path, &id)) files->emplace(id, InputRef{take, role});
    if (Identify(ParentOf(path), &id)) folders->emplace(id, InputRef{take, role});
  };
  add(manifest.path, -1, "manifest");
  for (size_t i = 0; i < manifest.takes.size(); ++i) {
    const BatchTake& take = manifest.takes[i];
    const int index = static_cast<int>(i);
    add(take.markers, index, "markers");
    if (take.subject != kAutoSubject && seen.count(take.subject) == 0) {
      add(take.subject, index, "subject");
      add(SubjectSkeletonPath(take.subject), index, "skeleton");
    }
    for (const std::string& c : take.characters) add(c, index, "character");
  }
}

// Where a path is: its folder's identity (or path, when missing) and its name.
std::string Place(const std::string& path) {
  FileId parent;
  const std::string folder = ParentOf(path);
  return (Identify(folder, &parent) ? std::to_string(parent.dev) + ":" + std::to_string(parent.ino) : folder) + "/" +
         BaseName(path);
}

// The output is no input, and (a folder) holds none.
Status CheckOutput(const BatchManifest& manifest, const InputMap& files, const InputMap& folders,
                   const BatchOutput& output) {
  FileId id;
  if (!Identify(output.path, &id)) return Status::Ok();
  if (const auto input = files.find(id); input != files.end()) {
    return Status::Error(output.what + " is " + Describe(manifest, input->second) +
                         " (refusing to overwrite an input)");
  }
  if (const auto input = folders.find(id); output.folder && input != folders.end()) {
    return Status::Error(output.what + " holds " + Describe(manifest, input->second) +
                         " (the batch replaces files there; refusing to remove an input)");
  }
  return Status::Ok();
}

}  // namespace

std::vector<BatchOutput> BatchOutputs(const std::string& out_dir, const std::string& summary_base,
                                      const std::string& work_dir, const std::string& write_manifest) {
  std::vector<BatchOutput> outputs;
  if (!write_manifest.empty()) outputs.push_back({"--write_manifest=" + write_manifest, write_manifest, false});
  if (out_dir.empty()) return outputs;
  outputs.push_back({"--out_dir=" + out_dir, out_dir, false});
  for (const char* extension : {".json", ".csv", ".html"}) {
    const std::string path = out_dir + "/" + summary_base + extension;
    outputs.push_back({"the summary " + path, path, false});
  }
  if (!work_dir.empty()) outputs.push_back({"the work folder " + work_dir, work_dir, true});
  return outputs;
}

Status CheckBatchOutputs(const BatchManifest& manifest, const std::string& out_dir,
                         const std::vector<BatchOutput>& outputs) {
  InputMap files, folders;
  CollectInputs(manifest, &files, &folders);
  std::unordered_map<std::string, const BatchOutput*> places;  // The listed outputs by place.
  for (const BatchOutput& output : outputs) {
    Status status = CheckOutput(manifest, files, folders, output);
    if (!status.ok()) return status;
    const auto [other, inserted] = places.emplace(Place(output.path), &output);
    if (!inserted) return Status::Error(output.what + " is also " + other->second->what);
  }
  if (out_dir.empty()) return Status::Ok();
  for (const BatchTake& take : manifest.takes) {
    const std::string path = out_dir + "/" + take.name;
    const BatchOutput output{"the folder of take " + QuoteToken(take.name) + " (" + path + ")", path, true};
    Status status = CheckOutput(manifest, files, folders, output);
    if (!status.ok()) return status;
    if (const auto other = places.find(Place(path)); other != places.end()) {
      return Status::Error(output.what + " is also " + other->second->what);
    }
  }
  return Status::Ok();
}

}  // namespace mocapsolve
