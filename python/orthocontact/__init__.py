"""orthocontact: the coupled orthotropic adhesion-friction contact law of
Konyukhov & Schweizerhof as an FMI co-simulation FMU, a rig harness that
reproduces the paper's analyses, and parameter identification.

Modules, one job each:
    fmu           -- access to the OrthotropicContact FMU through fmpy
    closed_forms  -- the paper's closed-form results (eq. 1, 11, 25-29, 31, 33, 37-41)
    rig           -- the carriage/block test rig coupled with the FMU
    scenarios     -- scenario files (TOML): parsing and validation
    sweep         -- orientation sweeps over worker processes
    report        -- CSV/JSON tables, PNG figures, Markdown reports
    identify      -- parameter identification with casadi
    cli           -- the `orthocontact` command
"""

__version__ = "0.2.0"
