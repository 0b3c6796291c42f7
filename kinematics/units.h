// Length units, explicit everywhere: every reader records the unit its file uses.
#ifndef MOCAPSOLVE_KINEMATICS_UNITS_H_
#define MOCAPSOLVE_KINEMATICS_UNITS_H_

#include <cstdio>
#include <string>

namespace mocapsolve {

struct LengthUnit {
  std::string name = "unknown";  // "cm", "mm", "m", "cmu" (ASF :units length 0.45), ...
  double metres_per_unit = 0.0;  // 0 when the file does not say (BVH).

  bool known() const { return metres_per_unit > 0.0; }
};

inline LengthUnit Metres() { return {"m", 1.0}; }
inline LengthUnit Centimetres() { return {"cm", 0.01}; }
inline LengthUnit Millimetres() { return {"mm", 0.001}; }
// Acclaim ASF ":units length L": one file unit is 1/L inches (CMU FAQ: L = 0.45).
inline LengthUnit AcclaimLength(double length_scale) {
  char name[48];
  std::snprintf(name, sizeof name, "asf length %g (1/%g inch)", length_scale, length_scale);
  return {name, 0.0254 / length_scale};
}

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_UNITS_H_
