"""identified.json's object read back, typed (from_json): every field
checked as identify writes it, InputError naming the file and the first
field that is not.  The file itself, built from an identification, its one
writer and its one reader with their checks: identified_file."""
from __future__ import annotations

import math
from pathlib import Path

from ..errors import InputError
from ..fmu import RULES
from . import identified
from .measurements import data_digest

WRITTEN_BY = "written by `orthocontact identify`"


def from_json(path, d: dict) -> identified.IdentifiedFile:
    """The typed file of identified.json's object `d` (read from `path`);
    InputError naming the file and the first field that is not as identify
    writes it (the parts in the order below)."""
    path = Path(path)
    top = _Fields(path, "", d)
    estimates = _estimates(path, top, d)
    assumptions = _assumptions(top, estimates, d)
    record = _data_record(path, top)
    points = _points(top)
    noise = _noise(top)
    joint = d.get("covariance_joint")
    assumed = d.get("noise_assumed", [])
    if not (isinstance(assumed, list) and all(isinstance(g, str) for g in assumed)):
        top.fail("noise_assumed", "a list of data groups", assumed)
    reduction = _reduction(top, d)
    intervals = d.get("intervals")
    if not isinstance(intervals, str):
        top.fail("intervals", "a string", intervals)
    fit = _fit_record(top.sub("fit"))
    return identified.IdentifiedFile(
        estimates=estimates, max_rule=top.obj("max_rule"), eq40=top.obj("eq40"), eq41=top.obj("eq41"),
        eq1=top.obj("eq1"), noise_estimate=dict(noise.d), noise_model=top.obj("noise_model", optional=False),
        intervals=intervals, noise_assumed=tuple(assumed),
        fit_residuals=top.obj("fit_residuals", optional=False), dof=top.integer("dof", lo=-10**9),
        covariance=_covariance(path, "covariance", d.get("covariance")),
        covariance_joint=None if joint is None else _covariance(path, "covariance_joint", joint),
        points=points, ramp_stick_points=top.integer("ramp_stick_points"),
        validation_fmu=top.obj("validation_fmu"), data=record, assumptions=assumptions, fit=fit,
        reduction=reduction, path=path)


def _estimates(path, top, d) -> dict:
    """The five reported parameters (each an estimate or why not) and those fitted too."""
    estimates = {}
    for name in identified.REPORTED + identified.FITTED_TOO:
        if name in d or name in identified.REPORTED:
            if not isinstance(d.get(name), dict):
                top.fail(name, f"an object {WRITTEN_BY}", d.get(name))
            estimates[name] = _estimate(path, name, d[name])
    return estimates


def _assumptions(top, estimates: dict, d) -> identified.Assumptions:
    """"assumptions": the rig and rule fitted on; F_int and the strip's
    viscosity "estimated" only with their estimates."""
    a = top.sub("assumptions")
    rule = a.d.get("rule")
    if rule not in RULES:
        a.fail("rule", f"one of {', '.join(RULES)}", rule)
    assumptions = identified.Assumptions(
        rule=rule, alpha_offset_deg=a.number("alpha_offset_deg", what="a finite number [deg]"),
        beta_offset_deg=a.number("beta_offset_deg", what="a finite number [deg]"),
        mass_kg=a.number("mass_kg", 0, lo_open=True), g=a.number("g", 0, lo_open=True),
        f_int_N=a.number_or_estimated("f_int_N"), ramp_angle_deg=a.number("ramp_angle_deg"),
        mu_strip=a.number("mu_strip", 0), c_strip_N_s_m=a.number_or_estimated("c_strip_N_s_m"),
        phi_convention=a.text("phi_convention"), ci=a.text("ci"))
    for key, name in (("f_int_N", "f_int"), ("c_strip_N_s_m", "c_strip")):
        estimated = isinstance(estimates.get(name), identified.Estimate)
        if getattr(assumptions, key) == "estimated" and not estimated:
            top.fail(name, f'its estimate (assumptions.{key} is "estimated")', d.get(name))
    return assumptions


def _data_record(path, top) -> identified.DataRecord:
    """"data": the folder and every file the identification read, with the
    digest over them (an edit of the file shows there)."""
    data = top.sub("data")
    files = data.d.get("files")
    if not isinstance(files, dict) or not files or not all(
            isinstance(k, str) and isinstance(v, str) for k, v in files.items()):
        raise InputError(f"{path}: data.files: expected the SHA-256 of every file the identification "
                         "read (`orthocontact identify` writes them; run it again)")
    stated = data.d.get("sha256")
    if stated != data_digest(files):
        raise InputError(f"{path}: data.sha256: expected the digest of data.files' listing "
                         f"({data_digest(files)[:12]}...), got {str(stated)[:12]}...: the file was edited")
    folder = data.d.get("folder")
    if not isinstance(folder, str) or not folder:
        raise InputError(f"{path}: data.folder: expected the measurement folder's path")
    return identified.DataRecord(folder=folder, absolute_folder=data.text("absolute_folder"),
                                 forces=data.integer("forces"), angles=data.integer("angles"),
                                 ramp=data.integer("ramp"), files=dict(files), sha256=stated)


