#include "io/marker_file.h"

#include <algorithm>
#include <cstdio>

#include "io/c3d_points.h"
#include "io/c3d_reader.h"
#include "io/c3d_writer.h"
#include "io/comma_list.h"
#include "io/input_limits.h"
#include "io/motion_file.h"
#include "io/trc_reader.h"
#include "io/trc_writer.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {

bool IsMarkerFile(const std::string& path) {
  const std::string ext = FileExtension(path);
  return ext == ".c3d" || ext == ".trc";
}

namespace {

MarkerReadOptions& DefaultOptions() {
  static MarkerReadOptions options;
  return options;
}

}  // namespace

void SetDefaultMarkerReadOptions(const MarkerReadOptions& options) { DefaultOptions() = options; }

const MarkerReadOptions& DefaultMarkerReadOptions() { return DefaultOptions(); }

namespace {

// The column of `label`: the label itself, else the one label whose name after a subject
// prefix ("Nick01:RTOE") is it; -1 when none, -2 when several.
int IgnoredColumn(const std::vector<std::string>& all, const std::string& label) {
  const auto it = std::find(all.begin(), all.end(), label);
  if (it != all.end()) return static_cast<int>(it - all.begin());
  int found = -1;
  for (size_t m = 0; m < all.size(); ++m) {
    const size_t colon = all[m].rfind(':');
    if (colon == std::string::npos || all[m].compare(colon + 1, std::string::npos, label) != 0) continue;
    found = found == -1 ? static_cast<int>(m) : -2;
  }
  return found;
}

Status IgnoreMarkers(const std::string& labels, MarkerTrajectories* trajectories) {
  for (const std::string& label : SplitCommaList(labels)) {
    const int m = IgnoredColumn(trajectories->labels(), label);
    if (m == -1) return Status::Error("--ignore_markers: the file has no marker " + QuoteToken(label));
    if (m == -2) {
      return Status::Error("--ignore_markers: " + QuoteToken(label) +
                           " names markers of several subjects; give the whole label ('Name:" + label + "')");
    }
    for (int f = 0; f < trajectories->num_frames(); ++f) trajectories->SetMissing(f, m);
  }
  return Status::Ok();
}

void Warn(const MarkerReadOptions& options, const std::string& warning) {
  if (options.warnings != nullptr) {
    options.warnings->push_back(warning);
  } else {
    std::fprintf(stderr, "warning: %s\n", warning.c_str());
  }
}

// A TRC has no SUBJECTS group: its subjects are its labels' "Name:" prefixes, and one is
// read as a C3D's is (io/c3d_points.h: --subject_prefix, the subject file's own prefix, else
// the one with the most points). Every column is a marker (no model-output rules).
Status SelectTrcSubject(const MarkerReadOptions& options, MarkerTrajectories* trajectories) {
  C3dPointLists lists;
  lists.labels = trajectories->labels();
  lists.labels_field = "marker labels";
  C3dPointSelection selection;
  const Status status = SelectC3dPoints(lists, options.subject_prefix, /*include_model_outputs=*/true, &selection,
                                        options.preferred_subject_prefix);
  if (!status.ok()) return status;
  for (const std::string& warning : selection.warnings) Warn(options, warning);
  std::vector<int> kept;
  for (int m = 0; m < trajectories->num_markers(); ++m) {
    if (selection.roles[m] == C3dPointSelection::Role::kMarker) kept.push_back(m);
  }
  if (kept.size() == static_cast<size_t>(trajectories->num_markers()) && selection.labels == lists.labels) {
    return Status::Ok();
  }
  MarkerTrajectories chosen = TrajectoryColumns(*trajectories, kept);
  for (size_t i = 0; i < kept.size(); ++i) chosen.set_label(static_cast<int>(i), selection.labels[kept[i]]);
  chosen.subject_prefixes = selection.subject_prefixes;
  *trajectories = std::move(chosen);
  return Status::Ok();
}

}  // namespace

