#!/usr/bin/env bash
# Installs what the project needs on a fresh machine: system tools (apt),
# a virtual environment in .venv with the Python dependencies, and the
# orthocontact package itself (whose install builds the FMU through CMake).
# Idempotent: when nothing the install reads has changed since it last
# succeeded (.venv/setup.stamp: a hash of pyproject.toml, VERSION, the
# sources, these scripts and the Python), it installs nothing; otherwise it
# rebuilds only what changed.
set -euo pipefail
cd "$(dirname "$0")/.."
# Two cores: compile the cross targets side by side.
export CMAKE_BUILD_PARALLEL_LEVEL="${CMAKE_BUILD_PARALLEL_LEVEL:-2}"

missing=()
command -v cmake >/dev/null 2>&1 || missing+=(cmake)
command -v cc >/dev/null 2>&1 || missing+=(gcc)
command -v make >/dev/null 2>&1 || missing+=(make)
command -v python3 >/dev/null 2>&1 || missing+=(python3)
python3 -c "import venv, ensurepip" >/dev/null 2>&1 || missing+=(python3-venv)
if [ ${#missing[@]} -gt 0 ]; then
  echo "bootstrap: installing system packages: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" = 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi

if [ ! -x .venv/bin/python ]; then
  echo "bootstrap: creating .venv"
  python3 -m venv .venv
fi
# One set-up at a time (two `make` started together, a test and a build):
# both would write the same build folder and site-packages.  The lock ends
# with this script.
if command -v flock >/dev/null 2>&1; then
  exec 9>.venv/setup.lock
  if ! flock -n 9; then
    echo "bootstrap: another set-up of this checkout is running; waiting for it"
    flock 9
  fi
fi

# What the install reads: the package's metadata and sources, the build's,
# the set-up's own scripts, and the Python it installs into.
stamp_file=.venv/setup.stamp
stamp=$(.venv/bin/python - <<'EOF'
import hashlib, os, sys
h = hashlib.sha256(f"{sys.version} {sys.executable} {os.getcwd()}".encode())
inputs = ["pyproject.toml", "VERSION", "README.md", "LICENSE", "CMakeLists.txt", "fmu_src", "master_src",
          "python", "tools/bootstrap.sh", "tools/requirements.py"]
for top in inputs:
    files = [top] if os.path.isfile(top) else sorted(
        os.path.join(d, f) for d, dirs, fs in os.walk(top) if "__pycache__" not in d for f in fs)
    for f in files:
        h.update(f.encode() + b"\0")
        with open(f, "rb") as fh:
            h.update(hashlib.sha256(fh.read()).digest())
print(h.hexdigest())
EOF
)
# ... and what was installed is still there (not uninstalled by hand, both
# FMUs found), asked without the source tree on the path.
installed() {
  local venv_python="$PWD/.venv/bin/python"
  (cd / && env -u PYTHONPATH -u ORTHOCONTACT_FMU -u ORTHOCONTACT_FMU3 "$venv_python" -c \
    "from orthocontact.fmu.files import find_fmu; find_fmu(fmi_version=2); find_fmu(fmi_version=3)") \
    >/dev/null 2>&1
}
if [ -f "$stamp_file" ] && [ "$(cat "$stamp_file")" = "$stamp" ] && installed; then
  echo "bootstrap: up to date (nothing the install reads changed since the last set-up;" \
       "rm $stamp_file to redo it)"
  exit 0
fi
rm -f "$stamp_file"

# pyproject.toml is read with tomllib (tomli before Python 3.11).
.venv/bin/python -c "import tomllib" 2>/dev/null || .venv/bin/python -c "import tomli" 2>/dev/null ||
  .venv/bin/python -m pip install -q --disable-pip-version-check "tomli>=1.1"
# The build requirements (pyproject's [build-system]), so that the package
# builds without isolation (faster, and incremental through build/); ziglang
# cross-compiles the FMU binaries for Linux, Windows and macOS.  The
# package's own dependencies (fmpy, numpy, casadi, matplotlib, dask) come
# with its install below.
# Those not yet satisfied, downloaded the first time; one that cannot be
# installed ends the set-up.
.venv/bin/python tools/requirements.py build --install
echo "bootstrap: building every model's FMUs (FMI 2.0 and 3.0) and installing orthocontact:" \
     "zig cross-compiles the binaries for 5 platforms; the first time zig also builds each" \
     "platform's C runtime (cached in ~/.cache/zig), which takes minutes: the Windows binaries" \
     "come last, after up to 2-3 minutes without a line. Later builds redo only what changed."
# pip shows a build's output only with -v, and then its own chatter too: the
# build's progress lines (one per compiled file or binary) are shown, the
# whole log kept in build/setup.log and shown in full if the install fails.
mkdir -p build
set +e
.venv/bin/python -m pip install -v --disable-pip-version-check --no-build-isolation . 2>&1 \
  | tee build/setup.log \
  | { grep --line-buffered -E '^ *\[ *[0-9]+/[0-9]+\]|\*\*\* (Configuring|Building|Installing|Created)|^Successfully installed' \
      | sed -u -e 's/^ */  /'; true; }
status=${PIPESTATUS[0]}
set -e
if [ $status -ne 0 ]; then
  echo "bootstrap: installing orthocontact failed (exit $status); the build log, build/setup.log:" >&2
  cat build/setup.log >&2
  exit $status
fi
echo "$stamp" > "$stamp_file"
