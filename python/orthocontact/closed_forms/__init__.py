"""The closed forms, in one place for tests, figures, checks and
identification: the paper's (paper) and, beyond it, the rig's steady state
with the Teflon strip and its settling length (rig), the pad's (pad) and the
rolling pad's brush (brush); FORMS, the table of the
forms a scenario can name (named).  `from orthocontact import closed_forms
as cf` gives them all."""
from .brush import (  # noqa: F401
    adhesion_length,
    creep_stiffness,
    deflection_profile,
    slip_onset,
    spin_coefficients,
    steady_force,
    steady_force_profile,
)
from .named import FORMS, NamedForm, named  # noqa: F401
from .pad import FULL_CONTACT, LIFT_OFF, TIPS, contact_fraction, pushed_at_height  # noqa: F401
from .paper import (  # noqa: F401
    G_STANDARD,
    adhesion_tensor,
    eigen_ratio_case4,
    eigen_ratio_case5,
    eps_ratio_from_r,
    eq1_mu,
    eq11_extremum,
    eq11_tan_phi,
    eq25_lambdas,
    eq25_tan_phi,
    eq27_alpha_ext,
    eq28_tan_phi_ext,
    eq29_ratio,
    eq31_tan_phi,
    eq33_tan_phi,
    eq40_objective,
    eq41_r2,
    friction_entries,
    friction_tensor,
    isotropic_eps_ratio,
    mat_extremum,
    mat_ratio,
    mat_tan_phi,
    of_law,
    rotated_diagonal,
    rotation,
    steady_drive_force,
    steady_phi_deg,
    steady_tan_phi,
    stick_stiffness_x1,
)
from .patch import (  # noqa: F401
    cell_centres,
    full_slip_rotation_grid,
    steady_force_direction,
    torsional_stiffness_grid,
)
from .rig import (  # noqa: F401
    STRIP_BISECTIONS,
    STRIP_GRID,
    settling_length_array,
    slip_force_tensor,
    steady_strip_state_array,
    steady_tan_phi_with_strip,
    steady_tan_phi_with_strip_array,
    strip_lateral_force,
)

__all__ = ['FORMS', 'NamedForm', 'named', 'of_law', 'G_STANDARD', 'rotation', 'adhesion_tensor',
           'friction_tensor', 'rotated_diagonal', 'steady_tan_phi', 'steady_drive_force',
           'stick_stiffness_x1', 'friction_entries', 'steady_phi_deg', 'eq11_tan_phi', 'eq25_tan_phi',
           'eq31_tan_phi', 'eq33_tan_phi', 'eigen_ratio_case4', 'eigen_ratio_case5', 'eq27_alpha_ext',
           'eq28_tan_phi_ext', 'eq29_ratio', 'eq11_extremum', 'eq1_mu', 'mat_ratio', 'mat_tan_phi',
           'mat_extremum', 'eps_ratio_from_r', 'isotropic_eps_ratio', 'eq40_objective', 'eq41_r2',
           'eq25_lambdas', 'slip_force_tensor', 'strip_lateral_force', 'STRIP_GRID', 'STRIP_BISECTIONS',
           'steady_strip_state_array', 'steady_tan_phi_with_strip_array', 'steady_tan_phi_with_strip',
           'settling_length_array', 'FULL_CONTACT', 'LIFT_OFF', 'TIPS', 'contact_fraction',
           'pushed_at_height', 'cell_centres', 'full_slip_rotation_grid', 'steady_force_direction',
           'torsional_stiffness_grid', 'adhesion_length', 'creep_stiffness', 'deflection_profile',
           'slip_onset', 'spin_coefficients', 'steady_force', 'steady_force_profile']
