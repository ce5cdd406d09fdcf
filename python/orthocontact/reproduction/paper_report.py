"""report.md and report.json: every number the paper prints beside the value
obtained here, with the kind of evidence each comparison is (closed-form,
round-trip, prediction), the calibration chain, the sensitivity section and
a section per group of scenario kinds (Section): the contact patch's
(patch_report) and the contact pad's (pad_report: not the paper's, not
counted), then the paper's scenarios.

Each scenario kind's part of the report (experiment.kinds.ReportPart: its
section, its lines, its entry in report.json, the paper's numbers it
compares with) is its piece "report", registered where it is written: the
sweep's and the step study's here, the patch's in patch_report and the
pad's in pad_report (imported here: this module has every part of the
report); the report asks each scenario's kind."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..experiment import KINDS as SCENARIO_KINDS
from ..experiment import ReportPart, Scenario, Section, kind_of, register
from ..output import write_json
from . import pad_report, patch_report  # noqa: F401  (register their kinds' parts: the report has them all)
from .sensitivity import report_lines

# The paper's scenarios, each with its figures: the report's last section
# (`orthocontact reproduce` prints the report up to its heading).
SCENARIOS = Section("Scenarios", always=True)


def sections() -> list[Section]:
    """The report's sections of scenarios, in order: those of the kinds'
    parts as the kinds come (experiment.kinds.KINDS), SCENARIOS last.
    (KINDS here are the kinds of evidence of the paper's rows.)"""
    found = [k.part("report").section for k in SCENARIO_KINDS.values()]
    return [s for s in dict.fromkeys(found) if s is not SCENARIOS] + [SCENARIOS]


def section_index(sc: Scenario) -> int:
    """The place of the scenario's section among sections()."""
    return sections().index(kind_of(sc).part("report").section)

# -- the paper reproduction report ---------------------------------------------------

KINDS = ("closed-form", "round-trip", "prediction")


KIND_MEANING = {
    "closed-form": "the FMU through the rig harness against the number the paper computes with "
                   "its own formula",
    "round-trip": "returns a number the scenario was calibrated on: it checks the chain, "
                  "not the model",
    "prediction": "the model computes it from inputs that do not contain it",
}


def paper_rows(sc: Scenario, summary: dict) -> list[dict]:
    """Each number the paper prints for the scenario beside the value
    obtained here (its kind's ReportPart.rows; none for most kinds)."""
    rows = kind_of(sc).part("report").rows
    return rows(sc, summary) if rows is not None else []


def sweep_rows(sc: Scenario, summary: dict) -> list[dict]:
    """Each number the paper prints for a sweep beside the value obtained
    here, with the kind of evidence the comparison is (KINDS).  Angles are
    signed in the paper's convention (ours negated where it counts phi the
    other way).  Tolerances: the paper's rounding (2 decimals for angles,
    0.05 N for forces, 3 decimals for mu) plus the fit's resolution."""
    p = sc.paper
    flip = -1.0 if p.get("phi_sign_differs") else 1.0
    convention = "the paper's sign: ours negated" if flip < 0 else "the paper's sign = ours"
    rows = []

    def add(key, quantity, paper, here, tol, unit="", other=None, conv="", match=None):
        kind = "round-trip" if key in p.get("calibrated_on", []) else p.get("evidence", "prediction")
        row = {"scenario": sc.name, "quantity": quantity, "paper": paper, "here": here,
               "difference": here - paper, "tolerance": tol, "unit": unit,
               "match": abs(here - paper) <= tol if match is None else match, "kind": kind,
               "convention": conv}
        if other is not None:
            row["other_rule"] = other
        rows.append(row)

    e = summary["extremum"] or {}
    o = e.get("other_rule")
    other = None if o is None else {"rule": o["rule"], "here": flip * o["phi_deg"]}
    if "extremum_phi_deg" in p:
        add("extremum_phi_deg", f"extremal φ, {sc.law.rule} rule", p["extremum_phi_deg"],
            flip * e["phi_deg"], 0.05, "deg", other, convention)
    if "extremum_angle_deg" in p:
        add("extremum_angle_deg", "angle of the extremum", p["extremum_angle_deg"], e["angle_deg"],
            0.05, "deg")
    if "phi_max_deg" in p:
        add("phi_max_deg", "max |φ|", p["phi_max_deg"], abs(e["phi_deg"]), 0.05, "deg")
    if "max_abs_phi_deg" in p:
        add("max_abs_phi_deg", "max |φ| (isotropy)", p["max_abs_phi_deg"], summary["max_abs_phi_deg"],
            "≤ paper", "deg", match=summary["max_abs_phi_deg"] <= p["max_abs_phi_deg"] + 1e-9)
    d = summary.get("drive_mean_N", {})
    if "drive_0_N" in p and "0" in d:
        add("drive_0_N", "driving force at 0°", p["drive_0_N"], d["0"], 0.05, "N")
    if "drive_90_N" in p and "90" in d:
        add("drive_90_N", "driving force at 90°", p["drive_90_N"], d["90"], 0.05, "N")
    mu = summary.get("mu_from_drive", {})
    if "mu1" in p and "mu1" in mu:
        add("mu1", "μ1 from the forces (eq. 1)", p["mu1"], mu["mu1"], 5e-4)
    if "mu2" in p and "mu2" in mu:
        add("mu2", "μ2 from the forces (eq. 1)", p["mu2"], mu["mu2"], 5e-4)
    return rows


# The paper's measured inputs of the calibration (sec. 2.2, 4.6).
PAPER_FORCES_N = (12.50, 16.50)     # driving force at mat angle 0 and 90 deg


PAPER_PHI_MAX_DEG = 11.5            # in the paper's convention (clockwise)


PAPER_RIG = {"mass_kg": 1.875, "f_int_N": 5.0}


def _paper_calibration(mu1=None, mu2=None):
    from pathlib import Path

    from ..experiment import RigSetup
    from ..identification import MeasurementSet, eq1, max_rule
    data = MeasurementSet(Path("paper"), RigSetup(**PAPER_RIG),
                          forces=np.array([[0.0, PAPER_FORCES_N[0]], [90.0, PAPER_FORCES_N[1]]]),
                          angles=np.array([[39.2, -PAPER_PHI_MAX_DEG]]))  # counterclockwise sign
    mu = eq1(data)
    return mu, max_rule(data, mu["mu1"] if mu1 is None else mu1, mu["mu2"] if mu2 is None else mu2)


def calibration_rows() -> list[dict]:
    """The paper's calibration (sec. 2.2, 4.6) run through orthocontact.identify
    on the paper's own inputs: forces 12.50 / 16.50 N with F_int = 5 N,
    m = 1.875 kg, and phi_max = 11.5 deg; eq. (39) with the paper's rounded mu,
    which is how the paper gets 1.251 (calibration_chain: from the forces)."""
    mu, mr = _paper_calibration(0.408, 0.625)
    rows = []
    for q, paper, here, tol in (("μ1 by eq. (1) from 12.50 N", 0.408, mu["mu1"], 5e-4),
                                ("μ2 by eq. (1) from 16.50 N", 0.625, mu["mu2"], 5e-4),
                                ("l1/l2 by the maximum rule, eq. (38)", 0.817, mr["l1_l2_ratio"], 5e-4),
                                ("ε1/ε2 by eq. (39) with the rounded μ 0.408, 0.625", 1.251,
                                 mr["eps_ratio"], 1e-3)):
        rows.append({"scenario": "calibration", "quantity": q, "paper": paper, "here": here,
                     "difference": here - paper, "tolerance": tol, "unit": "",
                     "match": abs(here - paper) <= tol, "kind": "closed-form", "convention": ""})
    return rows


def calibration_chain() -> list[dict]:
    """The calibration from the measurements, nothing rounded on the way:
    mu from the forces (eq. 1), then l1/l2 from phi_max (eq. 38), then
    eps1/eps2 from those mu (eq. 39).  Each step: what, value, from what."""
    mu, mr = _paper_calibration()
    _, rounded = _paper_calibration(0.408, 0.625)
    return [
        {"step": "μ1 by eq. (1)", "value": mu["mu1"], "from": "12.50 N at 0°, F_int 5 N, m 1.875 kg"},
        {"step": "μ2 by eq. (1)", "value": mu["mu2"], "from": "16.50 N at 90°"},
        {"step": "l1/l2 by eq. (38)", "value": mr["l1_l2_ratio"], "from": "φmax = 11.5°"},
        {"step": "ε1/ε2 by eq. (39)", "value": mr["eps_ratio"], "from": "l1/l2 and the unrounded μ"},
        {"step": "ε1/ε2 by eq. (39), paper", "value": rounded["eps_ratio"],
         "from": "the rounded μ 0.408, 0.625: the paper's 1.251"},
    ]


def counts(rows: list[dict]) -> dict:
    """kind -> {"matched", "rows"}."""
    return {k: {"matched": sum(r["match"] for r in rows if r["kind"] == k),
                "rows": sum(r["kind"] == k for r in rows)} for k in KINDS}


def headline(rows: list[dict]) -> str:
    c = counts(rows)
    parts = [f"{k}: {c[k]['matched']} of {c[k]['rows']} matched" for k in KINDS if c[k]["rows"]]
    missing = [k for k in KINDS if not c[k]["rows"]]
    text = "; ".join(parts)
    if missing:
        text += "; " + ", ".join(missing) + ": none among the paper's printed numbers"
    return text


def _rules_at_experiment(runs) -> dict | None:
    for sc, s in runs:
        e = s.get("extremum")   # a sweep's (the other kinds' summaries have none)
        if sc.paper.get("extremum_phi_deg") is not None and e and "other_rule" in e \
                and sc.closed_form == "mat":
            flip = -1.0 if sc.paper.get("phi_sign_differs") else 1.0
            return {"scenario": sc.name, "angle_deg": e["angle_deg"],
                    "measured_phi_deg": sc.paper["extremum_phi_deg"],
                    "rules": {sc.law.rule: flip * e["phi_deg"],
                              e["other_rule"]["rule"]: flip * e["other_rule"]["phi_deg"]},
                    "convention": "paper's: φ clockwise", "sign_free": sign_free_peaks(sc)}
    return None


def sign_free_peaks(sc: Scenario) -> dict:
    """Each implicit rule's largest |phi| over the scenario's range and its
    angle, from the steady closed form on a 0.01 deg grid: a comparison with
    the measured peak that does not depend on how the paper's sign is read."""
    from ..runs import closed_form_phi_deg_array
    lo = sc.sweep["start_deg"]
    grid = np.linspace(lo, lo + (sc.angle_count() - 1) * sc.sweep["step_deg"], 9001)
    out = {}
    for rule in ("coupled", "associated"):
        phi = closed_form_phi_deg_array(sc, grid, rule)
        k = int(np.argmax(np.abs(phi)))
        out[rule] = {"peak_abs_phi_deg": float(abs(phi[k])), "angle_deg": float(grid[k])}
    return out


SIGN_READING = [
    "## Signs: the reading this report uses", "",
    "The paper counts φ clockwise in the experiment: eq. (40) writes the mat's axis as "
    "β = 90° − α, a mirrored angle. Its Case 5 print (+36.87°) has the opposite sign of what its "
    "own eq. (28) gives for Case 5's eigenvalues (−36.87°), while its mat calibration (eq. 29, "
    "λ1/λ2 = 0.817) uses eq. (28) with the measured +11.5° as printed. This report reads both "
    "Case 5 and the experiment as clockwise (`paper.phi_sign_differs` in their scenario files), "
    "because that is the only reading under which the paper's printed numbers agree with each "
    "other and with its calibrated ε1/ε2 = 1.251: keeping Case 5's printed sign for the mat would "
    "turn the measured 11.5° into ε1/ε2 = 1.875. Its consequence: in one physical frame Case 5's "
    "law and the calibrated mat turn the block in opposite directions (docs/explanation/model-notes.md, "
    "erratum 6).", ""]



def _fmt(x):
    if isinstance(x, float):
        return f"{x:.4f}" if abs(x) < 1e4 else f"{x:.4g}"
    return str(x)


def reproduction_report(out: Path, runs: list[tuple[Scenario, dict]], rows: list[dict],
                        seconds: float, sensitivity: dict | None = None) -> str:
    """report.md and report.json (the rows with their kinds, the counts, the
    calibration chain, the two rules at the experiment) into out."""
    chain = calibration_chain()
    rules = _rules_at_experiment(runs)
    write_json(out / "report.json", {"rows": [{k: r[k] for k in ("scenario", "quantity", "paper", "here",
                                                                  "tolerance", "match", "kind", "unit",
                                                                  "convention", "other_rule") if k in r}
                                              for r in rows],
                                     "counts": counts(rows), "kinds": KIND_MEANING,
                                     "calibration_chain": chain, "rules_at_experiment": rules,
                                     "sensitivity": sensitivity,
                                     **{sec.json_key: section_json(sec, runs) for sec in sections()
                                        if sec.json_key}})
    lines = rows_lines(rows, seconds) + (rules_lines(rules) if rules else []) + chain_lines(chain)
    if sensitivity:
        lines += report_lines(sensitivity)
    for sec in sections():
        lines += section_lines(sec, runs)
    text = "\n".join(lines) + "\n"
    (out / "report.md").write_text(text)
    return text


def rows_lines(rows: list[dict], seconds: float) -> list[str]:
    """report.md's head: what each kind of evidence means, the table of
    every row against the paper, and the headline."""
    lines = ["# orthocontact: reproduction of Konyukhov & Schweizerhof (2007)", "",
             f"Every scenario of the paper run through the OrthotropicContact FMU in the rig "
             f"harness ({seconds:.0f} s). Each row says what kind of evidence it is:", ""]
    lines += [f"- **{k}**: {KIND_MEANING[k]}." for k in KINDS]
    lines += ["", "Signed angles are in the paper's convention where it gives one (the column "
              "says which); the other implicit rule's value at the same angle stands beside the "
              "scenario's own. Conventions and the paper's errata these results depend on: "
              "docs/explanation/model-notes.md in the repository.", "",
              "| scenario | quantity | kind | paper | here | other rule, here | tolerance | match |",
              "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        tol = r["tolerance"] if isinstance(r["tolerance"], str) else f"±{r['tolerance']:g}"
        o = r.get("other_rule")
        other = f"{o['rule']}: {_fmt(o['here'])} {r['unit']}" if o else ""
        conv = f"; {r['convention']}" if r.get("convention") else ""
        lines.append(f"| {r['scenario']} | {r['quantity']}{conv} | {r['kind']} | {_fmt(r['paper'])} "
                     f"{r['unit']} | {_fmt(r['here'])} {r['unit']} | {other} | {tol} | "
                     f"{'yes' if r['match'] else '**NO**'} |")
    return lines + ["", f"**{headline(rows)}.**", ""]


def rules_lines(rules: dict) -> list[str]:
    """report.md's section on which rule the experiment supports (the aged
    mat at its extremum under each rule, against the measured angle)."""
    lines = ["## Which rule the experiment supports", "",
             f"The aged mat at its extremum (mat angle {rules['angle_deg']:.2f}°, a location "
             "computed here: the paper prints none), φ in the paper's convention:", "",
             "| | φ [deg] |", "|---|---|",
             f"| measured (paper, sec. 4.6) | {rules['measured_phi_deg']:+.2f} |"]
    for rule, v in rules["rules"].items():
        lines.append(f"| {rule} rule | {v:+.2f} |")
    lines += ["", "The coupled rule's value is a round trip (ε1/ε2 was calibrated on it); the "
              "associated rule's direction depends on μ1, μ2 only, so its value is a "
              f"prediction from the forces: it turns the block the other way, "
              f"{abs(rules['rules']['associated'] - rules['measured_phi_deg']):.1f}° from the "
              "measurement.", ""]
    free = rules.get("sign_free")
    if free:
        c, a = free["coupled"], free["associated"]
        lines += ["Free of any sign reading, from the steady closed form: the associated rule's "
                  f"largest |φ| is {a['peak_abs_phi_deg']:.2f}° at a mat angle of "
                  f"{a['angle_deg']:.2f}°, against the measured "
                  f"{abs(rules['measured_phi_deg']):.1f}°; the coupled rule's is "
                  f"{c['peak_abs_phi_deg']:.2f}° at {c['angle_deg']:.2f}° (a round trip).", ""]
    return lines + SIGN_READING


def chain_lines(chain: list[dict]) -> list[str]:
    """report.md's calibration chain from the measurements."""
    lines = ["## The calibration chain from the measurements", "",
             "| step | value | from |", "|---|---|---|"]
    lines += [f"| {c['step']} | {c['value']:.4f} | {c['from']} |" for c in chain]
    return lines + ["", "Unrounded, the chain gives ε1/ε2 = "
                    f"{chain[3]['value']:.4f}; the paper's 1.251 is what its rounded μ give. The "
                    "scenarios use the paper's 1.251.", ""]


def section_runs(sec: Section, runs: list[tuple[Scenario, dict]]) -> list[tuple[Scenario, dict]]:
    """The runs of the kinds whose part is in `sec`, in order."""
    return [(sc, s) for sc, s in runs if kind_of(sc).part("report").section is sec]


def section_json(sec: Section, runs: list[tuple[Scenario, dict]]) -> dict:
    """report.json's entry of the section: each of its scenarios' entry."""
    return {sc.name: kind_of(sc).part("report").json(sc, s) for sc, s in section_runs(sec, runs)}


def section_lines(sec: Section, runs: list[tuple[Scenario, dict]]) -> list[str]:
    """report.md's lines of the section: its heading and opening, then its
    scenarios' lines, the kinds in their table's order; [] without a
    scenario of its kinds unless it is always written."""
    mine = section_runs(sec, runs)
    if not mine and not sec.always:
        return []
    order = list(SCENARIO_KINDS)
    lines = [f"## {sec.title}", "", *sec.intro]
    for sc, s in sorted(mine, key=lambda r: order.index(kind_of(r[0]).name)):
        lines += kind_of(sc).part("report").lines(sc, s)
    return lines


def scenario_heading(sc: Scenario) -> list[str]:
    """A scenario's heading in SCENARIOS: its title and description."""
    return [f"### {sc.title}", ""] + ([sc.description, ""] if sc.description else [])


def sweep_lines(sc: Scenario, s: dict) -> list[str]:
    """A sweep's lines in SCENARIOS: its extremum against the closed form,
    its figures and data."""
    e = s["extremum"]
    if e is None:  # a flat curve has no extremum
        shape = (f"flat: |φ| ≤ {s['max_abs_phi_deg']:.1e}° over the sweep (closed form "
                 f"({s['closed_form']}) likewise)")
    else:
        shape = (f"extremum φ = {e['phi_deg']:.3f}° at {e['angle_deg']:.3f}°; closed form "
                 f"({s['closed_form']}) {s['closed_form_extremum']['phi_deg']:.3f}° at "
                 f"{s['closed_form_extremum']['angle_deg']:.3f}°")
    return scenario_heading(sc) + [
        f"- mode {s['mode']}, rule {s['rule']}, {s['n_angles']} angles; {shape}; "
        f"largest deviation from the closed form {s['max_deviation_deg']:.2e}°.",
        f"- figures: [φ vs angle]({sc.name}/phi_vs_angle.png), "
        f"[trajectories]({sc.name}/trajectories.png), "
        f"[driving force]({sc.name}/force_vs_travel.png); "
        f"data: [{sc.name}/sweep.csv]({sc.name}/sweep.csv)", ""]


def step_study_lines(sc: Scenario, s: dict) -> list[str]:
    """A step study's lines in SCENARIOS: each rule's spread over the steps."""
    lines = scenario_heading(sc)
    for rule, d in s["rules"].items():
        lines.append(f"- {rule}: spread over step sizes {d['spread_deg']:.2e}°, largest "
                     f"deviation from the closed form {d['max_deviation_deg']:.3f}°")
    return lines + [f"- figure: [step study]({sc.name}/step_study.png); data: "
                    f"[{sc.name}/step_study.csv]({sc.name}/step_study.csv)", ""]


register("sweep", "report", ReportPart(SCENARIOS, sweep_lines, rows=sweep_rows))
register("step_study", "report", ReportPart(SCENARIOS, step_study_lines))
