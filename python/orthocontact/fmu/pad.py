"""Access to the ContactPad FMU (FMI 2.0 or 3.0 Co-Simulation) through
fmpy: the patch's cells (fmu.patch) on a Winkler foundation whose pressure
follows the pad's pose (fmu_src/models/ContactPad/table.h).

Units: displacement u [m] of the pad centre and rotation theta [rad] of the
body relative to the surface (counterclockwise about the normal X3); the
approach d [m] of the pad centre into the surface (> 0 pressed) and the
small tilts phi1, phi2 [rad] about the surface's X1, X2 (a point at (X, Y)
approaches by d + phi2 X - phi1 Y); the foundation's kn [N/m^3] and dn
[N s/m^3].  Outputs: T1, T2 [N], Mz [N m] as the patch's; Fn [N] (>= 0)
and M1, M2 [N m] the pressure's force and moments on the body about the pad
centre's X1, X2; contactFraction [-] the share of the area that presses.

Step semantics as the patch's: `set_inputs` computes every cell's normal
force and step without committing them, so a master can iterate on the
pending result with its derivatives (`jacobian`); `do_step` commits it.

Rolling: vr [m/s] is the speed at which the body's surface passes through
the pad along its axis 1 (> 0: entering at x = +length/2); each step moves
the cells' states with the material by the previous step's vr h, so a
creep u1 = xi vr t is the longitudinal creepage xi (docs/guides/contact-pad.md,
"Rolling")."""
from __future__ import annotations

from dataclasses import dataclass

from .generated import PAD_FLOAT_OUTPUTS, PAD_FOUNDATION, PAD_INPUTS, PAD_INTEGER_OUTPUTS, PAD_MODEL
from .param_checks import Row
from .params import ContactParams
from .patch import CellsFMU, PatchGeometry, refuse_problems, table_row, value_problem

# The foundation's parameters (its parameters the patch has not), in the table's order.
FOUNDATION = tuple(row.name for row in PAD_FOUNDATION)
# The pose: every input but the rolling speed vr, in the table's order; what
# set_inputs sets and jacobian differentiates (no output depends on vr directly).
ROLLING = "vr"
POSE = tuple(name for name in PAD_INPUTS if name != ROLLING)
# What load() reads: the six-component wrench on the body.
WRENCH = ("T1", "T2", "Mz", "Fn", "M1", "M2")


def foundation_row(name: str) -> Row:
    """The row of the foundation's parameter `name` (FOUNDATION) in the FMU's table."""
    return table_row(PAD_FOUNDATION, name, f"{PAD_MODEL} has no foundation parameter")


def foundation_problem(name: str, value) -> str | None:
    """What is wrong with `value` for the foundation's parameter `name` by
    the FMU's own table (a finite number in [min, max]: the patch's
    value_problem); None if it is right."""
    return value_problem(foundation_row(name), value)


@dataclass(frozen=True)
class Foundation:
    """The Winkler foundation under the pad: kn [N/m^3] the pressure per
    unit approach, dn [N s/m^3] per unit approach rate (the table's start,
    0, by default).  A value the FMU's table refuses raises ValueError."""
    kn: float
    dn: float = foundation_row("dn").start

    def __post_init__(self):
        refuse_problems(self, PAD_FOUNDATION)


class PadFMU(CellsFMU):
    """One instance of the ContactPad FMU, FMI 2.0 or 3.0."""
    MODEL = PAD_MODEL
    INPUTS = POSE
    FLOAT_OUTPUTS = PAD_FLOAT_OUTPUTS
    INTEGER_OUTPUTS = PAD_INTEGER_OUTPUTS
    LOAD = WRENCH

    def __init__(self, fmu_path=None, instance_name: str = "pad", fmi_version: int = 2):
        super().__init__(fmu_path, instance_name, fmi_version)

    def initialize(self, params: ContactParams, geometry: PatchGeometry, foundation: Foundation,
                   pose: tuple = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0), vr: float = 0.0):
        """Sets the law's parameters, the pad's geometry and foundation, the
        initial pose (u1 [m], u2 [m], theta [rad], d [m], phi1 [rad], phi2
        [rad]) and rolling speed vr [m/s], and enters step mode; every cell
        starts unloaded where the pose puts it (initialSlip = atInputs)."""
        if len(pose) != len(POSE):
            raise ValueError(f"pose must be ({', '.join(POSE)}), got {pose!r}")
        self._start(params, geometry, {name: float(getattr(foundation, name)) for name in FOUNDATION},
                    tuple(pose))
        if vr != 0.0:   # before the first step: the material moves from its commit on
            self._set_inputs(tuple(pose), {ROLLING: vr})

    def set_inputs(self, u1: float, u2: float, theta: float, d: float, phi1: float = 0.0,
                   phi2: float = 0.0, vr: float = 0.0):
        """The pad's pose: displacement [m], rotation [rad], approach [m] and
        tilts [rad], and its rolling speed [m/s] (it moves the states from
        the next step on); the pending step, not committed."""
        self._set_inputs((u1, u2, theta, d, phi1, phi2), {ROLLING: vr})

    def jacobian(self, knowns, outputs=WRENCH) -> list[list[float]]:
        """d(outputs)/d(knowns) of the pending step, a row per output and a
        column per known (names of INPUTS): the FMU's directional derivatives."""
        out_vr = [self.vr[n] for n in outputs]
        cols = [self._call(f"getting d({', '.join(outputs)})/d{k}", self._slave.getDirectionalDerivative,
                           out_vr, [self.vr[k]], [1.0]) for k in knowns]
        return [[col[i] for col in cols] for i in range(len(outputs))]

    def cell_normal_forces(self) -> list[list[float]]:
        """Each cell's normal force [N] in the pending step, [i][j] the i-th
        cell along length, the j-th along width: the FMI 3.0 array cellFn.
        FMI 2.0 has no arrays: ValueError there."""
        return self._cells("cellFn", getattr(self._slave, "getFloat64", None))
