#include "pipeline/subject.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <utility>

#include "io/atomic_file.h"
#include "io/input_limits.h"
#include "io/json_reader.h"
#include "io/json_writer.h"
#include "io/marker_file.h"
#include "io/marker_set_file.h"
#include "io/motion_file.h"
#include "io/skeleton_json.h"
#include "kinematics/unlabelled_label.h"

namespace mocapsolve {
namespace {

namespace fs = std::filesystem;

constexpr const char* kFormat = "mocapsolve.subject";

std::string Folder(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

// The skeleton named by a path in the subject file, with its unit made known.
Status LoadSkeletonPath(const std::string& path, const JsonNode& node, const JsonNode* units_node,
                        Subject* subject) {
  const fs::path given(node.string);
  const std::string resolved = given.is_absolute() ? given.string() : (fs::path(Folder(path)) / given).string();
  Skeleton skeleton;
  Status status = ReadSkeletonFile(resolved, &skeleton);
  if (!status.ok()) return Status::Error(node.Where(path) + ": skeleton: " + status.message());
  if (units_node != nullptr) {
    if (!units_node->is_string()) return Status::Error(units_node->Where(path) + ": skeleton_units: expected a string");
    const std::string& name = units_node->string;
    if (skeleton.unit().known()) {
      if (name != skeleton.unit().name) {
        const LengthUnit unit = LengthUnitFromName(name);
        if (!unit.known() || std::abs(unit.metres_per_unit / skeleton.unit().metres_per_unit - 1.0) > 1e-12) {
          return Status::Error(units_node->Where(path) + ": skeleton_units: '" + name + "', but " + resolved +
                               " states '" + skeleton.unit().name + "'");
        }
      }
    } else {
      const LengthUnit unit = LengthUnitFromName(name);
      if (!unit.known()) {
        return Status::Error(units_node->Where(path) + ": skeleton_units: '" + name + "': expected mm, cm, m or in");
      }
      std::vector<JointSpec> joints;
      for (int j = 0; j < skeleton.num_joints(); ++j) joints.push_back(skeleton.joint(j));
      Skeleton with_unit;
      status = Skeleton::Create(std::move(joints), skeleton.end_sites(), unit, &with_unit);
      if (!status.ok()) return Status::Error(node.Where(path) + ": skeleton: " + status.message());
      skeleton = std::move(with_unit);
    }
  }
  if (!skeleton.unit().known()) {
    return Status::Error(node.Where(path) + ": skeleton: " + resolved +
                         " states no length unit; add \"skeleton_units\" (mm, cm, m or in)");
  }
  subject->skeleton = std::move(skeleton);
  subject->skeleton_path = resolved;
  return Status::Ok();
}

// "mean_pose": {joint: [w, x, y, z], ...}: one unit quaternion per named joint, the
// others identity.
Status InterpretMeanPose(const std::string& path, const JsonNode& node, const Skeleton& skeleton,
                         QuaternionVector* mean_pose) {
  if (!node.is_object()) return Status::Error(node.Where(path) + ": mean_pose: expected an object {joint: [w, x, y, z]}");
  QuaternionVector result(skeleton.num_joints(), Eigen::Quaterniond::Identity());
  for (const auto& [name, value] : node.members) {
    const std::string field = value.Where(path) + ": mean_pose." + name + ": ";
    const int j = skeleton.FindJoint(name);
    if (j < 0) return Status::Error(field + "unknown joint");
    bool numbers = value.is_array() && value.items.size() == 4;
    for (size_t i = 0; numbers && i < 4; ++i) numbers = value.items[i].is_number();
    if (!numbers) return Status::Error(field + "expected [w, x, y, z]");
    const Eigen::Quaterniond q(value.items[0].number, value.items[1].number, value.items[2].number,
                               value.items[3].number);
    // As ValidateMotion's unit test; kept as read (the solver normalizes), so a file
    // written again is the same to the byte.
    if (!(std::abs(q.norm() - 1.0) <= 1e-6)) return Status::Error(field + "expected a unit quaternion");
    result[j] = q;
  }
  *mean_pose = std::move(result);
  return Status::Ok();
}

Status Interpret(const std::string& path, const JsonNode& root, Subject* subject) {
  const auto error = [&](const JsonNode& node, const std::string& message) {
    return Status::Error(node.Where(path) + ": " + message);
  };
  if (!root.is_object()) return error(root, "expected a subject object");
  const std::set<std::string> keys = {"format", "version", "name", "skeleton", "skeleton_units",
                                      "markerset", "marker_files", "amc_fps", "mean_pose"};
  if (const auto* member = FindUnknownKey(root, keys)) {
    return error(member->second, "unknown key '" + member->first + "' (known: " + KeyList(keys) + ")");
  }
  const JsonNode* format = root.Find("format");
  if (format == nullptr || !format->is_string() || format->string != kFormat) {
    return error(format ? *format : root, "format: expected \"" + std::string(kFormat) + "\"");
  }
  const JsonNode* version = root.Find("version");
  if (version == nullptr || !version->is_number() || version->number != 1.0) {
    return error(version ? *version : root, "version: expected 1 (the only version this build reads)");
  }
  Subject result;
  if (const JsonNode* name = root.Find("name")) {
    if (!name->is_string()) return error(*name, "name: expected a string");
    result.name = name->string;
  }
  const JsonNode* skeleton = root.Find("skeleton");
  if (skeleton == nullptr) return error(root, "missing \"skeleton\" (a skeleton file path or an inline skeleton)");
  const JsonNode* units = root.Find("skeleton_units");
  Status status = Status::Ok();
  if (skeleton->is_string()) {
    if (skeleton->string.empty()) return error(*skeleton, "skeleton: empty path");
    status = LoadSkeletonPath(path, *skeleton, units, &result);
    if (!status.ok()) return status;
  } else if (skeleton->is_object()) {
    if (units != nullptr) return error(*units, "skeleton_units: only with a skeleton path (an inline skeleton states its unit)");
    status = InterpretSkeletonJson(*skeleton, path, "skeleton", &result.skeleton);
    if (!status.ok()) return status;
    if (!result.skeleton.unit().known()) return error(*skeleton, "skeleton: metres_per_unit: the unit must be known");
  } else {
    return error(*skeleton, "skeleton: expected a file path or an inline skeleton object");
  }
  const JsonNode* markerset = root.Find("markerset");
  if (markerset == nullptr) return error(root, "missing \"markerset\" (the calibrated marker set, inline)");
  status = InterpretMarkerSet(*markerset, path, result.skeleton, &result.markers);
  if (!status.ok()) {
    // Name the field: "S.json:7:5: markerset: markers[3]: ...".
    const std::string& message = status.message();
    const std::string where = path + ":";
    size_t cut = std::string::npos;
    if (message.compare(0, where.size(), where) == 0) cut = message.find(": ", where.size());
    if (cut == std::string::npos) return Status::Error("markerset: " + message);
    return Status::Error(message.substr(0, cut) + ": markerset: " + message.substr(cut + 2));
  }
  if (const JsonNode* files = root.Find("marker_files")) {
    if (!files->is_object()) return error(*files, "marker_files: expected an object");
    const std::set<std::string> file_keys = {"axes", "scale", "label_prefix"};
    if (const auto* member = FindUnknownKey(*files, file_keys)) {
      return error(member->second, "marker_files: unknown key '" + member->first + "' (known: " +
                                       KeyList(file_keys) + ")");
    }
    if (const JsonNode* axes = files->Find("axes")) {
      if (!axes->is_string()) return error(*axes, "marker_files.axes: expected a string such as \"y,z,x\"");
      Eigen::Matrix3d rotation;
      status = ParseAxes(axes->string, &rotation);
      if (!status.ok()) return error(*axes, "marker_files.axes: " + status.message());
      result.axes = axes->string;
    }
    if (const JsonNode* scale = files->Find("scale")) {
      if (!scale->is_number() || !(scale->number >= 0.0)) {
        return error(*scale, "marker_files.scale: expected a number >= 0 (0: from the units)");
      }
      // 1e308 scaled every sample to inf: "no marker observed in any frame".
      if (Status bound = CheckUnitScale(scale->number, "marker_files.scale"); !bound.ok()) {
        return error(*scale, bound.message());
      }
      result.marker_scale = scale->number;
    }
    if (const JsonNode* prefix = files->Find("label_prefix")) {
      if (!prefix->is_string()) return error(*prefix, "marker_files.label_prefix: expected a string");
      result.label_prefix = prefix->string;
    }
  }
  if (const JsonNode* fps = root.Find("amc_fps")) {
    if (!fps->is_number() || !(fps->number > 0.0)) return error(*fps, "amc_fps: expected a number > 0");
    if (Status bound = CheckFrameRate(fps->number, "amc_fps"); !bound.ok()) return error(*fps, bound.message());
    result.amc_fps = fps->number;
  }
  if (const JsonNode* mean = root.Find("mean_pose")) {
    status = InterpretMeanPose(path, *mean, result.skeleton, &result.mean_pose);
    if (!status.ok()) return status;
  }
  *subject = std::move(result);
  return Status::Ok();
}

}  // namespace

Status ReadSubject(const std::string& path, Subject* subject) {
  JsonNode root;
  Status status = ReadJsonFile(path, &root);
  if (!status.ok()) return status;
  return Interpret(path, root, subject);
}

Status ParseSubject(const std::string& text, const std::string& name, Subject* subject) {
  JsonNode root;
  Status status = ParseJson(text, name, &root);
  if (!status.ok()) return status;
  return Interpret(name, root, subject);
}

std::string FormatSubject(const std::string& /*path*/, const Subject& subject) {
  std::string out = "{\n  \"format\": \"" + std::string(kFormat) + "\",\n  \"version\": 1,\n";
  if (!subject.name.empty()) out += "  \"name\": " + JsonQuote(subject.name) + ",\n";
  // Inline always: a subject file copied elsewhere still holds its skeleton (a path,
  // which old files hold, would break when the file moves without its skeleton).
  out += "  \"skeleton\": " + FormatSkeletonJson(subject.skeleton, 2) + ",\n";
  out += "  \"marker_files\": {\"axes\": " + JsonQuote(subject.axes) + ", \"scale\": " +
         JsonValue(subject.marker_scale).text() + ", \"label_prefix\": " + JsonQuote(subject.label_prefix) + "},\n";
  out += "  \"amc_fps\": " + JsonValue(subject.amc_fps).text() + ",\n";
  if (!subject.mean_pose.empty()) {
    out += "  \"mean_pose\": {";
    for (int j = 0; j < static_cast<int>(subject.mean_pose.size()); ++j) {
      const Eigen::Quaterniond& q = subject.mean_pose[j];
      out += (j == 0 ? "\n    " : ",\n    ") + JsonQuote(subject.skeleton.name(j)) + ": [" + JsonValue(q.w()).text() +
             ", " + JsonValue(q.x()).text() + ", " + JsonValue(q.y()).text() + ", " + JsonValue(q.z()).text() + "]";
    }
    out += "\n  },\n";
  }
  // The marker set as its own file writes it, indented one level.
  std::string markers = FormatMarkerSet(subject.skeleton, subject.markers);
  while (!markers.empty() && markers.back() == '\n') markers.pop_back();
  std::string indented;
  for (char c : markers) {
    indented += c;
    if (c == '\n') indented += "  ";
  }
  out += "  \"markerset\": " + indented + "\n}\n";
  return out;
}

Status WriteSubject(const std::string& path, const Subject& subject) {
  if (!subject.skeleton.unit().known()) return Status::Error(path + ": the subject's skeleton unit is unknown");
  Eigen::Matrix3d rotation;
  Status status = ParseAxes(subject.axes, &rotation);
  if (!status.ok()) return Status::Error(path + ": axes: " + status.message());
  if (!subject.mean_pose.empty() && static_cast<int>(subject.mean_pose.size()) != subject.skeleton.num_joints()) {
    return Status::Error(path + ": the mean pose has " + std::to_string(subject.mean_pose.size()) +
                         " rotations, the skeleton " + std::to_string(subject.skeleton.num_joints()) + " joints");
  }
  for (int m = 0; m < subject.markers.num_markers(); ++m) {
    for (const MarkerAttachment& a : subject.markers.marker(m).attachments) {
      if (a.joint < 0 || a.joint >= subject.skeleton.num_joints()) {
        return Status::Error(path + ": marker '" + subject.markers.label(m) + "' names joint index " +
                             std::to_string(a.joint) + ", not in the skeleton");
      }
    }
  }
  return WriteFileAtomically(path, FormatSubject(path, subject));
}

Status ReadMarkerFileForSubject(const Subject& subject, const std::string& markers_path,
                                MarkerTrajectories* trajectories) {
  MarkerReadOptions options = DefaultMarkerReadOptions();
  options.preferred_subject_prefix = subject.label_prefix;
  return ReadMarkerFile(markers_path, trajectories, options);
}

Status LoadTakeForSubject(const Subject& subject, const std::string& markers_path, MarkerTake* take) {
  MarkerTrajectories trajectories;
  Status status = ReadMarkerFileForSubject(subject, markers_path, &trajectories);
  if (!status.ok()) return status;
  return TakeForSubject(subject, std::move(trajectories), markers_path, take);
}

Status RequireTakeData(const std::string& path, const MarkerTake& take) {
  if (Status status = RequireMarkerData(path, take.trajectories); !status.ok()) return status;
  const int markers = take.markers.num_markers();
  std::vector<char> seen(markers, 0);
  for (const std::vector<Eigen::Vector3d>& frame : take.observed) {
    for (int m = 0; m < markers && m < static_cast<int>(frame.size()); ++m) seen[m] |= frame[m].allFinite();
  }
  if (std::find(seen.begin(), seen.end(), 1) == seen.end()) {
    return Status::Error(path + ": no marker of the marker set is observed in any frame");
  }
  return RequireObservableSegments(path, take.skeleton, take.markers, seen);
}

Status RequireObservableSegments(const std::string& path, const Skeleton& skeleton, const MarkerSet& markers,
                                 const std::vector<char>& seen) {
  const int joints = skeleton.num_joints();
  std::vector<char> carries(joints, 0), observed(joints, 0);
  std::vector<std::string> labels_on(joints);
  for (int m = 0; m < markers.num_markers(); ++m) {
    for (const MarkerAttachment& a : markers.marker(m).attachments) {
      carries[a.joint] = 1;
      observed[a.joint] |= seen[m];
      labels_on[a.joint] += (labels_on[a.joint].empty() ? "" : ", ") + markers.label(m);
    }
  }
  // A joint is observed through its own markers or any below it (parents come first).
  for (int j = joints - 1; j > 0; --j) observed[skeleton.parent(j)] |= observed[j];
  std::string blind;
  for (int j = 0; j < joints; ++j) {
    if (!carries[j] || observed[j]) continue;
    blind += (blind.empty() ? "" : "; ") + skeleton.joint(j).name + " (" + labels_on[j] + ")";
  }
  if (blind.empty()) return Status::Ok();
  return Status::Error(path + ": segments never observed (no sample in any frame of their markers or of any below "
                       "them), so their joints cannot be solved in this take: " + blind +
                       " (wrong subject or labels? a marker read as missing by --ignore_markers counts as never seen)");
}

namespace {

// A subject whose marker set the take does not match: one line naming, per segment (the
// joint a marker rides on; several for a blended one), the labels the take has no column for.
Status CheckTakeHasSubjectMarkers(const Skeleton& skeleton, const MarkerSet& markers,
                                  const MarkerTrajectories& file, const std::string& markers_path) {
  std::vector<std::string> segments;                // In order of first appearance.
  std::map<std::string, std::string> missing_on;    // Segment -> labels.
  std::map<std::string, int> needed;                // Segment -> the set's markers on it.
  int missing = 0;
  for (int m = 0; m < markers.num_markers(); ++m) {
    std::string segment;
    for (const MarkerAttachment& a : markers.marker(m).attachments) {
      segment += (segment.empty() ? "" : "+") + skeleton.joint(a.joint).name;
    }
    ++needed[segment];
    if (file.FindMarker(markers.label(m)) >= 0) continue;
    ++missing;
    if (missing_on.count(segment) == 0) segments.push_back(segment);
    std::string& labels = missing_on[segment];
    labels += (labels.empty() ? "" : ", ") + markers.label(m);
  }
  if (missing == 0) return Status::Ok();
  std::string text;
  for (const std::string& segment : segments) {
    text += (text.empty() ? "" : "; ") + segment + ": " + missing_on[segment] + " (of its " +
            std::to_string(needed[segment]) + ")";
  }
  return Status::Error(markers_path + ": the subject's marker set does not match the take: no column for " +
                       std::to_string(missing) + " of its " + std::to_string(markers.num_markers()) +
                       " markers, by segment: " + text);
}

}  // namespace

Status SubjectFileTransform(const Subject& subject, const MarkerTrajectories& file, const std::string& name,
                            MarkerFileToModel* transform) {
  Status status = ParseAxes(subject.axes, &transform->rotation);
  if (!status.ok()) return Status::Error("axes: " + status.message());
  if (Status bound = CheckUnitScale(subject.marker_scale, "marker scale"); subject.marker_scale > 0.0 && !bound.ok()) {
    return bound;
  }
  if (subject.marker_scale > 0.0) {
    transform->scale = subject.marker_scale;
  } else if (subject.marker_scale < 0.0 || !std::isfinite(subject.marker_scale)) {
    return Status::Error("marker scale must be positive (or 0: from the units)");
  } else {
    status = UnitScale(file.unit, subject.skeleton.unit(), &transform->scale);
    if (!status.ok()) return Status::Error(name + ": " + status.message());
  }
  return Status::Ok();
}

Status TakeForSubject(const Subject& subject, MarkerTrajectories trajectories, const std::string& markers_path,
                      MarkerTake* take) {
  MarkerTake result;
  result.name = markers_path;
  result.skeleton = subject.skeleton;
  result.markers = subject.markers;
  result.mean_pose = subject.mean_pose;
  result.trajectories = std::move(trajectories);
  Status status = Status::Ok();
  MarkerTrajectories matched = result.trajectories;
  if (!subject.label_prefix.empty()) {
    const std::string& prefix = subject.label_prefix;
    for (int m = 0; m < matched.num_markers(); ++m) {
      if (matched.label(m).compare(0, prefix.size(), prefix) == 0) {
        matched.set_label(m, matched.label(m).substr(prefix.size()));
      }
    }
  }
  status = SubjectFileTransform(subject, result.trajectories, markers_path, &result.transform);
  if (!status.ok()) return status;
  status = CheckTakeHasSubjectMarkers(result.skeleton, result.markers, matched, markers_path);
  if (!status.ok()) return status;
  status = GatherObservations(result.markers, matched, result.transform, &result.observed);
  if (!status.ok()) return Status::Error(markers_path + ": " + status.message());
  const Eigen::Vector3d nan = Eigen::Vector3d::Constant(std::nan(""));
  std::set<int> in_set;  // Columns the marker set reads (a set may name a marker "*52").
  for (int m = 0; m < result.markers.num_markers(); ++m) in_set.insert(matched.FindMarker(result.markers.label(m)));
  for (int c = 0; c < matched.num_markers(); ++c) {
    if (in_set.count(c) != 0) continue;
    if (!IsUnlabelledLabel(SplitSubjectPrefix(matched.label(c), matched.subject_prefixes).name)) continue;
    result.unlabelled.names.push_back(result.trajectories.label(c));
    result.unlabelled_columns.push_back(c);
  }
  const int tracks = result.unlabelled.num_tracks();
  result.unlabelled.points.assign(tracks > 0 ? matched.num_frames() : 0, std::vector<Eigen::Vector3d>(tracks, nan));
  for (int f = 0; f < static_cast<int>(result.unlabelled.points.size()); ++f) {
    for (int k = 0; k < tracks; ++k) {
      const int c = result.unlabelled_columns[k];
      if (matched.valid(f, c)) result.unlabelled.points[f][k] = result.transform.Apply(matched.position(f, c));
    }
  }
  *take = std::move(result);
  return Status::Ok();
}

namespace {

// The file's sample of the marker whose observation at frame f is `sample` (a relabelled
// one, exactly), else `sample` mapped back to the file's axes and units.
Eigen::Vector3d RelabelledFileSample(const MarkerTake& take, int f, const Eigen::Vector3d& sample) {
  for (int n = 0; n < take.markers.num_markers(); ++n) {
    if (!(take.observed[f][n] == sample)) continue;
    const int column = take.trajectories.FindMarker(take.markers.label(n));
    if (column >= 0 && take.trajectories.valid(f, column)) return take.trajectories.position(f, column);
  }
  return take.transform.Invert(sample);
}

}  // namespace

MarkerTrajectories WithRepairedSamples(const MarkerTake& take,
                                       const std::vector<std::vector<Eigen::Vector3d>>& repaired,
                                       int* rewritten, const std::vector<UnlabelledAssignment>& assigned,
                                       int* unlabelled_removed) {
  MarkerTrajectories out = take.trajectories;
  int count = 0;
  for (int m = 0; m < take.markers.num_markers(); ++m) {
    const int column = take.trajectories.FindMarker(take.markers.label(m));
    if (column < 0) continue;  // LoadTakeForSubject found every marker; defensive.
    for (int f = 0; f < out.num_frames() && f < static_cast<int>(repaired.size()); ++f) {
      const bool same = take.observed[f][m].allFinite() && repaired[f][m] == take.observed[f][m];
      if (same) continue;
      out.SetSample(f, column, RelabelledFileSample(take, f, repaired[f][m]));
      ++count;
    }
  }
  if (rewritten != nullptr) *rewritten = count;
  int removed = 0;
  for (const UnlabelledAssignment& a : assigned) {
    if (a.track < 0 || a.track >= static_cast<int>(take.unlabelled_columns.size())) continue;  // Defensive.
    const int column = take.unlabelled_columns[a.track];
    for (int f = std::max(a.first, 0); f <= a.last && f < out.num_frames(); ++f) {
      if (out.valid(f, column)) out.SetMissing(f, column), ++removed;
    }
  }
  if (unlabelled_removed != nullptr) *unlabelled_removed = removed;
  return out;
}

Status LoadSubjectFromFiles(const SubjectFiles& files, Subject* subject) {
  Subject result;
  Status status = ReadSkeletonFile(files.skeleton_path, &result.skeleton);
  if (status.ok()) status = SetSkeletonUnits(files.skeleton_units, &result.skeleton);
  if (!status.ok()) return status;
  if (!result.skeleton.unit().known()) {
    return Status::Error(files.skeleton_path + ": the skeleton's unit is unknown; give --skeleton_units");
  }
  result.skeleton_path = files.skeleton_path;
  status = ReadMarkerSet(files.markerset_path, result.skeleton, &result.markers);
  if (!status.ok()) return status;
  result.axes = files.axes;
  result.marker_scale = files.marker_scale;
  result.amc_fps = files.amc_fps;
  *subject = std::move(result);
  return Status::Ok();
}

}  // namespace mocapsolve
