#include "io/input_limits.h"

#include <cmath>

#include "kinematics/quote_token.h"

namespace mocapsolve {

int JsonNestingDepth(std::string_view text, int limit) {
  int depth = 0, deepest = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;  // The escaped character, whatever it is.
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > deepest) deepest = depth;
      if (deepest > limit) return limit + 1;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

int FbxBraceDepth(std::string_view text, int limit) {
  int depth = 0, deepest = 0;
  bool in_string = false, in_comment = false;
  for (const char c : text) {
    if (in_comment) {
      if (c == '\n') in_comment = false;
    } else if (in_string) {
      if (c == '"' || c == '\n') in_string = false;  // FBX strings do not span lines.
    } else if (c == '"') {
      in_string = true;
    } else if (c == ';') {
      in_comment = true;
    } else if (c == '{') {
      if (++depth > deepest) deepest = depth;
      if (deepest > limit) return limit + 1;
    } else if (c == '}' && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

Status CheckFrameRate(double rate, const std::string& field) {
  if (rate >= kMinFrameRate && rate <= kMaxFrameRate) return Status::Ok();
  return Status::Error(field + " " + ShortNumber(rate) + " is outside " + ShortNumber(kMinFrameRate) + ".." +
                       ShortNumber(kMaxFrameRate) + " Hz");
}

Status CheckCoordinates(const Eigen::Vector3d& value, const std::string& field) {
  for (int k = 0; k < 3; ++k) {
    if (!(std::abs(value[k]) <= kMaxCoordinate)) {
      return Status::Error(field + ": " + ShortNumber(value[k]) + " is beyond +-" + ShortNumber(kMaxCoordinate));
    }
  }
  return Status::Ok();
}

Status CheckUnitScale(double scale, const std::string& field) {
  if (scale == 0.0 || (scale >= 1.0 / kMaxUnitScale && scale <= kMaxUnitScale)) return Status::Ok();
  return Status::Error(field + ": " + ShortNumber(scale) + " is outside " + ShortNumber(1.0 / kMaxUnitScale) + ".." +
                       ShortNumber(kMaxUnitScale) + " (0: from the units)");
}

Status CheckMotionBounds(const Skeleton& skeleton, const Motion& motion, double scale) {
  if (Status s = CheckFrameRate(motion.frame_rate, "frame rate"); !s.ok()) return s;
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    const std::string field = "joint " + QuoteToken(skeleton.name(j)) + " offset";
    if (Status s = CheckCoordinates(skeleton.offset(j) * scale, field); !s.ok()) return s;
  }
  for (const EndSite& site : skeleton.end_sites()) {
    const std::string field = "end site " + QuoteToken(site.name) + " offset";
    if (Status s = CheckCoordinates(site.offset * scale, field); !s.ok()) return s;
  }
  for (int f = 0; f < motion.num_frames(); ++f) {
    const Pose& pose = motion.frames[f];
    for (size_t j = 0; j < pose.translations.size(); ++j) {
      if (((pose.translations[j] * scale).array().abs() <= kMaxCoordinate).all()) continue;  // NaN fails.
      const std::string name = static_cast<int>(j) < skeleton.num_joints() ? skeleton.name(static_cast<int>(j)) : "?";
      const std::string field = "frame " + std::to_string(f) + ", joint " + QuoteToken(name) + " translation";
      return CheckCoordinates(pose.translations[j] * scale, field);
    }
  }
  return Status::Ok();
}

Status CheckMarkerBounds(const MarkerTrajectories& trajectories) {
  if (Status s = CheckFrameRate(trajectories.frame_rate, "frame rate"); !s.ok()) return s;
  for (int f = 0; f < trajectories.num_frames(); ++f) {
    for (int m = 0; m < trajectories.num_markers(); ++m) {
      if (!trajectories.valid(f, m) || (trajectories.position(f, m).array().abs() <= kMaxCoordinate).all()) continue;
      const std::string field = "frame " + std::to_string(f) + ", marker " + QuoteToken(trajectories.label(m));
      return CheckCoordinates(trajectories.position(f, m), field);
    }
  }
  return Status::Ok();
}

}  // namespace mocapsolve
