"""The closed forms, in one place for tests, figures, checks and
identification: the paper's (paper) and, beyond it, the rig's steady state
with the Teflon strip and its settling length (rig); FORMS, the table of the
forms a scenario can name (named).  `from orthocontact import closed_forms
as cf` gives them all."""
from .named import FORMS, NamedForm, named  # noqa: F401
from .paper import (  # noqa: F401
    G_STANDARD,
    rotation,
    adhesion_tensor,
    friction_tensor,
    rotated_diagonal,
    steady_tan_phi,
    steady_drive_force,
    stick_stiffness_x1,
    friction_entries,
    steady_phi_deg,
    of_law,
    eq11_tan_phi,
    eq25_tan_phi,
    eq31_tan_phi,
    eq33_tan_phi,
    eigen_ratio_case4,
    eigen_ratio_case5,
    eq27_alpha_ext,
    eq28_tan_phi_ext,
    eq29_ratio,
    eq11_extremum,
    eq1_mu,
    mat_ratio,
    mat_tan_phi,
    mat_extremum,
    eps_ratio_from_r,
    isotropic_eps_ratio,
    eq40_objective,
    eq41_r2,
    eq25_lambdas)
from .rig import (  # noqa: F401
    slip_force_tensor,
    strip_lateral_force,
    STRIP_GRID,
    STRIP_BISECTIONS,
    steady_strip_state_array,
    steady_tan_phi_with_strip_array,
    steady_tan_phi_with_strip,
    settling_length_array)

__all__ = ['FORMS', 'NamedForm', 'named', 'of_law', 'G_STANDARD', 'rotation', 'adhesion_tensor', 'friction_tensor', 'rotated_diagonal', 'steady_tan_phi', 'steady_drive_force', 'stick_stiffness_x1', 'friction_entries', 'steady_phi_deg', 'eq11_tan_phi', 'eq25_tan_phi', 'eq31_tan_phi', 'eq33_tan_phi', 'eigen_ratio_case4', 'eigen_ratio_case5', 'eq27_alpha_ext', 'eq28_tan_phi_ext', 'eq29_ratio', 'eq11_extremum', 'eq1_mu', 'mat_ratio', 'mat_tan_phi', 'mat_extremum', 'eps_ratio_from_r', 'isotropic_eps_ratio', 'eq40_objective', 'eq41_r2', 'eq25_lambdas', 'slip_force_tensor', 'strip_lateral_force', 'STRIP_GRID', 'STRIP_BISECTIONS', 'steady_strip_state_array', 'steady_tan_phi_with_strip_array', 'steady_tan_phi_with_strip', 'settling_length_array']
