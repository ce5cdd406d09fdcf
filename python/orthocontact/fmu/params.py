"""The law's parameters as the FMU takes them (ContactParams: angles in rad,
stiffness in N/m) and the sliding rules' numbers.

ContactParams is built from the contact's variable table (the manifest's
"law" rows, fmu.variables): its fields, their order, units, ranges, checks
and its docstring, so that a parameter added to the table is a field here
with nothing typed.  Fields up to the first angle are required; an angle
defaults to 0 (its axis along X1), a later parameter to the table's start."""
from __future__ import annotations

import dataclasses
import inspect
import math
import numbers

from .variables import Variable, contact, law_parameters

# The sliding rules' names and the numbers the FMU's slidingRule takes (the
# table's enumeration SlidingRule).
RULES: dict[str, int] = dict(contact().enumerations["SlidingRule"])

ANGLE_UNIT = "rad"
DEFAULT_RULE = "coupled"


def _law_rows() -> tuple[Variable, ...]:
    return tuple(contact().variable(name) for name in law_parameters())


def _is_angle(v: Variable) -> bool:
    return v.unit == ANGLE_UNIT


def _angle_text(x: float) -> str:
    """An angle limit as the FMU's range states it: a multiple of pi where it is one."""
    turns = x / math.pi
    return f"{round(turns):d} pi" if abs(turns - round(turns)) < 1e-12 else repr(x)


def _unit_text(v: Variable) -> str:
    return f" [{v.unit or '-'}]"


def _check(v: Variable, value) -> None:
    """One law parameter against the table's type and range; ValueError names
    the unit and, for an angle, the degrees a user may have typed."""
    lo, hi = v.min, v.max
    positive = lo is not None and lo > 0 and not _is_angle(v)
    given = value                # as the user typed it, for the messages
    if _is_real(value):
        value = float(value)     # numpy's float32 compared with 1e150 would overflow
    if not isinstance(value, float) or not math.isfinite(value) or (positive and value <= 0):
        need = "a finite number > 0" if positive else "a finite number"
        unit = "" if positive else _unit_text(v)
        raise ValueError(f"ContactParams: {v.name}{unit} must be {need}, got {given!r}")
    if (lo is None or value >= lo) and (hi is None or value <= hi):
        return
    if _is_angle(v):
        raise ValueError(f"ContactParams: {v.name} = {given!r} rad is outside [{_angle_text(lo)}, "
                         f"{_angle_text(hi)}] rad, the FMU's range; degrees? ({v.name} is in rad: "
                         "ContactParams.from_degrees takes deg)")
    raise ValueError(f"ContactParams: {v.name} = {given!r}{_unit_text(v)} is outside [{lo!r}, {hi!r}], "
                     "the FMU's range")


