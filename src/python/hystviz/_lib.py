# SPDX-License-Identifier: MIT
"""The C library libhystviz, loaded with ctypes (a foreign call releases the
GIL for its whole duration, so long computations do not block other Python
threads).

Where the library is looked up, first found wins:
  1. $HYSTVIZ_LIB (a path to libhystviz.so.0), an explicit override;
  2. this package's own directory (a wheel, `pip install .`, carries it there);
  3. the system's library path by soname (libhystviz.so.0), as `meson install`
     leaves it: the dynamic loader's own search, no ldconfig or compiler run
     (ctypes.util.find_library runs both and costs 0.15-0.5 s an import).
"""
from __future__ import annotations

import ctypes
import importlib.machinery
import os

TYPE_CHECKING = False  # typing for the checker only (hystviz/__init__.py says why)
if TYPE_CHECKING:
    from typing import Any, List

_here = os.path.dirname(os.path.abspath(__file__))
_env = os.environ.get("HYSTVIZ_LIB")
SONAME = "libhystviz.so.0"


def _load() -> ctypes.CDLL:
    tried: List[str] = []
    cands = [_env] if _env else []
    own = os.path.join(_here, SONAME)
    if os.path.exists(own):
        cands.append(own)
    cands.append(SONAME)
    for c in cands:
        try:
            return ctypes.CDLL(c)
        except OSError as e:
            tried.append(f"{c}: {e}")
    raise ImportError("hystviz: cannot load libhystviz (pip install . at the repository root puts it in the "
                      "package; `meson install` on the library path; or set HYSTVIZ_LIB to libhystviz.so.0):\n  "
                      + "\n  ".join(tried))


lib = _load()


class Error(ctypes.Structure):
    _fields_ = [("code", ctypes.c_int), ("msg", ctypes.c_char * 512)]


class Loop(ctypes.Structure):
    """hy_loop of hy_loops.h."""
    _fields_ = [("rho_start", ctypes.c_double), ("rho_turn", ctypes.c_double), ("rho_close", ctypes.c_double),
                ("u_start", ctypes.c_double), ("u_turn", ctypes.c_double),
                ("y_start", ctypes.c_double), ("y_close", ctypes.c_double),
                ("area", ctypes.c_double), ("own_area", ctypes.c_double),
                ("depth", ctypes.c_int), ("starts_at_max", ctypes.c_int)]


class Loops(ctypes.Structure):
    """hy_loops of hy_loops.h (its first fields; the struct is only read)."""
    _fields_ = [("major", Loop), ("minor", ctypes.POINTER(Loop)), ("nminor", ctypes.c_size_t),
                ("area_period", ctypes.c_double)]


class TableSpec(ctypes.Structure):
    """hy_table_spec of hy_table.h: the columns u, y, t, split by name or 1-based index; scales of u, y, t."""
    _fields_ = [("col", ctypes.c_char_p * 4), ("scale", ctypes.c_double * 3)]


class Table(ctypes.Structure):
    """hy_table of hy_table.h (rows, records)."""
    _fields_ = [("n", ctypes.c_size_t), ("u", ctypes.POINTER(ctypes.c_double)), ("y", ctypes.POINTER(ctypes.c_double)),
                ("t", ctypes.POINTER(ctypes.c_double)), ("nrec", ctypes.c_size_t),
                ("rec", ctypes.POINTER(ctypes.c_size_t)), ("line", ctypes.POINTER(ctypes.c_size_t))]


_dp = ctypes.POINTER(ctypes.c_double)
_vp = ctypes.c_void_p
_sz = ctypes.c_size_t
_E = ctypes.POINTER(Error)


def _sig(name: str, res: Any, *args: Any) -> Any:
    f = getattr(lib, name)
    f.restype = res
    f.argtypes = list(args)
    return f


version = _sig("hy_version", ctypes.c_char_p)
from_text = _sig("hy_result_from_text", ctypes.c_int, ctypes.c_char_p, ctypes.c_char_p, _sz,
                 ctypes.POINTER(ctypes.c_char_p), _sz, ctypes.c_double, ctypes.POINTER(_vp), _E)
from_file = _sig("hy_result_from_file", ctypes.c_int, ctypes.c_char_p, ctypes.POINTER(ctypes.c_char_p), _sz,
                 ctypes.c_double, ctypes.POINTER(_vp), _E)
