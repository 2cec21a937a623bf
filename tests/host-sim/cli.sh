#!/bin/sh
# SPDX-License-Identifier: MIT
# volfix-sim from the outside: usage and help, and for every kind of bad input an exit status of 2 and exactly
# one line on stderr that names the file (and line) and says what was expected.
cd "$(dirname "$0")/../.." || exit 2
sim=${BUILD:-build}/volfix-sim
suite=cli program=$sim
. tests/check.inc

# usage and help
"$sim" >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q '^usage: volfix-sim COMMAND' "$tmp/err" && ok "no arguments print usage, status 2" ||
    fail "no arguments" "expected usage on stderr and status 2"
for cmd in render compare bench; do
    if "$sim" $cmd --help >"$tmp/out" 2>&1 && grep -q "^usage: volfix-sim $cmd" "$tmp/out" &&
        grep -q -- '--preset' "$tmp/out"; then
        ok "$cmd --help"
    else
        fail "$cmd --help" "$(head -n 2 "$tmp/out")"
    fi
done
expect_error "unknown command" "unknown command 'paint'" paint
expect_error "unknown option" "--colour: unknown option" render phantom:sphere:8 --colour red -o "$tmp/x.png"
expect_error "bad mode" "--mode lines: expected point, preint1, preclass or preint2" render phantom:sphere:8 --mode lines -o "$tmp/x.png"
expect_error "bad view" "--view 30: expected AZ,EL" render phantom:sphere:8 --view 30 -o "$tmp/x.png"
expect_error "bad size" "--size 0x10: expected WxH" render phantom:sphere:8 --size 0x10 -o "$tmp/x.png"
expect_error "bad format" "--format bgr: expected rgb888, rgb565 or xrgb8888" render phantom:sphere:8 --format bgr -o "$tmp/x.png"
expect_error "bad zoom" "--zoom 0: expected a number" render phantom:sphere:8 --zoom 0 -o "$tmp/x.png"
expect_error "bad table size" "--table-size 4096: expected an integer from 2 to 1024" render phantom:sphere:8 --table-size 4096 -o "$tmp/x.png"
expect_error "no output" "no output file (-o OUT.png, or --hash)" render phantom:sphere:8
expect_error "no volume" "no volume given" compare --json
expect_error "preset and tf" "give --preset or --tf, not both" render phantom:sphere:8 --preset ramp --tf x -o "$tmp/x.png"

# preint2 (docs/algorithm.md section 8): what it takes and only it takes, and its table's command
expect_error "bilinear preint2" "--lookup bilinear: preint2 looks its 3D table up nearest or trilinear" \
    render phantom:sphere:8 --mode preint2 --lookup bilinear -o "$tmp/x.png"
expect_error "trilinear preint1" "--lookup trilinear: only preint2 has a 3D table" \
    render phantom:sphere:8 --lookup trilinear -o "$tmp/x.png"
expect_error "preint2 partial slabs" "--partial-slabs: preint2 does not shorten its slabs" \
    render phantom:sphere:8 --mode preint2 --partial-slabs -o "$tmp/x.png"
expect_error "bad table2 size" "--table2-size 8: expected an integer from 16 to 128" \
    render phantom:sphere:8 --mode preint2 --table2-size 8 -o "$tmp/x.png"
expect_error "bad order" "--order 3: expected 1 or 2" tables --order 3
expect_error "bad order-2 size" "--size 200: expected an integer from 16 to 128" tables --order 2 --size 200
if "$sim" tables --order 2 --size 16 --table-size 32 --lit --repeat 1 --json >"$tmp/t2.json" 2>&1 &&
    grep -q '"size2": 16' "$tmp/t2.json" && grep -q '"table_bytes": 32768' "$tmp/t2.json" &&
    grep -q '"lit_bytes": 65536' "$tmp/t2.json" &&
    awk -F'"max_err_lsb": ' '{ split($2, v, ","); exit !(v[1] + 0 <= 1) }' "$tmp/t2.json" &&
    awk -F'"lit_max_err_lsb": ' '{ split($2, v, ","); exit !(v[1] + 0 <= 1) }' "$tmp/t2.json"; then
    ok "tables --order 2 --json: a 16^3 table's memory, and its values and lighting values within 1 LSB of double"
else
    fail "tables --order 2" "$(head -c 300 "$tmp/t2.json")"
fi

# --rays: 1, 2, 4, 8 or 16; above 1 only the reference has it (docs/algorithm.md section 4b)
for cmd in render compare bench ray; do
    if "$sim" $cmd --help 2>&1 | grep -q -- '--rays N'; then
        ok "$cmd --help documents --rays"
    else
        fail "$cmd --help" "no --rays"
    fi
