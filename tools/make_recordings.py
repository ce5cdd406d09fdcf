"""Synthetic raw recordings of the paper's experiment, with known truth: the
folder format `orthocontact identify` reads (docs/reference/file-formats.md, "Raw recordings"):
rig.toml, runs.csv, trajectories/<run>.csv (t_s,x1_m,x2_m), forces/<run>.csv
(t_s,force_N).

The physics comes from the independent reference simulator
(tools/rig_reference.py: the law from its definition, quasi-static rig with
the strip's viscosity); nothing here imports the package.  What a lab's
sensors add is modelled per run:

* the carriage starts from rest, reaches its velocity with a smooth (cosine)
  ramp over `accel_s`, cruises, and stops the same way; the block's inertia
  m a adds to the sensor's force while it accelerates;
* the tracker samples at its own rate from its own start time, with white
  noise and a slow drift (a random rate per run: a lateral drift shows up in
  the fitted angle as drift/velocity, i.e. as run-to-run scatter);
* the force sensor samples at its own rate from its own start time: a tare
  offset per run, a drift rate per run, white noise; and the mat's friction
  varies from run to run by a factor (1 + N(0, friction_scatter));
* carriage-only runs read F_int (with the same sensor errors) while moving
  and 0 at rest; ramp runs pull slowly from rest through the stick branch
  into sliding.

The steady path at a velocity is simulated once over `settle_m` (long enough
for the strip's viscous transient) and continued along its final slope.
Units: m, s, N, deg.

    python tools/make_recordings.py OUT_DIR [--seed 1] [--runs 10] [--small]
"""
from __future__ import annotations

import argparse
import math
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import rig_reference as ref  # noqa: E402


@dataclass
class Truth:
    mu1: float = 0.408
    mu2: float = 0.625
    eps1: float = 12510.0
    eps2: float = 10000.0
    rule: str = "coupled"
    alpha_offset_deg: float = 90.0
    beta_offset_deg: float = 0.0
    mass_kg: float = 1.875
    g: float = 9.806
    f_int_N: float = 5.0
    c_strip: float = 10.0          # N s/m

    @property
    def eps_ratio(self) -> float:
        return self.eps1 / self.eps2


@dataclass
class Sensors:
    tracker_hz: float = 100.0
    tracker_noise_m: float = 5e-5
    tracker_drift_m_s: float = 6e-4      # sd of the per-run lateral drift rate
    force_hz: float = 250.0
    force_noise_N: float = 0.05
    force_tare_N: float = 0.03            # sd of the per-run offset
    force_drift_N_s: float = 0.02         # sd of the per-run drift rate
    friction_scatter: float = 0.004       # sd of the per-run friction factor
    accel_s: float = 0.12
    rest_s: float = 0.25                  # at rest before and after a pull


@dataclass
class Design:
    angles_deg: list = field(default_factory=lambda: [0, 15, 30, 45, 60, 75, 90])
    velocities: dict = field(default_factory=lambda: {0.244: 6, 0.125: 4})  # m/s -> runs per angle
    travel_m: float = 0.3
    carriage_runs: int = 5
    ramp_runs: int = 3
    ramp_velocity: float = 0.002
    ramp_travel_m: float = 0.003
    settle_m: float = 0.02


def _velocity_profile(v, accel_s, travel):
    """x1(t) of a carriage that starts at t = 0, ramps up smoothly in
    accel_s, cruises and ramps down, covering `travel`; returns (x1(t), a(t),
    end time)."""
    ramp_x = v * accel_s / 2
    cruise_s = max(travel - 2 * ramp_x, 0.0) / v
    end = 2 * accel_s + cruise_s

    def x_of(t):
        t = np.clip(t, 0.0, end)
        up = v * (t / 2 - accel_s / (2 * math.pi) * np.sin(math.pi * t / accel_s))
        x = np.where(t < accel_s, up, ramp_x + v * (t - accel_s))
        td = t - accel_s - cruise_s
        down = ramp_x + v * cruise_s + v * (td / 2 + accel_s / (2 * math.pi) * np.sin(math.pi * td / accel_s))
        return np.where(td > 0, down, x)

    def a_of(t):
        a_up = v * math.pi / (2 * accel_s) * np.sin(math.pi * np.clip(t, 0, accel_s) / accel_s)
        td = t - accel_s - cruise_s
        a_dn = -v * math.pi / (2 * accel_s) * np.sin(math.pi * np.clip(td, 0, accel_s) / accel_s)
        return np.where((t > 0) & (t < accel_s), a_up, 0.0) + np.where((td > 0) & (td < accel_s), a_dn, 0.0)
    return x_of, a_of, end


