#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""tests/serve/fit_test.py HYSTVIZ: the fit button's endpoint, POST /api/fit
(src/serve/serve_fit.c; issue 32 item 6; docs/SERVE.md "Fitting on the page").

In its own temporary directory: a Preisach model's output at 113 inputs made by
`hystviz data` at known parameters (pr_hc 0.5, pr_width 0.2, pr_ys 1), plus
Gaussian noise of sigma 5e-3 (Python's random, seed 7: the same on every
machine), as a [data] scene whose [model] starts 20 % off; then through serve:
 - the fit's estimates lie within 3 standard errors of the truth (a correct
   standard error puts 99.7 % of them there) and its RMS within 30 % of sigma
   (the residual of a good fit is the noise); every field the page shows is in
   the answer; the estimates are those of `hystviz fit -j 1 -o` to the last
   bit (the same engine from the same start); the page's values (set=) are
   the start;
 - the fit's bounds are the sliders' ranges (GET /api/scene): one rule;
 - a scene without data, an unknown key, no free key: 4xx with a message;
 - serve's work budget: with --max-work 1000 (8 evaluations of 113 points)
   the fit is refused with 422 naming the budget;
 - cancellation, on a fit of 4001 points that runs for many seconds: a newer
   request of its page answers it 409 within 5 s, and a client that closes
   its connection stops it (serve's note on standard error) within 5 s.
Every wait has a deadline."""
import http.client
import json
import os
import random
import re
import shutil
import socket
import subprocess
import sys
import tempfile
import threading
import time
import urllib.parse

TRUTH = {"pr_hc": 0.5, "pr_width": 0.2, "pr_ys": 1.0}
SIGMA = 5e-3
fails = 0


def check(ok, what):
    global fails
    if not ok:
        fails += 1
        print("FAIL: " + what)


def scene(model, csv, path):
    with open(path, "w") as f:
        f.write("[model]\nkind = preisach\n" + "".join("%s = %.17g\n" % kv for kv in model.items()) +
                '[data d]\nfile = "%s"\nu = u\ny = y\n[input]\nkind = data\ndata = d\n[figure]\nkind = loop\n'
                "[series m]\ndata = measured\nof = d\nstyle = none\nmarker = circle\n"
                "[series f]\ndata = modelled\nof = d\n" % csv)


def inputs():
    u = [0.0]
    for a, b, n in ((0, 1.2, 15), (1.2, -1.2, 30), (-1.2, 1.2, 30), (1.2, -0.6, 22), (-0.6, 0.6, 15)):
        u += [a + (b - a) * i / n for i in range(1, n + 1)]
    return u


def make_data(hv, tmp, sdir):
    """The model at TRUTH by hystviz data, plus noise, into sdir/meas.csv."""
    gen = os.path.join(tmp, "gen")
    os.mkdir(gen)
    u = inputs()
    with open(os.path.join(gen, "u.csv"), "w") as f:
        f.write("u,y\n" + "".join("%.17g,0\n" % x for x in u))
    scene(TRUTH, "u.csv", os.path.join(gen, "truth.scene"))
    r = subprocess.run([hv, "data", os.path.join(gen, "truth.scene"), "-o", os.path.join(gen, "t.csv")],
                       capture_output=True, text=True, timeout=60)
    if r.returncode:
        print("hystviz data failed: " + r.stderr)
        sys.exit(1)
    y = [float(l.split(",")[2]) for l in open(os.path.join(gen, "t.csv")) if l.startswith("f,")]
    check(len(y) == len(u), "hystviz data: %d modelled points for %d inputs" % (len(y), len(u)))
    rnd = random.Random(7)
    with open(os.path.join(sdir, "meas.csv"), "w") as f:
        f.write("u,y\n" + "".join("%.17g,%.17g\n" % (a, b + rnd.gauss(0, SIGMA)) for a, b in zip(u, y)))


def serve(hv, sdir, *extra):
    p = subprocess.Popen([hv, "serve", sdir, "--port", "0"] + list(extra), stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    line = ""
    deadline = time.time() + 20
    while time.time() < deadline and "http://" not in line:
        line = p.stdout.readline()
        if not line and p.poll() is not None:
            break
    m = re.search(r"http://[^:]+:(\d+)/", line)
    if not m and p.poll() == 3:  # serve built without libmicrohttpd (-Dmicrohttpd=disabled): exit 3 names it
        print("SKIP: hystviz serve is not built here: " + p.stderr.read().strip())
        sys.exit(77)
    if not m:
        p.kill()
        print("serve did not start: " + line)
        sys.exit(1)
    return p, int(m.group(1))


def post(port, q, timeout=60):
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=timeout)
    c.request("POST", "/api/fit?" + q)
    r = c.getresponse()
    body = r.read().decode()
    c.close()
    try:
        return r.status, json.loads(body)
    except ValueError:
        return r.status, {"raw": body}


def get(port, path):
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
    c.request("GET", path)
    r = c.getresponse()
    body = r.read().decode()
    c.close()
    return r.status, json.loads(body)


def stop(p):
    p.terminate()
    try:
        return p.communicate(timeout=10)[1]
    except subprocess.TimeoutExpired:
        p.kill()
        return p.communicate()[1]


def test_fit(port, hv, sdir, tmp):
    q = "scene=fitme.scene&free=pr_hc,pr_width,pr_ys"
    st, j = post(port, q)
    check(st == 200, "fit: HTTP %d %s" % (st, j))
    if st != 200:
        return
    for k in ("params", "correlated", "rms", "nrms", "max_error", "iterations", "evaluations", "seconds", "cond",
              "data", "points"):
        check(k in j, "fit: no field " + k)
    check(j["points"] == 113 and j["data"] == ["d"], "fit: points %s data %s" % (j["points"], j["data"]))
    for p in j["params"]:
        name = p["key"][6:]
        t = TRUTH[name]
        ok = p["se"] is not None and p["se"] > 0 and abs(p["estimate"] - t) <= 3 * p["se"]
        check(ok, "fit: %s = %s, standard error %s, truth %g: not within 3 standard errors" %
              (name, p["estimate"], p["se"], t))
        check(p["ci_lo"] < p["estimate"] < p["ci_hi"] and not p["unidentifiable"], "fit: %s interval/flag %s" % (name, p))
    check(0.7 * SIGMA < j["rms"] < 1.3 * SIGMA, "fit: RMS %g, noise sigma %g" % (j["rms"], SIGMA))
    check(j["iterations"] > 0 and j["evaluations"] > j["iterations"], "fit: iterations %s evaluations %s" %
          (j["iterations"], j["evaluations"]))
    # the bounds are the sliders' ranges (hy_scene_key_range: one rule for both)
    st, info = get(port, "/api/scene?scene=fitme.scene")
    check(info.get("fit") == "d", "/api/scene: fit %s, want the data's name d" % info.get("fit"))
    ctl = {c["key"]: c for c in info["controls"]}
    for p in j["params"]:
        c = ctl.get(p["key"])
        check(c is not None and c["lo"] == p["lo"] and c["hi"] == p["hi"] and c["log"] == p["log"],
              "%s: slider [%s, %s] log %s, fit bounds [%s, %s] log %s" %
              (p["key"], c and c["lo"], c and c["hi"], c and c["log"], p["lo"], p["hi"], p["log"]))
    # the same fit as the command's (one start, one thread): the same estimates, bit for bit
    out = os.path.join(sdir, "cli_fitted.scene")  # next to the scene: its data file resolves
    r = subprocess.run([hv, "fit", os.path.join(sdir, "fitme.scene"), "--free", "pr_hc,pr_width,pr_ys", "-j", "1", "-q",
                        "-o", out], capture_output=True, text=True, timeout=60)
    cli = dict(re.findall(r"^(pr_\w+) = (\S+)$", open(out).read(), re.M)) if r.returncode == 0 else {}
    same = all(p["key"][6:] in cli and float(cli[p["key"][6:]]) == p["estimate"] for p in j["params"])
    check(same, "serve's estimates %s, hystviz fit -j 1's %s %s" % ([p["estimate"] for p in j["params"]], cli, r.stderr))
    # the page's values are the start
    st, j2 = post(port, q + "&set=" + urllib.parse.quote("model.pr_hc=0.55"))
    check(st == 200 and j2["params"][0]["start"] == 0.55, "fit with set: HTTP %d start %s" %
          (st, j2.get("params", [{}])[0].get("start")))


def test_refused(port):
    st, j = post(port, "scene=nodata.scene&free=play_r")
    check(st == 422 and "no measured data" in j.get("error", ""), "no data: HTTP %d %s" % (st, j))
    st, j = post(port, "scene=fitme.scene&free=nosuch")
    check(st == 422 and "has no key 'nosuch'" in j.get("error", ""), "unknown key: HTTP %d %s" % (st, j))
    st, j = post(port, "scene=fitme.scene")
    check(st == 400 and "free" in j.get("error", ""), "no free key: HTTP %d %s" % (st, j))
    st, j = post(port, "scene=fitme.scene&free=pr_hc&set=" + urllib.parse.quote('data.d.file="/etc/passwd"'))
    check(st == 400, "a page may not set a file: HTTP %d %s" % (st, j))


def test_superseded(port):
    """A newer request of the page stops its fit: 409 within 5 s."""
    out = {}

    def run():
        out["r"] = post(port, "scene=slow.scene&free=pr_hc,pr_width,pr_ys&page=fitpage&seq=1", timeout=30)
        out["t"] = time.time()
    th = threading.Thread(target=run)
    th.start()
    time.sleep(1.0)
    t0 = time.time()
    st, _ = get(port, "/api/render?scene=fitme.scene&fmt=json&page=fitpage&seq=2")
    th.join(10)
    check(not th.is_alive() and out.get("r", (0,))[0] == 409,
          "superseded fit: %s" % (out.get("r", ("still running",)),))
    if "t" in out:
        check(out["t"] - t0 < 5, "superseded fit answered after %.1f s" % (out["t"] - t0))
    check(st == 200, "the newer render: HTTP %d" % st)


def test_gone(port, proc_err_lines):
    """A client that closes its connection stops its fit (serve's note)."""
    s = socket.create_connection(("127.0.0.1", port), timeout=10)
    s.sendall(b"POST /api/fit?scene=slow.scene&free=pr_hc,pr_width,pr_ys HTTP/1.1\r\nHost: localhost\r\n"
              b"Content-Length: 0\r\n\r\n")
    time.sleep(1.0)
    s.close()
    t0 = time.time()
    while time.time() - t0 < 5:
        if any("client had gone" in l for l in proc_err_lines):
            return
        time.sleep(0.1)
    check(False, "a fit whose client went was not stopped within 5 s")


def main():
    hv = os.path.abspath(sys.argv[1])
    tmp = tempfile.mkdtemp(prefix="serve_fit_")
    try:
        sdir = os.path.join(tmp, "scenes")
        os.mkdir(sdir)
        make_data(hv, tmp, sdir)
        scene({"pr_hc": 0.6, "pr_width": 0.25, "pr_ys": 0.8}, "meas.csv", os.path.join(sdir, "fitme.scene"))
        # a fit of many seconds (4001 points, about 0.1 s an evaluation) for the cancellation
        import math
        with open(os.path.join(sdir, "slow.csv"), "w") as f:
            f.write("u,y\n" + "".join("%.17g,%.17g\n" % (1.2 * math.sin(i / 100 * math.pi), math.tanh(3 * math.sin(
                i / 100 * math.pi))) for i in range(4001)))
        scene({"pr_hc": 0.6, "pr_width": 0.25, "pr_ys": 0.8}, "slow.csv", os.path.join(sdir, "slow.scene"))
        with open(os.path.join(sdir, "nodata.scene"), "w") as f:
            f.write("[model]\nkind = play\nplay_r = 0.2\n[input]\nkind = triangle\nmin = -1\nmax = 1\n"
                    "[figure]\nkind = loop\n[series y]\ndata = input\n")
        p, port = serve(hv, sdir, "--max-work", "1e8")
        err_lines = []
        reader = threading.Thread(target=lambda: err_lines.extend(iter(p.stderr.readline, "")), daemon=True)
        reader.start()
        try:
            test_fit(port, hv, sdir, tmp)
            test_refused(port)
            test_superseded(port)
            test_gone(port, err_lines)
        finally:
            p.terminate()
            p.wait(10)
            reader.join(10)
        # a sanitizer build: nothing leaked or overrun on the fits' paths (done, refused, stopped)
        check(not any("Sanitizer" in l for l in err_lines), "serve's standard error: " + "".join(err_lines)[-2000:])
        p, port = serve(hv, sdir, "--max-work", "1000")
        try:
            st, j = post(port, "scene=fitme.scene&free=pr_hc,pr_width,pr_ys")
            check(st == 422 and "over its work budget" in j.get("error", ""), "--max-work 1000: HTTP %d %s" % (st, j))
        finally:
            err = stop(p)
            check("Sanitizer" not in err, "serve's standard error: " + err[-2000:])
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print("%s" % ("ok" if not fails else "%d failed" % fails))
    sys.exit(1 if fails else 0)


if __name__ == "__main__":
    main()