done
for bad in 0 3 32 -4 2.5 two; do
    expect_error "bad rays $bad" "--rays $bad: expected 1, 2, 4, 8 or 16" render phantom:sphere:8 --reference --rays $bad --hash
done
expect_error "rays missing" "--rays (missing): expected 1, 2, 4, 8 or 16" render phantom:sphere:8 --reference --hash --rays
# the core with rays and partial slabs, against the reference with the same options: within a level
for opts in "--rays 2" "--rays 4 --mode point" "--rays 8 --mode preclass" "--partial-slabs" \
    "--partial-slabs --rays 4 --mode point" "--partial-slabs --rays 2 --mode preclass --buffer image"; do
    # shellcheck disable=SC2086 # the options are words
    max=$("$sim" compare phantom:marschner-lobb:16 --size 64x56 --preset sharp --view 40,25 $opts --json 2>&1 |
        sed -n 's/.*"max_abs": \([0-9]*\).*/\1/p')
    if [ -n "$max" ] && [ "$max" -le 1 ]; then
        ok "compare $opts: the core within a level of the reference"
    else
        fail "compare $opts" "largest difference '$max' levels, expected at most 1"
    fi
done
expect_error "partial slabs with the lut" "goes with --correction rebuild" render phantom:sphere:8 --partial-slabs \
    --correction lut -o "$tmp/x.png"
# a volume that R x R pixels per voxel would make too wide for the 16-bit skip links: one line, exit 2
head -c $((4096 * 2 * 40)) /dev/zero >"$tmp/wide.raw"
expect_error "rays too many for a wide volume" "intermediate image would exceed" render "$tmp/wide.raw" --dims 4096,2,40 \
    --type uint8 --rays 16 -o "$tmp/x.png"
rays_hash() { "$sim" render phantom:marschner-lobb:16 --size 48x40 --preset sharp "$@" --hash 2>&1 | cut -c1-16; }
if [ "$(rays_hash --rays 1)" = "$(rays_hash)" ] && [ "$(rays_hash --reference --rays 1)" = "$(rays_hash --reference)" ] &&
    [ "$(rays_hash --reference --rays 1 --partial-slabs)" = "$(rays_hash --reference --partial-slabs)" ]; then
    ok "--rays 1 is the default, for the core and the reference"
else
    fail "--rays 1" "the hashes differ from the default's"
fi
# threads build the pre-integrated table in parts (vf_renderer_build_table_part): the same frame for any number
threads_same=yes
for size in 256 1024; do
    one=$(rays_hash --table-size "$size")
    for t in 2 3 16; do
        [ -n "$one" ] && [ "$(rays_hash --table-size "$size" --threads "$t")" = "$one" ] || threads_same="no: $size, $t"
    done
done
if [ "$threads_same" = yes ]; then
    ok "--threads 2, 3 and 16 render the frame of one thread (tables of 256 and 1024 built in parts)"
else
    fail "--threads" "hashes differ from one thread's ($threads_same)"
fi
if "$sim" render phantom:marschner-lobb:16 --size 48x40 --preset sharp --reference --rays 4 --hash >"$tmp/out" 2>&1 &&
    grep -q ' rays 4 48x40 ' "$tmp/out" && [ "$(cut -c1-16 "$tmp/out")" != "$(rays_hash --reference)" ] &&
    [ "$(rays_hash --truth --rays 4)" = "$(rays_hash --truth)" ]; then
    ok "--reference --rays 4 renders another image and says so; --truth ignores --rays"
else
    fail "--rays 4" "$(cat "$tmp/out")"
fi

# bench --rounds: a positive whole number of rounds, and --help says what it does
if "$sim" bench --help 2>&1 | grep -q -- '--rounds N'; then
    ok "bench --help documents --rounds"
else
    fail "bench --help" "no --rounds"
fi
for bad in 0 -1 x 2.5 1001; do
    expect_error "bad rounds $bad" "--rounds $bad: expected a number of rounds, 1..1000" bench phantom:sphere:8 --rounds $bad
done
expect_error "rounds missing" "--rounds (missing): expected a number of rounds" bench phantom:sphere:8 --rounds

