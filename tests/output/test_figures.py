"""The common look of every figure (orthocontact.output.figures): overlapping
curves stay distinguishable, legends say what the angle is and sit outside
the data; the drawing workers end with their parent."""
import contextlib
import os
import signal
import subprocess
import sys
import time

import matplotlib
import pytest

from paths import SCENARIOS
from procs import alive, children

matplotlib.use("Agg")

from orthocontact.experiment.scenario import load
from orthocontact.output import figures  # noqa: E402


def test_overlapping_curves_get_distinct_markers_dashes_and_staggered_marks():
    styles = [figures.curve_style(i, 400, 7) for i in range(7)]
    assert len({(s["marker"], s["linestyle"], s["color"]) for s in styles}) == 7
    assert len({s["markevery"][0] for s in styles}) == 7  # marks do not stack


def test_legend_names_the_mat_angle():
    assert figures.swept_label(load(SCENARIOS / "mat_aged.toml")) == \
        "mat angle a: α = a +90°, β = a"
    assert figures.swept_label(load(SCENARIOS / "case5.toml")) == \
        "mat angle a: α = a, β = a +90°"


def test_legend_outside_the_axes(tmp_path):
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1], label="x")
    seen = {}
    orig = plt.close

    def keep(f):
        fig.canvas.draw()
        seen["legend"] = ax.get_legend().get_window_extent()
        seen["axes"] = ax.get_window_extent()
        orig(f)
    plt.close = keep
    try:
        figures.finish(fig, ax, tmp_path / "f.png", "t", "legend", outside=True)
    finally:
        plt.close = orig
    assert seen["legend"].x0 >= seen["axes"].x1  # right of the data, not over it


# -- the drawing workers: they end with the process that started them -------------------

_HOLDS_A_DRAWER = """
import os, sys, time
from orthocontact.output.figures import FigureDrawer
with FigureDrawer(2) as draw:
    draw.submit(int).result()
    print("drawing", flush=True)
    time.sleep(120)
"""


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM], ids=["SIGKILL", "SIGTERM"])
def test_drawing_workers_end_with_their_parent(sig):
    proc = subprocess.Popen([sys.executable, "-c", _HOLDS_A_DRAWER], stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline() == "drawing\n"
    workers = children(proc.pid)   # the drawer's, as /proc lists them
    try:
        assert len(workers) == 2 and all(alive(w) for w in workers)
        os.kill(proc.pid, sig)  # SIGTERM: Python's default, no handler, no cleanup
        proc.wait(timeout=30)
        t0 = time.monotonic()
        while any(alive(w) for w in workers) and time.monotonic() - t0 < 10:
            time.sleep(0.05)
        assert [w for w in workers if alive(w)] == []
    finally:
        for w in [proc.pid] + workers:
            with contextlib.suppress(OSError):
                os.kill(w, signal.SIGKILL)
        proc.wait(timeout=10)
