#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/python/test_wheel.sh SOURCE_ROOT: `pip wheel .` at the repository root
# (meson-python, offline, --no-build-isolation: Debian's python3-mesonpy) on a
# copy of the source tree, the wheel installed into a fresh venv (Debian's
# NumPy through --system-site-packages), the copy removed, then from / with
# no PYTHONPATH, HYSTVIZ_LIB or LD_LIBRARY_PATH: import hystviz (from the
# venv, its library from the package's own directory), Fig. 15's minor-loop
# area (0.19910737569481529, as docs/examples/minor_loop_area.c prints it)
# and a rendered figure of the scene the wheel carries.  SKIP (77) without
# /usr/bin/python3's mesonpy, venv, pip or numpy (apt-get install python3-mesonpy
# python3-venv python3-pip python3-numpy); FAIL for those when CI=true.
set -u
. "$(dirname "$0")/../lib.sh"
src=$1
py=/usr/bin/python3
if ! "$py" -c "import mesonpy, venv, numpy, pip" 2>/dev/null; then
    msg="no python3-mesonpy, python3-venv, python3-pip or python3-numpy for $py (apt-get install python3-mesonpy python3-venv python3-pip python3-numpy)"
    [ "${CI:-}" = true ] && fatal "$msg"
    skip "$msg"
fi
T=$tmp

# the tree as a tarball would have it (no build directories, no caches):
# meson-python writes its native file into the tree it builds
mkdir "$T/src"
(cd "$src" && tar cf - --exclude='./build*' --exclude='__pycache__' --exclude='./.git' --exclude='./.mesonpy*' \
    --exclude='./gallery' --exclude='./tests' --exclude='./docs' .) | (cd "$T/src" && tar xf -) ||
    fatal "copying the source tree"
(cd "$T/src" && find . | sort) >"$T/before"
unset PYTHONPATH HYSTVIZ_LIB HYSTVIZ_SCENES LD_LIBRARY_PATH
export PIP_CONFIG_FILE=/dev/null PIP_NO_CACHE_DIR=1 PIP_DISABLE_PIP_VERSION_CHECK=1 HOME="$T/home"
# no ccache (setup.sh test exports one for its build directories): the wheel's
# -O3 compilations never hit it, and storing them cost 3.7 CPU s (37.5 against 33.8)
export CCACHE_DISABLE=1
(cd "$T/src" && timeout 900 "$py" -m pip wheel -q --no-build-isolation --no-deps --no-index -w "$T/wheel" . \
    --config-settings=compile-args=-j2 >"$T/wheel.log" 2>&1) || { tail -40 "$T/wheel.log"; fatal "pip wheel ."; }
# the tree is left as it was but for meson-python's native file (.gitignore'd):
# no build/, *.egg-info or other leftovers
left=$( (cd "$T/src" && find . | sort) | comm -13 "$T/before" - | grep -v '^\./\.mesonpy-native-file\.ini$')
[ -z "$left" ] && ok "pip wheel . leaves nothing in the tree (but .mesonpy-native-file.ini, ignored)" ||
    bad "pip wheel . left in the tree: $left"
grep -qx '/.mesonpy-native-file.ini' "$T/src/.gitignore" || bad ".gitignore does not name .mesonpy-native-file.ini"
whl=$(ls "$T"/wheel/hystviz-*.whl)
case "$whl" in
    *-linux_*.whl) ok "pip wheel . made $(basename "$whl") (platform-tagged)" ;;
    *) bad "wheel not tagged for the platform: $whl" ;;
esac
(cd "$T/src" && "$py" - "$whl") <<'PYEOF' && ok "the wheel carries libhystviz.so.0, every module, hystviz._fast, the scenes and LICENSE" || bad "wheel contents"
import os, sys, zipfile
names = set(zipfile.ZipFile(sys.argv[1]).namelist())
mods = {f"hystviz/{m}" for m in os.listdir("src/python/hystviz") if m.endswith(".py")} if os.path.isdir("src/python/hystviz") else set()
need = {"hystviz/libhystviz.so.0", "hystviz/__init__.py", "hystviz/py.typed", "hystviz/scenes/style.scene",
        "hystviz/scenes/fig15_minor_loop_ex4.scene"} | mods
