#!/usr/bin/env bash
# Benchmarks (not tests): the C step cost through the FMI calls, and the
# harness against a bare fmpy loop. Figures only; nothing here can fail a build.
set -euo pipefail
cd "$(dirname "$0")/.."
FMI_DIR=$(.venv/bin/python -c "import fmpy, os; print(os.path.join(os.path.dirname(fmpy.__file__), 'c-code'))")
cmake -S . -B build/ctest-release -DOC_BUILD_TESTS=ON -DFMI_HEADERS_DIR="$FMI_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/ctest-release -j2 --target bench_fmi2 bench_fmi3 bench_peer bench_master bench_patch >/dev/null
# The binaries `pip install .` ships (zig cc, the cross build) are what users
# and `orthocontact uq` run: measured beside the host build's.
SHIPPED=$(mktemp -d)
trap 'rm -rf "$SHIPPED"' EXIT
.venv/bin/python - "$SHIPPED" <<'PY'
import sys, zipfile
from orthocontact.fmu.files import find_fmu
for v, folder in ((2, "binaries/linux64/"), (3, "binaries/x86_64-linux/")):
    with zipfile.ZipFile(find_fmu(fmi_version=v)) as z:
        with open(f"{sys.argv[1]}/fmi{v}.so", "wb") as out:
            out.write(z.read(folder + "OrthotropicContact.so"))
PY
echo "== C: one step through the FMI calls, ours against the straightforward peer (targets: stick <= 1.0x, slip <= 0.5x, eq. (20) slip <= 1.0x) =="
echo "-- the shipped binaries (the installed FMUs' linux x86_64 binaries, zig cc)"
BENCH_OURS_FMI2="$SHIPPED/fmi2.so" BENCH_OURS_FMI3="$SHIPPED/fmi3.so" build/ctest-release/bench_peer
echo "-- the host build (this machine's compiler, the C tests' binaries)"
build/ctest-release/bench_peer
echo "== C: one step through the FMI calls, linked in (slip / stick) =="
build/ctest-release/bench_fmi2
build/ctest-release/bench_fmi3
echo "== C: the compiled master's rig step against the contact's own step (target: <= 1.5x), on the shipped binary =="
BENCH_OURS_FMI2="$SHIPPED/fmi2.so" build/ctest-release/bench_master
echo "== C: the contact patch's step against n point FMUs' steps and n linked-in law steps and the pad's beside it (targets: a cell <= 1.2x the law's step, 100 cells <= 0.5x 100 point steps; a pad cell <= 1.3x a patch cell, a pad rolling cell <= 1.3x a pad cell), host build =="
build/ctest-release/bench_patch
echo "== Python: harness vs bare fmpy, sweep scaling =="
.venv/bin/python benchmarks/bench_harness.py
echo "== Masters: rig runs/s, compiled vs fmpy (target: >= 20x) =="
.venv/bin/python benchmarks/bench_masters.py
echo "== make reproduce's command, wall time (target: <= 5 s) =="
.venv/bin/python benchmarks/bench_reproduce.py
echo "== identification: the joint fit against scipy's least_squares, same data (target: <= 2x) =="
.venv/bin/python tools/requirements.py test --install >/dev/null   # scipy: the peer
.venv/bin/python benchmarks/bench_fit.py
echo "== uncertainty propagation, 10^6 rig runs on Dask (target: <= 30 s) =="
.venv/bin/python benchmarks/bench_uq.py
echo "== identification intervals: coverage on independent data (target: 92-98 %) =="
.venv/bin/python benchmarks/bench_coverage.py --out docs
