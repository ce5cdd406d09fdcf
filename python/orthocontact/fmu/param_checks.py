"""What the law's parameters are checked against, as code that reads the
variable tables as data: a Row is one variable of a table (fmu/generated.py
writes the law's and the patch's rows from the tables), check() judges one
value by its row, and LawParameters is what the generated ContactParams does
beyond holding its fields (the checks, fmu_values, replace).

Units as the tables give them ("" for none); angles in rad."""
from __future__ import annotations

import dataclasses
import math
import numbers
from collections.abc import Mapping
from typing import ClassVar, TypeVar

ANGLE_UNIT = "rad"


@dataclasses.dataclass(frozen=True)
class Row:
    """One variable of a variable table: its type (the table's: Float64,
    Int32), unit ("" for none; an angle's is rad), range [min, max] (None:
    unbounded), start and description."""
    name: str
    type: str
    unit: str
    min: float | int | None
    max: float | int | None
    start: float | int | None
    description: str = ""

    @property
    def is_angle(self) -> bool:
        return self.unit == ANGLE_UNIT


def is_real(value) -> bool:
    """A real number of any kind (numpy's too), not a bool."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def angle_text(x: float) -> str:
    """An angle limit [rad] as the FMU's range states it: a multiple of pi where it is one."""
    turns = x / math.pi
    return f"{round(turns):d} pi" if abs(turns - round(turns)) < 1e-12 else repr(x)


def unit_text(row: Row) -> str:
    return f" [{row.unit or '-'}]"


def check(owner: str, row: Row, value) -> None:
    """One law parameter against its row's type and range; ValueError
    (starting with `owner`, the class's name) names the unit and, for an
    angle, the degrees a user may have typed."""
    lo, hi = row.min, row.max
    positive = lo is not None and lo > 0 and not row.is_angle
    given = value                # as the user typed it, for the messages
    if is_real(value):
        value = float(value)     # numpy's float32 compared with 1e150 would overflow
    if not isinstance(value, float) or not math.isfinite(value) or (positive and value <= 0):
        need = "a finite number > 0" if positive else "a finite number"
        unit = "" if positive else unit_text(row)
        raise ValueError(f"{owner}: {row.name}{unit} must be {need}, got {given!r}")
    if (lo is None or value >= lo) and (hi is None or value <= hi):
        return
    if row.is_angle and lo is not None and hi is not None:
        raise ValueError(f"{owner}: {row.name} = {given!r} rad is outside [{angle_text(lo)}, "
                         f"{angle_text(hi)}] rad, the FMU's range; degrees? ({row.name} is in rad: "
                         f"{owner}.from_degrees takes deg)")
    raise ValueError(f"{owner}: {row.name} = {given!r}{unit_text(row)} is outside [{lo!r}, {hi!r}], "
                     "the FMU's range")


def radians(degrees: float) -> float:
    """An angle given in degrees, in rad; a value that is no real number is
    passed on unchanged, for the check to refuse it as the user gave it."""
    return math.radians(degrees) if is_real(degrees) else degrees


def refuse_misnamed(cls: type, misnamed: Mapping[str, object]) -> None:
    """TypeError for a keyword from_degrees does not take: an angle named
    in rad (`alpha` for `alpha_deg`) or a name that is no parameter."""
    angles = {row.name for row in getattr(cls, "TABLE", ()) if row.is_angle}
    for key in misnamed:
        if key in angles:
            raise TypeError(f"{cls.__name__}.from_degrees takes {key}_deg (degrees), not {key}")
        raise TypeError(f"{cls.__name__}.from_degrees() got an unexpected keyword argument {key!r}")


P = TypeVar("P", bound="LawParameters")


class LawParameters:
    """The behaviour of a dataclass of the law's parameters whose fields are
    the rows of TABLE (floats) and `rule` (a name of RULE_NUMBERS): every
    field checked when it is made (numpy's numbers become floats), the FMU's
    parameters by name.  The subclass, generated, declares the fields."""
    TABLE: ClassVar[tuple[Row, ...]]            # the law's rows, in the table's order
    RULE_NUMBERS: ClassVar[Mapping[str, int]]    # the sliding rules' names and numbers
    RULE_VARIABLE: ClassVar[str]                 # the FMU's parameter that takes the number
    rule: str

    def __post_init__(self) -> None:
        owner = type(self).__name__
        if self.rule not in self.RULE_NUMBERS:
            raise ValueError(f"{owner}: rule must be one of {', '.join(map(repr, self.RULE_NUMBERS))}, "
                             f"got {self.rule!r}")
        for row in self.TABLE:
            value = getattr(self, row.name)
            check(owner, row, value)
            object.__setattr__(self, row.name, float(value))   # numpy's numbers become floats

    @classmethod
    def law_parameters(cls) -> tuple[str, ...]:
        """The law's parameters in the table's order (the fields but `rule`)."""
        return tuple(row.name for row in cls.TABLE)

    def replace(self: P, **changes: object) -> P:
        """A copy with the given fields changed (checked again)."""
        return dataclasses.replace(self, **changes)   # type: ignore[type-var]  # the subclass is one

    def fmu_values(self) -> dict[str, float | int]:
        """The contact FMU's parameters by the manifest's names: the law's in the
        table's order (floats: angles in rad, stiffnesses in N/m) and
        RULE_VARIABLE, slidingRule (the rule's number)."""
        values: dict[str, float | int] = {name: float(getattr(self, name)) for name in self.law_parameters()}
        values[self.RULE_VARIABLE] = self.RULE_NUMBERS[self.rule]
        return values
