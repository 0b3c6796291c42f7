// MarkerTrajectories: labelled 3D marker positions over time, as read from C3D or TRC.
//
// Layout: #F frames of #M markers. Positions are one 3 x (#F * #M) matrix, frame-major:
// the sample of marker m in frame f is column f * #M + m, so frame f's samples are a
// contiguous 3 x #M block. Values are in `unit` (the file's unit; nothing is rescaled on
// read) and in the file's axes (C3D data is often Z-up, TRC/OpenSim Y-up).
//
// Missing samples: a sample is either valid (finite position) or missing. Missing
// samples read as NaN (position()) *and* are flagged in the mask (valid(f, m) false); the
// two always agree, so code may test either (the whole array, positions(), holds NaN there
// too, except in a copy that shares its samples: see below). Nothing here treats (0,0,0) as a position:
// readers translate their files' gap conventions (negative C3D residual, empty TRC
// cells, ...) into this mask.
//
// Residuals: per sample, the C3D residual in `unit` (0 = valid with no residual
// information, e.g. TRC input or an interpolated C3D sample), -1 for missing samples.
// Camera masks: the C3D camera-contribution bits (bit i = camera i+1 saw the marker);
// 0 when unknown. Neither array is allocated until a sample sets a residual or a camera
// mask other than 0 (trajectories made from observations, X^ or a TRC file hold none: 5 of
// a sample's 30 bytes).
//
// Shared samples: SharingSamples() makes a copy that shares the positions array with its
// source (each keeps its own mask) until either of them writes a position; marking a
// sample missing then changes the mask only. A repair keeps several masks over one take's
// samples (captured, flagged, before the small gaps' fill): one positions array (24 of a
// sample's bytes) instead of one each. An ordinary copy copies the positions.
//
// Labels are kept exactly as the file spells them ("TakeoMonday:LBWT"); subject prefixes
// (C3D SUBJECTS:LABEL_PREFIXES, "TakeoMonday:") are recorded in `subject_prefixes` so
// FindMarker("LBWT") still finds the marker. Frame numbers: frame index f (0-based)
// corresponds to the file's frame number first_frame + f (C3D field number; TRC Frame#).
//
// Model outputs: points a C3D file stores beside the markers (Vicon Nexus joint angles,
// forces, moments, powers, centre of mass, Plug-in Gait virtual segment points) are not
// markers. The C3D reader leaves them out of the markers and carries them in
// `model_outputs` (read-only, shared between copies) so that a rewrite of the file keeps
// them unchanged; nothing else looks at them.
#ifndef MOCAPSOLVE_KINEMATICS_MARKER_TRAJECTORIES_H_
#define MOCAPSOLVE_KINEMATICS_MARKER_TRAJECTORIES_H_

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "kinematics/status.h"
#include "kinematics/units.h"

namespace mocapsolve {

struct ModelOutputPoints;

class MarkerTrajectories {
 public:
  // Metadata (free to edit; see set_label for labels).
  double frame_rate = 0.0;  // Frames per second.
  LengthUnit unit;          // Of positions and residuals.
  int first_frame = 1;      // File frame number of frame index 0.
  std::vector<std::string> subject_prefixes;  // "TakeoMonday:", ...; may be empty.
  // The file's non-marker points (see the header comment); null when there are none.
  std::shared_ptr<const ModelOutputPoints> model_outputs;

  // Largest |coordinate| a reader accepts, in file units: 1e9 mm is 1000 km. Beyond it
  // squares and sums overflow or lose all precision (a TRC value of 1e308 became
  // "rms change nan"), so readers reject such a sample with an error.
  static constexpr double kMaxCoordinate = 1e9;
  // Labels a reader may build trajectories from: no label repeated (a repeated label
  // would make FindMarker ambiguous). The error names the first repeat, quoted.
  static Status CheckLabels(const std::vector<std::string>& labels);

  MarkerTrajectories() = default;
  // #F frames of the labelled markers, every sample missing.
  MarkerTrajectories(std::vector<std::string> labels, int num_frames);
  // Copies copy the positions (see SharingSamples); moves move them.
  MarkerTrajectories(const MarkerTrajectories& other);
  MarkerTrajectories& operator=(const MarkerTrajectories& other);
  MarkerTrajectories(MarkerTrajectories&&) = default;
  MarkerTrajectories& operator=(MarkerTrajectories&&) = default;
  // A copy whose positions array is this one's until either writes a position (see the
  // header comment): the same samples, masks, residuals and metadata.
  MarkerTrajectories SharingSamples() const;

  int num_frames() const { return num_frames_; }
  int num_markers() const { return static_cast<int>(labels_.size()); }
  Eigen::Index index(int frame, int marker) const {
    return static_cast<Eigen::Index>(frame) * num_markers() + marker;
  }

  const std::vector<std::string>& labels() const { return labels_; }
  const std::string& label(int marker) const { return labels_[marker]; }
  void set_label(int marker, std::string label) { labels_[marker] = std::move(label); }

