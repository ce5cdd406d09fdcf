"""FMU access: the law's parameters (params), where the FMUs are
(files), and one instance of the contact FMU through fmpy (contact)."""
from .contact import ContactFMU, FMUError
from .files import (
    FMI_VERSIONS,
    FMU_ENV,
    MODEL_IDENTIFIER,
    RIG_MODEL_IDENTIFIER,
    find_fmu,
    fmi_version_of,
    installed_file,
    model_description,
)
from .params import ANGLE_LIMIT_RAD, RULES, ContactParams

__all__ = ["ContactFMU", "FMUError", "ContactParams", "RULES", "ANGLE_LIMIT_RAD", "find_fmu",
           "fmi_version_of", "installed_file", "model_description", "MODEL_IDENTIFIER",
           "RIG_MODEL_IDENTIFIER", "FMI_VERSIONS", "FMU_ENV"]
