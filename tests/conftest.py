import math
import sys

import pytest

from orthocontact.fmu.contact import ContactFMU
from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.params import ContactParams
from paths import ROOT, SCENARIOS, TOOLS

# The independent reference simulator and the recordings generator live in
# tools/ (free of package code), shared with the benchmarks.
sys.path.insert(0, str(TOOLS))

from cli_run import run_cli  # noqa: E402  (tests/ is on sys.path: the shared helpers)

# The optional parts' summary and the session's failure when a required one is missing.
from optional_parts import (  # noqa: E402,F401
    pytest_addoption,
    pytest_configure,
    pytest_runtest_setup,
    pytest_sessionfinish,
    pytest_terminal_summary,
    pytest_testnodedown,
)

CASE1 = ContactParams(mu1=0.1, mu2=0.5, eps1=1e4, eps2=1e4, rule="associated")
CASE5 = ContactParams(mu1=0.1, mu2=0.5, eps1=1e4, eps2=1e3, rule="coupled")
G_N = 1.875 * 9.806  # the rig's normal force [N]


@pytest.fixture(scope="session", params=[2, 3], ids=["fmi2", "fmi3"])
def fmu_path(request):
    """Each FMU test runs on both FMUs: the FMI 2.0 and the FMI 3.0 one."""
    return find_fmu(fmi_version=request.param)


@pytest.fixture(scope="session")
def fmi_version(fmu_path):
    from orthocontact.fmu.files import fmi_version_of
    return fmi_version_of(fmu_path)


@pytest.fixture
def make(fmu_path):
    """make(params) -> an initialized ContactFMU, closed after the test."""
    made = []

    def _make(params=None, name=None, **kw):
        f = ContactFMU(fmu_path, instance_name=name or f"t{len(made)}", **kw)
        made.append(f)
        if params is not None:
            f.initialize(params)
        return f

    yield _make
    for f in made:
        f.close()


@pytest.fixture
def last_figure(monkeypatch):
    """The axes of every figure, as they were when it was closed (the figure
    tests of reproduction and identification inspect them)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    seen = []
    orig = plt.close

    def keep(fig=None):
        if fig is not None and hasattr(fig, "canvas"):
            fig.canvas.draw()
            seen.append([(ax, ax.get_ylim(), ax.get_window_extent(),
                          ax.get_legend().get_window_extent() if ax.get_legend() else None,
                          [t.get_text() for t in ax.get_legend().get_texts()] if ax.get_legend() else [])
                         for ax in fig.axes])
        orig(fig)
    monkeypatch.setattr(plt, "close", keep)
    return seen


@pytest.fixture(scope="module")
def identified(tmp_path_factory):
    """The bundled example identified once per module (`orthocontact identify
    --no-validate`), for the tests of what takes an identified.json (uq,
    export, the CLI's edges)."""
    out = tmp_path_factory.mktemp("id") / "id"
    p = run_cli(["identify", SCENARIOS / "example_identification", "--out", out,
                 "--no-validate"], cwd=ROOT)
    assert p.returncode == 0, p.stderr
    return out / "identified.json"


@pytest.hookimpl(tryfirst=True)   # before -m deselects by marker
def pytest_collection_modifyitems(config, items):
    from tiers import mark_slow
    mark_slow(config, items)
    # The files with a slow test first, each kept whole (a module-scoped
    # fixture is made once): the long tests spread over the workers while
    # the fast ones fill the gaps, not one long test alone at the end.
    slow_files = {item.path for item in items if item.get_closest_marker("slow") is not None}
    items.sort(key=lambda item: item.path not in slow_files)


def deg(x):
    return math.radians(x)
