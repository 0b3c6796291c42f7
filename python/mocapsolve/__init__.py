"""mocapsolve: motion-capture problems as nonlinear least squares (Ceres and DLS).

Arrays are float64 numpy arrays: markers (frames, markers, 3) with NaN where a sample is
missing, rotations (frames, joints, 4) as x, y, z, w quaternions, joint positions
(frames, joints, 3) in the file's units. Options are keyword arguments named like the
command line's flags (``mocapsolve solve --help``); a bad value raises ValueError with
the command line's message, a missing input file OSError naming it. Solves release the
GIL, so a ThreadPoolExecutor over takes uses every core.
"""
import os as _os

# The viewer's runtime (pipeline's view.html) is found beside the CLI (build/tools/viewer);
# in the build tree this package sits in build/python/mocapsolve/, so point there unless
# MOCAPSOLVE_VIEWER_TOOLS already says where it is.
_tools = _os.path.join(_os.path.dirname(_os.path.abspath(__file__)), "..", "..", "tools", "viewer")
if "MOCAPSOLVE_VIEWER_TOOLS" not in _os.environ and _os.path.exists(_os.path.join(_tools, "three.bundle.js")):
    _os.environ["MOCAPSOLVE_VIEWER_TOOLS"] = _os.path.normpath(_tools)

from ._core import *  # noqa: E402,F401,F403
from ._core import __doc__ as _core_doc  # noqa: E402,F401

__version__ = "0.1.0"


def _naming_the_command(command, function):
    """function, whose ValueError names the command as the CLI's one-line error does:
    'mocapsolve repair: --reference: unknown ...' in Python and on the command line alike."""
    import functools

    @functools.wraps(function)
    def call(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except ValueError as error:
            raise ValueError("mocapsolve %s: %s" % (command, error)) from None
    return call


# The functions named after commands (one task under both front ends).
for _command in ("markers", "solve", "repair", "corrupt", "evaluate", "calibrate", "fit_skeleton", "retarget",
                 "distance", "propagate", "pipeline", "batch", "info", "view"):
    globals()[_command] = _naming_the_command(_command, globals()[_command])
del _command