def _is_real(value) -> bool:
    """A real number of any kind (numpy's too), not a bool."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def _post_init(self) -> None:
    if self.rule not in RULES:
        raise ValueError(f"ContactParams: rule must be one of {', '.join(map(repr, RULES))}, "
                         f"got {self.rule!r}")
    for v in _law_rows():
        value = getattr(self, v.name)
        _check(v, value)
        object.__setattr__(self, v.name, float(value))   # numpy's numbers become floats


def _from_degrees(cls, *args, **kwargs) -> "ContactParams":
    """The same parameters with the axis angles in degrees (as scenario files
    give them), counterclockwise from X1: positionally in the table's order,
    or by keyword with the angles named `<name>_deg`."""
    values = dict(zip(cls.law_parameters() + ("rule",), args))
    if len(args) > len(values):
        raise TypeError(f"ContactParams.from_degrees takes at most {len(values)} arguments, got {len(args)}")
    angles = _ANGLES
    for key, value in kwargs.items():
        name = key[:-len("_deg")] if key.endswith("_deg") and key[:-len("_deg")] in angles else key
        if name in angles and not key.endswith("_deg"):
            raise TypeError(f"ContactParams.from_degrees takes {name}_deg (degrees), not {name}")
        if name in values:
            raise TypeError(f"ContactParams.from_degrees got {key} twice")
        values[name] = value
    for name in angles & set(values):
        value = values[name]
        if _is_real(value):
            values[name] = math.radians(value)
    return cls(**values)


def _from_degrees_signature() -> inspect.Signature:
    params = [inspect.Parameter("cls", inspect.Parameter.POSITIONAL_OR_KEYWORD)]
    for f in dataclasses.fields(ContactParams):
        name = f"{f.name}_deg" if f.name in _ANGLES else f.name
        default = inspect.Parameter.empty if f.default is dataclasses.MISSING else (
            math.degrees(f.default) if f.name in _ANGLES else f.default)
        params.append(inspect.Parameter(name, inspect.Parameter.POSITIONAL_OR_KEYWORD, default=default,
                                        annotation="float" if f.name != "rule" else "str"))
    return inspect.Signature(params, return_annotation="ContactParams")


def _replace(self, **kw) -> "ContactParams":
    """A copy with the given fields changed (checked again)."""
    return dataclasses.replace(self, **kw)


def _fmu_values(self) -> dict:
    """The contact FMU's parameters by the manifest's names: the law's in the
    table's order (floats: angles in rad, stiffnesses in N/m) and slidingRule
    (the rule's number)."""
    return {**{name: float(getattr(self, name)) for name in self.law_parameters()},
            "slidingRule": RULES[self.rule]}


def _law_parameters(cls) -> tuple[str, ...]:
    """The law's parameters in the table's order (the fields but `rule`)."""
    return law_parameters()


def _degrees_property(name: str) -> property:
    return property(lambda self: math.degrees(getattr(self, name)), doc=f"{name} in degrees.")


def _fields() -> list[tuple]:
    fields, defaulted = [], False
    for v in _law_rows():
        defaulted = defaulted or _is_angle(v)
        if not defaulted:
            fields.append((v.name, float))
        else:
            fields.append((v.name, float, dataclasses.field(default=0.0 if _is_angle(v) else float(v.start))))
    fields.append(("rule", str, dataclasses.field(default=DEFAULT_RULE)))
    return fields


def _doc() -> str:
    rows = "\n".join(f"    {v.name:<6} {v.description}{_unit_text(v)}" for v in _law_rows())
    return (f"Parameters of the law (the contact's variable table):\n\n{rows}\n"
            f"    rule   sliding rule: {', '.join(map(repr, RULES))}\n\n"
            "The angles are in radians, as the FMU takes them; ContactParams.from_degrees\n"
            "takes degrees (`<name>_deg`), as scenario files do.  Invalid values raise ValueError.")


ContactParams = dataclasses.make_dataclass(
    "ContactParams", _fields(), frozen=True,
    namespace={"__post_init__": _post_init, "from_degrees": classmethod(_from_degrees),
               "law_parameters": classmethod(_law_parameters), "replace": _replace,
               "fmu_values": _fmu_values, "__doc__": _doc(), "__module__": __name__})
for _name, _member in list(vars(ContactParams).items()):   # help() names them as members
    _function = getattr(_member, "__func__", _member)
    if _name in ("__post_init__", "from_degrees", "law_parameters", "replace", "fmu_values"):
        _function.__name__, _function.__qualname__ = _name, f"ContactParams.{_name}"
_ANGLES = frozenset(v.name for v in _law_rows() if _is_angle(v))
for _name in _ANGLES:
    setattr(ContactParams, f"{_name}_deg", _degrees_property(_name))
ContactParams.from_degrees.__func__.__signature__ = _from_degrees_signature()

# The FMU's range of the axis angles [rad] (the table's, the same for every angle).
ANGLE_LIMIT_RAD = max(abs(v.max) for v in _law_rows() if _is_angle(v))