result_free = _sig("hy_result_free", None, _vp)
nseries = _sig("hy_result_nseries", _sz, _vp)
series = _sig("hy_result_series", _sz, _vp, _sz, ctypes.POINTER(_dp), ctypes.POINTER(_dp))
series_copy = _sig("hy_result_series_copy", _sz, _vp, _sz, _vp, _vp, _sz)
series_name = _sig("hy_result_series_name", ctypes.c_char_p, _vp, _sz)
series_data = _sig("hy_result_series_data", ctypes.c_char_p, _vp, _sz)
series_error = _sig("hy_result_series_error", ctypes.c_double, _vp, _sz, ctypes.POINTER(ctypes.c_char_p))
loops = _sig("hy_result_loops", ctypes.POINTER(Loops), _vp)
render = _sig("hy_result_render", ctypes.c_int, _vp, ctypes.c_char_p, ctypes.POINTER(ctypes.POINTER(ctypes.c_ubyte)),
              ctypes.POINTER(_sz), _E)
csv = _sig("hy_result_csv", ctypes.c_int, _vp, ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(_sz), _E)
write_file = _sig("hy_write_file", ctypes.c_int, ctypes.c_char_p, ctypes.c_char_p, _sz, _E)
schema_json = _sig("hy_schema_json", ctypes.c_void_p)
# hy_steady_loop: the arrays as addresses (c_void_p takes a numpy array's int
# address as it is, no pointer object made per call)
steady_loop = _sig("hy_steady_loop", ctypes.c_int, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p,
                   ctypes.POINTER(ctypes.c_char_p), _sz, _sz, _vp, _vp, _vp, _E)


def _load_fast() -> Any:
    """steady_loop's compiled fast path: hystviz._fast's steady_loop bound
    to this module's library, or None (then the package calls through
    ctypes).  The one place that chooses; first found wins:
      1. hystviz._fast in this package's directory (a wheel, `meson install`);
      2. _fast beside the library $HYSTVIZ_LIB names by a path (the build
         tree: meson builds it beside libhystviz);
    none where $HYSTVIZ_CTYPES is 1 (the ctypes path forced: tests compare
    the two), or where the module is not built or not loadable by this
    Python (another version's ABI)."""
    if os.environ.get("HYSTVIZ_CTYPES") == "1":
        return None
    # (a bare name in $HYSTVIZ_LIB is the loader's search: no directory of its own)
    dirs = [_here] + ([os.path.dirname(os.path.abspath(_env))] if _env and os.sep in _env else [])
    for d in dirs:
        for suffix in importlib.machinery.EXTENSION_SUFFIXES:
            path = os.path.join(d, "_fast" + suffix)
            if os.path.exists(path):
                try:
                    loader = importlib.machinery.ExtensionFileLoader("hystviz._fast", path)
                    spec = importlib.machinery.ModuleSpec("hystviz._fast", loader, origin=path)
                    mod = loader.create_module(spec)
                    loader.exec_module(mod)
                except ImportError:
                    continue
                mod.bind(ctypes.cast(lib.hy_steady_loop, ctypes.c_void_p).value)
                return mod.steady_loop
    return None


boucwen_run = _sig("hy_boucwen_run", ctypes.c_int, _dp, _sz, ctypes.c_double, _dp, _E)
fit_scene = _sig("hy_fit_scene", ctypes.c_int, ctypes.c_char_p, ctypes.POINTER(ctypes.c_char_p), _sz,
                 ctypes.POINTER(ctypes.c_char_p), _sz, _sz, ctypes.c_ulonglong, ctypes.c_int,
                 ctypes.POINTER(ctypes.c_void_p), _E)
fitted_free = _sig("hy_scene_fitted_free", None, _vp)
fitted_array = _sig("hy_scene_fitted_array", _dp, _vp, ctypes.c_char_p, ctypes.POINTER(_sz))
fitted_stat = _sig("hy_scene_fitted_stat", ctypes.c_double, _vp, ctypes.c_char_p)
fitted_key = _sig("hy_scene_fitted_key", ctypes.c_char_p, _vp, _sz)
fitted_data = _sig("hy_scene_fitted_data", ctypes.c_char_p, _vp, _sz)
fitted_text = _sig("hy_scene_fitted_text", ctypes.c_char_p, _vp)
table_parse = _sig("hy_table_parse", ctypes.c_int, ctypes.c_char_p, _sz, ctypes.c_char_p, ctypes.POINTER(TableSpec),
                   ctypes.c_int, ctypes.POINTER(Table), _E)
