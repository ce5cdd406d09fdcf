"""orthocontact.version: the file VERSION's version, at the bottom of the
layers, which the package's root re-exports."""
import orthocontact
from orthocontact.version import __version__, read_version
from paths import ROOT


def test_the_version_is_the_files_and_the_root_says_the_same():
    assert read_version() == __version__ == (ROOT / "VERSION").read_text().strip()
    assert orthocontact.__version__ is __version__
