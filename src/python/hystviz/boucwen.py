# SPDX-License-Identifier: MIT
"""The Bouc-Wen benchmark (Noël and Schoukens), from Python."""
from __future__ import annotations

import ctypes

import numpy as np

from . import _lib

TYPE_CHECKING = False  # typing for the checker only (hystviz/__init__.py says why)
if TYPE_CHECKING:
    from typing import Sequence, Union

    import numpy.typing as npt


def simulate(u: Union[Sequence[float], npt.NDArray[np.float64]], fs: float = 750.0) -> npt.NDArray[np.float64]:
    """The benchmark's output for a force, without measurement noise.

    Integrated at fs from rest with the benchmark's parameters and Newmark
    integrator: `hystviz boucwen data --input FILE --upsample 1 --fs FS
    --noise 0`.

    Parameters
    ----------
    u : array_like
        The force (N), one sample a 1/fs s; 1-D, at least one sample.
    fs : float
        The sampling rate (Hz).

    Returns
    -------
    ndarray
        The displacement y (m), float64, one a sample of u.

    Raises
    ------
    SceneError
        u is not 1-D with a sample, or fs out of the library's range.

    Examples
    --------
    >>> y = hystviz.boucwen.simulate(np.zeros(8))
    >>> y.shape, float(np.abs(y).max())
    ((8,), 0.0)
    """
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
