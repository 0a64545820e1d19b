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
    >>> fig = hystviz.render("scenes/fig15_minor_loop_ex4.scene", model__sigma0=2)  # doctest: +SKIP

Scene keys are written section.key; as a keyword argument, section__key
(model__sigma0=2), or pass a dict: render(scene, **{"model.sigma0": 2}).
Errors raise hystviz.SceneError with the C message (file:line:col first).
Model and Input take the keys of the scene file's [model] and [input]
sections (docs/SCENES.md; help(hystviz.Model) lists them with their ranges).
"""
import ctypes
import json
import math
import os

import numpy as np

from . import _lib

__all__ = ["SceneError", "Model", "Input", "models", "Result", "Figure", "MinorLoop", "run", "render", "steady_loop",
           "limit", "ygamma", "kcycles", "minor_loops", "schema", "boucwen", "read_data", "loop_area", "fit", "FitResult",
           "__version__", "sweep", "SweepError"]

__version__ = _lib.version().decode()


class SceneError(ValueError):
    """A scene or a parameter the library refused; str() is its message."""

    def __init__(self, code, msg):
        super().__init__(msg)
        self.code = code


def _check(rc, err):
    if rc:
        raise SceneError(rc, err.msg.decode("utf-8", "replace"))


def schema():
    """The scene vocabulary (sections, keys, kinds, ranges, defaults, docs) as a dict."""
    p = _lib.schema_json()
    if not p:
        raise MemoryError("hystviz: out of memory for the schema")
    try:
        return json.loads(ctypes.string_at(p).decode())
    finally:
        _lib.libc.free(p)


_SCHEMA = schema()
_SECTIONS = {s["name"]: s for s in _SCHEMA["sections"]}


def _keydoc(k):
    lo = hi = ""
    if k["min"] is not None:
        lo = ("> " if k["min_exclusive"] else ">= ") + repr(k["min"])
    if k["max"] is not None:
        hi = ("< " if k["max_exclusive"] else "<= ") + repr(k["max"])
    rng = ", ".join(x for x in (lo, hi) if x)
    dflt = f" (default {k['default']})" if k["default"] is not None else ""
    return f"    {k['name']} [{k['kind']}{', ' + rng if rng else ''}]{dflt}: {k['doc']}"


def _text_param(what, v):
    """A string parameter (a value, a key, a format name) as the library
    takes it: a NUL byte would cut it where C reads it and a line break would
    start a new line of scene text, so either is refused with ValueError."""
    s = v if isinstance(v, str) else str(v)
    for ch, name in (("\0", "a NUL byte"), ("\n", "a newline"), ("\r", "a carriage return")):
        if ch in s:
            raise ValueError(f"hystviz: {what}: {name} is not allowed here (got {s!r})")
    return s


def _set_value(key, v):
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


def _typed(v):
    """Whether v is a typed value (a number, a bool, or a list of them) that
    _fmt writes as scene text itself; anything else is a string, which goes to
    the library's own --set parser (_text_param), never into scene text."""
    if isinstance(v, (bool, int, float, np.integer, np.floating)):
        return True
    if isinstance(v, (list, tuple, np.ndarray)):
        return all(_typed(x) and not isinstance(x, (list, tuple, np.ndarray)) for x in v)
    return False


def _fmt(v):
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

    def __init__(self, kind, **params):
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
        self._sets = [f"{self.section}.{k}={_set_value(f'{self.section}.{k}', v)}".encode()
                      for k, v in params.items() if not _typed(v)]

    def scene_text(self):
        """The section's typed keys as scene text (its string keys are in scene_sets)."""
        return self._text

    def scene_sets(self):
        """The section's string keys as overrides b"section.key=value" for the library's --set parser."""
        return list(self._sets)

    def __repr__(self):
        args = ", ".join([repr(self.kind)] + [f"{k}={v!r}" for k, v in self.params.items()])
        return f"{type(self).__name__}({args})"


class Model(_Section):
    section = "model"

    def __init__(self, kind, **params):
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


_MODELS = {m["name"]: m for m in _SCHEMA["models"]}
_MODEL_KEYS = {k["name"]: k for k in _SECTIONS["model"]["keys"]}


