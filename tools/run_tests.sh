#!/usr/bin/env bash
# The whole test suite (`make test`, what CI runs): C unit tests under CTest
# (plain and with AddressSanitizer + UBSan), then pytest on the installed
# package and FMUs.
# --fast (`make check`): the release C tests and the tests not marked slow
# (tests/tiers.py): the law, the FMUs, the rig and the CLI's core, under
# 2 minutes after setup.
set -euo pipefail
cd "$(dirname "$0")/.."
fast=0
if [ "${1:-}" = --fast ]; then
  fast=1
  shift
fi
tools/bootstrap.sh
# What only the tests need: the other FMU/SSP importers (libcosim, Ecos,
# fmu-manipulation-toolbox's container), property-based testing, and
# qemu-user with the arm64 C library to run the aarch64 binary.
.venv/bin/python -m pip install -q --disable-pip-version-check "hypothesis>=6" "libcosimpy>=0.0.6" \
  "ecospy>=0.7" "fmu-manipulation-toolbox>=2.0"
# Ecos's library links against oneTBB (Debian's libtbb12).
if ! /sbin/ldconfig -p 2>/dev/null | grep -q 'libtbb\.so\.12'; then
  echo "run_tests: installing libtbb12 for Ecos (apt)"
  SUDO=""
  [ "$(id -u)" = 0 ] || SUDO="sudo"
  { $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq \
      libtbb12 >/dev/null; } || echo "run_tests: libtbb12 not installed; the Ecos runs are skipped"
fi
if [ $fast = 0 ] && { ! command -v qemu-aarch64 >/dev/null 2>&1 ||
                      [ ! -e /usr/aarch64-linux-gnu/lib/ld-linux-aarch64.so.1 ]; }; then
  echo "run_tests: installing qemu-user and libc6-arm64-cross (apt)"
  SUDO=""
  [ "$(id -u)" = 0 ] || SUDO="sudo"
  { $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq \
      qemu-user libc6-arm64-cross >/dev/null; } || echo "run_tests: qemu-user not installed; the aarch64 run is skipped"
fi
FMI_DIR=$(.venv/bin/python -c "import fmpy, os; print(os.path.join(os.path.dirname(fmpy.__file__), 'c-code'))")
variants=(release asan)
[ $fast = 0 ] || variants=(release)
for variant in "${variants[@]}"; do
  flags=(-DOC_BUILD_TESTS=ON -DFMI_HEADERS_DIR="$FMI_DIR")
  if [ "$variant" = asan ]; then
    flags+=(-DOC_SANITIZE=ON -DCMAKE_BUILD_TYPE=Debug)
  else
    flags+=(-DCMAKE_BUILD_TYPE=Release)
  fi
  echo "== C unit tests ($variant) =="
  cmake -S . -B "build/ctest-$variant" "${flags[@]}" >/dev/null
  cmake --build "build/ctest-$variant" -j2 >/dev/null
  (cd "build/ctest-$variant" && ctest --output-on-failure)
done
if [ $fast = 1 ]; then
  echo "== pytest, fast tier (-m 'not slow') =="
  .venv/bin/python -m pytest tests -q -p no:cacheprovider -m "not slow" "$@"
else
  echo "== pytest =="
  .venv/bin/python -m pytest tests -q -p no:cacheprovider "$@"
fi
