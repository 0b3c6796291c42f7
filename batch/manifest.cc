#include "batch/manifest.h"

#include <glob.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <map>
#include <set>
#include <unordered_set>

#include "io/atomic_file.h"
#include "io/json_writer.h"
#include "io/motion_file.h"
#include "kinematics/quote_token.h"

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
// `allowed` are its keys (AllowedKeys).
Status ReadEntry(const JsonNode& object, const std::string& file, const std::string& field,
                 const std::set<std::string>& allowed, const BatchOptions& pipeline_options,
                 const std::string& folder, BatchTake* take, bool* has_characters) {
  if (!object.is_object()) return Status::Error(object.Where(file) + ": " + field + ": expected an object");
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
      if (key == "subject") take->subject = value.string == kAutoSubject ? value.string : Resolve(folder, value.string);
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

std::set<std::string> AllowedKeys(const BatchOptions& pipeline_options, bool is_take) {
  std::set<std::string> allowed = {"subject", "characters"};
  if (is_take) allowed.insert({"name", "markers"});
  for (const auto& option : pipeline_options) allowed.insert(option.first);
  return allowed;
}

// Checks the take's required fields and its name (defaulted from the markers file);
// `name_where` prefixes an error about the name.
Status FinishTake(const std::string& where, const std::string& name_where, const std::vector<std::string>& reserved,
                  BatchTake* take) {
  if (take->markers.empty()) return Status::Error(where + ": missing 'markers'");
  if (take->subject.empty()) {
    return Status::Error(where + ": missing 'subject' (in the take or in defaults; \"auto\" fits one per take)");
  }
  if (take->name.empty()) take->name = FileStem(take->markers);
  const Status status = CheckTakeName(take->name, reserved);
  return status.ok() ? status : Status::Error(name_where + ": " + status.message());
}

Status CheckUniqueNames(const std::vector<BatchTake>& takes, const std::string& file) {
  std::unordered_set<std::string_view> names;
  names.reserve(takes.size());
  for (size_t i = 0; i < takes.size(); ++i) {
    if (!names.insert(takes[i].name).second) {
      return Status::Error(file + ": takes[" + std::to_string(i) + "]: the name " + QuoteToken(takes[i].name) +
                           " is used twice (give the takes distinct \"name\"s)");
    }
  }
  return Status::Ok();
}

// Frees what a parsed node holds (its members and strings), once it has been read.
void Release(JsonNode* node) {
  JsonNode empty;
  empty.line = node->line;
  empty.column = node->column;
  std::swap(*node, empty);
}

// The names a take may not have besides the summaries: the manifest's own file name.
std::vector<std::string> ReservedNames(const std::string& manifest_path) {
  if (manifest_path.empty()) return {};
  const size_t slash = manifest_path.find_last_of('/');
  return {slash == std::string::npos ? manifest_path : manifest_path.substr(slash + 1)};
}

}  // namespace

Status CheckTakeName(const std::string& name, const std::vector<std::string>& reserved) {
  const std::string quoted = QuoteToken(name);
  constexpr size_t kMaxName = 255;  // NAME_MAX: the name is a folder's.
  if (name.empty()) return Status::Error("the take name is empty");
  if (name.size() > kMaxName) {
    return Status::Error("the take name " + quoted + " is " + std::to_string(name.size()) +
                         " bytes long (at most 255: it names the take's folder)");
  }
  for (const char c : name) {
    if (c == '/' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      return Status::Error("the take name " + quoted + " holds a '/' or a control character (it names the "
                           "take's folder)");
    }
  }
  if (name[0] == '.') return Status::Error("the take name " + quoted + " starts with '.' (not a plain folder name)");
  const bool summary = name == "summary.json" || name == "summary.csv" || name == "summary.html" ||
                       name.compare(0, 13, "summary.shard") == 0;
  if (summary || std::find(reserved.begin(), reserved.end(), name) != reserved.end()) {
    return Status::Error("the take name " + quoted + " is a file the batch writes or reads itself");
  }
  return Status::Ok();
}

std::string GivenOptionsJson(const BatchManifest& manifest, const BatchTake& take) {
  if (take.overrides.empty()) return OptionsJson(manifest.defaults);
  BatchOptions given = manifest.defaults;
  for (const auto& [key, value] : take.overrides) SetOption(&given, key, value);
  return OptionsJson(given);
}

std::string ResolvedOptionsJson(const BatchManifest& manifest, const BatchTake& take) {
  BatchOptions options = manifest.pipeline;
  for (const auto& [key, value] : manifest.defaults) SetOption(&options, key, value);
  for (const auto& [key, value] : take.overrides) SetOption(&options, key, value);
  return OptionsJson(options);
}