def _points(top) -> identified.Points:
    """"points": the measured angles (with a velocity each, if any) and forces."""
    pts = top.sub("points")
    points = identified.Points(angles=pts.rows("angles", 2, "[[mat angle deg, phi deg], ...]"),
                               angle_velocities=pts.rows("angle_velocities", 1, "a velocity [m/s] per angle"),
                               forces=pts.rows("forces", 2, "[[mat angle deg, force N], ...]"))
    if points.angle_velocities is not None and len(points.angle_velocities) != len(points.angles or ()):
        pts.fail("angle_velocities", f"one velocity [m/s] per angle ({len(points.angles or ())})",
                 len(points.angle_velocities))
    return points


def _noise(top):
    """"noise_estimate": each group's noise >= 0, the angles' by velocity."""
    noise = top.sub("noise_estimate")
    for k, v in noise.d.items():
        if k == "angles_deg_by_velocity":
            if not (isinstance(v, dict) and all(is_number(_float(s)) and is_number(x) and x >= 0
                                                for s, x in v.items())):
                noise.fail(k, "{velocity m/s: number >= 0 [deg]}", v)
        else:
            noise.number(k, 0, what="a number >= 0")
    return noise


def _reduction(top, d) -> identified.ReductionSummary | None:
    """"reduction" (raw recordings only): the runs by kind, those left out
    or flagged, the table, figures and scenario written."""
    if d.get("reduction") is None:
        return None
    r = top.sub("reduction")
    runs, left, flagged, figures = (r.d.get(k) for k in ("runs", "left_out", "flagged", "figures"))
    if not (isinstance(runs, dict) and all(isinstance(n, int) for n in runs.values())):
        r.fail("runs", "{kind: count}", runs)
    if not (isinstance(left, list) and isinstance(flagged, dict) and isinstance(figures, list)):
        r.fail("", "runs, left_out, flagged, table, figures and scenario", d["reduction"])
    return identified.ReductionSummary(runs=dict(runs), left_out=tuple(left), flagged=dict(flagged),
                                       table=r.text("table"), figures=tuple(figures),
                                       scenario=r.text("scenario", optional=True))


def short_repr(v) -> str:
    """repr(v), cut to 60 characters: a value a message shows."""
    r = repr(v)
    return r if len(r) <= 60 else r[:57] + "..."


class _Fields:
    """Typed values out of one JSON object; InputError '<file>: <field>:
    expected <what>, got <value>'."""

    def __init__(self, path: Path, where: str, d):
        self.path, self.where = path, where
        if not isinstance(d, dict):
            self.fail("", f"an object {WRITTEN_BY}", d)
        self.d = d

    def fail(self, key, what, got, why=""):
        field = ".".join(k for k in (self.where, key) if k)
        raise InputError(f"{self.path}: {field}: expected {what}, got {short_repr(got)}{why}")

    def sub(self, key, optional=False):
        v = self.d.get(key)
        if v is None and optional:
            return None
        if not isinstance(v, dict):
            self.fail(key, f"an object {WRITTEN_BY}", v)
        return _Fields(self.path, ".".join(k for k in (self.where, key) if k), v)

    def number(self, key, lo=None, lo_open=False, what=None, optional=False):
        v = self.d.get(key)
        if v is None and optional:
            return None
        ok = is_number(v) and (lo is None or (v > lo if lo_open else v >= lo))
        if not ok:
            self.fail(key, what or ("a finite number" + ("" if lo is None else
                                                       f" {'>' if lo_open else '>='} {lo:g}")), v)
        return float(v)

    def integer(self, key, lo=0):
        v = self.d.get(key)
        if not (isinstance(v, int) and not isinstance(v, bool) and v >= lo):
            self.fail(key, f"an integer >= {lo}", v)
        return v

    def text(self, key, optional=False):
        v = self.d.get(key)
        if v is None and optional:
            return None
        if not isinstance(v, str):
            self.fail(key, "a string", v)
        return v

    def obj(self, key, optional=True):
        """An object kept as written (a section of the report)."""
        v = self.d.get(key)
        if not (isinstance(v, dict) or (v is None and optional)):
            self.fail(key, "an object" + (" or null" if optional else ""), v)
        return v

    def rows(self, key, width, what):
        """None, or a list of numbers (width 1) or of rows of `width` numbers."""
        v = self.d.get(key)
        if v is None:
            return None
        one = (lambda x: is_number(x)) if width == 1 else (
            lambda x: isinstance(x, list) and len(x) == width and all(is_number(y) for y in x))
        if not (isinstance(v, list) and all(one(x) for x in v)):
            self.fail(key, what + " or null", v)
        return tuple(float(x) for x in v) if width == 1 else tuple(tuple(float(y) for y in x) for x in v)

    def number_or_estimated(self, key, lo=0.0):
        v = self.d.get(key)
        if v == "estimated":
            return v
        return self.number(key, lo, what=f'a number >= {lo:g} or "estimated"')


