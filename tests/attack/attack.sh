#!/bin/sh
# SPDX-License-Identifier: MIT
# The attack suite: bad input, as classes (docs/usage.md, "Bad input"), against both programs. The cases are in
# tests/attack/*.cases, one a line:
#
#   STATUS|PHRASE|ARGUMENTS
#
# ARGUMENTS are read by the shell (quotes work: '' is an empty value) with $S for volfix-sim, $V for volfix, $F
# for the scratch folder (fixtures: volumes, transfer functions, boards, scripts, an existing PNG and a symlink
# to it) and $O for the output folder inside it. STATUS 2 is bad input: exit status 2, exactly one line on
# stderr containing PHRASE (the option or the file), nothing on stdout, and the output folder left empty. STATUS
# 0 is input that must work (the checks refuse nothing valid). For every case, a snapshot of the scratch folder
# (names, types, sizes, modes, link targets, inodes, change times) taken before and after must be the same:
# nothing outside the output path is created, changed or deleted. Each case runs under a timeout of CASE_SECONDS.
#
# tests/attack/numbers.matrix gives OPTION lines for each program: every OPTION is given each of the junk values
# below, and each must be refused naming the option. The cases run in LANES lanes side by side (default 2), each
# with a scratch folder of its own (tests/attack/fixtures.inc makes it). The signal, FIFO and lost-display cases
# are at the end of this file. STATUS 2+ is as 2 for a defect found only while the program runs (a log on
# /dev/full): what it printed and wrote before may stay.
cd "$(dirname "$0")/../.." || exit 2
BUILD=${BUILD:-build}
suite=attack
. tests/check.inc
S=$BUILD/volfix-sim
V=$BUILD/volfix
CASE_SECONDS=${CASE_SECONDS:-10}
for p in "$S" "$V"; do
    [ -x "$p" ] || { fail "programs" "$p is not built"; exit 1; }
done

