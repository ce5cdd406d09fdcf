"""The command line: its subcommands and their options with their units, each
command's added by a function of its own (the arguments' checks and
--version: cli.arguments)."""
from __future__ import annotations

import argparse
from pathlib import Path

from .arguments import (
    Parser,
    VersionAction,
    angle_deg,
    count,
    out_path,
    positive_float,
    positive_int,
    seed,
    workers,
)
from .commands import (
    cmd_design,
    cmd_export,
    cmd_identify,
    cmd_reproduce,
    cmd_run,
    cmd_sensitivity,
    cmd_ssp,
    cmd_uq,
)

OUT_RULE = "new, empty, or an earlier run's of this command, whose files are replaced"
OWNER_HELP = ("write into --out even if another command's run or files of your own are there: the "
              "other run's files are replaced, files of yours only where named as an output, and what "
              "the command reads is never removed; without it such a folder is refused")


DESCRIPTION = ("The coupled orthotropic adhesion-friction contact law (Konyukhov & "
               "Schweizerhof 2007) as FMI 2.0/3.0 FMUs: run the paper's carriage/block rig "
               "on scenario files, reproduce the paper, identify parameters from "
               "measurements.")
EPILOG = ("Exit status: 0 success, 1 a result that does not match the paper (or, with "
          "--strict, any warning), 2 bad input "
          "(one line naming the file or option; a file's every problem, one line each), 74 the "
          "system refused a read or a write "
          "(disk full, permission denied, a read-only file system; one line), 130 "
          "interrupted before the output was written; a closed standard output (| head) "
          "is no error.  CSV "
          "files separated by semicolons are read with decimal commas (0,5).  Angles in scenario and "
          "data files are in degrees, counterclockwise from the driving axis X1.")


def build_parser() -> argparse.ArgumentParser:
    """The command line: --version and the subcommands, in the order --help
    lists them, each added by its own function below."""
    ap = Parser(prog="orthocontact", description=DESCRIPTION, epilog=EPILOG)
    ap.add_argument("--version", action=VersionAction, help="print the package version and the "
                    "installed FMUs (FMI 2.0 and 3.0), then exit")
    sub = ap.add_subparsers(dest="cmd", required=True, metavar="COMMAND")
    for add in (add_run, add_reproduce, add_identify, add_ssp, add_export, add_sensitivity, add_uq,
                add_design):
        add(sub)
    return ap


# -- what several commands share -------------------------------------------------

def add_strict(p) -> None:
    p.add_argument("--strict", action="store_true",
                   help="exit with status 1 if any warning was printed (an implausible input, a "
                        "rig run that is not steady sliding); the results are written all the same")
    add_yes(p)


def add_yes(p) -> None:
    p.add_argument("--yes", action="store_true",
                   help="run even if the work is above the limits said before any run "
                        "(2e6 rig runs or 2e9 rig steps, about 5 minutes on 2 cores): a "
                        "sweep.step_deg or rig.step_s that small is usually a typo")


def add_force(p, what=OWNER_HELP) -> None:
    p.add_argument("--force", action="store_true", help=what)


def command(sub, name, func, reads, help, description):
    """A subcommand: `func` runs it; `reads` names its arguments that are
    files it reads (never replaced by what it writes)."""
    p = sub.add_parser(name, help=help, description=description)
    p.set_defaults(func=func, reads=reads)
    return p


def add_scenario(p, help) -> None:
    p.add_argument("scenario", metavar="SCENARIO", help=help)


def written_when(what) -> str:
    return f"output folder ({OUT_RULE}); written only when {what}"


def scenario_command(sub, name, func, help, description, scenario_help, done):
    """A command over one scenario file into an output folder (--out) with the common options."""
    p = command(sub, name, func, ("scenario",), help, description)
    add_scenario(p, scenario_help)
    add_common(p, written_when(done))
    return p


def add_common(p, out_help, scheduler=True, force_help=OWNER_HELP) -> None:
    """--out, --force, --workers, --fmi, --master, --strict, --yes and (with
    `scheduler`) --scheduler: the options of the commands that run the rig."""
    p.add_argument("--out", required=True, type=out_path, metavar="DIR", help=out_help)
    add_force(p, force_help)
    p.add_argument("--workers", type=workers, default=None, metavar="N",
                   help="worker processes for sweeps (default: the number of cores, at most 8; "
                        "refused above 4 per core or what the free memory holds, about 128 MB "
                        "each); they end with this command, however it ends")
    p.add_argument("--fmi", type=int, choices=(2, 3), default=2,
                   help="FMI version of the contact FMU the harness runs: 2 (default) or 3; "
                        "both give the same results bit for bit")
    p.add_argument("--master", choices=("auto", "c", "fmpy"), default="auto",
                   help="who runs the rig loop: c, the compiled master (FMI 2.0 FMUs, about "
                        "23-34x faster), fmpy, the Python harness, or auto (default: c where "
                        "it applies); both give the same angles")
    add_strict(p)
    if scheduler:
        p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                       help="run the sweeps on Dask: local (a LocalCluster of --workers "
                            "processes) or tcp://HOST:PORT (an existing scheduler); default: "
                            "local processes, which start faster for sweeps of this size")


