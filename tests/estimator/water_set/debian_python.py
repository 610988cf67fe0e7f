# Debian's python3-opencv and python3-numpy live in the system interpreter, not in a pyenv or venv
# one: the water-set scripts re-run themselves under /usr/bin/python3 when started from another.
import os
import sys


def require_opencv():
    """Returns when cv2 and numpy import; else re-runs the script under /usr/bin/python3 if that is
    another interpreter, or raises the ImportError."""
    try:
        import cv2  # noqa: F401
        import numpy  # noqa: F401
    except ImportError:
        if os.path.exists("/usr/bin/python3") and \
                os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3"):
            os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
        raise