def _model_class(spec):
    kind = spec["name"]

    def init(self, **params):
        Model.__init__(self, kind, **params)
    doc = (f"The '{kind}' model: Model('{kind}', **parameters).\n\nState: {spec['state']}.\n"
           f"Capabilities: {', '.join(spec['caps']) or 'none'}.\nQuantities drawn: "
           f"{', '.join(spec['quantities']) or '-'}.\n\nParameters (docs/SCENES.md):\n" +
           "\n".join(_keydoc(_MODEL_KEYS[p]) for p in spec["params"] if p in _MODEL_KEYS))
    name = "".join(w.capitalize() for w in kind.replace("_", "-").split("-"))
    return type(name, (Model,), {"__init__": init, "__doc__": doc})


# one class per kind of the model table: models["lugre"](sigma0=6), help(models["preisach"])
models = {kind: _model_class(spec) for kind, spec in _MODELS.items()}

for _cls in (Model, Input):
    _sec = _SECTIONS[_cls.section]
    _cls.__doc__ = (f"{_cls.__name__}(kind, **keys): the scene's [{_cls.section}] section.\n\n"
                    f"{_sec['doc']}\n\nKeys (as in docs/SCENES.md):\n" +
                    "\n".join(_keydoc(k) for k in _sec["keys"]))


class MinorLoop:
    """A loop of the steady state y°: where it starts and turns (u), its area
    ∮ y du (energy per cycle of the loop) and the area of its own (less the
    loops nested in it), depth 0 for the major loop."""

    def __init__(self, c):
        self.u_start, self.u_turn = c.u_start, c.u_turn
        self.y_start, self.y_close = c.y_start, c.y_close
        self.area, self.own_area, self.depth = c.area, c.own_area, c.depth

    def __repr__(self):
        return (f"MinorLoop(u_start={self.u_start!r}, u_turn={self.u_turn!r}, area={self.area!r}, "
                f"depth={self.depth})")


class Figure:
    """A rendered figure: Jupyter shows it (SVG); save() writes any format."""

    def __init__(self, result):
        self._result = result
        self.svg = result.render("svg")

    def _repr_svg_(self):
        return self.svg.decode("utf-8")

    def save(self, path, format=None):
        """Writes the figure to path in format (svg, pdf, png; default: from the
        extension) through libhystviz's output writer, as `hystviz render`
        writes (hy_write_file): a temporary beside path made with O_EXCL and
        renamed onto it, so path is whole or untouched; a symbolic link is
        followed only to a file in path's own directory or below (one out of
        it is refused); a FIFO or device at path is written, never replaced.
        OSError when it cannot be written; ValueError for a NUL byte in path
        or a NUL or line break in format."""
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
    """A computed scene: series (name -> (x, y) NumPy arrays), loops, figure."""

    def __init__(self, handle):
        self._h = handle
        self.series = {}
        self.data = {}
        self.errors = {}
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

    def render(self, format="svg"):
        """The figure's bytes in format (svg, pdf, png), as `hystviz render` writes them."""
        fmt = _text_param("render format", format).encode()
        buf = ctypes.POINTER(ctypes.c_ubyte)()
        n = _lib._sz()
        err = _lib.Error()
        _check(_lib.render(self._h, fmt, ctypes.byref(buf), ctypes.byref(n), ctypes.byref(err)), err)
        try:
            return ctypes.string_at(buf, n.value)
        finally:
            _lib.libc.free(ctypes.cast(buf, ctypes.c_void_p))

    def csv(self):
        """Every series as `hystviz data` prints it."""
        p = ctypes.c_void_p()
        n = _lib._sz()
        err = _lib.Error()
        _check(_lib.csv(self._h, ctypes.byref(p), ctypes.byref(n), ctypes.byref(err)), err)
        try:
            return ctypes.string_at(p, n.value).decode()
        finally:
            _lib.libc.free(p)

    def figure(self):
        return Figure(self)

    def __del__(self):
        if getattr(self, "_h", None):
            _lib.result_free(self._h)
            self._h = None


