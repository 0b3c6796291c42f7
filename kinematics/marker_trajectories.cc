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
  positions_.setConstant(3, samples, std::numeric_limits<double>::quiet_NaN());
  valid_mask_.assign(samples, 0);
  residuals_.assign(samples, -1.0f);
  camera_masks_.assign(samples, 0);
}

void MarkerTrajectories::SetSample(int frame, int marker, const Eigen::Vector3d& position,
                                   float residual, std::uint8_t camera_mask) {
  if (!position.allFinite()) {
    SetMissing(frame, marker);
    return;
  }
  const Eigen::Index i = index(frame, marker);
  positions_.col(i) = position;
  valid_mask_[i] = 1;
  residuals_[i] = residual >= 0.0f ? residual : 0.0f;  // Also maps NaN to 0.
  camera_masks_[i] = camera_mask;
}

void MarkerTrajectories::SetMissing(int frame, int marker) {
  const Eigen::Index i = index(frame, marker);
  positions_.col(i).setConstant(std::numeric_limits<double>::quiet_NaN());
  valid_mask_[i] = 0;
  residuals_[i] = -1.0f;
  camera_masks_[i] = 0;
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
  positions_ *= factor;
  for (size_t i = 0; i < residuals_.size(); ++i) {
    if (valid_mask_[i]) residuals_[i] = static_cast<float>(residuals_[i] * factor);
  }
}

MarkerTrajectories TrajectoryFrames(const MarkerTrajectories& trajectories, int first, int count) {
  first = std::max(0, std::min(first, trajectories.num_frames()));
  count = std::max(0, std::min(count, trajectories.num_frames() - first));
  MarkerTrajectories out(trajectories.labels(), count);
  out.frame_rate = trajectories.frame_rate;
  out.unit = trajectories.unit;
  out.first_frame = trajectories.first_frame + first;
  out.subject_prefixes = trajectories.subject_prefixes;
  for (int f = 0; f < count; ++f) {
    for (int m = 0; m < trajectories.num_markers(); ++m) {
      if (!trajectories.valid(first + f, m)) continue;
      out.SetSample(f, m, trajectories.position(first + f, m), trajectories.residual(first + f, m),
                    trajectories.camera_mask(first + f, m));
    }
  }
  return out;
}

MarkerTrajectories TrajectoryColumns(const MarkerTrajectories& trajectories, const std::vector<int>& columns) {
  std::vector<std::string> labels;
  for (const int m : columns) labels.push_back(trajectories.label(m));
  MarkerTrajectories out(std::move(labels), trajectories.num_frames());
  out.frame_rate = trajectories.frame_rate;
  out.unit = trajectories.unit;
  out.first_frame = trajectories.first_frame;
  out.subject_prefixes = trajectories.subject_prefixes;
  for (int f = 0; f < trajectories.num_frames(); ++f) {
    for (size_t i = 0; i < columns.size(); ++i) {
      if (!trajectories.valid(f, columns[i])) continue;
      out.SetSample(f, static_cast<int>(i), trajectories.position(f, columns[i]),
                    trajectories.residual(f, columns[i]), trajectories.camera_mask(f, columns[i]));
    }
  }
  return out;
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
