#!/usr/bin/env bash
# The whole test suite: C unit tests under CTest (plain and with
# AddressSanitizer + UBSan), then pytest on the installed package and FMU.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/bootstrap.sh
FMI_DIR=$(.venv/bin/python -c "import fmpy, os; print(os.path.join(os.path.dirname(fmpy.__file__), 'c-code'))")
for variant in release asan; do
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
echo "== pytest =="
.venv/bin/python -m pytest tests -q -p no:cacheprovider "$@"