# ---- the cases: one list, then LANES lanes side by side, each with a scratch folder of its own ----
LANES=${LANES:-2}
: >"$tmp/cases"
for file in tests/attack/*.cases; do
    n=0
    while IFS= read -r line; do
        n=$((n + 1))
        case "$line" in '#'* | '') continue ;; esac
        want=${line%%|*} rest=${line#*|}
        printf '%s\037%s\037%s\037%s\n' "$(basename "$file"):$n" "$want" "${rest%%|*}" "${rest#*|}" >>"$tmp/cases"
    done <"$file"
done
# Junk for every number an option takes: not a number, not finite, empty, out of any range, trailing junk,
# hexadecimal, a leading space, too many list values, a 32-bit overflow, a lone sign or comma, doubled separators.
junk="nan inf -inf '' 1e999 30junk 0x10 ' 1' 1,2,3,4,5 4294967297 - , 1,,2 +-1"
while IFS= read -r line; do
    case "$line" in '#'* | '') continue ;; esac
    prog=${line%%|*} option=${line#*|}
    case "$prog" in
    sim-*) cmd="\$S ${prog#sim-}" ;;
    viewer) cmd="\$V --board \$F/good.board \$F/good.nhdr --device \$O/frames --frames 1" ;;
    esac
    case "$prog" in
    sim-render | sim-compare | sim-bench | sim-ray) cmd="$cmd \$F/good.nhdr" ;;
    esac
    case "$prog" in
    sim-render) tail_args="-o \$O/x.png" ;;
    sim-ray | sim-study) tail_args="-o \$O/r" ;;
    *) tail_args= ;;
    esac
    eval "set -- $junk"
    for value in "$@"; do
        quoted=$(printf '%s' "$value" | sed "s/'/'\\\\''/g")
        printf '%s\037%s\037%s\037%s\n' "numbers:$prog $option '$value'" 2 "$option" "$cmd $option '$quoted' $tail_args" \
            >>"$tmp/cases"
    done
done <tests/attack/numbers.matrix

snapshot() { # the scratch folder, outside $O, as one text: names, types, sizes, modes, link targets, inodes and
    # change times (a write, a chmod or a replacement each shows)
    (cd "$F" && find . -mindepth 1 -path ./out -prune -o -printf '%p %y %s %m %l %i %T@ %C@\n' | LC_ALL=C sort)
}

# run_case NAME STATUS PHRASE ARGUMENTS: STATUS 2, 2+ (as 2, but the defect shows only while the program runs,
# as a log on /dev/full: what it wrote before may stay), or the status valid input must give
run_case() {
    name=$1 want=$2 phrase=$3 args=$4
    eval "set -- $args"
    timeout -k 2 "$CASE_SECONDS" "$@" >"$L/out" 2>"$L/err" </dev/null
    status=$?
    why=
    if [ $status -eq 124 ] || [ $status -eq 137 ]; then
        why="ran past $CASE_SECONDS s"
    elif [ "$want" = 2 ] || [ "$want" = 2+ ]; then
        lines=$(wc -l <"$L/err")
        if [ $status -ne 2 ]; then
            why="exit status $status, expected 2 ($(head -c 200 "$L/err" | head -n 1))"
        elif [ "$lines" -ne 1 ]; then
            why="$lines lines on stderr, expected one: $(head -c 300 "$L/err" | tr '\n' '|')"
        elif ! grep -qF -- "$phrase" "$L/err"; then
            why="stderr does not name '$phrase': $(cat "$L/err")"
        elif [ "$want" = 2 ] && [ -s "$L/out" ]; then
            why="output on stdout: $(head -n 1 "$L/out" | head -c 100)"
        elif [ "$want" = 2 ] && [ -n "$(ls -A "$O")" ]; then
            why="bad input left something in the output folder: $(ls -A "$O" | head -n 3 | tr '\n' ' ')"
        fi
    elif [ $status -ne "$want" ]; then
        why="exit status $status, expected $want ($(head -c 200 "$L/err" | head -n 1))"
    fi
    snapshot >"$L/after"
    if ! cmp -s "$L/before" "$L/after"; then
        why="${why:+$why; }the scratch folder changed: $(diff "$L/before" "$L/after" | grep '^[<>]' | head -n 3 |
            tr '\n' ' ')"
        mv "$L/after" "$L/before" # each change is told once, by the case that made it
    fi
    rm -rf "$O" && mkdir "$O"
    [ -z "$why" ] || fail "$name" "$why"
}

lane() { # K: the cases whose line number is K modulo LANES
    L=$tmp/lane$1
    F=$L/scratch
    O=$F/out
    mkdir -p "$L"
    if ! sh tests/attack/fixtures.inc "$F" >"$L/fixtures.err" 2>&1; then
        fail "fixtures" "tests/attack/fixtures.inc: $(head -n 1 "$L/fixtures.err")"
        return
    fi
    mkdir -p "$O"
    snapshot >"$L/before"
    awk -v k="$1" -v n="$LANES" 'NR % n == k' "$tmp/cases" >"$L/cases"
    while IFS="$(printf '\037')" read -r name want phrase args; do
        run_case "$name $args" "$want" "$phrase" "$args"
    done <"$L/cases"
}
k=0
while [ $k -lt "$LANES" ]; do
    lane $k >"$tmp/lane$k.out" &
    k=$((k + 1))
done
wait
cat "$tmp"/lane*.out
count=$(grep -c . "$tmp/cases")
failed=$(cat "$tmp"/lane*.out | grep -c '^not ok')
F=$tmp/lane0/scratch

# ---- signals and FIFOs ----
# A FIFO with no writer: the program waits, as cat does, and SIGINT or SIGTERM end it with 130 or 143.
signal_case() { # NAME SIGNAL WANT ARGS...
    name=$1 sig=$2 want=$3
    shift 3
    count=$((count + 1))
    "$@" >"$tmp/sig.out" 2>"$tmp/sig.err" </dev/null &
    pid=$!
    sleep 1
    kill -s "$sig" $pid 2>/dev/null
    i=0
    while kill -0 $pid 2>/dev/null && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
    if kill -0 $pid 2>/dev/null; then
        kill -s KILL $pid
        wait $pid
        failed=$((failed + 1))
        fail "signal:$name" "still running 5 s after SIG$sig"
        return
    fi
    wait $pid
    status=$?
    if [ $status -ne "$want" ]; then
        failed=$((failed + 1))
        fail "signal:$name" "exit status $status after SIG$sig, expected $want ($(head -n 1 "$tmp/sig.err"))"
    fi
}
mkfifo "$tmp/fifo.tf" "$tmp/fifo.nhdr" "$tmp/fifo.script"
printf '0 turn 0 1\n' >"$tmp/forever.script"
for sig in INT:130 TERM:143; do
    s=${sig%:*} w=${sig#*:}
    signal_case "volfix --tf FIFO without writer $s" "$s" "$w" "$V" --board "$F/good.board" "$F/good.nhdr" \
        --device "$tmp/sig-frames" --tf "$tmp/fifo.tf"
    signal_case "volfix FIFO volume without writer $s" "$s" "$w" "$V" --board "$F/good.board" "$tmp/fifo.nhdr" \
        --device "$tmp/sig-frames"
    signal_case "volfix --script FIFO without writer $s" "$s" "$w" "$V" --board "$F/good.board" "$F/good.nhdr" \
        --device "$tmp/sig-frames" --script "$tmp/fifo.script"
    signal_case "volfix in its loop $s" "$s" "$w" "$V" --board "$F/good.board" "$F/good.nhdr" \
        --device "$tmp/sig-frames" --script "$tmp/forever.script"
done

# A display that goes away: the png display's folder removed while the viewer runs is a clear exit 2 naming it
# (README: a lost display is looked for again, or the run ends with status 2; a folder of frames is not looked for).
count=$((count + 1))
i=0
while [ $i -lt 100 ]; do echo "$((i * 100)) turn 0 1"; i=$((i + 1)); done >"$tmp/long.script"
mkdir -p "$tmp/gone"
timeout 20 "$V" --board "$F/good.board" "$F/good.nhdr" --device "$tmp/gone/frames" --script "$tmp/long.script" \
    >"$tmp/gone.out" 2>"$tmp/gone.err" &
pid=$!
i=0
while [ ! -e "$tmp/gone/frames/frame-00002.png" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
rm -rf "$tmp/gone/frames"
wait $pid
status=$?
if [ $status -ne 2 ] || [ "$(wc -l <"$tmp/gone.err")" -ne 1 ] || ! grep -q "gone/frames" "$tmp/gone.err"; then
    failed=$((failed + 1))
    fail "display:folder removed while running" "status $status: $(head -c 300 "$tmp/gone.err" | tr '\n' '|')"
fi

# A FIFO fed once: the volume, the transfer function and the script are each read once, as streams.
count=$((count + 1))
sed "s#^data file: #data file: $F/#" "$F/good.nhdr" >"$tmp/fifo.nhdr" &
printf '0 0 0 0 0\n255 1 1 1 1\n' >"$tmp/fifo.tf" &
if timeout 10 "$S" render "$tmp/fifo.nhdr" --tf "$tmp/fifo.tf" --hash >"$tmp/fifo.out" 2>&1 &&
    timeout 10 "$S" render "$F/good.nhdr" --tf "$F/ramp.tf" --hash >"$tmp/file.out" 2>&1 &&
    [ "$(cut -d' ' -f1 "$tmp/fifo.out")" = "$(cut -d' ' -f1 "$tmp/file.out")" ]; then
    :
else
    failed=$((failed + 1))
    fail "fifo:volume and tf from FIFOs" "$(cat "$tmp/fifo.out") / $(cat "$tmp/file.out")"
fi
wait

echo "# $count cases, $failed failed"
[ "$count" -ge 400 ] && ok "at least 400 cases ($count)" || fail "case count" "only $count cases"
[ "$failed" -eq 0 ] && ok "every case ($count): bad input exits 2 with one line naming it, nothing else touched"
