# SPDX-License-Identifier: MIT
"""hystviz: hysteresis models and their exact figures, from Python.

The numbers come from libhystviz, the C library the `hystviz` command is
built from: what this package returns is bit for bit what `hystviz data`
prints for the same scene, and `render` gives the bytes `hystviz render`
writes.

    >>> import hystviz
    >>> m = hystviz.Model("lugre", sigma0=6)
    >>> u = hystviz.Input("bimodal", umin1=0, umin2=0.5, umax1=1, umax2=1.5)
    >>> [round(l.area, 6) for l in hystviz.minor_loops(m, u)]
    [0.199107]
    >>> fig = hystviz.render(hystviz.scene_path("fig15_minor_loop_ex4"), model__sigma0=2)

Scene keys are written section.key; as a keyword argument, section__key
(model__sigma0=2), or pass a dict: render(scene, **{"model.sigma0": 2}).
A scene the library refuses raises hystviz.SceneError with the C message
(file:line:col first); a file that is missing or unreadable raises
FileNotFoundError or PermissionError.  Model and Input take the keys of the
scene file's [model] and [input] sections (docs/SCENES.md; help(hystviz.Model)
lists them with their ranges and units).  scene_path(name) finds the papers'
scenes that the package carries; plot(..., ax=...) draws into matplotlib.
"""
from __future__ import annotations

import ctypes
import functools
import json
import math
import os
import numpy as np

from . import _lib

# typing and numpy.typing only for the checker (annotations are not evaluated:
# `from __future__ import annotations`): `import typing` was half of what
# `import hystviz` cost beyond NumPy (tests/bench/bench_import.py); mypy
# takes the name TYPE_CHECKING as true wherever it is defined
TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Type, Union

    import numpy.typing as npt
    Array = npt.NDArray[Any]
    ArrayLike = npt.ArrayLike
    PathLike = Union[str, "os.PathLike[str]"]
    Value = Any

__all__ = ["SceneError", "Model", "Input", "models", "Result", "Figure", "MinorLoop", "run", "render", "steady_loop",
           "limit", "ygamma", "kcycles", "minor_loops", "schema", "boucwen", "read_data", "read_forc", "forc",
           "loop_area", "fit", "FitResult", "scene_path", "plot", "__version__", "sweep", "SweepError"]

__version__: str = _lib.version().decode()


class SceneError(ValueError):
    """A scene or a parameter the library refused.

    Parameters
    ----------
    code : int
        The library's status (hy_error.code; 1 for a check made in Python).
    msg : str
        The message, a file's first: "FILE:LINE:COL: what is wrong".

    Examples
    --------
    >>> try:
    ...     hystviz.minor_loops(hystviz.Model("lugre", sigma0=-1), hystviz.Input("bimodal"))
    ... except hystviz.SceneError as e:
    ...     print(e)
    <python>/scene.scene:3:10: 'sigma0' in [model] must be > 0, got -1
    """

    def __init__(self, code: int, msg: str) -> None:
        super().__init__(msg)
        self.code = code


def _check(rc: int, err: _lib.Error) -> None:
    if rc:
        raise SceneError(rc, err.msg.decode("utf-8", "replace"))


def _readable(path: PathLike) -> bytes:
    """path as bytes for C, after the checks Python's own open() makes: a
    missing file is FileNotFoundError, an unreadable one PermissionError,
    a directory IsADirectoryError (each names the path); ValueError for a
    NUL byte."""
    p = os.fsencode(path)
    if b"\0" in p:
        raise ValueError(f"hystviz: a NUL byte is not allowed in a path (got {path!r})")
    with open(path, "rb"):  # as given: the exception names the path as the caller wrote it
        pass
    return p


def schema() -> Dict[str, Any]:
    """The scene vocabulary as a dict.

    Returns
    -------
    dict
        "version" and "sections" (each with "name", "doc" and "keys": each
        key's "name", "kind", "min", "max", "default", "enums", "doc",
        "unit" (SI, None for none or dimensionless) and "symbol"), and
        "models" (each kind's "params", "quantities", "state", "caps").

    Raises
    ------
    MemoryError
        When the library is out of memory.

    Examples
    --------
    >>> s = hystviz.schema()
    >>> [k["unit"] for k in s["sections"][0]["keys"] if k["name"] == "c"]
    ['N s/m']
    """
    p = _lib.schema_json()
    if not p:
        raise MemoryError("hystviz: out of memory for the schema")
    try:
        out: Dict[str, Any] = json.loads(ctypes.string_at(p).decode())
        return out
    finally:
        _lib.libc.free(p)


_SCHEMA = schema()
_SECTIONS = {s["name"]: s for s in _SCHEMA["sections"]}


def _keydoc(k: Mapping[str, Any]) -> str:
    lo = hi = ""
    if k["min"] is not None:
        lo = ("> " if k["min_exclusive"] else ">= ") + repr(k["min"])
    if k["max"] is not None:
        hi = ("< " if k["max_exclusive"] else "<= ") + repr(k["max"])
    rng = ", ".join(x for x in (lo, hi) if x)
    dflt = f" (default {k['default']})" if k["default"] is not None else ""
    unit = f", {k['unit']}" if k.get("unit") else ""
    return f"    {k['name']} : {k['kind']}{unit}{', ' + rng if rng else ''}{dflt}\n        {k['doc']}"


def _text_param(what: str, v: object) -> str:
    """A string parameter (a value, a key, a format name) as the library
    takes it: a NUL byte would cut it where C reads it and a line break would
    start a new line of scene text, so either is refused with ValueError."""
    s = v if isinstance(v, str) else str(v)
    for ch, name in (("\0", "a NUL byte"), ("\n", "a newline"), ("\r", "a carriage return")):
        if ch in s:
            raise ValueError(f"hystviz: {what}: {name} is not allowed here (got {s!r})")
    return s


def _set_value(key: str, v: Value) -> str:
    """v as the value of the override key ("section.key" or
    "section.NAME.key") for the library's --set parser: a typed value as _fmt
    writes it; a string checked (_text_param), and for a text key (kind
    string or path) quoted as the scene format quotes ("..." with \\" and
    \\\\), so spaces, quotes and '#' are the value's own characters."""
    if _typed(v):
        return _fmt(v)
    if isinstance(v, (list, tuple)):  # a list of words (identifiers: formats = svg, png)
        return ", ".join(_set_value(key, x) for x in v)
    text = _text_param(key, v)
    parts = key.split(".")
    sec = _SECTIONS.get(parts[0].strip())
    kind = next((k["kind"] for k in sec["keys"] if k["name"] == parts[-1].strip()), None) if sec else None
    if kind in ("string", "path"):
        return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'
    return text


def _typed(v: object) -> bool:
    """Whether v is a typed value (a number, a bool, or a list of them) that
    _fmt writes as scene text itself; anything else is a string, which goes to
    the library's own --set parser (_text_param), never into scene text."""
    if isinstance(v, (bool, int, float, np.integer, np.floating)):
        return True
    if isinstance(v, (list, tuple, np.ndarray)):
        return all(_typed(x) and not isinstance(x, (list, tuple, np.ndarray)) for x in v)
    return False


def _fmt(v: Value) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if isinstance(v, (float, np.floating)):
        if not math.isfinite(v):
            raise SceneError(1, f"{v!r} is not a finite number")
        return repr(float(v))
    if isinstance(v, (list, tuple, np.ndarray)):
        return ", ".join(_fmt(x) for x in v)
    return str(v)


