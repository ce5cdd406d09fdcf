#!/usr/bin/env bash
# Installs what the project needs on a fresh machine: system tools (apt),
# a virtual environment in .venv with the Python dependencies, and the
# orthocontact package itself (whose install builds the FMU through CMake).
# Idempotent: a second run only rebuilds what changed.
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
# Build requirements too, so that the package builds without isolation
# (faster, and incremental through build/); ziglang cross-compiles the FMU
# binaries for Linux, Windows and macOS.
echo "bootstrap: Python packages into .venv (fmpy, ziglang, numpy, casadi, matplotlib, dask, pytest;" \
     "downloaded the first time)"
.venv/bin/python -m pip install -q --disable-pip-version-check \
  "scikit-build-core>=0.9" "fmpy>=0.3.20" "ziglang>=0.13" "numpy>=1.22" "casadi>=3.6" \
  "matplotlib>=3.5" "dask>=2024.1" "distributed>=2024.1" "pytest>=7"
echo "bootstrap: building both models' FMUs (FMI 2.0 and 3.0) and installing orthocontact:" \
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