# bad volumes
printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n' >"$tmp/trunc.nrrd"
head -c 40 /dev/zero >>"$tmp/trunc.nrrd"
expect_error "truncated data" "trunc.nrrd: truncated: expected 64 bytes of voxel data, found 40" render "$tmp/trunc.nrrd" -o "$tmp/x.png"
printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n' >"$tmp/long.nrrd"
head -c 65 /dev/zero >>"$tmp/long.nrrd"
expect_error "size mismatch" "long.nrrd: expected 64 bytes of voxel data, found 65" render "$tmp/long.nrrd" -o "$tmp/x.png"
printf 'NRRD0004\ntype: uint8\ndimension 3\n' >"$tmp/line.nrrd"
expect_error "bad header line" "line.nrrd:3: expected 'field: value'" render "$tmp/line.nrrd" -o "$tmp/x.png"
printf 'NRRD0004\ntype: float\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n' >"$tmp/float.nrrd"
expect_error "unsupported type" "float.nrrd:2: unsupported type 'float'" render "$tmp/float.nrrd" -o "$tmp/x.png"
printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: bzip2\n\n' >"$tmp/bz.nrrd"
expect_error "unsupported encoding" "bz.nrrd:5: unsupported encoding 'bzip2'" render "$tmp/bz.nrrd" -o "$tmp/x.png"
head -c 64 /dev/urandom | gzip -c | head -c 20 >"$tmp/cut.raw.gz"
printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: gzip\ndata file: cut.raw.gz\n' >"$tmp/cut.nhdr"
expect_error "gzip error" "cut.raw.gz: gzip error" render "$tmp/cut.nhdr" -o "$tmp/x.png"
printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: raw\ndata file: gone.raw\n' >"$tmp/lost.nhdr"
expect_error "missing data file" "lost.nhdr:6: cannot open data file" render "$tmp/lost.nhdr" -o "$tmp/x.png"
expect_error "missing file" "nowhere.nrrd" render "$tmp/nowhere.nrrd" -o "$tmp/x.png"
head -c 64 /dev/zero >"$tmp/voxels.raw"
expect_error "raw without dims" "voxels.raw: raw data needs --dims" render "$tmp/voxels.raw" -o "$tmp/x.png"
expect_error "raw size mismatch" "voxels.raw: truncated: expected 128 bytes" render "$tmp/voxels.raw" --dims 4,4,4 --type uint16 -o "$tmp/x.png"
expect_error "bad dims" "--dims" render "$tmp/voxels.raw" --dims 4,4 --type uint8 -o "$tmp/x.png"
expect_error "bad phantom" "unknown phantom 'box'" render phantom:box:16 -o "$tmp/x.png"
head -c 348 /dev/zero >"$tmp/empty.nii"
expect_error "bad nifti header" "empty.nii" render "$tmp/empty.nii" -o "$tmp/x.png"

# bad transfer functions and windows
printf '# a comment\n0 0 0 0 0\n0.5 1 1 1\n' >"$tmp/short.tf"
expect_error "tf short line" "short.tf:3: expected a control point 'scalar r g b a'" render phantom:sphere:8 --tf "$tmp/short.tf" -o "$tmp/x.png"
printf '0.5 0 0 0 0\n0.2 1 1 1 1\n' >"$tmp/down.tf"
expect_error "tf decreasing" "down.tf:2: scalar 0.2 is below the previous point's 0.5" render phantom:sphere:8 --tf "$tmp/down.tf" -o "$tmp/x.png"
printf '0 0 0 0 0\n1 1 1 1 1.5\n' >"$tmp/big.tf"
expect_error "tf out of range" "big.tf:2: colour and opacity must be within [0, 1]" render phantom:sphere:8 --tf "$tmp/big.tf" -o "$tmp/x.png"
expect_error "unknown preset" "unknown preset 'bones'" render phantom:sphere:8 --preset bones -o "$tmp/x.png"
expect_error "bad window" "--window" render phantom:sphere:8 --window 5 -o "$tmp/x.png"

# good runs
if "$sim" render phantom:sphere:16 --size 64x48 -o "$tmp/s.png" >"$tmp/out" 2>&1 &&
    [ "$(head -c 4 "$tmp/s.png" | od -An -tx1 | tr -d ' ')" = 89504e47 ] && grep -q 's.png: phantom:sphere:16' "$tmp/out"; then
    ok "render writes a PNG and says what it rendered"
else
    fail "render" "$(cat "$tmp/out")"
fi
if "$sim" compare phantom:marschner-lobb:24 --size 64x64 --json >"$tmp/out" 2>&1 &&
    grep -q '"psnr_db": ' "$tmp/out" && grep -q '"max_abs": ' "$tmp/out" && grep -q '"mean_abs": ' "$tmp/out" &&
    grep -q '"over1_pct": ' "$tmp/out"; then
    ok "compare --json has psnr_db, max_abs, mean_abs, over1_pct"
else
    fail "compare --json" "$(cat "$tmp/out")"
fi
if "$sim" bench phantom:sphere:24 --size 64x64 --frames 3 --json >"$tmp/out" 2>&1 &&
    grep -q '"ms_per_frame": ' "$tmp/out" && grep -q '"frames": 3' "$tmp/out"; then
    ok "bench --json reports ms_per_frame over the frames asked"