def is_number(v) -> bool:
    """A finite int or float (not a bool)."""
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _estimate(path, name, d) -> identified.Estimate | identified.NotIdentified:
    f = _Fields(path, name, d)
    if "value" not in d:
        if d.get("identifiable") is False:
            return identified.NotIdentified(f.text("reason"))
        f.fail("value", "a finite number > 0 (or identifiable: false and the reason)", None)
    value = f.number("value", 0, lo_open=True)
    stderr = f.number("stderr", 0)
    ci = d.get("ci95")
    if not (isinstance(ci, list) and len(ci) == 2 and all(is_number(x) for x in ci) and ci[0] <= ci[1]):
        f.fail("ci95", "[low, high], low <= high", ci)
    dof = d.get("dof")
    if dof == "inf":
        dof = math.inf
    elif dof is not None:
        dof = f.number("dof", 0, lo_open=True, what='a number > 0, "inf" or null')
    return identified.Estimate(value, stderr, (float(ci[0]), float(ci[1])), dof,
                               f.text("unit", optional=True), f.text("note", optional=True))


def _covariance(path, where, d) -> identified.Covariance:
    if not isinstance(d, dict) or not {"parameters", "values", "matrix"} <= set(d):
        raise InputError(f"{path}: {where}: expected parameters, values and matrix "
                         f"({WRITTEN_BY}; run it again)")
    names = d["parameters"]
    if not (isinstance(names, list) and names and all(isinstance(n, str) for n in names)
            and len(set(names)) == len(names)):
        raise InputError(f"{path}: {where}.parameters: expected the names of the estimates, "
                         f"got {short_repr(names)}")
    k, values, matrix = len(names), d["values"], d["matrix"]
    if not (isinstance(values, list) and len(values) == k and isinstance(matrix, list) and len(matrix) == k
            and all(isinstance(r, list) and len(r) == k for r in matrix)):
        raise InputError(f"{path}: {where}: expected {k} values and a {k}x{k} matrix, got "
                         f"{len(values) if isinstance(values, list) else 0} and {short_repr(matrix)}")
    if not (all(is_number(v) for v in values) and all(is_number(x) for r in matrix for x in r)):
        raise InputError(f"{path}: {where}: expected finite numbers")
    if any(v <= 0 for v in values):
        raise InputError(f"{path}: {where}.values: expected estimates > 0, got {short_repr(values)}")
    return identified.Covariance(tuple(names), tuple(float(v) for v in values),
                                 tuple(tuple(float(x) for x in r) for r in matrix))


def _fit_record(fields) -> identified.FitRecord:
    """identified.json's "fit": how the joint fit ended (identified.FitRecord)."""
    d = fields.d
    if not isinstance(d.get("converged"), bool) or not isinstance(d.get("forced", False), bool):
        fields.fail("converged", "true or false", d.get("converged"))
    convergence, solves, tests = d.get("convergence"), d.get("solves"), d.get("lack_of_fit")
    if not (isinstance(convergence, dict) and all(isinstance(v, bool) for v in convergence.values())):
        fields.fail("convergence", "{part: true or false}", convergence)
    if not (isinstance(solves, list) and solves and all(isinstance(x, dict) for x in solves)):
        fields.fail("solves", "a list of the solves' outcomes", solves)
    if not (isinstance(tests, dict) and all(isinstance(t, dict) and isinstance(t.get("rejected"), bool)
                                            and isinstance(t.get("line"), str) for t in tests.values())):
        fields.fail("lack_of_fit", "{group: its test}", tests)
    if d["converged"] != all(convergence.values()):
        fields.fail("converged", f"{str(all(convergence.values())).lower()} (as its convergence says)",
                    d["converged"])
    return identified.FitRecord(converged=d["converged"], convergence=dict(convergence),
                                reweighting_rounds=fields.integer("reweighting_rounds"), solves=tuple(solves),
                                lack_of_fit=dict(tests), forced=d.get("forced", False))


def _float(s):
    try:
        return float(s)
    except (TypeError, ValueError):
        return None
