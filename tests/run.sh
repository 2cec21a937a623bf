#!/bin/sh
# Run every test: the compiled suites (build/tests/**/test_*) and the shell suites (tests/**/*.sh).
# Each prints "ok - NAME" or "not ok - NAME: why" per case; this counts them and ends with one line,
# "N passed, N failed". A suite that dies without saying why counts as one failure.
# Usage: tests/run.sh [PATTERN]   (only suites whose path contains PATTERN)
cd "$(dirname "$0")/.." || exit 2
BUILD=${BUILD:-build}
export BUILD
export VOLFIX_DATA="${VOLFIX_DATA:-../shared/data}"
pattern=${1:-}
log=$(mktemp)
trap 'rm -f "$log"' EXIT

run_suite() {
    name=$1
    shift
    out=$(mktemp)
    "$@" >"$out" 2>&1
    status=$?
    grep -E '^(ok|not ok) - ' "$out" >>"$log"
    grep -E '^not ok - ' "$out"
    if [ $status -ne 0 ] && ! grep -q '^not ok - ' "$out"; then
        echo "not ok - $name: exited with status $status" | tee -a "$log"
        tail -n 5 "$out" | sed 's/^/    /'
    fi
    rm -f "$out"
}

for t in $(find "$BUILD/tests" -type f -name 'test_*' -perm -u+x 2>/dev/null | sort); do
    case "$t" in *"$pattern"*) run_suite "$t" "$t" ;; esac
done
# tests/hw boots a VM and tests/long runs for minutes: they have their own targets (make test-hw, test-long).
for t in $(find tests \( -path tests/hw -o -path tests/long \) -prune -o -name '*.sh' ! -name run.sh -print 2>/dev/null |
    sort); do
    case "$t" in *"$pattern"*) run_suite "$t" sh "$t" ;; esac
done

passed=$(grep -c '^ok - ' "$log")
failed=$(grep -c '^not ok - ' "$log")
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
