# SPDX-License-Identifier: MIT
"""hystviz.sweep: a table-only parameter study as a NumPy structured array,
computed in C on several threads (libhystviz's hy_sweep_npy; the GIL is
released during the call), nothing written to disk (docs/STUDIES.md,
issue 37)."""
from __future__ import annotations

import ctypes
import os
from collections.abc import Mapping

TYPE_CHECKING = False  # typing for the checker only (hystviz/__init__.py says why)
if TYPE_CHECKING:
    from typing import Any, Iterable, Optional, Sequence, Tuple, Union

import numpy as np

from . import _lib

__all__ = ["sweep", "grid_text", "SweepError"]

_npy = _lib._sig("hy_sweep_npy", ctypes.c_int, ctypes.c_char_p, ctypes.POINTER(ctypes.c_char_p), _lib._sz,
                 ctypes.POINTER(ctypes.c_char_p), ctypes.POINTER(_lib._dp), ctypes.POINTER(_lib._sz), _lib._sz,
                 ctypes.c_long, ctypes.c_long, ctypes.c_long, ctypes.c_double, ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(_lib._sz), _lib._E)


class SweepError(ValueError):
    """A scene, grid key, grid value or column that hystviz.sweep refused.

    Parameters
    ----------
    msg : str
        The message (``str()`` of the exception), naming what was refused.

    Examples
    --------
    >>> try:
    ...     hystviz.sweep(hystviz.scene_path("fig15_minor_loop_ex4"), grid={"model.no_such_key": [1.0]})
    ... except hystviz.SweepError as e:
    ...     print("refused")
    refused
    """


def grid_text(v: float) -> str:
    """The text `hystviz sweep` gives a grid value (and puts in the point's
    name): the shortest of %.15g, %.16g, %.17g that reads back to v.

    Example
    -------
    >>> grid_text(0.1), grid_text(1.0), grid_text(1 / 3)
    ('0.1', '1', '0.3333333333333333')
    """
    for p in (15, 16, 17):
        t = "%.*g" % (p, v)
        if float(t) == v:
            return t
    return t


def _axis(key: str, values: Any) -> "np.ndarray[Any, Any]":
    if not isinstance(key, str) or not key or "\0" in key or "=" in key:
        raise SweepError(f"hystviz.sweep: grid key {key!r}: expected 'section.key' (a str without '=' or NUL)")
    a = np.ascontiguousarray(np.atleast_1d(np.asarray(values, dtype=np.float64)))
    if a.ndim != 1 or a.size == 0:
        raise SweepError(f"hystviz.sweep: grid key {key!r}: expected a non-empty 1-D sequence of numbers")
    return a


