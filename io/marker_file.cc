#include "io/marker_file.h"

#include <cstdio>

#include "io/c3d_reader.h"
#include "io/c3d_writer.h"
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

Status ReadMarkerFile(const std::string& path, MarkerTrajectories* trajectories) {
  return ReadMarkerFile(path, trajectories, DefaultMarkerReadOptions());
}

Status ReadMarkerFile(const std::string& path, MarkerTrajectories* trajectories,
                      const MarkerReadOptions& options) {
  const std::string ext = FileExtension(path);
  if (ext == ".c3d") {
    C3dReadOptions c3d;
    c3d.include_model_outputs = options.include_model_outputs;
    c3d.subject_prefix = options.subject_prefix;
    C3dFileInfo info;
    Status status = ReadC3d(path, trajectories, &info, c3d);
    for (const std::string& warning : info.warnings) {
      if (options.warnings != nullptr) {
        options.warnings->push_back(warning);
      } else {
        std::fprintf(stderr, "warning: %s\n", warning.c_str());
      }
    }
    return status;
  }
  if (ext == ".trc") return ReadTrc(path, trajectories);
  return Status::Error(path + ": unknown marker format " + QuoteToken(ext) + " (expected .c3d or .trc)");
}

Status WriteMarkerFile(const std::string& path, const MarkerTrajectories& trajectories) {
  const std::string ext = FileExtension(path);
  // Nothing a reader would refuse (the C3D writer alone refused only float overflow).
  if (ext == ".c3d" || ext == ".trc") {
    if (Status status = trajectories.CheckReadable(); !status.ok()) return Status::Error(path + ": " + status.message());
  }
  if (ext == ".c3d") return WriteC3d(path, trajectories);
  if (ext == ".trc") return WriteTrc(path, trajectories);
  return Status::Error(path + ": unknown marker format " + QuoteToken(ext) + " (expected .c3d or .trc)");
}

}  // namespace mocapsolve