Status SetDefaultOptions(const BatchOptions& options, BatchManifest* manifest) {
  for (const auto& [key, value] : options) {
    const JsonNode* known = FindOption(manifest->pipeline, key);
    if (known == nullptr) return Status::Error("--" + key + ": not a pipeline option");
    if (known->type != value.type) {
      return Status::Error("--" + key + ": expected a " + std::string(JsonTypeName(known->type)) + ", got a " +
                           JsonTypeName(value.type));
    }
    SetOption(&manifest->defaults, key, value);
  }
  return Status::Ok();
}

bool TakeGivesOption(const BatchManifest& manifest, const BatchTake& take, const std::string& key) {
  return FindOption(manifest.defaults, key) != nullptr || FindOption(take.overrides, key) != nullptr;
}

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
  std::string text;
  Status status = ReadFileToString(path, &text);
  return status.ok() ? ParseManifest(text, path, pipeline_options, manifest) : status;
}

Status ParseManifest(std::string_view text, const std::string& path, const BatchOptions& pipeline_options,
                     BatchManifest* manifest) {
  JsonNode root;
  Status status = ParseJson(text, path, &root);
  if (!status.ok()) return status;
  if (!root.is_object()) return Status::Error(root.Where(path) + ": expected a manifest object");
  if (const auto* unknown = FindUnknownKey(root, {"defaults", "takes"})) {
    return Status::Error(unknown->second.Where(path) + ": unknown key '" + unknown->first +
                         "' (expected: defaults, takes)");
  }
  BatchManifest result;
  result.path = path;
  result.pipeline = pipeline_options;
  const std::string folder = Folder(path);
  BatchTake defaults;
  if (const JsonNode* node = root.Find("defaults")) {
    status = ReadEntry(*node, path, "defaults", AllowedKeys(pipeline_options, false), pipeline_options, folder,
                       &defaults, &result.has_default_characters);
    if (!status.ok()) return status;
  }
  result.defaults = defaults.overrides;
  result.default_subject = defaults.subject;
  result.default_characters = defaults.characters;
  JsonNode* takes = nullptr;  // Not const: each take's node is released once read.
  for (auto& [key, value] : root.members) {
    if (key == "takes") takes = &value;
  }
  if (takes == nullptr) return Status::Error(root.Where(path) + ": missing 'takes'");
  if (!takes->is_array() || takes->items.empty()) {
    return Status::Error(takes->Where(path) + ": takes: expected a non-empty array of takes");
  }
  const std::vector<std::string> reserved = ReservedNames(path);
  const std::set<std::string> allowed = AllowedKeys(pipeline_options, true);
  result.takes.reserve(takes->items.size());
  for (size_t i = 0; i < takes->items.size(); ++i) {
    JsonNode& node = takes->items[i];
    const std::string field = "takes[" + std::to_string(i) + "]";
    BatchTake take;
    take.subject = defaults.subject;
    take.characters = defaults.characters;
    bool has_characters = false;
    status = ReadEntry(node, path, field, allowed, pipeline_options, folder, &take, &has_characters);
    const std::string where = node.Where(path) + ": " + field;
    if (status.ok()) status = FinishTake(where, where + ".name", reserved, &take);
    if (!status.ok()) return status;
    result.takes.push_back(std::move(take));
    Release(&node);  // The parsed take is no longer needed: peak memory is one copy of the takes.
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
  if (subject.empty()) return Status::Error("--markers_glob needs --subject (a file, or auto: fitted per take)");
  BatchManifest result;
  result.pipeline = pipeline_options;
  result.default_subject = subject == kAutoSubject ? subject : AbsolutePath(subject);
  for (const std::string& c : characters) result.default_characters.push_back(AbsolutePath(c));
  result.has_default_characters = !characters.empty();
  std::map<std::string, int> stems;  // How many matches have each file stem.
  for (const std::string& path : paths) ++stems[FileStem(path)];
  result.takes.reserve(paths.size());
  for (const std::string& path : paths) {
    BatchTake take;
    take.markers = AbsolutePath(path);
    take.subject = result.default_subject;
    take.characters = result.default_characters;
    take.name = FileStem(path);
    if (stems[take.name] > 1) {  // Same name in other folders: "<folder>_<name>".
      const std::string folder = Folder(take.markers);
      const size_t slash = folder.find_last_of('/', folder.size() >= 2 ? folder.size() - 2 : 0);
      take.name = folder.substr(slash + 1, folder.size() - slash - 2) + "_" + take.name;
    }
    const std::string where = "--markers_glob: " + path;
    Status status = FinishTake(where, where, {}, &take);
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
    if (!subject.empty()) object->Add("subject", subject == kAutoSubject ? subject : AbsolutePath(subject));
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
