#include "kinematics/marker_trajectories.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <string_view>
#include <unordered_map>

#include "kinematics/quote_token.h"

namespace mocapsolve {

Status MarkerTrajectories::CheckLabels(const std::vector<std::string>& labels) {
  std::unordered_map<std::string_view, int> first;
  for (int m = 0; m < static_cast<int>(labels.size()); ++m) {
    const auto [it, inserted] = first.emplace(labels[m], m);
    if (!inserted) {
      return Status::Error("marker label " + QuoteToken(labels[m]) + " is used twice (markers " +
                           std::to_string(it->second + 1) + " and " + std::to_string(m + 1) + ")");
    }
  }
  return Status::Ok();
}

MarkerTrajectories::MarkerTrajectories(std::vector<std::string> labels, int num_frames)
    : num_frames_(std::max(num_frames, 0)), labels_(std::move(labels)) {
  const Eigen::Index samples = static_cast<Eigen::Index>(num_frames_) * num_markers();
  positions_ = std::make_shared<Eigen::Matrix3Xd>(3, samples);
  positions_->setConstant(std::numeric_limits<double>::quiet_NaN());
  valid_mask_.assign(samples, 0);
}

MarkerTrajectories::MarkerTrajectories(const MarkerTrajectories& other)
    : frame_rate(other.frame_rate),
      unit(other.unit),
      first_frame(other.first_frame),
      subject_prefixes(other.subject_prefixes),
      model_outputs(other.model_outputs),
      num_frames_(other.num_frames_),
      labels_(other.labels_),
      positions_(other.positions_ != nullptr ? std::make_shared<Eigen::Matrix3Xd>(*other.positions_) : nullptr),
      valid_mask_(other.valid_mask_),
      residuals_(other.residuals_),
      camera_masks_(other.camera_masks_) {}

MarkerTrajectories& MarkerTrajectories::operator=(const MarkerTrajectories& other) {
  if (this != &other) *this = MarkerTrajectories(other);
  return *this;
}

MarkerTrajectories MarkerTrajectories::SharingSamples() const {
  MarkerTrajectories out;
  out.frame_rate = frame_rate;
  out.unit = unit;
  out.first_frame = first_frame;
  out.subject_prefixes = subject_prefixes;
  out.model_outputs = model_outputs;
  out.num_frames_ = num_frames_;
  out.labels_ = labels_;
  out.positions_ = positions_;
  out.valid_mask_ = valid_mask_;
  out.residuals_ = residuals_;
  out.camera_masks_ = camera_masks_;
  return out;
}

const Eigen::Matrix3Xd& MarkerTrajectories::positions() const {
  static const Eigen::Matrix3Xd kNone;
  return positions_ != nullptr ? *positions_ : kNone;
}

Eigen::Matrix3Xd& MarkerTrajectories::OwnPositions() {
  if (positions_ == nullptr) {
    positions_ = std::make_shared<Eigen::Matrix3Xd>();
  } else if (positions_.use_count() > 1) {
    // Missing samples' columns may hold the other's: NaN again, as in unshared trajectories.
    auto own = std::make_shared<Eigen::Matrix3Xd>(*positions_);
    for (size_t i = 0; i < valid_mask_.size(); ++i) {
      if (valid_mask_[i] == 0) own->col(static_cast<Eigen::Index>(i)).setConstant(std::numeric_limits<double>::quiet_NaN());
    }
    positions_ = std::move(own);
  }
  return *positions_;
}

void MarkerTrajectories::SetSample(int frame, int marker, const Eigen::Vector3d& position,
                                   float residual, std::uint8_t camera_mask) {
  if (!position.allFinite()) {
    SetMissing(frame, marker);
    return;
  }
  const Eigen::Index i = index(frame, marker);
  OwnPositions().col(i) = position;
  valid_mask_[i] = 1;
  const float stored = residual >= 0.0f ? residual : 0.0f;  // Also maps NaN to 0.
  if (residuals_.empty() && (stored != 0.0f || std::signbit(stored))) {
    residuals_.resize(valid_mask_.size());
    for (size_t k = 0; k < valid_mask_.size(); ++k) residuals_[k] = valid_mask_[k] != 0 ? 0.0f : -1.0f;
  }
  if (!residuals_.empty()) residuals_[i] = stored;
  if (camera_masks_.empty() && camera_mask != 0) camera_masks_.assign(valid_mask_.size(), 0);
  if (!camera_masks_.empty()) camera_masks_[i] = camera_mask;
}

void MarkerTrajectories::SetMissing(int frame, int marker) {
  const Eigen::Index i = index(frame, marker);
  // Shared positions stay as they are: the mask says the sample is missing.
  if (positions_.use_count() == 1) positions_->col(i).setConstant(std::numeric_limits<double>::quiet_NaN());
  valid_mask_[i] = 0;
  if (!residuals_.empty()) residuals_[i] = -1.0f;
  if (!camera_masks_.empty()) camera_masks_[i] = 0;
}

int MarkerTrajectories::CountMissing() const {
  return static_cast<int>(std::count(valid_mask_.begin(), valid_mask_.end(), 0));
}

int MarkerTrajectories::CountMissing(int marker) const {
  int missing = 0;
  for (int f = 0; f < num_frames_; ++f) missing += valid(f, marker) ? 0 : 1;
  return missing;
}

int MarkerTrajectories::FindMarker(const std::string& label) const {
  for (int m = 0; m < num_markers(); ++m) {
    if (labels_[m] == label) return m;
  }
  int found = -1;
  for (int m = 0; m < num_markers(); ++m) {
    if (SplitSubjectPrefix(labels_[m], subject_prefixes).name != label) continue;
    if (found >= 0) return -1;  // Ambiguous: several subjects carry this marker name.
    found = m;
  }
  return found;
}

void MarkerTrajectories::ScaleLengths(double factor) {
  // Missing columns are NaN and stay NaN; residual -1 marks missing and must stay -1.
  OwnPositions() *= factor;
  for (size_t i = 0; i < residuals_.size(); ++i) {
    if (valid_mask_[i]) residuals_[i] = static_cast<float>(residuals_[i] * factor);
  }
}

namespace {

// Frames first, first + step, ... (count of them) of the markers `columns`, then `more`
// markers with every sample missing; metadata as the source's (first_frame following, the
// frame rate divided by step), no model outputs.
MarkerTrajectories Subset(const MarkerTrajectories& trajectories, int first, int count, const std::vector<int>& columns,
                          const std::vector<std::string>& more = {}, int step = 1) {
  std::vector<std::string> labels;
  for (const int m : columns) labels.push_back(trajectories.label(m));
  labels.insert(labels.end(), more.begin(), more.end());
  MarkerTrajectories out(std::move(labels), count);
  out.frame_rate = trajectories.frame_rate / step;
  out.unit = trajectories.unit;
  out.first_frame = trajectories.first_frame + first;
  out.subject_prefixes = trajectories.subject_prefixes;
  for (int f = 0; f < count; ++f) {
    const int source = first + f * step;
    for (size_t i = 0; i < columns.size(); ++i) {
      if (!trajectories.valid(source, columns[i])) continue;
      out.SetSample(f, static_cast<int>(i), trajectories.position(source, columns[i]),
                    trajectories.residual(source, columns[i]), trajectories.camera_mask(source, columns[i]));
    }
  }
  return out;
}

std::vector<int> AllColumns(const MarkerTrajectories& trajectories) {
  std::vector<int> columns(trajectories.num_markers());
  for (int m = 0; m < trajectories.num_markers(); ++m) columns[m] = m;
  return columns;
}

}  // namespace

MarkerTrajectories TrajectoryFrames(const MarkerTrajectories& trajectories, int first, int count) {
  first = std::max(0, std::min(first, trajectories.num_frames()));
  count = std::max(0, std::min(count, trajectories.num_frames() - first));
  return Subset(trajectories, first, count, AllColumns(trajectories));
}

MarkerTrajectories EveryNthFrame(const MarkerTrajectories& trajectories, int step) {
  step = std::max(1, step);
  const int count = (trajectories.num_frames() + step - 1) / step;
  return Subset(trajectories, 0, count, AllColumns(trajectories), {}, step);
}

MarkerTrajectories TrajectoryColumns(const MarkerTrajectories& trajectories, const std::vector<int>& columns) {
  return Subset(trajectories, 0, trajectories.num_frames(), columns);
}

MarkerTrajectories WithMoreMarkers(const MarkerTrajectories& trajectories, const std::vector<std::string>& labels) {
  return Subset(trajectories, 0, trajectories.num_frames(), AllColumns(trajectories), labels);
}

Status ConvertUnits(const LengthUnit& to, MarkerTrajectories* trajectories) {
  if (!trajectories->unit.known()) {
    return Status::Error("cannot convert marker units to " + to.name + ": source unit '" +
                         trajectories->unit.name + "' is unknown");
  }
  if (!to.known()) {
    return Status::Error("cannot convert marker units: target unit '" + to.name +
                         "' is unknown");
  }
  const double factor = trajectories->unit.metres_per_unit / to.metres_per_unit;
  if (factor != 1.0) trajectories->ScaleLengths(factor);
  trajectories->unit = to;
  return Status::Ok();
}

SubjectLabel SplitSubjectPrefix(const std::string& label,
                                const std::vector<std::string>& known_prefixes) {
  size_t best = 0;
  for (const std::string& prefix : known_prefixes) {
    if (!prefix.empty() && prefix.size() > best && label.size() > prefix.size() &&
        label.compare(0, prefix.size(), prefix) == 0) {
      best = prefix.size();
    }
  }
  if (best == 0) {
    const size_t colon = label.rfind(':');
    if (colon != std::string::npos && colon + 1 < label.size()) best = colon + 1;
  }
  return {label.substr(0, best), label.substr(best)};
}

LengthUnit LengthUnitFromName(const std::string& name) {
  std::string lower;
  for (char c : name) {
    if (!std::isspace(static_cast<unsigned char>(c))) {
      lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
  }
  if (lower == "mm" || lower == "millimeter" || lower == "millimeters" ||
      lower == "millimetre" || lower == "millimetres") {
    return Millimetres();
  }
  if (lower == "cm" || lower == "centimeter" || lower == "centimeters" ||
      lower == "centimetre" || lower == "centimetres") {
    return Centimetres();
  }
  if (lower == "m" || lower == "meter" || lower == "meters" || lower == "metre" ||
      lower == "metres") {
    return Metres();
  }
  if (lower == "in" || lower == "inch" || lower == "inches") return {"in", 0.0254};
  return {name.empty() ? std::string("unknown") : name, 0.0};
}

}  // namespace mocapsolve
