"""The package's version, at the bottom of the layers so that any module
may say it (a manifest, an exported FMU's documentation, `--version`)
without importing the package's root, which re-exports it."""
from __future__ import annotations

from pathlib import Path


def read_version() -> str:
    """The version of the file VERSION: read from it in a source tree (an
    editable install, or the package run from the repository), else the
    installed package's metadata, which the build took from it."""
    source_tree = Path(__file__).resolve().parents[2]
    if (source_tree / "pyproject.toml").is_file() and (source_tree / "VERSION").is_file():
        return (source_tree / "VERSION").read_text().strip()
    from importlib.metadata import version
    return version("orthocontact")


__version__ = read_version()

__all__ = ["__version__", "read_version"]
