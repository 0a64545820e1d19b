# SPDX-License-Identifier: MIT
"""The Bouc-Wen benchmark (Noël and Schoukens), from Python."""
import ctypes

import numpy as np

from . import _lib


def simulate(u, fs=750.0):
    """The benchmark's output y (NumPy array) for the force u sampled at fs Hz,
    integrated at that rate from rest with the benchmark's parameters and
    Newmark integrator, without measurement noise: `hystviz boucwen data
    --input FILE --upsample 1 --fs FS --noise 0`."""
    from . import SceneError
    ua = np.ascontiguousarray(u, dtype=np.float64)
    if ua.ndim != 1 or ua.size < 1:
        raise SceneError(1, "boucwen.simulate: u must be a 1-D array of at least one sample")
    y = np.empty_like(ua)
    err = _lib.Error()
    rc = _lib.boucwen_run(ua.ctypes.data_as(_lib._dp), ua.size, float(fs), y.ctypes.data_as(_lib._dp),
                          ctypes.byref(err))
    if rc:
        raise SceneError(rc, err.msg.decode("utf-8", "replace"))
    return y