def sweep(scene: Union[str, "os.PathLike[str]"], grid: Mapping[str, Union[Sequence[float], "np.ndarray[Any, Any]"]],
          columns: Optional[Iterable[str]] = None, sets: Optional[Mapping[str, object]] = None,
          jobs: Optional[int] = None, max_work: float = 0.0, shard: Tuple[int, int] = (0, 1)) -> "np.ndarray[Any, Any]":
    """A table-only parameter study of a scene, as a NumPy structured array.

    Computes `scene` at every point of the Cartesian product of `grid`'s axes
    (row-major: the first key is the outermost axis, the last varies fastest),
    in C on `jobs` threads, and returns one record per point with the fields of
    `hystviz sweep --table npy` (docs/STUDIES.md): ``index``, ``status`` (0 ok,
    1 invalid, 2 failed), ``name``, the grid keys, ``ysteady_min``,
    ``ysteady_max``, ``nminor``, ``major_area``, ``minor1_area``,
    ``minor_areas`` (8,), ``energy``, ``err_measured_1_in_1000``, ``SERIES.err``,
    ``SERIES.dist``, ``message``.  Nothing is written to disk.

    The records are bit for bit the ``sweep.npy`` that ``hystviz sweep SCENE
    --grid KEY=V1,V2,... --formats none --table npy`` writes, each ``V`` being
    ``grid_text`` of the value.

    Parameters
    ----------
    scene : str or os.PathLike
        Path of a .scene file.
    grid : mapping of str to 1-D array_like of float
        ``{"model.sigma0": np.logspace(0, 2, 2000), "input.umin2": ...}``:
        a scene key and its finite values.
    columns : iterable of str, optional
        The fields to return, in this order (default: all).
    sets : mapping of str to value, optional
        Overrides applied at every point, as ``hystviz.run``'s ``sets``.
    jobs : int, optional
        Threads (default: ``os.cpu_count()``).
    max_work : float, optional
        The work budget of each point (<= 0: the default of ``hystviz render``).
    shard : (int, int), optional
        ``(k, n)``: only the points ``i`` with ``i % n == k``, as ``hystviz
        sweep --shard k/n`` (default ``(0, 1)``: all).  Their records are the
        whole study's (global index, name, error sample): ``t[k::n]`` of the
        whole table, so shards computed apart (Dask, docs/STUDIES.md) join
        into it exactly.

    Returns
    -------
    numpy.ndarray
        A structured array of one record per point (a packed copy holding only
        ``columns`` when given).

    Raises
    ------
    SweepError
        A key the scene does not have, a value it refuses, a non-finite value,
        an unknown column, or a scene that does not load (the message names it).
        A point the scene refuses at compute time is a record with status 1 or
        2 and its ``message``, not an exception.

    Examples
    --------
    >>> t = hystviz.sweep(hystviz.scene_path("fig15_minor_loop_ex4"), grid={"model.sigma0": [1.0, 10.0]},
    ...                   columns=["model.sigma0", "status"])
    >>> t["model.sigma0"].tolist(), t["status"].tolist()
    ([1.0, 10.0], [0, 0])
    >>> import numpy as np, hystviz
    >>> t = hystviz.sweep("scenes/fig15_minor_loop_ex4.scene",
    ...                   grid={"model.sigma0": np.logspace(0, 2, 200), "input.umin2": np.linspace(0.1, 0.5, 50)},
    ...                   columns=["model.sigma0", "input.umin2", "minor1_area"])  # doctest: +SKIP
    >>> t["minor1_area"].reshape(200, 50).max()  # doctest: +SKIP
    """
    from . import _sets, SceneError  # the package's override encoding (one place)
    path = os.fsencode(scene)
    if b"\0" in path or b"\n" in path:
        raise SweepError(f"hystviz.sweep: expected a scene file's path (got {scene!r}); scene text is not accepted")
    if not isinstance(grid, Mapping) or not grid:
        raise SweepError("hystviz.sweep: grid must be a non-empty mapping {'section.key': values, ...}")
    keys = list(grid)
    axes = [_axis(k, grid[k]) for k in keys]
    try:
        enc = _sets(sets, {})
    except SceneError as e:
        raise SweepError(f"hystviz.sweep: sets: {e}") from None
    c_sets = (ctypes.c_char_p * max(len(enc), 1))(*enc)
    c_keys = (ctypes.c_char_p * len(keys))(*[k.encode() for k in keys])
    c_vals = (_lib._dp * len(axes))(*[a.ctypes.data_as(_lib._dp) for a in axes])
    c_counts = (_lib._sz * len(axes))(*[a.size for a in axes])
    nthreads = int(jobs) if jobs is not None else (os.cpu_count() or 1)
    buf, n, err = ctypes.c_void_p(), _lib._sz(), _lib.Error()
    k, n_shards = (int(x) for x in shard)
    rc = _npy(path, c_sets, len(enc), c_keys, c_vals, c_counts, len(axes), k, n_shards, nthreads, float(max_work),
              ctypes.byref(buf), ctypes.byref(n), ctypes.byref(err))
    if rc:
        raise SweepError("hystviz.sweep: " + err.msg.decode("utf-8", "replace"))
    # here, not at import: numpy.lib.recfunctions imports numpy.ma, which
    # `import hystviz` would pay for every time (tests/bench/bench_import.py)
    import io
    import numpy.lib.format as npy_format
    import numpy.lib.recfunctions as rfn
    try:
        raw = (ctypes.c_char * n.value).from_address(buf.value or 0)
        head = memoryview(raw)
        f = io.BytesIO(bytes(head[:min(n.value, 65536 + 64)]))
        npy_format.read_magic(f)  # type: ignore[no-untyped-call]
        shape, _, dtype = npy_format.read_array_header_1_0(f)  # type: ignore[no-untyped-call]
        data = np.frombuffer(head, dtype=dtype, count=shape[0], offset=f.tell())
        if columns is None:
            return data.copy()
        cols = list(columns)
        for c in cols:
            if c not in dtype.names:
                raise SweepError(f"hystviz.sweep: unknown column {c!r} (the columns: {', '.join(dtype.names)})")
        packed: np.ndarray[Any, Any] = rfn.repack_fields(data[cols])
        return packed
    finally:
        _lib.libc.free(buf)
