"""Where the FMUs are: a given path, $ORTHOCONTACT_FMU / $ORTHOCONTACT_FMU3,
or the ones installed with the package; their model descriptions (parsed
once per file).  Their unpacked folders: runtime.temp.unzipped."""
from __future__ import annotations

import os
import sys
from pathlib import Path

MODEL_IDENTIFIER = "OrthotropicContact"


FMU_ENV = {2: "ORTHOCONTACT_FMU", 3: "ORTHOCONTACT_FMU3"}


FMI_VERSIONS = (2, 3)


RIG_MODEL_IDENTIFIER = "CarriageBlock"


PACKAGE_ROOT = Path(__file__).resolve().parents[1]   # the orthocontact folder


def installed_file(rel, folder: bool = False) -> Path | None:
    """A file (or, with folder, a folder) installed with the package, `rel`
    relative to it: in the package's folder, or (an editable install, whose
    code stays in the source tree) under `orthocontact/` in a site-packages
    folder on sys.path."""
    exists = Path.is_dir if folder else Path.is_file
    here = PACKAGE_ROOT / rel
    if exists(here):
        return here
    for entry in sys.path:
        candidate = Path(entry or ".") / "orthocontact" / rel
        if exists(candidate):
            return candidate
    return None


def _installed(fmi_version: int, model: str = MODEL_IDENTIFIER):
    """The FMU of `model` installed with the package, or None."""
    return installed_file(Path(f"fmi{fmi_version}") / (model + ".fmu"))


def find_fmu(path: str | os.PathLike | None = None, fmi_version: int = 2,
             model: str = MODEL_IDENTIFIER) -> Path:
    """The FMU to use: `path`, else $ORTHOCONTACT_FMU ($ORTHOCONTACT_FMU3 for
    FMI 3.0), else the one installed with the package (regular or editable
    install).  fmi_version: 2 (default) or 3; model: "OrthotropicContact" (the
    contact, default) or "CarriageBlock" (the rig of the experiment).  Raises
    FileNotFoundError with a one-line message saying what to do."""
    if fmi_version not in FMI_VERSIONS:
        raise ValueError(f"fmi_version must be 2 or 3, got {fmi_version!r}")
    env = FMU_ENV[fmi_version] if model == MODEL_IDENTIFIER else None
    for given, where in ((path, "given path"), (os.environ.get(env) if env else None, f"${env}")):
        if given:
            if not Path(given).is_file():
                raise FileNotFoundError(f"FMU not found: {given} ({where})")
            return Path(given)
    installed = _installed(fmi_version, model)
    if installed is not None:
        return installed
    raise FileNotFoundError(
        f"the FMI {fmi_version}.0 {model}.fmu is not installed with the package; run "
        f"`pip install .` (or `pip install -e .`) from the repository, which builds it"
        + (f", or set {env}" if env else ""))


_descriptions: dict = {}


def model_description(path):
    """fmpy's reading of the FMU's modelDescription.xml, parsed once per
    file version and process (a reproduction asks for it dozens of times).
    fmpy is imported here, when a description is first read: a command's
    start (`orthocontact --help`) does without it."""
    from fmpy import read_model_description
    p = Path(path).resolve()
    st = p.stat()
    key = (p, st.st_mtime_ns, st.st_size)
    if key not in _descriptions:
        _descriptions[key] = read_model_description(str(p))
    return _descriptions[key]


def fmi_version_of(path) -> int:
    """2 or 3: the FMI version of the FMU at `path`."""
    return int(model_description(path).fmiVersion.split(".")[0])
