// PYBIND11_MODULE: the compiled part of the `mocapsolve` package (mocapsolve/_core).
#include "python/bindings.h"

PYBIND11_MODULE(_core, m) {
  m.doc() =
      "mocapsolve: motion-capture problems as nonlinear least squares (Ceres and DLS).\n\n"
      "Arrays are float64 numpy arrays: markers (frames, markers, 3) with NaN where a\n"
      "sample is missing, rotations (frames, joints, 4) as x, y, z, w quaternions, joint\n"
      "positions (frames, joints, 3) in the file's units. Options are keyword arguments\n"
      "named like the command line's flags (`mocapsolve solve --help`); a bad value raises\n"
      "ValueError with the command line's message, a missing file OSError naming it.";
  using namespace mocapsolve::python;
  BindKinematics(m);
  BindIo(m);
  BindSolve(m);
  BindSkeletonFitting(m);  // Before repair: evaluate's docs read SkeletonFitSettings.
  BindRepair(m);
  BindRetarget(m);
  BindPropagate(m);
  BindPyramid(m);
  BindPipeline(m);
}
