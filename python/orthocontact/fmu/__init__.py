"""FMU access: the law's parameters (params), where the FMUs are
(files), and one instance of the contact FMU through fmpy (contact)."""
from .contact import ContactFMU, FMUError
from .files import (
    FMI_VERSIONS,
    FMU_ENV,
    MODEL_IDENTIFIER,
    PACKAGE_ROOT,
    RIG_MODEL_IDENTIFIER,
    find_fmu,
    fmi_version_of,
    installed_file,
    model_description,
)
from .generated import LAW
from .pad import PAD_MODEL, Foundation, PadFMU, foundation_problem
from .param_checks import check as check_parameter
from .params import ANGLE_LIMIT_RAD, RULES, ContactParams
from .patch import (
    GEOMETRY,
    PATCH_MODEL,
    PatchFMU,
    PatchGeometry,
    cells_problem,
    geometry_problem,
    geometry_range,
)
from .start_values import write_with_start_values
from .variables import law_parameters, models

__all__ = ["ContactFMU", "FMUError", "ContactParams", "RULES", "ANGLE_LIMIT_RAD", "find_fmu",
           "fmi_version_of", "installed_file", "model_description", "MODEL_IDENTIFIER",
           "RIG_MODEL_IDENTIFIER", "FMI_VERSIONS", "FMU_ENV", "PACKAGE_ROOT", "LAW", "check_parameter",
           "PAD_MODEL", "Foundation", "PadFMU", "foundation_problem", "GEOMETRY", "PATCH_MODEL", "PatchFMU",
           "PatchGeometry", "cells_problem", "geometry_problem", "geometry_range", "write_with_start_values",
           "law_parameters", "models"]