  // Per-sample access; frame in [0, #F), marker in [0, #M).
  bool valid(int frame, int marker) const { return valid_mask_[index(frame, marker)] != 0; }
  // NaN where missing.
  Eigen::Vector3d position(int frame, int marker) const {
    const Eigen::Index i = index(frame, marker);
    return valid_mask_[i] != 0 ? Eigen::Vector3d(positions_->col(i))
                               : Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  float residual(int frame, int marker) const {
    const Eigen::Index i = index(frame, marker);
    return !residuals_.empty() ? residuals_[i] : valid_mask_[i] != 0 ? 0.0f : -1.0f;
  }
  std::uint8_t camera_mask(int frame, int marker) const {
    return camera_masks_.empty() ? 0 : camera_masks_[index(frame, marker)];
  }

  // A non-finite position stores the sample as missing (keeps the mask and NaNs in step).
  // A negative residual of a valid sample is stored as 0 (unknown).
  void SetSample(int frame, int marker, const Eigen::Vector3d& position, float residual = 0.0f,
                 std::uint8_t camera_mask = 0);
  void SetMissing(int frame, int marker);

  // Whole-array views. positions(): 3 x (#F * #M), NaN where missing, except in
  // trajectories that share their samples (SharingSamples), where a missing sample's column
  // may hold the other's sample: test valid() (or read position()).
  const Eigen::Matrix3Xd& positions() const;
  // The positions array to write into (Python's view of it), no longer shared, NaN where missing.
  double* mutable_positions_data() { return OwnPositions().data(); }
  const std::vector<std::uint8_t>& valid_mask() const { return valid_mask_; }  // #F * #M, 1 = valid.

  int CountMissing() const;
  int CountMissing(int marker) const;  // Over all frames.

  // Index of the marker with this label, or -1. An exact match of the raw label wins;
  // otherwise the label is compared with every marker's name without its subject prefix
  // (SplitSubjectPrefix), and a unique match is returned (-1 when several subjects have
  // a marker of that name: ask with the prefixed label then).
  int FindMarker(const std::string& label) const;

  // Multiplies every valid position and residual by factor (> 0); unit is left alone.
  void ScaleLengths(double factor);

 private:
  // The positions to write into: copied first when shared (NaN where this one's mask is missing).
  Eigen::Matrix3Xd& OwnPositions();

  int num_frames_ = 0;
  std::vector<std::string> labels_;
  // Shared with copies made by SharingSamples; null when there are no samples (or moved from).
  std::shared_ptr<Eigen::Matrix3Xd> positions_;
  std::vector<std::uint8_t> valid_mask_;
  std::vector<float> residuals_;             // #F * #M, or empty: 0 where valid, -1 where missing.
  std::vector<std::uint8_t> camera_masks_;   // #F * #M, or empty: 0 everywhere.
};

// Points of a C3D file that are not markers, kept for rewriting the file.
struct ModelOutputPoints {
  // Per point, the POINT parameter that lists it ("ANGLES", "FORCES", "MOMENTS", "POWERS",
  // "REACTIONS", "SCALARS"), or "" for a point recognised by its name only.
  std::vector<std::string> kinds;
  MarkerTrajectories points;  // Same frames as the markers; raw values (degrees, N, ...).
};

// Frames [first, first + count) of `trajectories` (clamped to its frames), every sample as it
// was (residuals, camera masks); first_frame follows, model outputs are dropped.
MarkerTrajectories TrajectoryFrames(const MarkerTrajectories& trajectories, int first, int count);

// Frames 0, step, 2 step, ... of `trajectories` (step >= 1), every sample as it was; the
// frame rate divided by step (so times stay right), first_frame follows (frame index i is
// file frame first_frame + i * step), model outputs are dropped.
MarkerTrajectories EveryNthFrame(const MarkerTrajectories& trajectories, int step);

// The markers `columns` of `trajectories` (indices, in that order), every sample as it was;
// the metadata follows, model outputs are dropped.
MarkerTrajectories TrajectoryColumns(const MarkerTrajectories& trajectories, const std::vector<int>& columns);

// The trajectories with markers `labels` added after their own, every sample of those
// missing; the metadata follows, model outputs are dropped.
MarkerTrajectories WithMoreMarkers(const MarkerTrajectories& trajectories, const std::vector<std::string>& labels);

// Rescales positions and residuals into `to` and sets unit. Fails (and changes nothing)
// when either unit is unknown.
Status ConvertUnits(const LengthUnit& to, MarkerTrajectories* trajectories);

// A label split into its subject prefix and marker name:
// "TakeoMonday:LBWT" -> {"TakeoMonday:", "LBWT"}.
struct SubjectLabel {
  std::string prefix;  // Including the separator, "" when there is none.
  std::string name;
};
// Strips the longest non-empty known prefix the label starts with; when none of them
// matches (or none are known), splits after the last ':' if there is one (Vicon's
// "Subject:Marker" convention); otherwise the whole label is the name.
SubjectLabel SplitSubjectPrefix(const std::string& label,
                                const std::vector<std::string>& known_prefixes = {});

// The unit a C3D POINT:UNITS / TRC Units string names ("mm", "cm", "m", "in", and the
// spelled-out forms, any case); a LengthUnit that is not known() otherwise.
LengthUnit LengthUnitFromName(const std::string& name);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_MARKER_TRAJECTORIES_H_
