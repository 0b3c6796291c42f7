#include "batch/take_key.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <memory>

#include "io/json_reader.h"

namespace mocapsolve {

void Fnv1a64::Update(std::string_view bytes) {
  uint64_t h = hash_;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  hash_ = h;
}

std::string HexHash(uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

Status HashFile(const std::string& path, uint64_t* hash) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return Status::Error(path + ": cannot open the file");
  constexpr size_t kChunk = 1 << 20;
  std::unique_ptr<char[]> buffer(new char[kChunk]);
  Fnv1a64 fnv;
  while (true) {
    const ssize_t n = ::read(fd, buffer.get(), kChunk);
    if (n < 0) {
      ::close(fd);
      return Status::Error(path + ": cannot read the file");
    }
    if (n == 0) break;
    fnv.Update(std::string_view(buffer.get(), static_cast<size_t>(n)));
  }
  ::close(fd);
  *hash = fnv.value();
  return Status::Ok();
}

namespace {

// The skeleton file a subject names ("skeleton": "path"), resolved; "" when inline.
std::string SubjectSkeletonPath(const std::string& subject_path) {
  JsonNode root;
  if (!ReadJsonFile(subject_path, &root).ok()) return "";  // The pipeline reports it.
  const JsonNode* skeleton = root.Find("skeleton");
  if (skeleton == nullptr || !skeleton->is_string() || skeleton->string.empty()) return "";
  if (skeleton->string[0] == '/') return skeleton->string;
  const size_t slash = subject_path.find_last_of('/');
  return (slash == std::string::npos ? "" : subject_path.substr(0, slash + 1)) + skeleton->string;
}

}  // namespace

Status ComputeTakeKey(const BatchTake& take, const std::string& version, TakeKey* key,
                      std::map<std::string, uint64_t>* cache) {
  TakeKey result;
  result.inputs.push_back({"markers", take.markers});
  result.inputs.push_back({"subject", take.subject});
  const std::string skeleton = SubjectSkeletonPath(take.subject);
  if (!skeleton.empty()) result.inputs.push_back({"skeleton", skeleton});
  for (const std::string& c : take.characters) result.inputs.push_back({"character", c});
  result.options_json = OptionsJson(take.options);
  result.given_json = OptionsJson(take.given);
  result.version = version;
  Fnv1a64 fnv;
  fnv.Update("mocapsolve.batch_key 1");
  fnv.Update(std::string_view("\0", 1));
  fnv.Update(version);
  fnv.Update(std::string_view("\0", 1));
  fnv.Update(result.options_json);
  fnv.Update(std::string_view("\0", 1));
  fnv.Update(result.given_json);
  for (KeyInput& input : result.inputs) {
    const auto cached = cache != nullptr ? cache->find(input.path) : std::map<std::string, uint64_t>::iterator();
    if (cache != nullptr && cached != cache->end()) {
      input.hash = cached->second;
    } else {
      Status status = HashFile(input.path, &input.hash);
      if (!status.ok()) return Status::Error(input.role + ": " + status.message());
      if (cache != nullptr) (*cache)[input.path] = input.hash;
    }
    fnv.Update(std::string_view("\0", 1));
    fnv.Update(input.role);
    fnv.Update(HexHash(input.hash));
  }
  result.key = fnv.value();
  *key = std::move(result);
  return Status::Ok();
}

}  // namespace mocapsolve