class _Section:
    """A [section] of a scene: kind plus keys, checked against the schema."""
    section = ""
    _example = ""  # the docstring's example's arguments

    def __init__(self, kind: str, **params: Value) -> None:
        keys = {k["name"] for k in _SECTIONS[self.section]["keys"]}
        kinds = next(k["enums"] for k in _SECTIONS[self.section]["keys"] if k["name"] == "kind")
        if kind not in kinds:
            raise SceneError(1, f"{self.section} kind '{kind}': one of {', '.join(kinds)}")
        for k in params:
            if k not in keys or k == "kind":
                raise SceneError(1, f"[{self.section}] has no key '{k}' (help(hystviz.{type(self).__name__}))")
        self.kind = kind
        self.params = dict(params)
        # numbers are written as scene text (typed: repr of a float or int);
        # strings go to the library's --set parser as "section.key=value"
        lines = [f"[{self.section}]", f"kind = {kind}"] + [f"{k} = {_fmt(v)}" for k, v in params.items() if _typed(v)]
        self._text = "\n".join(lines) + "\n"  # the section as scene text, made once
        self._btext = self._text.encode()  # and as the library reads it (steady_loop's call)
        self._sets = [f"{self.section}.{k}={_set_value(f'{self.section}.{k}', v)}".encode()
                      for k, v in params.items() if not _typed(v)]

    def scene_text(self) -> str:
        """The section's typed keys as scene text (its string keys are in scene_sets).

        Returns
        -------
        str
            "[section]", "kind = ...", then one "key = value" line a key.

        Examples
        --------
        >>> print(hystviz.Input("sine", amp=2).scene_text(), end="")
        [input]
        kind = sine
        amp = 2
        """
        return self._text

    def scene_sets(self) -> List[bytes]:
        """The section's string keys as overrides for the library's --set parser.

        Returns
        -------
        list of bytes
            b"section.key=value", one a string key.

        Examples
        --------
        >>> hystviz.Input("sine").scene_sets()
        []
        """
        return list(self._sets)

    def __repr__(self) -> str:
        args = ", ".join([repr(self.kind)] + [f"{k}={v!r}" for k, v in self.params.items()])
        return f"{type(self).__name__}({args})"


class Model(_Section):
    section = "model"
    _example = "'lugre', sigma0=6"
    #: each parameter's unit from the schema (None: dimensionless or none);
    #: a class of hystviz.models has its kind's parameters, Model all keys
    units: Dict[str, Optional[str]] = {}

    def __init__(self, kind: str, **params: Value) -> None:
        spec = _MODELS.get(kind)
        if spec is not None:
            allowed = set(spec["params"])
            for k in params:
                if k in _MODEL_KEYS and k not in allowed:
                    raise SceneError(1, f"model kind '{kind}' has no parameter '{k}'; its parameters: "
                                        f"{', '.join(spec['params'])}")
        super().__init__(kind, **params)


class Input(_Section):
    section = "input"
    _example = "'sine', amp=2"


_MODELS = {m["name"]: m for m in _SCHEMA["models"]}
_MODEL_KEYS = {k["name"]: k for k in _SECTIONS["model"]["keys"]}


def _model_class(spec: Mapping[str, Any]) -> Type[Model]:
    kind = spec["name"]
    units = {p: _MODEL_KEYS[p]["unit"] for p in spec["params"] if p in _MODEL_KEYS}

    def init(self: Model, **params: Value) -> None:
        Model.__init__(self, kind, **params)
    doc = (f"The '{kind}' model: Model('{kind}', **parameters).\n\nState: {spec['state']}.\n"
           f"Capabilities: {', '.join(spec['caps']) or 'none'}.\nQuantities drawn: "
           f"{', '.join(spec['quantities']) or '-'}.\n\nParameters\n----------\n" +
           "\n".join(_keydoc(_MODEL_KEYS[p]) for p in spec["params"] if p in _MODEL_KEYS))
    doc += (f"\n\nRaises\n------\nSceneError\n    A key that is not one of these.\n\nExamples\n--------\n"
            f">>> hystviz.models[{kind!r}]().kind\n{kind!r}\n"
            f">>> sorted(hystviz.models[{kind!r}].units)[:2]\n{sorted(units)[:2]!r}\n")
    name = "".join(w.capitalize() for w in kind.replace("_", "-").split("-"))
    return type(name, (Model,), {"__init__": init, "__doc__": doc, "units": units})


# one class per kind of the model table: models["lugre"](sigma0=6), help(models["preisach"])
models: Dict[str, Type[Model]] = {kind: _model_class(spec) for kind, spec in _MODELS.items()}
Model.units = {k["name"]: k["unit"] for k in _SECTIONS["model"]["keys"] if k["name"] != "kind"}

for _cls in (Model, Input):
    _sec = _SECTIONS[_cls.section]
    _cls.__doc__ = (f"{_cls.__name__}(kind, **keys): the scene's [{_cls.section}] section.\n\n"
                    f"{_sec['doc']}\n\nParameters\n----------\n" +
                    "\n".join(_keydoc(k) for k in _sec["keys"]) +
                    "\n\nRaises\n------\nSceneError\n    An unknown kind or key.\n\n"
                    f"Examples\n--------\n>>> hystviz.{_cls.__name__}({_cls._example})\n"
                    f"{_cls.__name__}({_cls._example})\n")


class MinorLoop:
    """A loop of the steady state y°, as minor_loops() and Result.minor give it.

    Parameters
    ----------
    c : hystviz._lib.Loop
        The library's hy_loop (not made by hand).

    Attributes
    ----------
    u_start, u_turn : float
        Where the loop starts and turns, in the input's unit.
    y_start, y_close : float
        The output where it starts and closes, in the output's unit.
    area : float
        ∮ y du over the loop: energy per cycle (output unit x input unit,
        e.g. N m = J for a friction force against a displacement).
    own_area : float
        area less that of the loops nested in it.
    depth : int
        0 for the major loop, 1 for a loop inside it, ...

    Examples
    --------
    >>> loop = hystviz.minor_loops(hystviz.Model("lugre", sigma0=6),
    ...                            hystviz.Input("bimodal", umin1=0, umin2=0.5, umax1=1, umax2=1.5))[0]
    >>> loop.depth, round(loop.area, 6)
    (1, 0.199107)
    """

    def __init__(self, c: _lib.Loop) -> None:
        self.u_start, self.u_turn = c.u_start, c.u_turn
        self.y_start, self.y_close = c.y_start, c.y_close
        self.area, self.own_area, self.depth = c.area, c.own_area, c.depth

    def __repr__(self) -> str:
        return (f"MinorLoop(u_start={self.u_start!r}, u_turn={self.u_turn!r}, area={self.area!r}, "
                f"depth={self.depth})")