else
    fail "bench --json" "$(cat "$tmp/out")"
fi

# bench in rounds. check_rows ROUNDS FRAMES ROWS <JSON: every row has the fields, ROUNDS round means, positive
# ratios within their min and max, point's exactly 1; prints what is wrong, if anything. Never a timing.
check_rows() {
    awk -v rounds="$1" -v frames="$2" -v want="$3" '
        function num(key,   r) {
            if (!match($0, "\"" key "\": -?[0-9.]+")) { bad = bad " no " key; return -1 }
            r = substr($0, RSTART, RLENGTH); sub(/.*: /, "", r); return r + 0
        }
        function list(key,   l, n, a, i) {
            if (!match($0, "\"" key "\": \\[[^]]*\\]")) { bad = bad " no " key; return }
            l = substr($0, RSTART, RLENGTH); sub(/.*\[/, "", l); sub(/\]/, "", l)
            n = split(l, a, ",")
            if (n != rounds) bad = bad " " key " has " n " entries"
            for (i = 1; i <= n; i++) if (!(a[i] + 0 > 0)) bad = bad " " key " entry " a[i]
        }
        /"mode": / {
            rows++
            for (k = split("mode lookup correction buffer", names, " "); k > 0; k--)
                if ($0 !~ "\"" names[k] "\": \"[a-z0-9]+\"") bad = bad " no " names[k]
            if (num("frames") != frames) bad = bad " frames"
            if (num("rounds") != rounds) bad = bad " rounds"
            if (!(num("ms_per_frame") > 0)) bad = bad " ms_per_frame"
            list("ms_per_frame_rounds")
            x = num("x_point"); lo = num("x_point_min"); hi = num("x_point_max")
            if (!(lo > 0 && lo <= x && x <= hi)) bad = bad " ratio " lo " " x " " hi
            if ($0 ~ /"mode": "point"/) { points++; if (x != 1 || lo != 1 || hi != 1) bad = bad " point " x }
            if ($0 ~ /"mode": "preint2"/) { p2++; if ($0 !~ /"table2_size": (32|64|128),/) bad = bad " table2_size" }
        }
        END { if (p2 != 7) bad = bad " " p2 " preint2 rows"
              if (rows != want || points != 1) bad = bad " " rows " rows, " points " of point"; if (bad) print bad }'
}
if [ -f "$VOLFIX_DATA/bucky.nhdr" ]; then small=$VOLFIX_DATA/bucky.nhdr; else small=phantom:sphere:32; fi
if "$sim" bench "$small" --matrix --size 64x64 --frames 2 --rounds 2 --json >"$tmp/out" 2>"$tmp/err"; then
    why=$(check_rows 2 2 17 <"$tmp/out")
    if [ -z "$why" ] && [ "$(head -n 1 "$tmp/out")" = "[" ] && [ "$(tail -n 1 "$tmp/out")" = "]" ] &&
        [ "$(grep -c '^volfix-sim bench: round [12] of 2 done' "$tmp/err")" -eq 2 ] && ! grep -q 'volfix-sim' "$tmp/out"; then
        ok "bench --matrix --rounds 2 --json: 17 rows (preint2 7 of them) with two round means, ratios to point per round, progress on stderr"
    else
        fail "bench --matrix --rounds 2 --json" "${why:-$(head -c 300 "$tmp/out") | $(cat "$tmp/err")}"
    fi
else
    fail "bench --matrix --rounds 2 --json" "$(cat "$tmp/err")"
fi
if "$sim" bench phantom:sphere:8 --matrix --size 16x16 --frames 1 --json >"$tmp/out" 2>/dev/null &&
    why=$(check_rows 3 1 17 <"$tmp/out") && [ -z "$why" ]; then
    ok "bench --matrix measures 3 rounds unless told"
else
    fail "bench --matrix default rounds" "${why:-$(head -c 300 "$tmp/out")}"
fi
if "$sim" bench phantom:sphere:16 --size 32x32 --frames 2 --rounds 3 --json >"$tmp/out" 2>"$tmp/err" &&
    grep -q '"rounds": 3' "$tmp/out" && grep -q '"ms_per_frame_rounds": \[[0-9.]*, [0-9.]*, [0-9.]*\]' "$tmp/out" &&
    [ "$(grep -c '^volfix-sim bench: round' "$tmp/err")" -eq 3 ] &&
    "$sim" bench phantom:sphere:16 --size 32x32 --frames 2 --json 2>&1 | grep -q '"rounds": 1, '; then
    ok "bench --rounds 3 without --matrix: three round means; one round unless told"
else
    fail "bench --rounds without --matrix" "$(cat "$tmp/out" "$tmp/err")"
fi