# -- one function a command ------------------------------------------------------

def add_run(sub) -> None:
    scenario_command(sub, "run", cmd_run,
                     help="run one scenario file (a sweep over the mat/axis angle in degrees, a "
                          "step-size study, the contact patch's twist or towed block, or the contact "
                          "pad's block pushed at a height)",
                     description="Run one scenario file and write summary.json, CSV tables, PNG figures "
                                 "into DIR.",
                     scenario_help="scenario file (TOML; format in docs/reference/file-formats.md); angles "
                                   "in degrees, forces in N, lengths in m",
                     done="the run completes")


BUNDLED = "the paper's, the contact patch's and the contact pad's"   # the packaged scenarios


def add_reproduce(sub) -> None:
    p = command(sub, "reproduce", cmd_reproduce, ("scenarios",),
                help=f"run every bundled scenario ({BUNDLED}) and write report.md",
                description=f"Run every scenario of the folder (default: {BUNDLED}, packaged) and write "
                            "report.md beside one folder per scenario into DIR.")
    add_common(p, f"output folder for report.md, summary.json and one folder per scenario ({OUT_RULE}); "
                  "written only when everything completes")
    p.add_argument("--scenarios", default=None, metavar="FOLDER",
                   help="folder of scenario files (*.toml; default: the packaged ones)")


def add_identify(sub) -> None:
    i = command(sub, "identify", cmd_identify, ("data",),
                help="identify mu1, mu2, the stiffness ratio and the absolute stiffness [N/m] from "
                     "measurements",
                description="Identify the law's parameters from a measurement folder (mu1, "
                            "mu2 [-], eps1/eps2 [-], eps1, eps2 [N/m]) and write "
                            "identified.json, identified.md, fit.png into DIR; from a lab's raw "
                            "recordings also their reduction (reduction.csv, reduction.json, "
                            "reduction_<angle>deg.png) and, where mu1, mu2 and eps1/eps2 are "
                            "identified, rig_scenario.toml for uq.")
    i.add_argument("data", type=Path, metavar="DATA_DIR",
                   help="measurement folder: rig.toml and any of forces.csv (mat_angle_deg,force_N), "
                        "angles.csv (mat_angle_deg,phi_deg, optionally velocity_m_s per row), ramp.csv "
                        "(x1_m,force_N); or a lab's raw recordings: rig.toml, runs.csv "
                        "(run,kind,mat_angle_deg,velocity_m_s), trajectories/RUN.csv (t_s,x1_m,x2_m), "
                        "forces/RUN.csv (t_s,force_N); angles in degrees, forces in N, positions in m, "
                        "times in s, velocity in m/s")
    add_common(i, written_when("the fit completes"), scheduler=False,
               force_help="write a fit that did not converge (marked so in identified.json; export refuses "
                          "it), and " + OWNER_HELP)
    i.add_argument("--no-validate", action="store_true",
                   help="skip the validation runs of the identified parameters on the FMU")


def add_ssp(sub) -> None:
    s = command(sub, "ssp", cmd_ssp, ("scenario",),
                help="write the experiment at one angle as an SSP 1.0 package (rig FMU + contact FMU) "
                     "for any SSP-capable simulator",
                description="Write SystemStructure.ssd and both FMI 2.0 FMUs (CarriageBlock, "
                            "OrthotropicContact) with the scenario's parameters as an .ssp.")
    add_scenario(s, "sweep scenario file (TOML); angles in degrees, forces in N, lengths in m")
    s.add_argument("--angle", type=angle_deg, required=True, metavar="DEG",
                   help="the mat angle a [deg] (the scenario's geometry sets the law's axes from it)")
    s.add_argument("--out", type=out_path, required=True, metavar="FILE.ssp",
                   help="the package to write (an SSP there is replaced; any other file only with --force, "
                        "and never the scenario it reads)")
    add_force(s, "replace the file --out names even if it is no SSP package")


