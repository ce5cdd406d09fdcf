#!/bin/sh
# Builds the libFuzzer targets over FMI call sequences (every model of CMake's
# OC_MODELS, FMI 2.0 and 3.0: fuzz_targets.txt; tests/fuzz/fuzz_fmi.c) with
# clang, ASan and UBSan, and runs each in
# turn for SECONDS (default 600), niced, on one core.  Corpora and findings
# stay in build/fuzz (corpus/<target>, artifacts/).  Exit status 1 if any
# target found something.
# FUZZ_KEEP_GOING=1 runs libFuzzer's fork mode past findings (-fork=1
# -ignore_crashes=1), to collect them all in artifacts/.
# FUZZ_COVERAGE=1 then replays each corpus through a build with clang's
# source-based coverage and prints the line coverage of fmu_src (llvm-cov).
#   tools/fuzz.sh [SECONDS] [TARGET...]   e.g. tools/fuzz.sh 60 fuzz_CarriageBlock_fmi3
# Needs clang with libFuzzer (Debian: apt-get install clang libfuzzer-14-dev)
# and the FMI headers (fmpy's c-code, or FMI_HEADERS_DIR).
set -eu
secs=${1:-600}
[ $# -gt 0 ] && shift
root=$(cd "$(dirname "$0")/.." && pwd)
build="$root/build/fuzz"
if [ -z "${FMI_HEADERS_DIR:-}" ]; then
    py=python3
    [ -x "$root/.venv/bin/python" ] && py="$root/.venv/bin/python"
    FMI_HEADERS_DIR=$("$py" -c "import fmpy, os; print(os.path.join(os.path.dirname(fmpy.__file__), 'c-code'))")
fi
CC=${CC:-clang} cmake -S "$root" -B "$build" -DOC_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DFMI_HEADERS_DIR="$FMI_HEADERS_DIR" >/dev/null
# every model's targets, as CMake's list of models (OC_MODELS) makes them
targets=${*:-$(cat "$build/fuzz_targets.txt")}
# shellcheck disable=SC2086
cmake --build "$build" -j2 --target $targets
mkdir -p "$build/artifacts"
status=0
for t in $targets; do
    corpus="$build/corpus/$t"
    mkdir -p "$corpus"
    # Seeds, generated: instantiate, initialize, set inputs, step, save and restore.
    printf '\000\010\001\010\002\000\001\010\200\005\001\002\005\001\014' > "$corpus/seed-steps"
    printf '\000\010\001\000\004\010\030\011\030\012\002\010\002\005\001\005\001\014\015\000\000\000' \
        > "$corpus/seed-slide"
    echo "== $t: $secs s"
    rm -f "$build/artifacts/$t-"*
    keep=""
    [ "${FUZZ_KEEP_GOING:-0}" = 1 ] && keep="-fork=1 -ignore_crashes=1"
    # shellcheck disable=SC2086
    if ! nice -n 10 "$build/$t" "$corpus" -max_total_time="$secs" -print_final_stats=1 $keep \
            -artifact_prefix="$build/artifacts/$t-" 2> "$build/$t.log" ||
            ls "$build/artifacts/$t-"* >/dev/null 2>&1; then
        status=1
        echo "   FINDING: see $build/$t.log and $build/artifacts/"
    fi
    # the last status line (executions, coverage; in fork mode also the count of findings)
    grep -E "^#[0-9]+" "$build/$t.log" | tail -n 1 | sed 's/^/   /'
    ls "$build/artifacts/$t-"* 2>/dev/null | sed 's/^/   finding: /'
done
if [ "${FUZZ_COVERAGE:-0}" = 1 ]; then
    cov="$root/build/fuzz-cov"
    CC=${CC:-clang} cmake -S "$root" -B "$cov" -DOC_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DFMI_HEADERS_DIR="$FMI_HEADERS_DIR" -DCMAKE_C_FLAGS="-fprofile-instr-generate -fcoverage-mapping" \
        -DCMAKE_EXE_LINKER_FLAGS="-fprofile-instr-generate" >/dev/null
    # shellcheck disable=SC2086
    cmake --build "$cov" -j2 --target $targets >/dev/null
    for t in $targets; do
        rm -f "$cov/$t.profraw"
        LLVM_PROFILE_FILE="$cov/$t.profraw" nice -n 10 "$cov/$t" "$build/corpus/$t" -runs=0 \
            >/dev/null 2>&1 || true
        llvm-profdata merge -sparse "$cov/$t.profraw" -o "$cov/$t.profdata"
        echo "== $t: line coverage of fmu_src by its corpus"
        llvm-cov report "$cov/$t" -instr-profile="$cov/$t.profdata" \
            $(cd "$root" && find fmu_src -name '*.c' ! -name 'gen_model_description*' | sort | sed "s|^|$root/|") |
            awk 'NR == 1 || /fmu_src|TOTAL/' | sed 's/^/   /'
    done
fi
exit $status