table_free = _sig("hy_table_free", None, ctypes.POINTER(Table))
table_area = _sig("hy_table_area", ctypes.c_double, _dp, _dp, _sz)
table_max_bytes = 64 << 20  # HY_TABLE_MAX_BYTES
fast_steady_loop = _load_fast()
# GSL's default handler aborts the process on a GSL error; off, every GSL
# status comes back through the library call as a SceneError (hy_gsl_quiet in
# hystviz.h says why the library leaves it to its host)
_sig("hy_gsl_quiet", None)()
libc = ctypes.CDLL(None)
libc.free.argtypes = [ctypes.c_void_p]
libc.free.restype = None


# ---- FORC (hy_forc.h, exported by libhystviz as every core public header) ----
class ForcCurve(ctypes.Structure):
    """hy_forc_curve of hy_forc.h."""
    _fields_ = [("ha", ctypes.c_double), ("first", ctypes.c_size_t), ("n", ctypes.c_size_t),
                ("cal_h", ctypes.c_double), ("cal_m", ctypes.c_double), ("line", ctypes.c_size_t)]


class ForcData(ctypes.Structure):
    """hy_forc_data of hy_forc.h."""
    _fields_ = [("curve", ctypes.POINTER(ForcCurve)), ("ncurves", ctypes.c_size_t),
                ("hb", ctypes.POINTER(ctypes.c_double)), ("m", ctypes.POINTER(ctypes.c_double)),
                ("npoints", ctypes.c_size_t), ("units", ctypes.c_int), ("field_unit", ctypes.c_char_p),
                ("moment_unit", ctypes.c_char_p), ("field_to_tesla", ctypes.c_double), ("hsat", ctypes.c_double),
                ("hcal", ctypes.c_double), ("hncr", ctypes.c_double), ("ncrv", ctypes.c_long),
                ("ndata", ctypes.c_long), ("ncal", ctypes.c_size_t)]


class ForcOpts(ctypes.Structure):
    """hy_forc_opts of hy_forc.h."""
    _fields_ = [("sf", ctypes.c_double), ("sc0", ctypes.c_double), ("sc1", ctypes.c_double),
                ("ramp", ctypes.c_double), ("extend", ctypes.c_int), ("da", ctypes.c_double), ("db", ctypes.c_double)]


class ForcGrid(ctypes.Structure):
    """hy_forc_grid of hy_forc.h."""
    _fields_ = [("hc0", ctypes.c_double), ("hc1", ctypes.c_double), ("hu0", ctypes.c_double),
                ("hu1", ctypes.c_double), ("nc", ctypes.c_size_t), ("nu", ctypes.c_size_t),
                ("rho", ctypes.POINTER(ctypes.c_double))]


class ForcProtocol(ctypes.Structure):
    """hy_forc_protocol of hy_forc.h."""
    _fields_ = [("hsat", ctypes.c_double), ("ha_lo", ctypes.c_double), ("ha_hi", ctypes.c_double),
                ("hb_max", ctypes.c_double), ("ncurves", ctypes.c_size_t)]


_FD = ctypes.POINTER(ForcData)
# hy_rateind_fn: int (*)(void *ctx, double u, double *y, hy_error *err)
RateindFn = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_double, _dp, ctypes.c_void_p)
forc_read = _sig("hy_forc_read", ctypes.c_int, _FD, ctypes.c_char_p, _sz, ctypes.c_char_p, _E)
forc_data_set = _sig("hy_forc_data_set", ctypes.c_int, _FD, _sz, _dp, ctypes.POINTER(_sz), _dp, _dp, _E)
forc_data_free = _sig("hy_forc_data_free", None, _FD)
forc_drift = _sig("hy_forc_drift", ctypes.c_int, _FD, _E)
forc_defaults = _sig("hy_forc_defaults", ForcOpts)
forc_grid_auto = _sig("hy_forc_grid_auto", None, _FD, ctypes.POINTER(ForcOpts), ctypes.POINTER(ForcGrid))
forc_rho = _sig("hy_forc_rho", ctypes.c_int, _FD, ctypes.POINTER(ForcOpts), ctypes.POINTER(ForcGrid),
                ctypes.POINTER(_sz), _E)
forc_grid_free = _sig("hy_forc_grid_free", None, ctypes.POINTER(ForcGrid))
forc_protocol_run = _sig("hy_forc_protocol_run", ctypes.c_int, _FD, ctypes.POINTER(ForcProtocol), RateindFn,
                         ctypes.c_void_p, _E)
forc_max_bytes = 64 << 20  # what hystviz forc reads of a file
