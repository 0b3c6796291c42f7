#include "batch/manifest.h"

#include <glob.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <set>

#include "io/motion_file.h"
#include "io/json_writer.h"

namespace mocapsolve {
namespace {

std::string Folder(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

std::string Resolve(const std::string& folder, const std::string& path) {
  return path.empty() || path[0] == '/' ? path : folder + path;
}

const JsonNode* FindOption(const BatchOptions& options, const std::string& key) {
  for (const auto& [name, value] : options) {
    if (name == key) return &value;
  }
  return nullptr;
}

void SetOption(BatchOptions* options, const std::string& key, const JsonNode& value) {
  for (auto& [name, old] : *options) {
    if (name == key) {
      old = value;
      return;
    }
  }
  options->emplace_back(key, value);
}

std::string JsonText(const JsonNode& node) {
  if (node.is_bool()) return node.boolean ? "true" : "false";
  if (node.is_number()) return JsonValue(node.number).text();
  if (node.is_string()) return JsonQuote(node.string);
  return "null";
}

// Reads the members of `object` (a take or "defaults") that are paths or options.
Status ReadEntry(const JsonNode& object, const std::string& file, const std::string& field, bool is_take,
                 const BatchOptions& pipeline_options, const std::string& folder, BatchTake* take,
                 bool* has_characters) {
  if (!object.is_object()) return Status::Error(object.Where(file) + ": " + field + ": expected an object");
  std::set<std::string> allowed = {"subject", "characters"};
  if (is_take) allowed.insert({"name", "markers"});
  for (const auto& option : pipeline_options) allowed.insert(option.first);
  if (const auto* unknown = FindUnknownKey(object, allowed)) {
    return Status::Error(unknown->second.Where(file) + ": " + field + ": unknown key '" + unknown->first +
                         "' (expected: name, markers, subject, characters or a pipeline option; "
                         "see mocapsolve pipeline --print_config)");
  }
  for (const auto& [key, value] : object.members) {
    const std::string where = value.Where(file) + ": " + field + "." + key;
    if (key == "name" || key == "markers" || key == "subject") {
      if (!value.is_string() || value.string.empty()) return Status::Error(where + ": expected a non-empty string");
      if (key == "name") take->name = value.string;
      if (key == "markers") take->markers = Resolve(folder, value.string);
      if (key == "subject") take->subject = Resolve(folder, value.string);
    } else if (key == "characters") {
      if (!value.is_array()) return Status::Error(where + ": expected an array of file names");
      take->characters.clear();
      for (const JsonNode& item : value.items) {
        if (!item.is_string() || item.string.empty()) {
          return Status::Error(item.Where(file) + ": " + field + ".characters: expected a file name");
        }
        take->characters.push_back(Resolve(folder, item.string));
      }
      *has_characters = true;
    } else {
      const JsonNode* known = FindOption(pipeline_options, key);
      if (known->type != value.type) {
        return Status::Error(where + ": expected a " + JsonTypeName(known->type) + ", got a " +
                             JsonTypeName(value.type));
      }
      SetOption(&take->overrides, key, value);
    }
  }
  return Status::Ok();
}

// Fills the take's resolved options and checks its name and files.
Status FinishTake(const BatchOptions& pipeline_options, const BatchOptions& defaults, const std::string& where,
                  BatchTake* take) {
  if (take->markers.empty()) return Status::Error(where + ": missing 'markers'");
  if (take->subject.empty()) return Status::Error(where + ": missing 'subject' (in the take or in defaults)");
  if (take->name.empty()) take->name = FileStem(take->markers);
  const std::string& name = take->name;
  if (name == "." || name == ".." || name[0] == '.' || name.find('/') != std::string::npos ||
      name == "summary.json" || name == "summary.csv") {
    return Status::Error(where + ": name '" + name + "' is not a plain folder name");
  }
  std::vector<std::pair<std::string, std::string>> files = {{"markers", take->markers}, {"subject", take->subject}};
  for (const std::string& c : take->characters) files.emplace_back("characters", c);
  for (const auto& [field, path] : files) {
    if (::access(path.c_str(), R_OK) != 0) return Status::Error(where + ": " + field + ": " + path + ": cannot read the file");
  }
  take->given = defaults;
  for (const auto& [key, value] : take->overrides) SetOption(&take->given, key, value);
  take->options = pipeline_options;
  for (const auto& [key, value] : take->given) SetOption(&take->options, key, value);
  return Status::Ok();
}

Status CheckUniqueNames(const std::vector<BatchTake>& takes, const std::string& file) {
  std::set<std::string> names;
  for (size_t i = 0; i < takes.size(); ++i) {
    if (!names.insert(takes[i].name).second) {
      return Status::Error(file + ": takes[" + std::to_string(i) + "]: the name '" + takes[i].name +
                           "' is used twice (give the takes distinct \"name\"s)");
    }
  }
  return Status::Ok();
}

}  // namespace

std::string AbsolutePath(const std::string& path) {
  if (path.empty() || path[0] == '/') return path;
  char buffer[4096];
  if (::getcwd(buffer, sizeof(buffer)) == nullptr) return path;
  std::string relative = path;
  while (relative.compare(0, 2, "./") == 0) relative = relative.substr(2);
  return std::string(buffer) + "/" + relative;
}

Status ParsePipelineOptions(const std::string& config_json, BatchOptions* options) {
  JsonNode root;
  Status status = ParseJson(config_json, "pipeline --print_config", &root);
  if (!status.ok()) return status;
  if (!root.is_object() || root.members.empty()) {
    return Status::Error("pipeline --print_config: expected an object of options");
  }
  *options = root.members;
  return Status::Ok();
}

Status ReadManifest(const std::string& path, const BatchOptions& pipeline_options, BatchManifest* manifest) {
  JsonNode root;
  Status status = ReadJsonFile(path, &root);
  if (!status.ok()) return status;
  if (!root.is_object()) return Status::Error(root.Where(path) + ": expected a manifest object");
  if (const auto* unknown = FindUnknownKey(root, {"defaults", "takes"})) {
    return Status::Error(unknown->second.Where(path) + ": unknown key '" + unknown->first +
                         "' (expected: defaults, takes)");
  }
  BatchManifest result;
  result.path = path;
  const std::string folder = Folder(path);
  BatchTake defaults;
  if (const JsonNode* node = root.Find("defaults")) {
    status = ReadEntry(*node, path, "defaults", false, pipeline_options, folder, &defaults,
                       &result.has_default_characters);
    if (!status.ok()) return status;
  }
  result.defaults = defaults.overrides;
  result.default_subject = defaults.subject;
  result.default_characters = defaults.characters;
  const JsonNode* takes = root.Find("takes");
  if (takes == nullptr) return Status::Error(root.Where(path) + ": missing 'takes'");
  if (!takes->is_array() || takes->items.empty()) {
    return Status::Error(takes->Where(path) + ": takes: expected a non-empty array of takes");
  }
  for (size_t i = 0; i < takes->items.size(); ++i) {
    const JsonNode& node = takes->items[i];
    const std::string field = "takes[" + std::to_string(i) + "]";
    BatchTake take;
    take.subject = defaults.subject;
    take.characters = defaults.characters;
    bool has_characters = false;
    status = ReadEntry(node, path, field, true, pipeline_options, folder, &take, &has_characters);
    if (status.ok()) status = FinishTake(pipeline_options, result.defaults, node.Where(path) + ": " + field, &take);
    if (!status.ok()) return status;
    result.takes.push_back(std::move(take));
  }
  status = CheckUniqueNames(result.takes, path);
  if (!status.ok()) return status;
  *manifest = std::move(result);
  return Status::Ok();
}

Status ManifestFromGlob(const std::string& markers_glob, const std::string& subject,
                        const std::vector<std::string>& characters, const BatchOptions& pipeline_options,
                        BatchManifest* manifest) {
  glob_t matches;
  const int code = ::glob(markers_glob.c_str(), 0, nullptr, &matches);
  std::vector<std::string> paths;
  if (code == 0) {
    for (size_t i = 0; i < matches.gl_pathc; ++i) paths.push_back(matches.gl_pathv[i]);
  }
  ::globfree(&matches);
  if (paths.empty()) return Status::Error("--markers_glob='" + markers_glob + "': no file matches");
  if (subject.empty()) return Status::Error("--markers_glob needs --subject");
  BatchManifest result;
  result.default_subject = AbsolutePath(subject);
  for (const std::string& c : characters) result.default_characters.push_back(AbsolutePath(c));
  result.has_default_characters = !characters.empty();
  for (const std::string& path : paths) {
    BatchTake take;
    take.markers = AbsolutePath(path);
    take.subject = result.default_subject;
    take.characters = result.default_characters;
    Status status = FinishTake(pipeline_options, {}, "--markers_glob: " + path, &take);
    if (!status.ok()) return status;
    result.takes.push_back(std::move(take));
  }
  Status status = CheckUniqueNames(result.takes, "--markers_glob='" + markers_glob + "'");
  if (!status.ok()) return status;
  *manifest = std::move(result);
  return Status::Ok();
}

std::string OptionsJson(const BatchOptions& options) {
  JsonObject object;
  for (const auto& [key, value] : options) object.Add(key, JsonValue::Raw(JsonText(value)));
  return object.ToString(/*indent=*/false);
}

std::string FormatManifest(const BatchManifest& manifest, const BatchOptions& /*pipeline_options*/) {
  auto entry = [](JsonObject* object, const std::string& subject, const std::vector<std::string>& characters,
                  bool with_characters, const BatchOptions& options) {
    if (!subject.empty()) object->Add("subject", AbsolutePath(subject));
    if (with_characters) {
      std::vector<JsonValue> list;
      for (const std::string& c : characters) list.push_back(AbsolutePath(c));
      object->Add("characters", list);
    }
    for (const auto& [key, value] : options) object->Add(key, JsonValue::Raw(JsonText(value)));
  };
  JsonObject defaults;
  entry(&defaults, manifest.default_subject, manifest.default_characters, manifest.has_default_characters,
        manifest.defaults);
  std::vector<JsonObject> takes;
  for (const BatchTake& take : manifest.takes) {
    JsonObject object;
    object.Add("name", take.name).Add("markers", AbsolutePath(take.markers));
    const bool own_characters = take.characters != manifest.default_characters;
    entry(&object, take.subject == manifest.default_subject ? "" : take.subject, take.characters, own_characters,
          take.overrides);
    takes.push_back(object);
  }
  JsonObject root;
  root.Add("defaults", defaults).Add("takes", takes);
  return root.ToString() + "\n";
}

}  // namespace mocapsolve