class Figure:
    """A rendered figure: Jupyter shows it (SVG); save() writes any format.

    Parameters
    ----------
    result : Result
        The computed scene whose [figure] it draws.

    Attributes
    ----------
    svg : bytes
        The figure as SVG, as `hystviz render --format svg` writes it.

    Examples
    --------
    >>> fig = hystviz.render(hystviz.scene_path("fig15_minor_loop_ex4"))
    >>> fig.svg[:5]
    b'<?xml'
    """

    def __init__(self, result: Result) -> None:
        self._result = result
        self.svg: bytes = result.render("svg")

    def _repr_svg_(self) -> str:
        return self.svg.decode("utf-8")

    def save(self, path: PathLike, format: Optional[str] = None) -> None:
        """Writes the figure to a file, as `hystviz render` writes it.

        Through libhystviz's output writer (hy_write_file): a temporary beside
        path made with O_EXCL and renamed onto it, so path is whole or
        untouched; a symbolic link is followed only to a file in path's own
        directory or below; a FIFO or device at path is written, never replaced.

        Parameters
        ----------
        path : str or os.PathLike
            The file to write.
        format : str, optional
            svg, pdf or png; default: path's extension.

        Raises
        ------
        OSError
            When path cannot be written (the library's message).
        ValueError
            A NUL byte in path, or a NUL or line break in format.
        SceneError
            A format the library does not write.

        Examples
        --------
        >>> import os, tempfile
        >>> with tempfile.TemporaryDirectory() as d:
        ...     hystviz.render(hystviz.scene_path("fig15_minor_loop_ex4")).save(os.path.join(d, "f.pdf"))
        ...     print(open(os.path.join(d, "f.pdf"), "rb").read(5))
        b'%PDF-'
        """
        p = os.fsencode(path)
        if b"\0" in p:
            raise ValueError(f"hystviz: Figure.save: a NUL byte is not allowed in the path (got {path!r})")
        fmt = format if format is not None else os.path.splitext(os.fsdecode(p))[1].lstrip(".").lower()
        fmt = _text_param("Figure.save format", fmt)
        data = self.svg if fmt == "svg" else self._result.render(fmt)
        err = _lib.Error()
        if _lib.write_file(p, data, len(data), ctypes.byref(err)):
            raise OSError(err.msg.decode("utf-8", "replace"))


class Result:
    """A computed scene: its series, loops and figure, as run() returns it.

    Parameters
    ----------
    handle : int
        The library's hy_result (run() makes it; the Result frees it).

    Attributes
    ----------
    series : dict of str to (ndarray, ndarray)
        Each [series NAME]: x (time in s, or the input in its unit for a
        loop figure) and y (the series' quantity in its unit), float64.
    data : dict of str to str
        Each series' data key (input, ysteady, ygamma, minor, ...).
    errors : dict of str to (float, str or None)
        Each series' largest error against its reference, and the reference.
    major : MinorLoop or None
        The steady state's major loop (None when the figure has no loops).
    minor : list of MinorLoop
        Its minor loops.
    energy : float
        ∮ y du over one period (output unit x input unit); NaN without loops.

    Examples
    --------
    >>> r = hystviz.run(hystviz.scene_path("fig15_minor_loop_ex4"))
    >>> sorted(r.series)[:2], len(r.minor)
    (['major', 'minor'], 1)
    """

    def __init__(self, handle: int) -> None:
        self._h: Optional[int] = handle
        self.series: Dict[str, Tuple[Array, Array]] = {}
        self.data: Dict[str, str] = {}
        self.errors: Dict[str, Tuple[float, Optional[str]]] = {}
        self.major: Optional[MinorLoop]
        self.minor: List[MinorLoop]
        self.energy: float
        for i in range(_lib.nseries(handle)):
            x, y = _lib._dp(), _lib._dp()
            n = _lib.series(handle, i, ctypes.byref(x), ctypes.byref(y))
            name = _lib.series_name(handle, i).decode()
            xa = _array(x, n) if n else np.empty(0)
            ya = _array(y, n) if n else np.empty(0)
            self.series[name] = (xa, ya)
            self.data[name] = _lib.series_data(handle, i).decode()
            ref = ctypes.c_char_p()
            self.errors[name] = (_lib.series_error(handle, i, ctypes.byref(ref)),
                                 ref.value.decode() if ref.value else None)
        lp = _lib.loops(handle)
        if lp:
            L = lp.contents
            self.major = MinorLoop(L.major)
            self.minor = [MinorLoop(L.minor[k]) for k in range(L.nminor)]
            self.energy = L.area_period
        else:
            self.major, self.minor, self.energy = None, [], float("nan")

    def render(self, format: str = "svg") -> bytes:
        """The figure's bytes, as `hystviz render` writes them.

        Parameters
        ----------
        format : str
            svg, pdf or png.

        Returns
        -------
        bytes
            The file's bytes.

        Raises
        ------
        SceneError
            A format the library does not write.

        Examples
        --------
        >>> hystviz.run(hystviz.scene_path("fig15_minor_loop_ex4")).render("png")[:4]
        b'\\x89PNG'
        """
        fmt = _text_param("render format", format).encode()
        buf = ctypes.POINTER(ctypes.c_ubyte)()
        n = _lib._sz()
        err = _lib.Error()
        _check(_lib.render(self._h, fmt, ctypes.byref(buf), ctypes.byref(n), ctypes.byref(err)), err)
        try:
            return ctypes.string_at(buf, n.value)
        finally:
            _lib.libc.free(ctypes.cast(buf, ctypes.c_void_p))

    def csv(self) -> str:
        """Every series as `hystviz data` prints it.

        Returns
        -------
        str
            "series,x,y" then one line a point, numbers as %.17g.

        Examples
        --------
        >>> hystviz.run(hystviz.scene_path("fig15_minor_loop_ex4")).csv().splitlines()[0]
        'series,x,y'
        """
        p = ctypes.c_void_p()
        n = _lib._sz()
        err = _lib.Error()
        _check(_lib.csv(self._h, ctypes.byref(p), ctypes.byref(n), ctypes.byref(err)), err)
        try:
            return ctypes.string_at(p, n.value).decode()
        finally:
            _lib.libc.free(p)

    def figure(self) -> Figure:
        """The scene's figure.

        Returns
        -------
        Figure
            Its SVG, and save() for any format.

        Examples
        --------
        >>> hystviz.run(hystviz.scene_path("fig15_minor_loop_ex4")).figure().svg[:5]
        b'<?xml'
        """
        return Figure(self)

    def __del__(self) -> None:
        if getattr(self, "_h", None):
            _lib.result_free(self._h)
            self._h = None


def _sets(sets: Optional[Mapping[str, Value]], overrides: Mapping[str, Value]) -> List[bytes]:
    """Overrides as b"section.key=value" for the library's --set parser
    (_set_value: typed values as _fmt writes them, strings checked and, for
    text keys, quoted)."""
    d = dict(sets or {})
    d.update({k.replace("__", "."): v for k, v in overrides.items()})
    return [f"{_text_param('override key', k)}={_set_value(k, v)}".encode() for k, v in d.items()]


def _carray(enc: Sequence[Optional[bytes]]) -> "ctypes.Array[ctypes.c_char_p]":
    return (ctypes.c_char_p * max(len(enc), 1))(*enc)


def _run(scene: PathLike, enc: Sequence[bytes], max_work: float = 0.0) -> Result:
    """run() on overrides already encoded (_sets, scene_sets)."""
    arr = _carray(enc)
    h = ctypes.c_void_p()
    err = _lib.Error()
    if isinstance(scene, str) and "\n" in scene:
        text = scene.encode()
        rc = _lib.from_text(_PY_NAME, text, len(text), arr, len(enc), max_work, ctypes.byref(h),
                            ctypes.byref(err))
    else:
        path = _readable(scene)
        rc = _lib.from_file(path, arr, len(enc), max_work, ctypes.byref(h), ctypes.byref(err))
    _check(rc, err)
    assert h.value is not None  # a status of 0 comes with a result
    return Result(h.value)