def add_export(sub) -> None:
    x = command(sub, "export", cmd_export, ("identification", "scenario"),
                help="write both contact FMUs calibrated with an identification's estimates, an SSV "
                     "file and an SSP of the rig",
                description="Write DIR/fmi2/ and DIR/fmi3/OrthotropicContact.fmu whose parameters' "
                            "start values are identified.json's estimates (used by the FMU itself when "
                            "an importer sets nothing), with the intervals, the data's SHA-256, the date "
                            "and the version in documentation/calibration.html; DIR/calibration.ssv; "
                            "and DIR/rig_<angle>.ssp, the rig at --angle on the calibrated FMU.")
    x.add_argument("identification", type=Path, metavar="IDENTIFIED.json",
                   help="identified.json written by `orthocontact identify` (its data folder must be "
                        "readable: the export names the data's digest)")
    x.add_argument("--out", type=out_path, required=True, metavar="DIR",
                   help=written_when("everything completes"))
    x.add_argument("--angle", type=float, default=45.0, metavar="DEG",
                   help="mat angle [deg] in the measurement's geometry that the FMUs' axes alpha, "
                        "beta are set for and the SSP's rig runs at (default 45)")
    x.add_argument("--scenario", type=Path, default=None, metavar="SCENARIO",
                   help="sweep scenario file (TOML) whose rig the SSP uses (default: the data's "
                        "rig.toml)")
    add_force(x, "export values the plausibility gate refuses or warns about, a fit that did not converge or "
                 "data the fitted law does not describe (lack of fit) (each said in a warning and in "
                 "the FMUs' documentation and model description), and write into --out even if another "
                 "command's run is there (its files are replaced; what export reads is never removed)")


def add_sensitivity(sub) -> None:
    scenario_command(sub, "sensitivity", cmd_sensitivity,
                     help="how the rig's unmeasured strip friction and viscosity, and the velocity, move "
                          "the peak angle and the identified eps1/eps2",
                     description="For a mat scenario: the peak |phi| [deg] against the Teflon strip's "
                                 "friction mu_strip (0-0.2) at 0.125 and 0.244 m/s (rig and closed form), "
                                 "the eps1/eps2 the paper's calibration would return for each, and for a "
                                 "viscous strip c_strip [N s/m] the peak at 0.244 m/s after calibrating at "
                                 "0.125 m/s; CSV, JSON, PNG into DIR.",
                     scenario_help="a sweep scenario with the experiment's geometry (closed_form = "
                                   "\"mat\"), e.g. scenarios/mat_aged.toml",
                     done="everything completes")


def add_uq(sub) -> None:
    u = command(sub, "uq", cmd_uq, ("identification", "scenario"),
                help="propagate an identification's uncertainty to the predicted trajectory angle over a "
                     "scenario's angles (Dask)",
                description="Draw parameter sets from identified.json's estimates and covariance (only "
                            "mu, eps > 0), run the rig over the scenario's angles for each (compiled "
                            "master, on Dask unless --scheduler none), and write the predictive bands "
                            "of phi [deg] and of the driving force [N] (median, 2.5 and 97.5 %) as "
                            "uq_bands.csv, uq.json, uq.png, and the drawn sets as samples.csv.")
    u.add_argument("identification", type=Path, metavar="IDENTIFICATION.json",
                   help="identified.json written by `orthocontact identify`")
    u.add_argument("--scenario", required=True, type=Path, metavar="SCENARIO",
                   help="sweep scenario file (TOML) giving the rig and the angles [deg]; its rule "
                        "must be the identification's")
    u.add_argument("--samples", required=True, type=positive_int("parameter sets"), metavar="N",
                   help="parameter sets to draw; rig runs = N x the scenario's angles")
    u.add_argument("--out", required=True, type=out_path, metavar="DIR",
                   help=written_when("all runs complete"))
    add_force(u)
    u.add_argument("--seed", type=seed, default=0, metavar="S",
                   help="seed of the draws (default 0): the same seed gives the same files, "
                        "serial or on any cluster")
    u.add_argument("--scheduler", default="local", metavar="ADDRESS",
                   help="where the runs go: local (default: a Dask LocalCluster, --workers "
                        "processes), tcp://HOST:PORT (an existing Dask scheduler), or none (this "
                        "process, no Dask)")
    u.add_argument("--workers", type=workers, default=None, metavar="N",
                   help="worker processes of the local cluster (default: the number of cores, at "
                        "most 8; refused above 4 per core or what the free memory holds); the "
                        "cluster listens on 127.0.0.1 only and ends with this command")
    u.add_argument("--step-s", type=positive_float, default=None, metavar="SECONDS",
                   help="communication step of the rig [s] (default: 0.004 for the implicit rules, "
                        "step-size independent; the scenario's for eq20); checked against the "
                        "scenario's step at the estimates")
    u.add_argument("--chunk-runs", type=positive_int("runs"), default=20000, metavar="RUNS",
                   help="most rig runs per task sent to a worker (default 20000; the last tasks are smaller)")
    add_strict(u)