def _sets(sets, overrides):
    """Overrides as b"section.key=value" for the library's --set parser
    (_set_value: typed values as _fmt writes them, strings checked and, for
    text keys, quoted)."""
    d = dict(sets or {})
    d.update({k.replace("__", "."): v for k, v in overrides.items()})
    return [f"{_text_param('override key', k)}={_set_value(k, v)}".encode() for k, v in d.items()]


def _carray(enc):
    return (ctypes.c_char_p * max(len(enc), 1))(*enc)


def _run(scene, enc, max_work=0.0):
    """run() on overrides already encoded (_sets, scene_sets)."""
    arr = _carray(enc)
    h = ctypes.c_void_p()
    err = _lib.Error()
    if "\n" in scene:
        text = scene.encode()
        rc = _lib.from_text(b"<python>/scene.scene", text, len(text), arr, len(enc), max_work, ctypes.byref(h),
                            ctypes.byref(err))
    else:
        path = os.fsencode(scene)
        if b"\0" in path:
            raise ValueError(f"hystviz: a NUL byte is not allowed in a scene path (got {scene!r})")
        rc = _lib.from_file(path, arr, len(enc), max_work, ctypes.byref(h), ctypes.byref(err))
    _check(rc, err)
    return Result(h.value)


def run(scene, sets=None, max_work=0.0, **overrides):
    """Computes a scene: a path to a .scene file, or its text (anything with a
    newline).  Overrides as section__key=value or sets={"section.key": value}:
    numbers are passed as typed values, strings to the library's --set parser,
    quoted there for text keys (a title "a b" is the text a b, not '"a b"');
    a NUL byte or a line break in a key or a string is a ValueError.
    Returns a Result."""
    return _run(scene, _sets(sets, overrides), max_work)


def render(scene, sets=None, **overrides):
    """The scene's figure (Jupyter displays it; .save(path) writes svg, pdf or png)."""
    return run(scene, sets, **overrides).figure()


def _scene(model, inp, series, points, cycles=1, extra="", kind="timeseries"):
    return (model.scene_text() + inp.scene_text() + f"[compute]\npoints = {int(points)}\ncycles = {int(cycles)}\n"
            + extra + f"[figure]\nkind = {kind}\n" + ("[series u]\ndata = input\n" if kind == "timeseries" else "")
            + series)


def _array(p, n):
    """A copy of n doubles at the C pointer p (one memmove into a new array;
    np.ctypeslib.as_array costs tens of µs a call)."""
    a = np.empty(n)
    ctypes.memmove(a.ctypes.data, p, 8 * n)
    return a


