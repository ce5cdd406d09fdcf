#!/usr/bin/env bash
# The whole test suite (`make test`, what CI runs): C unit tests under CTest
# (plain and with AddressSanitizer + UBSan), then pytest on the installed
# package and FMUs.
# Both begin with `ruff check` (pyproject's [tool.ruff]).
# --fast (`make check`): the release C tests and the tests not marked slow
# (tests/tiers.py): the law, the FMUs, the rig and the CLI's core, under
# 2 minutes after setup.  The set-up installs only what is missing or changed.
set -euo pipefail
cd "$(dirname "$0")/.."
fast=0
if [ "${1:-}" = --fast ]; then
  fast=1
  shift
fi
tools/bootstrap.sh
# What only the tests need: pyproject's `test` extra (pytest, hypothesis, the
# other FMU/SSP importers: libcosim, Ecos, fmu-manipulation-toolbox's
# container), those not yet satisfied; then the system's parts: oneTBB for
# Ecos's library, qemu-user with the arm64 C library to run the aarch64
# binary and wine64 to run the win64 ones (`make test` only).  A part that
# cannot be installed is reported by pytest as not run, and fails `make test`
# and CI (tests/optional_parts.py).
.venv/bin/python tools/requirements.py test --install ||
  echo "run_tests: the tests needing what is not installed will be reported not run"
# The linter and import order (pyproject's [tool.ruff]; in the test extra):
# a finding fails the run before anything is built.
echo "== ruff check =="
.venv/bin/python -m ruff check .
# apt for what pip cannot install.  `make check` tries once per .venv (a
# failed attempt is remembered in .venv/apt-failed-*); `make test` each time.
apt_install() {
  local failed=".venv/apt-failed-$1"
  shift
  if [ $fast = 1 ] && [ -e "$failed" ]; then
    echo "run_tests: $* missing (apt failed before; make test tries again)"
    return 0
  fi
  echo "run_tests: installing $* (apt)"
  local SUDO=""
  [ "$(id -u)" = 0 ] || SUDO="sudo"
  if { $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "$@" \
         >/dev/null; }; then
    rm -f "$failed"
  else
    touch "$failed"
    echo "run_tests: $* not installed: the tests needing them will be reported not run"
  fi
}
# Ecos's library links against oneTBB (Debian's libtbb12).
if ! /sbin/ldconfig -p 2>/dev/null | grep -q 'libtbb\.so\.12'; then
  apt_install ecos libtbb12
fi
if [ $fast = 0 ] && { ! command -v qemu-aarch64 >/dev/null 2>&1 ||
                      [ ! -e /usr/aarch64-linux-gnu/lib/ld-linux-aarch64.so.1 ]; }; then
  apt_install qemu qemu-user libc6-arm64-cross
fi
# clang-format for the C sources' style (tests/contracts/test_c_format.py).
if ! command -v clang-format >/dev/null 2>&1; then
  apt_install clang-format clang-format
fi
# wine64 to run the win64 binaries (tests/fmus/test_windows.py; `make test` only).
if [ $fast = 0 ] && ! command -v wine64 >/dev/null 2>&1 && [ ! -x /usr/lib/wine/wine64 ]; then
  apt_install wine wine64
fi
FMI_DIR=$(.venv/bin/python -c "import fmpy, os; print(os.path.join(os.path.dirname(fmpy.__file__), 'c-code'))")
variants=(release asan)
[ $fast = 0 ] || variants=(release)
for variant in "${variants[@]}"; do
  flags=(-DOC_BUILD_TESTS=ON -DFMI_HEADERS_DIR="$FMI_DIR")
  target=all
  if [ "$variant" = asan ]; then
    # The C tests alone (the release build compiles everything else), at -O1
    # as the sanitizers' docs advise (at -O0 the law's random sequences were
    # most of `make test`'s C part).  GCC's -Wstringop-overflow misreads the
    # sanitized 2x2 matrix products at -O1 (the release build has no such warning).
    flags+=(-DOC_SANITIZE=ON -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_C_FLAGS_DEBUG=-O1 -g -Wno-stringop-overflow")
    target=c_tests
  else
    flags+=(-DCMAKE_BUILD_TYPE=Release)
  fi
  echo "== C unit tests ($variant) =="
  cmake -S . -B "build/ctest-$variant" "${flags[@]}" >/dev/null
  cmake --build "build/ctest-$variant" -j2 --target "$target" >/dev/null
  # both cores: the tests are independent processes (the sanitized ones take most of it)
  (cd "build/ctest-$variant" && ctest --output-on-failure -j2)
done
# pytest's configuration: pyproject.toml.  Its summary lists the optional
# parts; every one is required in `make test` (and wherever CI=true).
# One worker process per core (pytest-xdist, in the test extra), or as many
# as OC_TEST_WORKERS says (0: pytest's own process, one test after another);
# an idle worker takes tests queued for the other (worksteal), and the slow
# tests are queued first (conftest.py).
workers=()
if .venv/bin/python -c "import xdist" 2>/dev/null; then
  workers=(-n "${OC_TEST_WORKERS:-auto}" --dist worksteal)
fi
if [ $fast = 1 ]; then
  echo "== pytest, fast tier (-m 'not slow') =="
  .venv/bin/python -m pytest -q -m "not slow" "${workers[@]}" "$@"
else
  echo "== pytest =="
  # the 20 slowest beside the result: where the suite's minutes go, in CI's log too
  .venv/bin/python -m pytest -q --require-parts --durations=20 "${workers[@]}" "$@"
fi
