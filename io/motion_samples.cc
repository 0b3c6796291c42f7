#include "io/motion_samples.h"

#include <string>

#include "io/input_limits.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {

Status MotionSamples::Validate(const Skeleton& skeleton) const {
  // What the readers accept (io/input_limits.h): a frame time of 1e308 wrote a time
  // accessor whose "max" was inf, JSON null.
  if (Status s = CheckMotionBounds(skeleton, motion_); !s.ok()) return s;
  return ValidateMotion(skeleton, motion_);
}

Status CompactSamples::Validate(const Skeleton& skeleton) const {
  Motion none;
  none.frame_rate = motion_.frame_rate();
  if (Status s = CheckMotionBounds(skeleton, none); !s.ok()) return s;
  if (motion_.num_joints() != skeleton.num_joints()) {
    return Status::Error("pose has the wrong joint count (" + std::to_string(motion_.num_joints()) + ", skeleton " +
                         std::to_string(skeleton.num_joints()) + ")");
  }
  Pose pose;
  for (int f = 0; f < motion_.num_frames(); ++f) {
    motion_.Frame(f, &pose);
    const std::string frame = "frame " + std::to_string(f);
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      if (Status s = CheckCoordinates(pose.translations[j], frame + ", joint " + QuoteToken(skeleton.name(j)) +
                                                                " translation");
          !s.ok()) {
        return s;
      }
    }
    if (Status s = ValidatePose(skeleton, pose, frame); !s.ok()) return s;
  }
  return Status::Ok();
}

}  // namespace mocapsolve
