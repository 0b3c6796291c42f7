#include "batch/take_key.h"

#include "io/json_reader.h"

namespace mocapsolve {

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