def run(scene: PathLike, sets: Optional[Mapping[str, Value]] = None, max_work: float = 0.0,
        **overrides: Value) -> Result:
    """Computes a scene, as `hystviz data` does.

    Parameters
    ----------
    scene : str or os.PathLike
        A .scene file, or a scene's text (a str with a newline).
    sets : dict, optional
        Overrides {"section.key": value}, as `--set section.key=value`.
    max_work : float
        The work limit (0: the library's default).
    **overrides
        More overrides as section__key=value (model__sigma0=2).  Numbers
        are typed values in the key's unit (docs/SCENES.md); strings go to
        the library's --set parser, quoted for text keys.

    Returns
    -------
    Result
        The series, loops and figure.

    Raises
    ------
    FileNotFoundError, PermissionError
        The scene file is missing or unreadable.
    SceneError
        The library refused the scene or an override ("FILE:LINE:COL: ...").
    ValueError
        A NUL byte or a line break in a key or a string.

    Examples
    --------
    >>> r = hystviz.run(hystviz.scene_path("fig15_minor_loop_ex4"), model__sigma0=2.5)
    >>> r.series["minor"][0].dtype
    dtype('float64')
    """
    return _run(scene, _sets(sets, overrides), max_work)


def render(scene: PathLike, sets: Optional[Mapping[str, Value]] = None, **overrides: Value) -> Figure:
    """The scene's figure (Jupyter displays it; .save(path) writes svg, pdf or png).

    Parameters
    ----------
    scene : str or os.PathLike
        A .scene file, or a scene's text (a str with a newline).
    sets : dict, optional
        Overrides {"section.key": value}.
    **overrides
        More overrides as section__key=value, as for run().

    Returns
    -------
    Figure
        The figure `hystviz render` draws.

    Raises
    ------
    FileNotFoundError, PermissionError
        The scene file is missing or unreadable.
    SceneError
        The library refused the scene or an override.

    Examples
    --------
    >>> hystviz.render(hystviz.scene_path("fig15_minor_loop_ex4"), model__sigma0=2).svg[:5]
    b'<?xml'
    """
    return run(scene, sets, **overrides).figure()


def _scene(model: Model, inp: Input, series: str, points: int, cycles: int = 1, extra: str = "",
           kind: str = "timeseries") -> str:
    """The scene text of model and inp computing series on points samples a period."""
    return _scene_bytes(model.scene_text(), inp.scene_text(), series, points, cycles, extra, kind).decode()


@functools.lru_cache(maxsize=256)
def _scene_bytes(model_text: str, inp_text: str, series: str, points: int, cycles: int = 1, extra: str = "",
                 kind: str = "timeseries") -> bytes:
    """_scene's text, encoded, made once for each combination (a Model's and
    an Input's text is fixed when they are made): a repeated call with the
    same arguments does no string work (limit, ygamma, kcycles)."""
    return (model_text + inp_text + f"[compute]\npoints = {int(points)}\ncycles = {int(cycles)}\n"
            + extra + f"[figure]\nkind = {kind}\n" + ("[series u]\ndata = input\n" if kind == "timeseries" else "")
            + series).encode()


# steady_loop's hot path: the library call, numpy.empty, the scene name of the
# package's calls, the range of [compute] points (the schema's)
_steady = _lib.steady_loop
_steady_fast = _lib.fast_steady_loop
_empty = np.empty
_addressof = ctypes.addressof
_c_char = ctypes.c_char
_PY_NAME = b"<python>/scene.scene"
_POINTS_SPEC = next(k for k in _SECTIONS["compute"]["keys"] if k["name"] == "points")
_POINTS_MIN, _POINTS_MAX = int(_POINTS_SPEC["min"]), int(_POINTS_SPEC["max"])


def _array(p: Any, n: int) -> Array:
    """A copy of n doubles at the C pointer p (one memmove into a new array;
    np.ctypeslib.as_array costs tens of µs a call)."""
    a = np.empty(n)
    ctypes.memmove(a.ctypes.data, p, 8 * n)
    return a


def _tuy(text: Union[str, bytes], points: int, sets: Sequence[bytes] = ()) -> Tuple[Array, Array, Array]:
    """(t, u, y) of a _scene: series 0 is the input, series 1 the output, on
    the same grid; straight through the C calls, no Result, one copy of each
    series into one (3, n) array (limit, ygamma, kcycles; steady_loop is
    one call of hy_steady_loop, which does this in C)."""
    b = text.encode() if isinstance(text, str) else text
    h = ctypes.c_void_p()
    err = _lib.Error()
    _check(_lib.from_text(_PY_NAME, b, len(b), _carray(sets) if sets else None, len(sets), 0.0,
                          ctypes.byref(h), ctypes.byref(err)), err)
    try:
        cap = points + 1
        while True:
            out = np.empty((3, cap))
            p = out.ctypes.data
            n = _lib.series_copy(h, 0, p, p + 8 * cap, cap)
            if n <= cap:
                break
            cap = n
        if _lib.series_copy(h, 1, None, p + 16 * cap, cap) != n or not n:
            raise RuntimeError("hystviz: input and output sampled on different grids")
    finally:
        _lib.result_free(h)
    # the series read here (input, ysteady, ystar, ygamma, yk) are sampled on
    # one grid without gaps: NaN separates pieces only in the minor and major
    # loop series (src/pipeline/scene_run.c)
    return out[0, :n], out[1, :n], out[2, :n]


def _sets_of(model: Model, inp: Input, *more: bytes) -> List[bytes]:
    """The string keys of model and inp, and more, as overrides (scene_sets)."""
    return model.scene_sets() + inp.scene_sets() + list(more)


