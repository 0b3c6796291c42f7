// --method: each command that offers one declares its own, with its own choices, default and
// help (evaluate: what is measured; propagate: the falloff; distance: the distances; blend:
// the blend). A name means one thing per command, and `--help` shows that command's.
#ifndef MOCAPSOLVE_SETTINGS_METHOD_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_METHOD_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct MethodSetting {
  std::string method;
};

const OptionGroup<MethodSetting>& EvaluateMethodOption();   // repair | leave_one_out | small_errors.
const OptionGroup<MethodSetting>& PropagateMethodOption();  // green | harmonic | spline.
const OptionGroup<MethodSetting>& DistanceMethodOption();   // green, diffusion, isomap (comma-separated).
const OptionGroup<MethodSetting>& BlendMethodOption();      // multires | weighted.

// A command's default method (the Python keyword's default).
inline std::string DefaultMethod(const OptionGroup<MethodSetting>& group) { return group.Defaults().method; }

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_METHOD_SETTINGS_H_