Status ReadMarkerFile(const std::string& path, MarkerTrajectories* trajectories) {
  return ReadMarkerFile(path, trajectories, DefaultMarkerReadOptions());
}

Status ReadMarkerFile(const std::string& path, MarkerTrajectories* trajectories,
                      const MarkerReadOptions& options) {
  const std::string ext = FileExtension(path);
  Status status = Status::Ok();
  if (ext == ".c3d") {
    C3dReadOptions c3d;
    c3d.include_model_outputs = options.include_model_outputs;
    c3d.subject_prefix = options.subject_prefix;
    c3d.preferred_subject_prefix = options.preferred_subject_prefix;
    C3dFileInfo info;
    status = ReadC3d(path, trajectories, &info, c3d);
    for (const std::string& warning : info.warnings) Warn(options, warning);
  } else if (ext == ".trc") {
    status = ReadTrc(path, trajectories);
    if (status.ok()) {
      status = SelectTrcSubject(options, trajectories);
      if (!status.ok()) status = Status::Error(path + ": " + status.message());
    }
  } else {
    status = Status::Error(path + ": unknown marker format " + QuoteToken(ext) + " (expected .c3d or .trc)");
  }
  if (!status.ok()) return status;
  status = IgnoreMarkers(options.ignore_markers, trajectories);
  if (!status.ok()) return Status::Error(path + ": " + status.message());
  // What every writer can represent (io/input_limits.h): a rate of 1e308 or 1e-310 is
  // refused here, not written as NaN or 0.
  status = CheckMarkerBounds(*trajectories);
  return status.ok() ? status : Status::Error(path + ": " + status.message());
}

Status ReadMarkerFileShape(const std::string& path, MarkerFileShape* shape) {
  *shape = MarkerFileShape();
  MarkerTrajectories trajectories;
  if (FileExtension(path) != ".c3d") {
    const Status status = ReadMarkerFile(path, &trajectories);
    if (!status.ok()) return status;
    *shape = {trajectories.num_frames(), trajectories.num_markers(), trajectories.frame_rate};
    return Status::Ok();
  }
  const MarkerReadOptions& options = DefaultMarkerReadOptions();
  C3dReadOptions c3d;
  c3d.include_model_outputs = options.include_model_outputs;
  c3d.subject_prefix = options.subject_prefix;
  c3d.header_only = true;
  C3dFileInfo info;
  const Status status = ReadC3d(path, &trajectories, &info, c3d);
  if (!status.ok()) return status;
  *shape = {info.frames, trajectories.num_markers(), trajectories.frame_rate};
  return Status::Ok();
}

Status WriteMarkerFile(const std::string& path, const MarkerTrajectories& trajectories) {
  const std::string ext = FileExtension(path);
  // Nothing a reader would refuse (the C3D writer alone refused only float overflow).
  if (ext == ".c3d" || ext == ".trc") {
    if (Status status = CheckMarkerBounds(trajectories); !status.ok()) return Status::Error(path + ": " + status.message());
  }
  if (ext == ".c3d") return WriteC3d(path, trajectories);
  if (ext == ".trc") return WriteTrc(path, trajectories);
  return Status::Error(path + ": unknown marker format " + QuoteToken(ext) + " (expected .c3d or .trc)");
}

Status RequireMarkerData(const std::string& path, const MarkerTrajectories& trajectories) {
  if (trajectories.num_frames() == 0) {
    return Status::Error(path + ": the take has no frames (this command needs at least one)");
  }
  if (trajectories.num_markers() == 0) {
    return Status::Error(path + ": the take has no markers (this command needs at least one)");
  }
  if (trajectories.CountMissing() == static_cast<long long>(trajectories.num_frames()) * trajectories.num_markers()) {
    return Status::Error(path + ": every sample of the take is missing (this command needs at least one)");
  }
  return Status::Ok();
}

}  // namespace mocapsolve
