#!/bin/sh
# SPDX-License-Identifier: MIT
# The fuzz harnesses' regression check in make test: every file of tests/fuzz/seeds/ and tests/fuzz/regress/ (the
# inputs that once found a bug) through every harness, built without libFuzzer as $BUILD/tests/fuzz/replay_NAME
# (tests/fuzz/replay.c), so the normal and the sanitizer (make SAN=1) builds both check them. Every file goes
# through every harness: an input for one parser is a good bad input for the others. One line per harness.
cd "$(dirname "$0")/../.." || exit 2
build=${BUILD:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

files=$(find tests/fuzz/seeds tests/fuzz/regress -type f 2>/dev/null | sort)
count=$(echo "$files" | grep -c .)
if [ "$count" -eq 0 ]; then
    echo "not ok - fuzz/replay: no inputs in tests/fuzz/seeds or tests/fuzz/regress"
    exit 0
fi
# A hang is a finding too: give up on a harness after this long (when timeout(1) is there).
limit=""
command -v timeout >/dev/null 2>&1 && limit="timeout 300"

for src in tests/fuzz/fuzz_*.c; do
    name=${src#tests/fuzz/fuzz_}
    name=${name%.c}
    bin=$build/tests/fuzz/replay_$name
    if [ ! -x "$bin" ]; then
        echo "not ok - fuzz/replay/$name: $bin is missing (make builds it)"
        continue
    fi
    # shellcheck disable=SC2086 # $files is a list of paths without spaces; $limit is a command or nothing
    if $limit "$bin" $files >"$tmp/out" 2>&1; then
        echo "ok - fuzz/replay/$name: $count inputs"
    else
        status=$?
        last=$(grep '^replay: ' "$tmp/out" | tail -n 1)
        echo "not ok - fuzz/replay/$name: status $status on ${last#replay: }"
        grep -E 'ERROR|SUMMARY|runtime error' "$tmp/out" | head -n 3 | sed 's/^/    /'
    fi
done
