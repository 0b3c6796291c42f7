// A fixed small skeleton (BVH text, parsed once) for the fuzz targets whose readers
// resolve joint names against a skeleton: marker sets, edit files.
#ifndef MOCAPSOLVE_FUZZ_FUZZ_SKELETON_H_
#define MOCAPSOLVE_FUZZ_FUZZ_SKELETON_H_

#include <cstdlib>

#include "io/bvh_reader.h"

namespace mocapsolve {

inline const Skeleton& FuzzSkeleton() {
  static const Skeleton* skeleton = [] {
    static const char kBvh[] =
        "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition "
        "Zrotation Xrotation Yrotation\n JOINT LeftUpLeg\n {\n  OFFSET 10 0 0\n  CHANNELS 3 "
        "Zrotation Xrotation Yrotation\n  End Site\n  {\n   OFFSET 0 -40 0\n  }\n }\n JOINT "
        "Spine\n {\n  OFFSET 0 10 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n  End Site\n  "
        "{\n   OFFSET 0 30 0\n  }\n }\n}\nMOTION\nFrames: 1\nFrame Time: 0.033333\n"
        "0 90 0 0 0 0 0 0 0 0 0 0\n";
    auto* out = new Skeleton;
    Motion motion;
    if (!ParseBvh(kBvh, "fuzz.bvh", out, &motion).ok()) std::abort();
    return out;
  }();
  return *skeleton;
}

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_FUZZ_FUZZ_SKELETON_H_