missing = need - names
# the compiled fast path, where this Python has its headers (python3-dev)
import importlib.machinery, sysconfig
if os.path.exists(os.path.join(sysconfig.get_paths()["include"], "Python.h")):
    fast = {"hystviz/_fast" + importlib.machinery.EXTENSION_SUFFIXES[0]}
    missing |= fast - names
lic = any(n.endswith(".dist-info/LICENSE") for n in names)
print("missing:", sorted(missing) or "none", "| LICENSE:", lic)
sys.exit(0 if not missing and lic else 1)
PYEOF
rm -rf "$T/src"  # the source tree out of reach
# the venv without a pip of its own (ensurepip costs 8 of this test's CPU
# seconds): Debian's pip installs into it (pip --python, pip >= 22.3)
"$py" -m venv --without-pip --system-site-packages "$T/venv" >"$T/venv.log" 2>&1 || { cat "$T/venv.log"; fatal "venv"; }
timeout 300 "$py" -m pip --python "$T/venv/bin/python" install -q --no-deps --no-index "$whl" >"$T/pip.log" 2>&1 ||
    { cat "$T/pip.log"; fatal "pip install the wheel"; }
[ -z "$(ls "$T"/venv/lib/python3*/site-packages/hystviz/__init__.py 2>/dev/null)" ] && fatal "pip put hystviz outside the venv"
out=$(cd / && timeout 300 "$T/venv/bin/python" - "$T" <<'PYEOF' 2>&1
import os, sys
import hystviz
from hystviz import _lib
tmp = sys.argv[1]
pkg = os.path.dirname(hystviz.__file__)
assert pkg.startswith(os.path.join(tmp, "venv")), f"hystviz imported from {pkg}"
assert os.path.dirname(_lib.lib._name) == pkg, f"libhystviz loaded from {_lib.lib._name}, not the package"
# found without ctypes.util.find_library (it runs ldconfig and a compiler)
print("find_library", "ctypes.util" in sys.modules or "subprocess" in sys.modules)
fast = hystviz._steady_fast
print("fast", fast is not None and os.path.dirname(fast.__self__.__file__) == pkg)
m = hystviz.Model("lugre", sigma0=6)
u = hystviz.Input("bimodal", umin1=0, umin2=0.5, umax1=1, umax2=1.5)
print(f"area {hystviz.minor_loops(m, u)[0].area:.17g}")
fig = hystviz.render(hystviz.scene_path("fig15_minor_loop_ex4"), model__sigma0=2)
png = os.path.join(tmp, "fig15.png")
fig.save(png)
with open(png, "rb") as f:
    print("png", f.read(8) == b"\x89PNG\r\n\x1a\n", "svg", fig.svg.startswith(b"<?xml"))
PYEOF
)
echo "$out"
case "$out" in *"area 0.19910737569481529"*) ok "Fig. 15's minor-loop area from the venv, run from /" ;;
    *) bad "minor-loop area from the venv" ;; esac
case "$out" in *"find_library False"*) ok "import hystviz loads no ctypes.util nor subprocess" ;;
    *) bad "import hystviz imported ctypes.util or subprocess" ;; esac
if "$py" -c 'import os, sys, sysconfig; sys.exit(not os.path.exists(os.path.join(sysconfig.get_paths()["include"], "Python.h")))'; then
    case "$out" in *"fast True"*) ok "steady_loop through the wheel's compiled fast path (hystviz._fast in the package)" ;;
        *) bad "the wheel's hystviz._fast not used" ;; esac
else
    echo "(no Python.h for $py: no hystviz._fast to check)"
fi
case "$out" in *"png True svg True"*) ok "render(scene_path('fig15_minor_loop_ex4')) writes a PNG and an SVG" ;;
    *) bad "render from the venv" ;; esac
finish python-wheel
