"""Figures for people: the common look of every PNG the package writes
(matplotlib off-screen), and a pool that draws them in worker processes."""
from __future__ import annotations

from pathlib import Path

from ..experiment import Scenario


def pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def label(ax, title: str, legend_title: str | None = None, outside: bool = False, size: int = 10) -> None:
    """A panel's title (size pt), grid and legend (size - 2 pt). outside:
    the legend goes right of the axes, where it cannot cover data."""
    ax.set_title(title, fontsize=size, y=1.0)  # an explicit y skips a costly auto placement
    ax.grid(alpha=0.3)
    place = dict(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0) if outside else {}
    ax.legend(fontsize=size - 2, title=legend_title, title_fontsize=size - 2, **place)


def save(fig, path: Path) -> None:
    """The figure's PNG, and the figure closed."""
    fig.savefig(path, dpi=120, pil_kwargs={"compress_level": 3})
    pyplot().close(fig)


def finish(fig, ax, path: Path, title: str, legend_title: str | None = None,
           outside: bool = False) -> None:
    """The common end of a figure of one panel: its label, margins, file, close."""
    label(ax, title, legend_title, outside)
    # Fixed margins, sized for these labels, instead of tight_layout: its
    # extra layout pass was a third of each figure's time, and make
    # reproduce draws 22 of them.
    width = fig.get_size_inches()[0]
    fig.subplots_adjust(left=0.75 / width, bottom=0.12, top=0.93,
                        right=1 - (2.0 if outside else 0.2) / width)
    save(fig, path)


# Lines that lie on top of each other stay distinguishable: each curve gets its
# own marker and dash pattern besides its colour.
_MARKERS = ("o", "s", "^", "v", "D", "P", "X", "*", "<", ">")


_DASHES = ("-", "--", "-.", ":")


def curve_style(i: int, n_points: int, n_lines: int = 8) -> dict:
    """Curve i of n_lines: colour, marker, dash pattern, and markers staggered
    along the curve so that identical curves show every one of them."""
    every = max(1, n_points // 8)
    return {"marker": _MARKERS[i % len(_MARKERS)], "linestyle": _DASHES[i % len(_DASHES)],
            "markevery": ((i * every) // max(n_lines, 1) % every, every), "ms": 4,
            "color": f"C{i % 10}"}


def swept_label(sc: Scenario) -> str:
    """What the mat angle a is, in terms of the law's axes."""
    def rel(d):
        return "a" if abs(d) < 1e-12 else f"a {d:+g}°"
    return f"mat angle a: α = {rel(sc.geometry.alpha_offset_deg)}, β = {rel(sc.geometry.beta_offset_deg)}"


def draw_here(fn, *args):
    fn(*args)


def _init_drawer():
    pyplot()  # matplotlib's import, once per worker, while the rig still runs


class _Done:
    def __init__(self, value):
        self._value = value

    def result(self):
        return self._value


class FigureDrawer:
    """Draws figures in `workers` processes while the caller goes on:
    drawer(fn, *args) hands over one figure; leaving the `with` block waits
    for all of them and raises the first failure.  workers <= 1 draws each
    figure at once, here.  An exception in the block stops the workers."""

    def __init__(self, workers: int):
        self.workers = workers
        self._ex = None
        self._futures = []

    def __enter__(self):
        if self.workers > 1:
            from ..runtime import process_pool, stop_pool
            self._ex = process_pool(self.workers, _init_drawer)
            try:
                # Start the workers now, so that matplotlib's import in them
                # overlaps the first rig runs instead of delaying the first figure.
                self._ex.submit(int)
            except BaseException:  # an interrupt held while they forked: __exit__ will not run
                stop_pool(self._ex)
                raise
        return self

    def __call__(self, fn, *args):
        self.submit(fn, *args)

    def submit(self, fn, *args):
        """fn(*args) in a worker (here if there is none); something with
        .result() that gives its value."""
        if self._ex is None:
            return _Done(fn(*args))
        f = self._ex.submit(fn, *args)
        self._futures.append(f)
        return f

    def __exit__(self, kind, value, tb):
        if self._ex is None:
            return False
        from ..runtime import stop_pool
        if kind is not None:
            stop_pool(self._ex)
            return False
        try:
            for f in self._futures:
                f.result()
        except BaseException:
            stop_pool(self._ex)
            raise
        self._ex.shutdown()
        return False
