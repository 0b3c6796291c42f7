#include "batch/take_key.h"

#include "io/json_reader.h"

namespace mocapsolve {

std::string SubjectSkeletonPath(const std::string& subject_path) {
  JsonNode root;
  if (!ReadJsonFile(subject_path, &root).ok()) return "";  // The pipeline reports it.
  const JsonNode* skeleton = root.Find("skeleton");
  if (skeleton == nullptr || !skeleton->is_string() || skeleton->string.empty()) return "";
  if (skeleton->string[0] == '/') return skeleton->string;
  const size_t slash = subject_path.find_last_of('/');
  return (slash == std::string::npos ? "" : subject_path.substr(0, slash + 1)) + skeleton->string;
}

Status ComputeTakeKey(const BatchManifest& manifest, const BatchTake& take, const std::string& version,
                      TakeKey* key, TakeKeyCache* cache) {
  TakeKey result;
  result.inputs.push_back({"markers", take.markers});
  std::string skeleton;
  // A subject fitted by the take's own pipeline is no file: the markers and options make it.
  if (take.subject != kAutoSubject) {
    result.inputs.push_back({"subject", take.subject});
    if (cache == nullptr) {
      skeleton = SubjectSkeletonPath(take.subject);
    } else if (const auto found = cache->skeletons.find(take.subject); found != cache->skeletons.end()) {
      skeleton = found->second;
    } else {
      skeleton = cache->skeletons[take.subject] = SubjectSkeletonPath(take.subject);
    }
  }
  if (!skeleton.empty()) result.inputs.push_back({"skeleton", skeleton});
  for (const std::string& c : take.characters) result.inputs.push_back({"character", c});
  if (cache != nullptr && take.overrides.empty()) {  // The same for every such take: made once.
    if (cache->options_json.empty()) {
      cache->options_json = ResolvedOptionsJson(manifest, take);
      cache->given_json = GivenOptionsJson(manifest, take);
    }
    result.options_json = cache->options_json;
    result.given_json = cache->given_json;
  } else {
    result.options_json = ResolvedOptionsJson(manifest, take);
    result.given_json = GivenOptionsJson(manifest, take);
  }
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
    // Markers are a take's own: only the shared files are cached.
    const bool shared = cache != nullptr && input.role != "markers";
    const auto cached = shared ? cache->hashes.find(input.path) : std::map<std::string, uint64_t>::iterator();
    if (shared && cached != cache->hashes.end()) {
      input.hash = cached->second;
    } else {
      Status status = HashFile(input.path, &input.hash);
      if (!status.ok()) return Status::Error(input.role + ": " + status.message());
      if (shared) cache->hashes[input.path] = input.hash;
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