def steady_paths(truth: Truth, angles, velocities, settle_m, steps=200):
    """{(angle, v): (x1 grid, x2 grid, q1 grid)} simulated over settle_m."""
    N = truth.mass_kg * truth.g
    out = {}
    for a in angles:
        for v in velocities:
            t = math.radians(a)
            x1, x2, q1 = ref.run_rig(truth.mu1, truth.mu2, truth.eps1, truth.eps2,
                                     t + math.radians(truth.alpha_offset_deg),
                                     t + math.radians(truth.beta_offset_deg), truth.rule, N,
                                     settle_m, steps, c_strip=truth.c_strip, velocity=v)
            out[(a, v)] = (np.r_[0.0, x1], np.r_[0.0, x2], np.r_[0.0, q1])
    return out


def ramp_path(truth: Truth, travel, steps=600):
    N = truth.mass_kg * truth.g
    x1, _, q1 = ref.run_rig(truth.mu1, truth.mu2, truth.eps1, truth.eps2,
                            math.radians(truth.alpha_offset_deg), math.radians(truth.beta_offset_deg),
                            truth.rule, N, travel, steps)
    return np.r_[0.0, x1], np.r_[0.0, q1]


def _extend(grid_x, grid_y, x):
    """grid_y(x), continued beyond the grid along the final slope."""
    k = max(len(grid_x) // 4, 2)
    slope = (grid_y[-1] - grid_y[-k]) / (grid_x[-1] - grid_x[-k])
    return np.where(x <= grid_x[-1], np.interp(x, grid_x, grid_y), grid_y[-1] + slope * (x - grid_x[-1]))


def truth_steady(paths):
    """{(angle, v): (phi_deg, push q1 [N])} of the simulated steady state."""
    out = {}
    for key, (x1, x2, q1) in paths.items():
        k = len(x1) // 4
        slope = (x2[-1] - x2[-k]) / (x1[-1] - x1[-k])
        out[key] = (math.degrees(math.atan(slope)), float(q1[-1]))
    return out


def _times(rng, hz, end):
    start = rng.uniform(0.0, 1.0 / hz)
    return np.arange(start, end, 1.0 / hz)


def make_runs(truth: Truth, sensors: Sensors, design: Design, rng, paths=None, ramp=None):
    """The recordings as {run: (kind, angle, v, trajectory array or None,
    force array)}; arrays (t_s, x1_m, x2_m) and (t_s, force_N)."""
    s = sensors
    if paths is None:
        paths = steady_paths(truth, design.angles_deg, list(design.velocities), design.settle_m)
    if ramp is None:
        ramp = ramp_path(truth, design.ramp_travel_m)
    runs = {}

    def force_log(t, pushing, moving, accel):
        tare = rng.normal(0, s.force_tare_N)
        drift = rng.normal(0, s.force_drift_N_s)
        f = np.where(moving, truth.f_int_N, 0.0) + pushing + truth.mass_kg * accel
        return f + tare + drift * t + rng.normal(0, s.force_noise_N, len(t))

    def tracker(t, x1, x2):
        drift = rng.normal(0, s.tracker_drift_m_s)
        n = rng.normal(0, s.tracker_noise_m, (2, len(t)))
        return np.column_stack([t, x1 + n[0], x2 + drift * t + n[1]])

    for a in design.angles_deg:
        for v, count in design.velocities.items():
            gx1, gx2, gq1 = paths[(a, v)]
            for i in range(count):
                name = f"a{a:03.0f}_v{round(v * 1000):03d}_{i + 1:02d}"
                x_of, a_of, end = _velocity_profile(v, s.accel_s, design.travel_m)
                t0, t_end = s.rest_s, s.rest_s + end + s.rest_s
                tt = _times(rng, s.tracker_hz, t_end)
                x1 = x_of(tt - t0)
                x2 = _extend(gx1, gx2, x1)
                traj = tracker(tt, x1, x2)
                tf = _times(rng, s.force_hz, t_end)
                xf = x_of(tf - t0)
                moving = (tf > t0) & (tf < t0 + end)
                push = np.where(moving, _extend(gx1, gq1, xf), 0.0) * (1 + rng.normal(0, s.friction_scatter))
                forces = np.column_stack([tf, force_log(tf, push, moving, a_of(tf - t0))])
                runs[name] = ("slide", a, v, traj, forces)
    v0 = max(design.velocities, key=design.velocities.get)
    for i in range(design.carriage_runs):
        x_of, a_of, end = _velocity_profile(v0, s.accel_s, design.travel_m)
        t0, t_end = s.rest_s, 2 * s.rest_s + end
        tf = _times(rng, s.force_hz, t_end)
        moving = (tf > t0) & (tf < t0 + end)
        # the carriage alone: no block, so no push and no block inertia
        f = np.where(moving, truth.f_int_N, 0.0) + rng.normal(0, s.force_tare_N) + \
            rng.normal(0, s.force_drift_N_s) * tf + rng.normal(0, s.force_noise_N, len(tf))
        runs[f"carriage_{i + 1:02d}"] = ("carriage", 0.0, v0, None, np.column_stack([tf, f]))
    gx, gq = ramp
    for i in range(design.ramp_runs):
        v = design.ramp_velocity
        x_of, a_of, end = _velocity_profile(v, s.accel_s, design.ramp_travel_m)
        t0, t_end = 0.5, 0.5 + end + s.rest_s
        tt = _times(rng, s.tracker_hz, t_end)
        x1 = x_of(tt - t0)
        traj = tracker(tt, x1, np.zeros_like(x1))
        tf = _times(rng, s.force_hz * 4, t_end)
        xf = x_of(tf - t0)
        moving = (tf > t0) & (tf < t0 + end)
        push = np.where(tf > t0, np.interp(xf, gx, gq), 0.0) * (1 + rng.normal(0, s.friction_scatter))
        forces = np.column_stack([tf, force_log(tf, push, moving, a_of(tf - t0))])
        runs[f"ramp_{i + 1:02d}"] = ("ramp", 0.0, v, traj, forces)
    return runs


def write_folder(out: Path, truth: Truth, runs: dict, f_int_in_toml: bool = False, digits=6):
    out = Path(out)
    (out / "trajectories").mkdir(parents=True, exist_ok=True)
    (out / "forces").mkdir(parents=True, exist_ok=True)
    toml = [f"mass_kg = {truth.mass_kg!r}", f"g = {truth.g!r}", f'rule = "{truth.rule}"',
            f"alpha_offset_deg = {truth.alpha_offset_deg!r}", f"beta_offset_deg = {truth.beta_offset_deg!r}",
            "ramp_angle_deg = 0.0"]
    if f_int_in_toml:
        toml.append(f"f_int_N = {truth.f_int_N!r}")
    (out / "rig.toml").write_text("\n".join(toml) + "\n")
    lines = ["run,kind,mat_angle_deg,velocity_m_s"]
    for name, (kind, a, v, traj, forces) in runs.items():
        lines.append(f"{name},{kind},{a:g},{v:g}")
        if traj is not None:
            body = "\n".join(f"{t:.5f},{x:.{digits}f},{y:.{digits}f}" for t, x, y in traj.tolist())
            (out / "trajectories" / f"{name}.csv").write_text("t_s,x1_m,x2_m\n" + body + "\n")
        body = "\n".join(f"{t:.5f},{f:.4f}" for t, f in forces.tolist())
        (out / "forces" / f"{name}.csv").write_text("t_s,force_N\n" + body + "\n")
    (out / "runs.csv").write_text("\n".join(lines) + "\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", type=Path)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--small", action="store_true", help="4 angles, 5 runs each, one velocity")
    args = ap.parse_args(argv)
    truth, design = Truth(), Design()
    if args.small:
        design = Design(angles_deg=[0, 30, 60, 90], velocities={0.244: 5}, carriage_runs=3, ramp_runs=2)
        truth = Truth(c_strip=0.0)
    runs = make_runs(truth, Sensors(), design, np.random.default_rng(args.seed))
    write_folder(args.out, truth, runs)
    print(f"wrote {len(runs)} runs to {args.out}")


if __name__ == "__main__":
    main()
