import math

import pytest

from orthocontact.fmu import ContactFMU, ContactParams, find_fmu

CASE1 = ContactParams(mu1=0.1, mu2=0.5, eps1=1e4, eps2=1e4, rule="associated")
CASE5 = ContactParams(mu1=0.1, mu2=0.5, eps1=1e4, eps2=1e3, rule="coupled")
G_N = 1.875 * 9.806  # the rig's normal force [N]


@pytest.fixture(scope="session")
def fmu_path():
    return find_fmu()


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


def deg(x):
    return math.radians(x)