def read_data(path: PathLike, u: Union[str, int] = "1", y: Union[str, int] = "2", t: Union[str, int, None] = None,
              split: Union[str, int, None] = None, u_scale: float = 1.0, y_scale: float = 1.0, t_scale: float = 1.0,
              record: int = 0) -> Dict[str, Array]:
    """Measured samples of a CSV or whitespace-separated file.

    Read by the same reader as a scene's [data NAME] (hy_table.h;
    docs/SCENES.md "Measured data").

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    u, y, t : str or int
        The columns of the input, the output and (optional) time: a header
        name or a 1-based index.
    split : str or int, optional
        A column whose changes start a new record.
    u_scale, y_scale, t_scale : float
        Factors to the units wanted (1e-3 for a column in mm to m).
    record : int
        Keep only this record (1-based); 0 keeps all.

    Returns
    -------
    dict of str to ndarray
        "u", "y" (and "t") in the scaled units; "records" (row offsets:
        record j = rows records[j]:records[j+1]); "area" (each record's
        shoelace area ∮ u dy, unit of u x unit of y, counter-clockwise > 0).

    Raises
    ------
    FileNotFoundError, PermissionError
        The file is missing or unreadable.
    SceneError
        A bad file ("FILE:LINE:COL: what"), or a record it does not have.

    Examples
    --------
    >>> import os, tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = os.path.join(d, "sq.csv")
    ...     _ = open(p, "w").write("u,y\\n0,0\\n1,0\\n1,1\\n0,1\\n")
    ...     print(hystviz.read_data(p, u="u", y="y")["area"])
    [1.]
    """
    with open(path, "rb") as f:
        text = f.read(_lib.table_max_bytes + 1)
    spec = _lib.TableSpec()
    for i, c in enumerate((u, y, t, split)):
        spec.col[i] = None if c is None else str(c).encode()
    spec.scale[0], spec.scale[1], spec.scale[2] = float(u_scale), float(y_scale), float(t_scale)
    tb = _lib.Table()
    err = _lib.Error()
    _check(_lib.table_parse(text, len(text), os.fsencode(path), ctypes.byref(spec), 1, ctypes.byref(tb),
                            ctypes.byref(err)), err)
    try:
        rec = np.array([tb.rec[j] for j in range(tb.nrec + 1)], dtype=np.int64)
        if record:
            if not 1 <= record <= tb.nrec:
                raise SceneError(1, f"{path}: record {record} does not exist: the file has {tb.nrec} records")
            a, b = int(rec[record - 1]), int(rec[record])
            rec = np.array([0, b - a], dtype=np.int64)
        else:
            a, b = 0, int(tb.n)
        out = {"u": _array(ctypes.addressof(tb.u.contents), tb.n)[a:b].copy(),
               "y": _array(ctypes.addressof(tb.y.contents), tb.n)[a:b].copy(), "records": rec}
        if t is not None:
            out["t"] = _array(ctypes.addressof(tb.t.contents), tb.n)[a:b].copy()
    finally:
        _lib.table_free(ctypes.byref(tb))
    out["area"] = np.array([loop_area(out["u"][rec[j]:rec[j + 1]], out["y"][rec[j]:rec[j + 1]])
                            for j in range(len(rec) - 1)])
    return out


def _forc_arrays(d: _lib.ForcData) -> Dict[str, Any]:
    """ha, hb, m (one entry per point), curve (the row offsets) of an hy_forc_data."""
    nc, n = int(d.ncurves), int(d.npoints)
    hb = _array(ctypes.addressof(d.hb.contents), n).copy() if n else np.zeros(0)
    m = _array(ctypes.addressof(d.m.contents), n).copy() if n else np.zeros(0)
    first = np.array([d.curve[i].first for i in range(nc)] + [n], dtype=np.int64)
    ha = np.repeat(np.array([d.curve[i].ha for i in range(nc)]), np.diff(first))
    return {"ha": ha, "hb": hb, "m": m, "curves": first}


def read_forc(path: PathLike, drift: bool = False) -> Dict[str, Any]:
    """A measured FORC file (MicroMag 2900/3900 text or CSV rows H_a,H_b,M).

    Read by libhystviz's reader (hy_forc_read, the one of `hystviz forc`
    and of a scene's [forc] file; docs/FORC.md).

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    drift : bool
        Apply the drift correction (the calibration points').

    Returns
    -------
    dict
        NumPy arrays "ha", "hb" (fields, in the file's field unit), "m"
        (moment, in its moment unit), one entry a point, curve after curve;
        "curves" (row offsets: curve i = rows curves[i]:curves[i+1]); and
        the file's "field_unit", "moment_unit", "field_to_tesla".

    Raises
    ------
    FileNotFoundError, PermissionError
        The file is missing or unreadable.
    SceneError
        A bad file ("FILE:LINE:COL: what").

    Examples
    --------
    >>> d = hystviz.read_forc(hystviz.scene_path("data/forc/conventional_example.forc"))
    >>> d["field_unit"], len(d["curves"]) - 1
    ('T', 120)
    """
    d = _forc_load(path=path, drift=drift)
    try:
        out = _forc_arrays(d)
        out.update(field_unit=d.field_unit.decode(), moment_unit=d.moment_unit.decode(),
                   field_to_tesla=d.field_to_tesla)
    finally:
        _lib.forc_data_free(ctypes.byref(d))
    return out


def _forc_load(path: Optional[PathLike] = None, drift: bool = False, ha: Optional[ArrayLike] = None,
               hb: Optional[ArrayLike] = None, m: Optional[ArrayLike] = None,
               model: Optional[Callable[[float], float]] = None,
               protocol: Optional[Mapping[str, float]] = None) -> _lib.ForcData:
    d = _lib.ForcData()
    err = _lib.Error()
    if path is not None:
        with open(path, "rb") as f:
            text = f.read(_lib.forc_max_bytes + 1)
        if len(text) > _lib.forc_max_bytes:
            raise SceneError(1, f"{path}: larger than {_lib.forc_max_bytes} bytes")
        _check(_lib.forc_read(ctypes.byref(d), text, len(text), os.fsencode(path), ctypes.byref(err)), err)
    elif model is not None:
        if protocol is None:
            raise ValueError("forc: a model needs protocol=dict(hsat=, ha_lo=, ha_hi=, ncurves=)")
        pr = _lib.ForcProtocol(float(protocol["hsat"]), float(protocol["ha_lo"]), float(protocol["ha_hi"]),
                               float(protocol.get("hb_max", protocol["ha_hi"])), int(protocol["ncurves"]))
        failure: List[BaseException] = []

        def step(ctx: Any, u: float, y: Any, e: Any) -> int:
            assert model is not None
            try:
                y[0] = float(model(u))
                return 0
            except Exception as ex:  # raised again below, after the C call returns
                failure.append(ex)
                return 1

        cb = _lib.RateindFn(step)
        rc = _lib.forc_protocol_run(ctypes.byref(d), ctypes.byref(pr), cb, None, ctypes.byref(err))
        if failure:
            _lib.forc_data_free(ctypes.byref(d))
            raise failure[0]
        _check(rc, err)
    else:
        if ha is None or hb is None or m is None:
            raise ValueError("forc: give ha, hb and m together")
        ha, hb, m = (np.ascontiguousarray(a, dtype=np.float64) for a in (ha, hb, m))
        if not (ha.shape == hb.shape == m.shape and ha.ndim == 1):
            raise ValueError("forc: ha, hb and m must be 1-D arrays of one length")
        starts = np.flatnonzero(np.r_[True, ha[1:] != ha[:-1]]) if len(ha) else np.zeros(0, dtype=np.int64)
        counts = np.diff(np.r_[starts, len(ha)]).astype(np.uintp)
        has = np.ascontiguousarray(ha[starts])
        _check(_lib.forc_data_set(ctypes.byref(d), len(starts), has.ctypes.data_as(_lib._dp),
                                  counts.ctypes.data_as(ctypes.POINTER(ctypes.c_size_t)), hb.ctypes.data_as(_lib._dp),
                                  m.ctypes.data_as(_lib._dp), ctypes.byref(err)), err)
    if drift:
        rc = _lib.forc_drift(ctypes.byref(d), ctypes.byref(err))
        if rc:
            _lib.forc_data_free(ctypes.byref(d))
            _check(rc, err)
    return d


