#!/bin/sh
# SPDX-License-Identifier: MIT
# Run the libFuzzer harnesses built by `make fuzz` (tests/fuzz/README.md), FUZZ_JOBS at a time (default: the
# processors online), each for SECONDS, and print one line per harness:
#   fuzz_nrrd: 1234567 runs in 60 s, cov 812, ft 2990, corpus 431 files
# A crash, leak, sanitizer report, hang (-timeout=10), out-of-memory (-rss_limit_mb=2048) or single allocation
# above -malloc_limit_mb=256 fails the run; its input is in BUILD/crashes/NAME/ and the line says which file and what happened.
# Usage: tools/fuzz.sh BUILD SECONDS NAME...
set -u
cd "$(dirname "$0")/.." || exit 2
build=$1 seconds=$2
shift 2
jobs=${FUZZ_JOBS:-$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)}
[ "$jobs" -ge 1 ] 2>/dev/null || jobs=1

# The longest input worth trying, per format: room for a header and a small volume, or a long text file.
max_len() {
    case "$1" in
        tf) echo 16384 ;;
        board | script) echo 8192 ;;
        *) echo 4096 ;;
    esac
}

run_one() {
    name=$1
    corpus=$build/corpus/$name crashes=$build/crashes/$name
    mkdir -p "$corpus" "$crashes"
    # -malloc_limit_mb: an input of a few kilobytes needs a few megabytes at most (gzip inflates ~1000 times), so
    # one allocation above 256 MB means a reader believed a header's sizes before it found the data missing.
    set -- "$build/fuzz_$name" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=256 \
        -max_len="$(max_len "$name")" -artifact_prefix="$crashes/" -print_final_stats=1
    dict=tests/fuzz/${name%%_*}.dict # nrrd_detached uses nrrd.dict, nifti_gz nifti.dict
    [ -f "$dict" ] && set -- "$@" -dict="$dict"
    set -- "$@" "$corpus"
    for d in "tests/fuzz/seeds/$name" "tests/fuzz/regress/$name"; do
        [ -d "$d" ] && set -- "$@" "$d"
    done
    # stdin from /dev/null: a header that names /dev/stdin as its data file must not wait for a terminal.
    "$@" </dev/null >"$build/fuzz_$name.log" 2>&1
    echo $? >"$build/fuzz_$name.status"
}

started=0
for name in "$@"; do
    run_one "$name" &
    started=$((started + 1))
    if [ $((started % jobs)) -eq 0 ]; then
        wait
    fi
done
wait

failed=0
for name in "$@"; do
    log=$build/fuzz_$name.log
    status=$(cat "$build/fuzz_$name.status" 2>/dev/null || echo 2)
    files=$(find "$build/corpus/$name" -type f | wc -l)
    # "#123456	DONE   cov: 812 ft: 2990 corp: 431/20Kb ..." is the last progress line of a run that ended well.
    last=$(grep -E '^#[0-9]+' "$log" | tail -n 1)
    runs=$(grep '^stat::number_of_executed_units:' "$log" | tail -n 1 | awk '{print $2}')
    [ -n "$runs" ] || runs=$(echo "$last" | sed -E 's/^#([0-9]+).*/\1/')
    cov=$(echo "$last" | sed -nE 's/.* cov: ([0-9]+).*/\1/p')
    ft=$(echo "$last" | sed -nE 's/.* ft: ([0-9]+).*/\1/p')
    if [ "$status" -eq 0 ]; then
        echo "fuzz_$name: ${runs:-?} runs in $seconds s, cov ${cov:-?}, ft ${ft:-?}, corpus $files files"
    else
        failed=$((failed + 1))
        input=$(sed -nE 's/.*Test unit written to (.*)$/\1/p' "$log" | tail -n 1)
        what=$(grep -E '^SUMMARY: |ERROR: libFuzzer: |==[0-9]+==ERROR: ' "$log" | head -n 1)
        echo "fuzz_$name: FAILED (status $status) after ${runs:-?} runs: ${what:-see $log}"
        echo "    input: ${input:-none saved}; log: $log; replay: $build/fuzz_$name ${input:-INPUT}"
    fi
done
[ "$failed" -eq 0 ]
