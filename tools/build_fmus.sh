#!/usr/bin/env bash
# `make fmus`: every model's FMUs (OC_MODELS in CMakeLists.txt; FMI 2.0
# and 3.0, binaries for five platforms) into dist/, with a C compiler, cmake
# and a Python that has fmpy's FMI headers and Zig's C compiler: none of the
# analysis stack (casadi, matplotlib, dask).  Uses .venv when it has both,
# else a light environment in build/fmus-venv (fmpy's files without its
# dependencies, and ziglang).
set -euo pipefail
cd "$(dirname "$0")/.."
export CMAKE_BUILD_PARALLEL_LEVEL="${CMAKE_BUILD_PARALLEL_LEVEL:-2}"
# Run from `make fmus`, the build's own make would print every directory it enters.
unset MAKEFLAGS MFLAGS MAKELEVEL
has_tools() { [ -x "$1" ] && "$1" -c "import importlib.util as u; assert u.find_spec('fmpy') and u.find_spec('ziglang')" 2>/dev/null; }
py=.venv/bin/python
if ! has_tools "$py"; then
  py=build/fmus-venv/bin/python
  if ! has_tools "$py"; then
    echo "fmus: creating build/fmus-venv with fmpy (for the FMI headers) and ziglang"
    python3 -m venv build/fmus-venv
    "$py" -m pip install -q --disable-pip-version-check --no-deps "fmpy>=0.3.20" "ziglang>=0.13"
  fi
fi
echo "fmus: configuring build/fmus (cross build with zig)"
cmake -S . -B build/fmus -DOC_CROSS=ON -DPython3_EXECUTABLE="$PWD/$py" >/dev/null
echo "fmus: building (one line per step; the first time zig also builds each platform's C runtime: minutes)"
cmake --build build/fmus --target dist
ls -l dist/fmi2/*.fmu dist/fmi3/*.fmu
