#!/bin/sh
# SPDX-License-Identifier: MIT
# Run the test suites: the compiled ones ($BUILD/tests/**/test_*) and the shell ones (tests/**/*.sh; tests/hw and
# tests/long boot a VM or run for minutes and have their own targets, make test-hw and make test-long), TEST_JOBS
# at a time (default: the processors online), the slowest of the last run first. Each suite writes to a file of
# its own; when it ends, its failures and skips are printed in one piece, so suites running side by side never
# mix their lines. A shell suite with a line "# run alone: WHY" (one that times what it checks) runs first, by
# itself.
#
# A case prints "ok - NAME", "not ok - NAME: why", or "skip - NAME: why, and the package that would let it run";
# "ok - NAME # skip ..." counts as skipped, not passed. A suite that dies without saying why is one failure. A
# suite the build left out for want of a package ($BUILD/config.mk, LEFT_OUT_TESTS) is one skip.
# The summary names every skipped suite, ends with "N passed, N failed, N skipped", and the exit status is 1 when
# anything failed or was skipped: "0 failed" never hides a suite that did not run.
#
# Usage: tests/run.sh [PATTERN...]   (only the suites whose path contains one of the PATTERNs)
# Environment: BUILD (default build), TEST_JOBS, VOLFIX_DATA (make exports it; asked of the Makefile otherwise).
cd "$(dirname "$0")/.." || exit 2
BUILD=${BUILD:-build}
export BUILD

# tests/run.sh --one RESULTS SUITE: run one suite (for xargs), leave its lines, report and time in RESULTS.
if [ "${1:-}" = --one ]; then
    results=$2 suite=$3
    out=$results/$(printf '%s' "$suite" | tr '/' '%')
    start=$(date +%s%N)
    case "$suite" in
    *.sh) sh "$suite" ;;
    *) "$suite" ;;
    esac >"$out.out" 2>&1 </dev/null
    status=$?
    end=$(date +%s%N)
    grep -E '^(ok|not ok|skip) - ' "$out.out" >"$out.lines"
    grep -E '^(not ok|skip) - |^ok - .* # skip' "$out.out" >"$out.report"
    if [ $status -ne 0 ] && ! grep -qE '^(not ok|skip) - ' "$out.out"; then
        echo "not ok - $suite: exited with status $status" | tee -a "$out.lines" >>"$out.report"
        tail -n 5 "$out.out" | sed 's/^/    /' >>"$out.report"
    fi
    echo "$(((end - start) / 1000000)) $suite" >"$out.time"
    if [ -s "$out.report" ]; then
        if command -v flock >/dev/null 2>&1; then flock "$results/lock" cat "$out.report"; else cat "$out.report"; fi
    fi
    exit 0
fi

# The sample volumes' folder: the Makefile names the default, in one place.
if [ -z "${VOLFIX_DATA+set}" ]; then
    VOLFIX_DATA=$(${MAKE:-make} -s --no-print-directory print-VOLFIX_DATA 2>/dev/null)
fi
export VOLFIX_DATA
jobs=${TEST_JOBS:-$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)}
[ "$jobs" -ge 1 ] 2>/dev/null || jobs=1
results=$(mktemp -d)
trap 'rm -rf "$results"' EXIT
started=$(date +%s)

patterns="$*"
wanted() { # PATH: does it contain one of the command line's patterns (or are there none)?
    [ -z "$patterns" ] && return 0
    for p in $patterns; do
        case "$1" in *"$p"*) return 0 ;; esac
    done
    return 1
}

# The suites the build left out: one skip each, with the packages that bring them in.
left_out=$(sed -n 's/^LEFT_OUT_TESTS = //p' "$BUILD/config.mk" 2>/dev/null)
for w in $left_out; do
    suite=$BUILD/${w%%:*}
    if wanted "$suite"; then
        echo "skip - $suite: left out of the build, which needs $(echo "${w#*:}" | sed 's/+/ and /g')" |
            tee -a "$results/left-out.lines"
    fi
done

{
    find "$BUILD/tests" -type f -name 'test_*' -perm -u+x 2>/dev/null
    find tests \( -path tests/hw -o -path tests/long \) -prune -o -name '*.sh' ! -name run.sh -print 2>/dev/null
} | sort | while IFS= read -r suite; do
    case " $left_out " in *" ${suite#"$BUILD"/}:"*) continue ;; esac # a stale binary of a suite left out
    if wanted "$suite"; then echo "$suite"; fi
done >"$results/suites"

# Slowest first (the last run's times; a suite without one counts as slow), so that the long ones start early.
times=$BUILD/tests/durations
[ -f "$times" ] || times=/dev/null
awk 'FILENAME == ARGV[1] { t[$2] = $1; next } { print (($0 in t) ? t[$0] : 1000000000), $0 }' "$times" \
    "$results/suites" | sort -k1,1nr -k2 | cut -d' ' -f2- >"$results/order"
# shellcheck disable=SC2046 # suite paths have no spaces
grep -l '^# run alone: ' $(grep '\.sh$' "$results/order") /dev/null 2>/dev/null >"$results/alone"
for suite in $(cat "$results/alone"); do sh tests/run.sh --one "$results" "$suite"; done
grep -vxF -f "$results/alone" "$results/order" | tr '\n' '\0' |
    xargs -0 -n 1 -P "$jobs" sh tests/run.sh --one "$results"

cat "$results"/*.lines >"$results/all" 2>/dev/null
passed=$(grep '^ok - ' "$results/all" | grep -vc ' # skip')
failed=$(grep -c '^not ok - ' "$results/all")
skipped=$(grep -cE '^skip - |^ok - .* # skip' "$results/all")
# Keep this run's times, and the last known ones of the suites it did not run.
cat "$results"/*.time >"$results/times" 2>/dev/null
if [ -d "$BUILD/tests" ]; then
    awk 'FILENAME == ARGV[1] { new[$2] = 1; print; next } !($2 in new)' "$results/times" "$times" \
        >"$results/durations" && cp "$results/durations" "$BUILD/tests/durations"
fi
count=$(grep -c . "$results/order")
slowest=$(sort -nr "$results/times" 2>/dev/null | head -n 3 |
    awk '{ printf "%s%s %.0f s", (NR > 1 ? ", " : ""), $2, $1 / 1000 }')
echo "# $count suites in $(($(date +%s) - started)) s, $jobs at a time; the slowest: $slowest"
if [ "$skipped" -gt 0 ]; then
    echo "skipped, so this run proves nothing about them (install what they name, then run the tests again):"
    grep -E '^skip - |^ok - .* # skip' "$results/all" | sed 's/^/  /'
fi
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ] && [ "$skipped" -eq 0 ] && [ "$passed" -gt 0 ]