def _tuy(text, points, sets=()):
    """(t, u, y) of a _scene: series 0 is the input, series 1 the output, on
    the same grid; straight through the C calls, no Result, one copy of each
    series into one (3, n) array (the short path of the call-overhead
    benchmark: a few µs over the C call, tests/bench/bench_python.py)."""
    b = text.encode()
    h = ctypes.c_void_p()
    err = _lib.Error()
    _check(_lib.from_text(b"<python>/scene.scene", b, len(b), _carray(sets) if sets else None, len(sets), 0.0,
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


def _sets_of(model, inp, *more):
    """The string keys of model and inp, and more, as overrides (scene_sets)."""
    return model.scene_sets() + inp.scene_sets() + list(more)


def read_data(path, u="1", y="2", t=None, split=None, u_scale=1.0, y_scale=1.0, t_scale=1.0, record=0):
    """Measured samples of a CSV or whitespace-separated file, read by the same
    reader as a scene's [data NAME] (hy_table.h; docs/SCENES.md "Measured
    data"): the columns u, y (and t) chosen by header name or 1-based index,
    each times its scale, and split into records at the column split.
    Returns a dict of NumPy arrays: "u", "y" (and "t"), "records" (the row
    offsets, record j = rows records[j]:records[j+1]) and "area" (each
    record's shoelace area, counter-clockwise > 0); record=K (1-based) keeps
    only that record.  A bad file raises SceneError "FILE:LINE:COL: what"."""
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


def _forc_arrays(d):
    """ha, hb, m (one entry per point), curve (the row offsets) of an hy_forc_data."""
    nc, n = int(d.ncurves), int(d.npoints)
    hb = _array(ctypes.addressof(d.hb.contents), n).copy() if n else np.zeros(0)
    m = _array(ctypes.addressof(d.m.contents), n).copy() if n else np.zeros(0)
    first = np.array([d.curve[i].first for i in range(nc)] + [n], dtype=np.int64)
    ha = np.repeat(np.array([d.curve[i].ha for i in range(nc)]), np.diff(first))
    return {"ha": ha, "hb": hb, "m": m, "curves": first}


def read_forc(path, drift=False):
    """A measured FORC file (MicroMag 2900/3900 text or CSV rows H_a,H_b,M),
    read by libhystviz's reader (hy_forc_read, the one of `hystviz forc` and
    of a scene's [forc] file; docs/FORC.md).  Returns a dict of NumPy
    arrays "ha", "hb", "m" (one entry per point, curve after curve),
    "curves" (row offsets: curve i = rows curves[i]:curves[i+1]) and the
    file's "field_unit", "moment_unit", "field_to_tesla"; drift=True applies
    the drift correction.  A bad file raises SceneError "FILE:LINE:COL: what"."""
    d = _forc_load(path=path, drift=drift)
    try:
        out = _forc_arrays(d)
        out.update(field_unit=d.field_unit.decode(), moment_unit=d.moment_unit.decode(),
                   field_to_tesla=d.field_to_tesla)
    finally:
        _lib.forc_data_free(ctypes.byref(d))
    return out


def _forc_load(path=None, drift=False, ha=None, hb=None, m=None, model=None, protocol=None):
    d = _lib.ForcData()
    err = _lib.Error()
    if path is not None:
        with open(path, "rb") as f:
            text = f.read(_lib.forc_max_bytes + 1)
        if len(text) > _lib.forc_max_bytes:
            raise SceneError(1, f"{path}: larger than {_lib.forc_max_bytes} bytes")
        _check(_lib.forc_read(ctypes.byref(d), text, len(text), os.fsencode(path), ctypes.byref(err)), err)
    elif model is not None:
        pr = _lib.ForcProtocol(float(protocol["hsat"]), float(protocol["ha_lo"]), float(protocol["ha_hi"]),
                               float(protocol.get("hb_max", protocol["ha_hi"])), int(protocol["ncurves"]))
        failure = []

        def step(ctx, u, y, e):
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


def forc(path=None, *, ha=None, hb=None, m=None, model=None, protocol=None, sf=3.0, sc0=None, sc1=None,
         extend=True, drift=False):
    """The FORC curves and distribution rho = -1/2 d2M/dH_a dH_b (local
    second-order regression, Pike et al. 1999; docs/FORC.md), computed by
    libhystviz as `hystviz forc` computes it, of
      - a measured file (path: MicroMag or CSV), or
      - arrays ha, hb, m (one entry per point; consecutive equal ha = a curve), or
      - the FORC protocol on a rate-independent model given as a Python
        callable model(u) -> y that moves the model monotonically to u, with
        protocol = dict(hsat=, ha_lo=, ha_hi=, ncurves=, hb_max= (default ha_hi)).
    Returns a dict of NumPy arrays: the curves "ha", "hb", "m", "curves" (row
    offsets) and the distribution "hc" (nc), "hu" (nu), "rho" (nu x nc: rho[iu,
    ic], NaN outside the data).  Errors raise SceneError (a file's with
    FILE:LINE:COL)."""
    if sum(x is not None for x in (path, ha, model)) != 1:
        raise ValueError("forc: give one of path, ha/hb/m or model")
    d = _forc_load(path=path, drift=drift, ha=ha, hb=hb, m=m, model=model, protocol=protocol)
    g = _lib.ForcGrid()
    err = _lib.Error()
    try:
        o = _lib.forc_defaults()
        o.sf, o.extend = float(sf), 1 if extend else 0
        if sc0 is not None or sc1 is not None:
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


def loop_area(u, y):
    """The signed area of the closed polygon (u[i], y[i]): (1/2) sum(u_i y_{i+1} - u_{i+1} y_i)
    = ∮ u dy, positive counter-clockwise (hy_table_area)."""
    u = np.ascontiguousarray(u, dtype=float)
    y = np.ascontiguousarray(y, dtype=float)
    if u.shape != y.shape:
        raise ValueError("loop_area: u and y differ in length")
    return _lib.table_area(u.ctypes.data_as(_lib._dp), y.ctypes.data_as(_lib._dp), len(u))


def steady_loop(model, input, points=2000):
    """The steady state y° over one period: (t, u, y) NumPy arrays (points samples)."""
    return _tuy(_scene(model, input, "[series y]\ndata = ysteady\n", points), points, _sets_of(model, input))


def limit(model, input, points=2000, cycles=1):
    """The limit y*_u as γ → ∞ from the model's x0: (t, u, y*)."""
    return _tuy(_scene(model, input, "[series y]\ndata = ystar\n", points, cycles), points * cycles,
                _sets_of(model, input))


def ygamma(model, input, gamma, points=2000, cycles=1, solver="exact"):
    """The output y_γ at time scale gamma: (t, u, y)."""
    solver = f"compute.solver={_text_param('solver', solver)}".encode()  # the --set parser, not scene text
    return _tuy(_scene(model, input, f"[series y]\ndata = ygamma\ngamma = {_fmt(float(gamma))}\n", points,
                       cycles), points * cycles, _sets_of(model, input, solver))


def kcycles(model, input, k, points=2000):
    """y*_{u,k}, the limit on its k-th period, against the time within the
    period (t in [0, T]): (t, u, y)."""
    return _tuy(_scene(model, input, f"[series y]\ndata = yk\nk = {int(k)}\n", points), points,
                _sets_of(model, input))


def minor_loops(model, input):
    """The minor loops of the steady state y° (list of MinorLoop with areas)."""
    return _run(_scene(model, input, "[series y]\ndata = minor\n", 2, kind="loop"), _sets_of(model, input)).minor


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
    """

    _arrays = {"estimates": "theta", "std_errors": "se", "ci_low": "ci_lo", "ci_high": "ci_hi", "start": "start",
               "lower": "lo", "upper": "hi", "unidentifiable": "unident", "u": "u", "measured": "y",
               "model": "model", "residuals": "resid"}
    _stats = ("rss", "rms", "nrms", "max_abs", "fit_index", "cond", "dof", "iterations", "evaluations", "seconds",
              "starts", "failed")

    def __init__(self, h):
        def arr(name):
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

    def __repr__(self):
        est = ", ".join(f"{k}={v:.6g}\u00b1{s:.2g}" for k, v, s in zip(self.keys, self.estimates, self.std_errors))
        return f"<hystviz.FitResult {est}; RMS {self.rms:.4g}>"


def fit(scene, free, data=None, starts=0, seed=1, jobs=1):
    """Fits the [model] keys free (a list, or "a,b") of the scene file to its
    measured data: `hystviz fit SCENE --free ... [--data ...] --starts N
    --seed S -j J` as a call (docs/FIT.md).  data: the [data] names fitted at
    once (default: the one [input] names).  Returns a FitResult; a bad key
    or data file raises SceneError with the command's message."""
    keys = free.split(",") if isinstance(free, str) else list(free)
    names = [] if data is None else (data.split(",") if isinstance(data, str) else list(data))
    ek = [_text_param("free key", k).encode() for k in keys]
    ed = [_text_param("data name", d).encode() for d in names]
    path = os.fsencode(scene)
    if b"\0" in path:
        raise ValueError(f"hystviz: a NUL byte is not allowed in a scene path (got {scene!r})")
    h = ctypes.c_void_p()
    err = _lib.Error()
    rc = _lib.fit_scene(path, _carray(ek), len(ek), _carray(ed) if ed else None, len(ed), int(starts), int(seed),
                        int(jobs), ctypes.byref(h), ctypes.byref(err))
    _check(rc, err)
    try:
        return FitResult(h.value)
    finally:
        _lib.fitted_free(h.value)
