#include "pipeline/repair_report.h"

namespace mocapsolve {

std::vector<JsonObject> CarriedJointsJson(const Skeleton& skeleton, const std::vector<CarriedJointRun>& runs) {
  std::vector<JsonObject> json;
  for (const CarriedJointRun& run : runs) {
    JsonObject o;
    o.Add("joint", skeleton.name(run.joint)).Add("first_frame", run.first).Add("last_frame", run.last)
        .Add("frames", run.last - run.first + 1);
    json.push_back(o);
  }
  return json;
}

JsonObject HeldJointsJson(const Skeleton& skeleton, const std::vector<int>& held_frames) {
  JsonObject held;
  for (size_t j = 0; j < held_frames.size(); ++j) {
    if (held_frames[j] > 0) held.Add(skeleton.name(static_cast<int>(j)), held_frames[j]);
  }
  return held;
}

}  // namespace mocapsolve
