"""mocapsolve: motion-capture problems as nonlinear least squares (Ceres and DLS).

Arrays are float64 numpy arrays: markers (frames, markers, 3) with NaN where a sample is
missing, rotations (frames, joints, 4) as x, y, z, w quaternions, joint positions
(frames, joints, 3) in the file's units. Options are keyword arguments named like the
command line's flags (``mocapsolve solve --help``); a bad value raises ValueError with
the command line's message, a missing input file OSError naming it. Solves release the
GIL, so a ThreadPoolExecutor over takes uses every core.
"""
from ._core import *  # noqa: F401,F403
from ._core import __doc__ as _core_doc  # noqa: F401

__version__ = "0.1.0"
