"""orthocontact: the coupled orthotropic adhesion-friction contact law of
Konyukhov & Schweizerhof as FMI 2.0 and 3.0 co-simulation FMUs, a rig harness
that reproduces the paper's analyses, and parameter identification.

The public API (docs/reference/python-api.md):

    ContactFMU            one instance of the contact FMU (FMI 2.0 or 3.0)
    ContactParams         the law's parameters; angles in rad, or
                          ContactParams.from_degrees(...)
    find_fmu              the installed FMU of an FMI version (contact or rig)
    Rig, run_rig          the carriage/block rig and one run of it (RigResult)
    load_scenario         read and validate a scenario file (degrees, N, m)
    load_measurements     read and validate a measurement folder
    identify_parameters   identification from a measurement folder or set

Subpackages by layer, lowest first (tests/contracts/test_structure.py keeps every
import going down):
    errors, version, plausibility -- one-line errors; the version; the plausible ranges of inputs
    runtime        -- a command's processes and folders: scratch, workers, signals
    fmu            -- the law's parameters, the installed FMUs, an FMU instance through fmpy
    closed_forms   -- the paper's closed forms; the rig's steady state with its strip
    rig            -- the carriage/block rig: harness (fmpy), compiled master (C), self-checks
    experiment     -- scenario files, a lab's rig.toml, the experiment as an SSP package
    runs           -- many runs: batches on an executor and a master, sweeps, Dask
    output         -- CSV/JSON tables and PNG figures
    identification -- measurements, the joint casadi fit, statistics, the job and its report
    uq, reproduction -- uncertainty propagation; the paper reproduced, sensitivity
    cli            -- the `orthocontact` command
"""
from .experiment import load_scenario
from .fmu import ContactFMU, ContactParams, find_fmu
from .rig import Rig, RigResult
from .rig import run as run_rig
from .version import __version__


def load_measurements(folder):
    """Reads and validates a measurement folder (rig.toml and any of
    forces.csv, angles.csv, ramp.csv; angles in degrees, forces in N, travel in
    m).  Raises orthocontact.errors.InputError with a one-line message."""
    from .identification import load_data
    return load_data(folder)


def identify_parameters(data, validate: bool = True, workers=None, fmi_version: int = 2):
    """Identifies mu1, mu2, the stiffness ratio and (with a ramp) the absolute
    stiffness [N/m] from a measurement folder or a set from load_measurements.
    Returns an Identification; .as_json() gives the values, standard errors and
    95 % intervals (what the command writes to identified.json)."""
    from .identification import MeasurementSet, identify
    if not isinstance(data, MeasurementSet):
        data = load_measurements(data)
    return identify(data, validate, workers, str(find_fmu(fmi_version=fmi_version)))


__all__ = ["ContactFMU", "ContactParams", "find_fmu", "Rig", "RigResult", "run_rig",
           "load_scenario", "load_measurements", "identify_parameters", "__version__"]