def forc(path: Optional[PathLike] = None, *, ha: Optional[ArrayLike] = None,
         hb: Optional[ArrayLike] = None, m: Optional[ArrayLike] = None,
         model: Optional[Callable[[float], float]] = None, protocol: Optional[Mapping[str, float]] = None,
         sf: float = 3.0, sc0: Optional[float] = None, sc1: Optional[float] = None, extend: bool = True,
         drift: bool = False) -> Dict[str, Any]:
    """The FORC curves and distribution rho = -1/2 d2M/dH_a dH_b.

    Local second-order regression (Pike et al. 1999; docs/FORC.md),
    computed by libhystviz as `hystviz forc` computes it.  Give one source.

    Parameters
    ----------
    path : str or os.PathLike, optional
        A measured file (MicroMag or CSV).
    ha, hb, m : array_like, optional
        One entry a point (fields in T or A/m, moment in any unit);
        consecutive equal ha make a curve.
    model : callable, optional
        A rate-independent model model(u) -> y that moves monotonically to
        u, run through the FORC protocol.
    protocol : dict, optional
        For model: hsat, ha_lo, ha_hi, ncurves, hb_max (default ha_hi), fields
        in the model's input unit.
    sf : float
        The smoothing factor (points each side of the fit).
    sc0, sc1 : float, optional
        Vary the smoothing factor from sc0 to sc1 across H_c (both or none).
    extend : bool
        Extend the data into H_b < H_a (Harrison & Feinberg).
    drift : bool
        Apply the drift correction.

    Returns
    -------
    dict
        The curves "ha", "hb", "m", "curves" (row offsets) and the
        distribution: "hc" (nc), "hu" (nu), "rho" (nu x nc, moment unit per
        field unit squared; NaN outside the data).

    Raises
    ------
    ValueError
        Not one source, or arrays of different lengths.
    FileNotFoundError, PermissionError
        path is missing or unreadable.
    SceneError
        A bad file ("FILE:LINE:COL: what") or data the method cannot use.

    Examples
    --------
    >>> hb = np.linspace(-1, 1, 21)
    >>> ha = np.repeat(np.linspace(-1, 1, 21), 21)
    >>> d = hystviz.forc(ha=ha, hb=np.tile(hb, 21), m=np.tanh(np.tile(hb, 21)))
    >>> d["rho"].shape == (len(d["hu"]), len(d["hc"]))
    True
    """
    if sum(x is not None for x in (path, ha, model)) != 1:
        raise ValueError("forc: give one of path, ha/hb/m or model")
    d = _forc_load(path=path, drift=drift, ha=ha, hb=hb, m=m, model=model, protocol=protocol)
    g = _lib.ForcGrid()
    err = _lib.Error()
    try:
        o = _lib.forc_defaults()
        o.sf, o.extend = float(sf), 1 if extend else 0
        if sc0 is not None or sc1 is not None:
            if sc0 is None or sc1 is None:
                raise ValueError("forc: give both sc0 and sc1, or neither")
            o.sc0, o.sc1 = float(sc0), float(sc1)
        _lib.forc_grid_auto(ctypes.byref(d), ctypes.byref(o), ctypes.byref(g))
        nfit = ctypes.c_size_t()
        _check(_lib.forc_rho(ctypes.byref(d), ctypes.byref(o), ctypes.byref(g), ctypes.byref(nfit),
                             ctypes.byref(err)), err)
        out = _forc_arrays(d)
        nc, nu = int(g.nc), int(g.nu)
        dc = (g.hc1 - g.hc0) / (nc - 1) if nc > 1 else 0.0
        du = (g.hu1 - g.hu0) / (nu - 1) if nu > 1 else 0.0
        out["hc"] = g.hc0 + np.arange(nc) * dc  # as hystviz forc computes each node's value
        out["hu"] = g.hu0 + np.arange(nu) * du
        out["rho"] = _array(ctypes.addressof(g.rho.contents), nc * nu).copy().reshape(nu, nc)
    finally:
        _lib.forc_grid_free(ctypes.byref(g))
        _lib.forc_data_free(ctypes.byref(d))
    return out


def loop_area(u: ArrayLike, y: ArrayLike) -> float:
    """The signed area of the closed polygon (u[i], y[i]) (hy_table_area).

    (1/2) sum(u_i y_{i+1} - u_{i+1} y_i) = ∮ u dy, positive counter-clockwise.

    Parameters
    ----------
    u, y : array_like
        The vertices, one length (any units).

    Returns
    -------
    float
        The area, in the unit of u times the unit of y.

    Raises
    ------
    ValueError
        u and y differ in length.

    Examples
    --------
    >>> hystviz.loop_area([0, 1, 1, 0], [0, 0, 1, 1])
    1.0
    """
    ua = np.ascontiguousarray(u, dtype=float)
    ya = np.ascontiguousarray(y, dtype=float)
    if ua.shape != ya.shape:
        raise ValueError("loop_area: u and y differ in length")
    return float(_lib.table_area(ua.ctypes.data_as(_lib._dp), ya.ctypes.data_as(_lib._dp), len(ua)))


def steady_loop(model: Model, input: Input, points: int = 2000) -> Tuple[Array, Array, Array]:
    """The steady state y° over one period (hy_steady_loop).

    Parameters
    ----------
    model : Model
        The model (its keys in their units: docs/SCENES.md, help(hystviz.models[kind])).
    input : Input
        The periodic input u.
    points : int
        Samples over the period (points + 1 values with both ends).

    Returns
    -------
    t, u, y : ndarray
        Time (s), the input (its unit) and the output (the model's output
        unit: N for a friction force, A/m for a magnetisation), float64.

    Raises
    ------
    SceneError
        A key out of its range, points out of [compute] points' range, or a
        model and input the library refuses.

    Examples
    --------
    >>> m = hystviz.Model("lugre", sigma0=6)
    >>> u = hystviz.Input("bimodal", umin1=0, umin2=0.5, umax1=1, umax2=1.5)
    >>> t, uu, y = hystviz.steady_loop(m, u, points=200)
    >>> t.shape, float(y[0]) == float(y[-1])
    ((201,), True)
    """
    n = int(points) + 1
    if not _POINTS_MIN < n <= _POINTS_MAX + 1:  # before the arrays are made
        raise SceneError(1, f"steady_loop: 'points' in [compute] must be {_POINTS_MIN} to {_POINTS_MAX}, got {n - 1}")
    out = _empty((3, n))
    # err NULL: the message is asked for only where the call failed (the same
    # call again, as the library is deterministic), so the usual call makes no
    # hy_error; the GIL is released for the call.  The compiled fast path
    # where _lib found it (src/python/_fast.c), else ctypes
    if _steady_fast is not None:
        rc = _steady_fast(_PY_NAME, model._btext, input._btext, model._sets, input._sets, n - 1, out)
    else:
        a = _addressof(_c_char.from_buffer(out))  # type: ignore[arg-type]  # (a buffer; a third of out.ctypes.data)
        sets = model._sets + input._sets
        rc = _steady(_PY_NAME, model._btext, input._btext, _carray(sets) if sets else None, len(sets), n - 1,
                     a, a + 8 * n, a + 16 * n, None)
    if rc:
        sets = model._sets + input._sets
        err = _lib.Error()
        _steady(_PY_NAME, model._btext, input._btext, _carray(sets) if sets else None, len(sets), n - 1,
                None, None, None, ctypes.byref(err))
        _check(rc, err)
    return out[0], out[1], out[2]