def add_design(sub) -> None:
    """orthocontact design: the plan's size and criterion, its noise, its
    prior, and its candidate runs."""
    d = command(sub, "design", cmd_design, ("prior", "fixed"),
                help="plan the lab's runs: the D-optimal (or A-optimal) mat angles and velocities of the "
                     "slide runs, ramp samples and carriage runs for the law's parameters",
                description="Plan the rig's runs before going to the lab: at a prior (the paper's aged mat "
                            "and rig, or an identification) choose the slide runs (mat angle in degrees x "
                            "velocity in m/s), ramp samples and carriage runs whose Fisher information is "
                            "largest (D: det M; A: the sum of the relative variances), from the joint fit's "
                            "own model; write plan.csv, design.json (predicted standard errors, the "
                            "paper's design beside it, the efficiency, the equivalence theorem's check), "
                            "design.png and design.md into DIR.")
    d.add_argument("--runs", type=positive_int("slide runs"), required=True, metavar="N",
                   help="slide runs to plan (each gives a driving force [N] and a trajectory angle [deg])")
    d.add_argument("--out", type=out_path, required=True, metavar="DIR",
                   help=written_when("the design completes"))
    add_force(d)
    d.add_argument("--criterion", choices=("D", "A"), default="D",
                   help="D (default): the largest det of the information; A: the smallest sum of the "
                        "parameters' relative variances (sd / prior value)^2")
    add_design_noise(d)
    add_design_prior(d)
    add_design_candidates(d)


def add_design_noise(d) -> None:
    d.add_argument("--sigma-force", type=positive_float, default=None, metavar="REL",
                   help="noise of a driving force as a share of the force (0.01 for one percent); default "
                        "0.01, or the --prior identification's force noise [N]")
    d.add_argument("--sigma-angle", type=positive_float, default=None, metavar="DEG",
                   help="noise of a trajectory angle [deg]; default 1.0, or the --prior identification's "
                        "(at each velocity where it has one)")
    d.add_argument("--sigma-ramp", type=positive_float, default=0.05, metavar="N",
                   help="noise of a ramp sample's force [N] (default 0.05)")


def add_design_prior(d) -> None:
    d.add_argument("--no-strip", action="store_true",
                   help="a rig without the Teflon strip's viscosity: the law is rate-independent, so the "
                        "runs' velocity does not matter (the prior's rig velocity, 0.244 m/s for the "
                        "paper's); "
                        "only mu1, mu2, eps1/eps2 (and eps2 with --ramp-samples) are designed")
    d.add_argument("--prior", type=Path, default=None, metavar="IDENTIFIED.json",
                   help="identified.json of an earlier identification: the design is optimal at its "
                        "estimates, on its rig, with its noise (unless --sigma-force, --sigma-angle say "
                        "otherwise); default: the paper's aged mat (mu1 0.408, mu2 0.625, eps1/eps2 1.251, "
                        "eps2 1e4 N/m, F_int 5 N) on its rig (1.875 kg), with a strip of 10 N s/m unless "
                        "--no-strip")
    d.add_argument("--fixed", type=Path, default=None, metavar="PLAN.csv",
                   help="runs already made (a plan.csv or a recording folder's runs.csv: kind, "
                        "mat_angle_deg, velocity_m_s): the next --runs given those (sequential design)")


def add_design_candidates(d) -> None:
    d.add_argument("--ramp-samples", type=count, default=0, metavar="K",
                   help="samples of a ramp run (a slow pull through the stick branch) to place on its "
                        "travel x1 [m]; designs eps2 [N/m] too (default 0: no ramp)")
    d.add_argument("--carriage-runs", type=count, default=0, metavar="C",
                   help="carriage runs to plan (the carriage alone: F_int [N], then estimated with the "
                        "rest as a nuisance parameter); default 0: F_int known, as the prior's")
    d.add_argument("--angle-step", type=positive_float, default=1.0, metavar="DEG",
                   help="the candidate mat angles' step [deg] over 0-90 (0-180 where the prior's axes' "
                        "offsets are not multiples of 90 deg) (default 1.0)")
    d.add_argument("--velocity-min", type=positive_float, default=0.05, metavar="M/S",
                   help="the lowest carriage velocity [m/s] a slide run may use, with a strip (default 0.05)")
    d.add_argument("--velocity-max", type=positive_float, default=0.5, metavar="M/S",
                   help="the highest carriage velocity [m/s] a slide run may use, with a strip (default 0.5)")
    d.add_argument("--velocity-step", type=positive_float, default=0.05, metavar="M/S",
                   help="the candidate velocities' step [m/s] between them (default 0.05)")
