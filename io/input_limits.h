// Cheap pre-scans that bound what a hostile file can make a third-party parser do.
//
// tinygltf (glTF JSON, `extras` parsed recursively by ParseJsonAsValue) and assimp (ASCII
// FBX, one recursion per brace) recurse once per nesting level of their input, so a file
// of a few tens of kilobytes of '[' or '{' exhausts the stack. Before handing bytes to
// them, io/ measures the nesting depth here, in one linear pass without recursion, and
// refuses files nested deeper than any real one (real glTF and FBX files nest < 20 deep).
//
// Both scans stop counting as soon as the depth passes `limit`: O(bytes), no allocation.
#ifndef MOCAPSOLVE_IO_INPUT_LIMITS_H_
#define MOCAPSOLVE_IO_INPUT_LIMITS_H_

#include <cstddef>
#include <string>
#include <string_view>

#include "kinematics/marker_trajectories.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

// Deepest nesting any reader hands to a third-party parser.
constexpr int kMaxThirdPartyNesting = 128;

// Deepest '[' / '{' nesting of JSON text (brackets inside strings, with \" escapes, do
// not count); returns limit + 1 as soon as the depth exceeds `limit`.
int JsonNestingDepth(std::string_view text, int limit = kMaxThirdPartyNesting);

// Deepest '{' nesting of ASCII FBX text (braces inside "strings" and after a ';' comment
// to the end of its line do not count); returns limit + 1 as soon as it exceeds `limit`.
int FbxBraceDepth(std::string_view text, int limit = kMaxThirdPartyNesting);

// Numbers every reader accepts and every writer can represent. A reader refuses a file
// beyond them (so nothing downstream sees a rate of 1e-308 Hz or a root at 1e308), and
// every writer (C3D, TRC, BVH, glTF) refuses to write beyond them, so what one writes
// the others read back unchanged: C3D and glTF store rates, times and coordinates as
// 32-bit floats (a rate of 1e308 became inf, then NaN; 1e-310 became 0), BVH stores
// the frame time 1 / rate, and a glTF time accessor's "max" of inf is JSON null.
//
// Frame rates, Hz: from one frame per kMinFrameRate^-1 = 1000 s to 1 MHz (a frame time
// of 1 us, the BVH reader's bound since issue 15).
constexpr double kMinFrameRate = 1e-3;
constexpr double kMaxFrameRate = 1e6;
// Largest |coordinate| (marker positions, joint offsets and translations), in file
// units: 1e9 mm is 1000 km (MarkerTrajectories::kMaxCoordinate, where it began).
constexpr double kMaxCoordinate = MarkerTrajectories::kMaxCoordinate;
// Most frames a take may have: 2^24 is 39 hours at 120 Hz. Bounds what a header's frame
// count makes a reader allocate when the frames themselves take no bytes (a C3D of 0
// points declared 2^31 - 1 frames).
constexpr int kMaxFrames = 1 << 24;

// A scale from marker file units to skeleton units (a subject's marker_files.scale,
// --marker_scale): mm to km and back is 1e6; 0 means "from the files' units".
constexpr double kMaxUnitScale = 1e6;

// Ok if kMinFrameRate <= rate <= kMaxFrameRate, else "<field> <rate> is outside
// 0.001..1e+06 Hz" (field: "frame rate", "POINT:RATE", ...).
Status CheckFrameRate(double rate, const std::string& field);
// Ok if |value| <= kMaxCoordinate for every coefficient, else "<field>: <value> is beyond
// +-1e9" (field: "frame 3, joint 'Hips' translation", ...).
Status CheckCoordinates(const Eigen::Vector3d& value, const std::string& field);
// A motion both readers and writers hold to: the frame rate, and every offset (joints
// and end sites) and translation times `scale` (a writer's unit change) within bounds.
// The error names the field; callers prefix the file.
Status CheckMotionBounds(const Skeleton& skeleton, const Motion& motion, double scale = 1.0);
// Ok if scale is 0 or within [1 / kMaxUnitScale, kMaxUnitScale], else "<field>: <scale>
// is outside 1e-06..1e+06 (0: from the units)".
Status CheckUnitScale(double scale, const std::string& field);
// The same for marker trajectories: the frame rate and every valid sample.
Status CheckMarkerBounds(const MarkerTrajectories& trajectories);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_INPUT_LIMITS_H_
