#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""tests/serve/fit_page_test.py HYSTVIZ SCENES: the page's fit button in
chromium (issue 32 item 6; docs/SERVE.md "Fitting on the page"), in the frame
of browser_test.py (its own directory, serve, chromium headless; SKIP without
chromium).

A play operator's loop computed here by hand (r = 0.3 from y0 = 0, driven
0 -> 1 -> -1 -> 1, as tests/fit/test_scene_cli.sh does: an independent
computation) is a [data] scene whose model starts at r = 0.2.  The page:
 - draws the measured data under the model (the render's series: 61 measured
   points and the model's) and offers the fit: a "fit to data" button and a
   "fit" tick beside the r slider, each with an accessible name;
 - without a tick, says what to do and asks the server nothing;
 - ticked and clicked: the r slider takes the estimate (0.3 within 1e-6: the
   data are exact), the figure is drawn again with it (the command line says
   --set model.play_r=0.3...), the statistics panel shows the estimate and
   RMS, the polite live region says "fit done: ...", every interactive node
   still has a name and every text of the panel is at WCAG AA."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import a11y_test as ax  # noqa: E402
import browser_test as bt  # noqa: E402
from browser_test import check  # noqa: E402


def play_data():
    """u, y of the play operator with r = 0.3 from y0 = 0 (by hand)."""
    rows, y, r = [], 0.0, 0.3
    for i in range(61):
        x = i / 60 * 4
        u = x if x < 1 else 2 - x if x < 3 else x - 4
        if u - y > r:
            y = u - r
        if y - u > r:
            y = u + r
        rows.append((u, y))
    return rows


def write_scene(scenes):
    with open(os.path.join(scenes, "fitplay.csv"), "w") as f:
        f.write("u,y\n" + "".join("%.17g,%.17g\n" % p for p in play_data()))
    with open(os.path.join(scenes, "fitplay.scene"), "w") as f:
        f.write('[model]\nkind = play\nplay_r = 0.2\n[data d]\nfile = "fitplay.csv"\nu = u\ny = y\n'
                "[input]\nkind = data\ndata = d\n[figure]\nkind = loop\n"
                "[series m]\ndata = measured\nof = d\nstyle = none\nmarker = circle\nlabel = measured\n"
                "[series f]\ndata = modelled\nof = d\nlabel = model\n")


def test_fit_page(dt, base, scenes, shot=None):
    write_scene(scenes)
    ax.viewport(dt, 1400, 1000)
    check(ax.open_scene(dt, base, "fitplay.scene", "the play data scene"), "the play data scene opens")
    series = dt.js("""fetch('/api/render?scene=fitplay.scene&fmt=json&hover=1&set=model.play_r%3D0.25')
        .then(r => r.json()).then(j => j.series.map(s => [s.name, s.x.length]))""")
    check(series and ["m", 61] in series and any(s[0] == "f" for s in series),
          f"the measured data are drawn with the model while a slider moves: {series}")
    names = dt.js("""[document.getElementById('fitbtn') && document.getElementById('fitbtn').textContent,
        (document.querySelector('input[type=checkbox][data-key="model.play_r"]') || {getAttribute: () => null}).getAttribute('aria-label')]""")
    check(names[0] == "fit to data" and names[1] and names[1].startswith("fit r"),
          f"a fit button and a tick beside the r slider, named: {names}")
    # no tick: a note, no request
    dt.js("document.getElementById('fitbtn').click()")
    check(dt.wait("document.getElementById('say').textContent.startsWith('tick the parameters')", 5, "the note"),
          "without a tick the page says to tick the parameters")
    dt.js("""(() => { const b = document.querySelector('input[type=checkbox][data-key="model.play_r"]');
        b.click(); document.getElementById('fitbtn').click(); })()""")
    ok = dt.wait("hv.fit && hv.sets['model.play_r'] && !hv.fitAbort && !hv.inflight && !hv.pending && "
                 "hv.cmd.includes('model.play_r=')", 30, "the fit and its render")
    r = float(dt.js("hv.sets['model.play_r'] || 'nan'"))
    check(ok and abs(r - 0.3) < 1e-6, f"the r slider takes the estimate 0.3: {r}")
    got = dt.js("""[document.getElementById('fit').hidden, document.getElementById('fitrows').textContent,
        document.getElementById('fitstats').textContent, document.getElementById('say').textContent,
        document.querySelector('input[type=text][data-key="model.play_r"]').value,
        document.querySelector('input[type=checkbox][data-key="model.play_r"]').checked]""")
    check(not got[0] and got[1].startswith("r") and "RMS" in got[2] and "evaluations" in got[2],
          f"the panel shows the estimate and the statistics: {got[1][:80]!r} {got[2][:120]!r}")
    check(got[3].startswith("fit done: r = 0.3"), f"the live region says the result: {got[3][:80]!r}")
    check(got[4] == dt.js("hv.sets['model.play_r']") and got[5], f"the box shows the estimate, the tick stays: {got[4:]}")
    if shot:  # for a person to look at (--screenshot PNG)
        import base64
        with open(shot, "wb") as f:
            f.write(base64.b64decode(dt.call("Page.captureScreenshot", format="png")["data"]))
    ax.ax_tree(dt, "the page after a fit")
    ax.contrast(dt, "the page after a fit")


def main():
    hv, src = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2])
    shot = os.path.realpath(sys.argv[sys.argv.index("--screenshot") + 1]) if "--screenshot" in sys.argv else None

    def body(dt, base, scenes, tmp):
        dt.call("DOM.enable")
        dt.call("Accessibility.enable")
        test_fit_page(dt, base, scenes, shot)
    rc = bt.run_session(hv, src, "hystviz-fitpage-", body)
    if rc == 0:
        print("all fit page tests passed")
    return rc


if __name__ == "__main__":
    sys.exit(main())