def limit(model: Model, input: Input, points: int = 2000, cycles: int = 1) -> Tuple[Array, Array, Array]:
    """The limit y*_u as γ → ∞ from the model's x0.

    Parameters
    ----------
    model : Model
        The model (its keys in their units: docs/SCENES.md, help(hystviz.models[kind])).
    input : Input
        The periodic input u.
    points : int
        Samples a period.
    cycles : int
        Periods.

    Returns
    -------
    t, u, y : ndarray
        Time (s), the input (its unit) and the output (the model's output
        unit: N for a friction force, A/m for a magnetisation), float64.

    Raises
    ------
    SceneError
        A key out of its range, or a model and input the library refuses.

    Examples
    --------
    >>> m = hystviz.Model("lugre", sigma0=6)
    >>> u = hystviz.Input("bimodal", umin1=0, umin2=0.5, umax1=1, umax2=1.5)
    >>> hystviz.limit(m, u, points=100, cycles=2)[2].shape
    (201,)
    """
    return _tuy(_scene_bytes(model.scene_text(), input.scene_text(), "[series y]\ndata = ystar\n", points, cycles),
                points * cycles, _sets_of(model, input))


def ygamma(model: Model, input: Input, gamma: float, points: int = 2000, cycles: int = 1,
           solver: str = "exact") -> Tuple[Array, Array, Array]:
    """The output y_γ at time scale gamma (the input u(γ t) run slower as γ grows).

    Parameters
    ----------
    model : Model
        The model (its keys in their units: docs/SCENES.md, help(hystviz.models[kind])).
    input : Input
        The periodic input u.
    gamma : float
        The time scale (dimensionless, > 0).
    points : int
        Samples a period.
    cycles : int
        Periods.
    solver : str
        exact, or one of the schema's [compute] solver names (GSL steppers).

    Returns
    -------
    t, u, y : ndarray
        Time (s), the input (its unit) and the output (the model's output
        unit: N for a friction force, A/m for a magnetisation), float64.

    Raises
    ------
    SceneError
        A key out of its range, or a model and input the library refuses.

    Examples
    --------
    >>> m = hystviz.Model("lugre", sigma0=6)
    >>> u = hystviz.Input("bimodal", umin1=0, umin2=0.5, umax1=1, umax2=1.5)
    >>> hystviz.ygamma(m, u, 10, points=100)[2].shape
    (101,)
    """
    solver_set = f"compute.solver={_text_param('solver', solver)}".encode()  # the --set parser, not scene text
    return _tuy(_scene_bytes(model.scene_text(), input.scene_text(),
                             f"[series y]\ndata = ygamma\ngamma = {_fmt(float(gamma))}\n", points, cycles),
                points * cycles, _sets_of(model, input, solver_set))


def kcycles(model: Model, input: Input, k: int, points: int = 2000) -> Tuple[Array, Array, Array]:
    """y*_{u,k}, the limit on its k-th period, against the time within the period.

    Parameters
    ----------
    model : Model
        The model (its keys in their units: docs/SCENES.md, help(hystviz.models[kind])).
    input : Input
        The periodic input u.
    k : int
        The period (1 = the first).
    points : int
        Samples a period.

    Returns
    -------
    t, u, y : ndarray
        Time (s), the input (its unit) and the output (the model's output
        unit: N for a friction force, A/m for a magnetisation), float64.

    Raises
    ------
    SceneError
        A key out of its range, or a model and input the library refuses.

    Examples
    --------
    >>> m = hystviz.Model("lugre", sigma0=6)
    >>> u = hystviz.Input("bimodal", umin1=0, umin2=0.5, umax1=1, umax2=1.5)
    >>> t, _, y = hystviz.kcycles(m, u, 2, points=100)
    >>> float(t[0]), t.shape
    (0.0, (101,))
    """
    return _tuy(_scene_bytes(model.scene_text(), input.scene_text(), f"[series y]\ndata = yk\nk = {int(k)}\n", points),
                points, _sets_of(model, input))


def minor_loops(model: Model, input: Input) -> List[MinorLoop]:
    """The minor loops of the steady state y°, with their areas.

    Parameters
    ----------
    model : Model
        The model (its keys in their units: docs/SCENES.md, help(hystviz.models[kind])).
    input : Input
        The periodic input u.

    Returns
    -------
    list of MinorLoop
        Each loop's turning points and area ∮ y du (output unit x input unit).

    Raises
    ------
    SceneError
        A key out of its range, or a model and input the library refuses.

    Examples
    --------
    >>> m = hystviz.Model("lugre", sigma0=6)
    >>> u = hystviz.Input("bimodal", umin1=0, umin2=0.5, umax1=1, umax2=1.5)
    >>> [round(loop.area, 6) for loop in hystviz.minor_loops(m, u)]
    [0.199107]
    """
    return _run(_scene(model, input, "[series y]\ndata = minor\n", 2, kind="loop"), _sets_of(model, input)).minor


_HERE = os.path.dirname(os.path.abspath(__file__))


def _scene_dirs() -> List[str]:
    """Where scene_path looks, in order (see its docstring)."""
    env = os.environ.get("HYSTVIZ_SCENES")
    return ([env] if env else []) + [os.path.join(_HERE, "scenes"),
                                     os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(_HERE))), "scenes")]


def scene_path(name: str) -> str:
    """The path of one of the papers' scenes (or files beside them) that hystviz ships.

    Looked up in $HYSTVIZ_SCENES when set, then in the package's own
    scenes/ (a wheel carries them there; `meson install` links it to
    share/hystviz/scenes), then in the source tree's scenes/ (the package
    run from src/python).  The scenes include style.scene beside them.

    Parameters
    ----------
    name : str
        A scene's name with or without ".scene" ("fig15_minor_loop_ex4"),
        or a path below scenes/ ("data/forc").

    Returns
    -------
    str
        The absolute path of the first one found.

    Raises
    ------
    FileNotFoundError
        No such scene in any of those places (the message lists them).

    Examples
    --------
    >>> os.path.basename(hystviz.scene_path("fig15_minor_loop_ex4"))
    'fig15_minor_loop_ex4.scene'
    """
    tried = []
    for d in _scene_dirs():
        for cand in (name + ".scene", name) if not name.endswith(".scene") else (name,):
            p = os.path.join(d, cand)
            if os.path.exists(p):
                return os.path.abspath(p)
        tried.append(d)
    raise FileNotFoundError(f"hystviz: no scene {name!r} in {', '.join(tried)} (set HYSTVIZ_SCENES to a scenes "
                            "directory)")


def plot(scene_or_result: Union[PathLike, Result], ax: Any = None, **overrides: Value) -> Any:
    """Draws a scene's series into a matplotlib Axes, beside the user's own.

    Each [series NAME] becomes one line labelled NAME; a gap (NaN) in a
    series breaks its line as in the figure; the axes get the scene's
    quantities as labels when the figure has one x and one y series kind.

    Parameters
    ----------
    scene_or_result : str, os.PathLike or Result
        A .scene file or a scene's text (computed with run()), or a Result.
    ax : matplotlib.axes.Axes, optional
        Where to draw; default: matplotlib.pyplot.gca().
    **overrides
        Overrides for run() (model__sigma0=2), for a scene only.

    Returns
    -------
    matplotlib.axes.Axes
        ax, with one Line2D a series.

    Raises
    ------
    ImportError
        No ax given and matplotlib is not installed (apt-get install
        python3-matplotlib).
    FileNotFoundError, PermissionError
        The scene file is missing or unreadable.
    SceneError
        The library refused the scene.
    ValueError
        Overrides given with a Result.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> _ = hystviz.plot(hystviz.scene_path("fig15_minor_loop_ex4"), ax=ax)
    >>> sorted(line.get_label() for line in ax.get_lines())
    ['major', 'minor', 't1', 't5']
    >>> plt.close(fig)
    """
    if isinstance(scene_or_result, Result):
        if overrides:
            raise ValueError("hystviz.plot: overrides apply to a scene, not to a Result")
        res = scene_or_result
    else:
        res = run(scene_or_result, **overrides)
    if ax is None:
        import matplotlib.pyplot as plt  # type: ignore[import]
        ax = plt.gca()
    for name, (x, y) in res.series.items():
        ax.plot(x, y, label=name)
    return ax


