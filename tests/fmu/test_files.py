"""Where the FMUs are (orthocontact.fmu.files): the version asked for, a
given path or environment variable, their model descriptions."""
import pytest

from orthocontact.fmu.files import find_fmu, fmi_version_of


def test_find_fmu_picks_the_version():
    assert fmi_version_of(find_fmu()) == 2
    assert fmi_version_of(find_fmu(fmi_version=2)) == 2
    assert fmi_version_of(find_fmu(fmi_version=3)) == 3
    with pytest.raises(ValueError, match="2 or 3"):
        find_fmu(fmi_version=1)
