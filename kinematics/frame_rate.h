// The frame rate a take's key times are written at.
//
// NominalFrameRate(r): a rate within 1e-5 of a whole number n (|r - n| <= 1e-5 n) is n, any
// other rate is itself. A BVH's frame time has 5-6 significant digits (CMU's 0.0083333 s is
// 120.00048 fps); readers of FBX (whose TimeMode names whole rates) and of glTF
// (io/gltf_reader.h rounds a key rate within 1e-3 of a whole number) sample at the whole
// rate, so keys written at the unrounded rate would drift from the frames read back by up
// to (frames - 1) x 4e-6 frames (0.005 frames, 0.4 mm of a walk, at the end of 1,247 frames).
#ifndef MOCAPSOLVE_KINEMATICS_FRAME_RATE_H_
#define MOCAPSOLVE_KINEMATICS_FRAME_RATE_H_

namespace mocapsolve {

double NominalFrameRate(double frame_rate);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_FRAME_RATE_H_