from . import boucwen  # noqa: E402  (uses the names above)
from ._sweep import sweep, SweepError  # noqa: E402,F401  (a parameter study as arrays, issue 37)


class FitResult:
    """What fit() returns: the numbers `hystviz fit` prints, bit for bit.

    keys: the free [model] keys; estimates, std_errors, ci_low, ci_high,
    start, lower, upper (per key, numpy arrays); unidentifiable (per key: 0,
    or 1 a direction the data do not see | 2 an error wider than the range);
    correlation (p x p); u, measured, model, residuals (per measured point,
    the data sets one after another; residual = model - measured); data (the
    [data] names) and offsets (where each begins in those arrays); rss, rms,
    nrms, max_abs, fit_index, cond, dof, iterations, evaluations, seconds,
    starts, failed; scene_text (the scene with the estimates written in).
    Units: each key's own (docs/SCENES.md); residuals in the output's unit.

    Parameters
    ----------
    h : int
        The library's hy_scene_fitted (fit() makes it and frees it).

    Examples
    --------
    >>> import os, tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     with open(os.path.join(d, "p.csv"), "w") as f:
    ...         _ = f.write("u,y\\n0,0\\n1,0.7\\n2,1.7\\n1,1.3\\n0,0.3\\n-1,-0.7\\n-2,-1.7\\n")
    ...     with open(os.path.join(d, "p.scene"), "w") as f:
    ...         _ = f.write("[model]\\nkind = play\\nplay_r = 0.2\\n[data d]\\nfile = p.csv\\nu = u\\ny = y\\n"
    ...                     "[input]\\nkind = data\\ndata = d\\n[figure]\\nkind = loop\\n"
    ...                     "[series m]\\ndata = modelled\\nof = d\\n")
    ...     r = hystviz.fit(os.path.join(d, "p.scene"), ["play_r"])
    >>> r.keys, r.estimates.shape, round(float(r.estimates[0]), 6)
    (['play_r'], (1,), 0.3)
    """

    _arrays = {"estimates": "theta", "std_errors": "se", "ci_low": "ci_lo", "ci_high": "ci_hi", "start": "start",
               "lower": "lo", "upper": "hi", "unidentifiable": "unident", "u": "u", "measured": "y",
               "model": "model", "residuals": "resid"}
    _stats = ("rss", "rms", "nrms", "max_abs", "fit_index", "cond", "dof", "iterations", "evaluations", "seconds",
              "starts", "failed")

    keys: List[str]
    data: List[str]
    scene_text: str
    estimates: Array
    std_errors: Array
    correlation: Array
    offsets: Any
    unidentifiable: Any
    rms: float

    def __init__(self, h: int) -> None:
        def arr(name: str) -> Array:
            n = ctypes.c_size_t()
            p = _lib.fitted_array(h, name.encode(), ctypes.byref(n))
            return _array(p, n.value) if n.value else np.empty(0)

        for attr, name in self._arrays.items():
            setattr(self, attr, arr(name))
        self.unidentifiable = self.unidentifiable.astype(int)
        p = len(self.estimates)
        self.correlation = arr("corr").reshape(p, p)
        self.offsets = arr("offsets").astype(int)
        for s in self._stats:
            v = _lib.fitted_stat(h, s.encode())
            setattr(self, s, int(v) if s in ("dof", "iterations", "evaluations", "starts", "failed") else v)
        self.keys = [_lib.fitted_key(h, j).decode() for j in range(p)]
        self.data = [_lib.fitted_data(h, j).decode() for j in range(len(self.offsets) - 1)]
        self.scene_text = _lib.fitted_text(h).decode()

    def __repr__(self) -> str:
        est = ", ".join(f"{k}={v:.6g}\u00b1{s:.2g}" for k, v, s in zip(self.keys, self.estimates, self.std_errors))
        return f"<hystviz.FitResult {est}; RMS {self.rms:.4g}>"


def fit(scene: PathLike, free: Union[str, Sequence[str]], data: Union[str, Sequence[str], None] = None,
        starts: int = 0, seed: int = 1, jobs: int = 1) -> FitResult:
    """Fits [model] keys of a scene to its measured data, as `hystviz fit` does.

    `hystviz fit SCENE --free ... [--data ...] --starts N --seed S -j J`
    as a call (docs/FIT.md).

    Parameters
    ----------
    scene : str or os.PathLike
        The .scene file with its [data] sections.
    free : str or list of str
        The [model] keys to fit ("a,b" or ["a", "b"]).
    data : str or list of str, optional
        The [data] names fitted at once (default: the one [input] names).
    starts : int
        Extra random starts (multistart); 0: the scene's values only.
    seed : int
        The starts' random seed.
    jobs : int
        Threads.

    Returns
    -------
    FitResult
        Estimates in each key's unit, their errors, the fit's statistics.

    Raises
    ------
    FileNotFoundError, PermissionError
        The scene is missing or unreadable.
    SceneError
        A bad key or data file (the command's message).
    ValueError
        A NUL byte or a line break in a key or name.

    Examples
    --------
    >>> import os, tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     with open(os.path.join(d, "p.csv"), "w") as f:
    ...         _ = f.write("u,y\\n0,0\\n1,0.7\\n2,1.7\\n1,1.3\\n0,0.3\\n-1,-0.7\\n-2,-1.7\\n")
    ...     with open(os.path.join(d, "p.scene"), "w") as f:
    ...         _ = f.write("[model]\\nkind = play\\nplay_r = 0.2\\n[data d]\\nfile = p.csv\\nu = u\\ny = y\\n"
    ...                     "[input]\\nkind = data\\ndata = d\\n[figure]\\nkind = loop\\n"
    ...                     "[series m]\\ndata = modelled\\nof = d\\n")
    ...     r = hystviz.fit(os.path.join(d, "p.scene"), ["play_r"])
    >>> round(float(r.estimates[0]), 6), r.rms < 1e-9
    (0.3, True)
    """
    keys = free.split(",") if isinstance(free, str) else list(free)
    names = [] if data is None else (data.split(",") if isinstance(data, str) else list(data))
    ek = [_text_param("free key", k).encode() for k in keys]
    ed = [_text_param("data name", d).encode() for d in names]
    path = _readable(scene)
    h = ctypes.c_void_p()
    err = _lib.Error()
    rc = _lib.fit_scene(path, _carray(ek), len(ek), _carray(ed) if ed else None, len(ed), int(starts), int(seed),
                        int(jobs), ctypes.byref(h), ctypes.byref(err))
    _check(rc, err)
    assert h.value is not None  # a status of 0 comes with a result
    try:
        return FitResult(h.value)
    finally:
        _lib.fitted_free(h.value)
