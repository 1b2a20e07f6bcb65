#!/usr/bin/env bash
# `daylit df` with the reflected components on the room sample (4 x 5 x 3 m, 80 sensors): the CSV
# has sc, erc, irc, df and the error estimate, df = sc + erc + irc row by row, the sky component
# is that of --components sc to the last digit, the summary reports the mesh, the solver, the
# error estimate, the energy balance and the materials; bad reflectances and mirrors fail cleanly
# with no output.
set -u
daylit=$(realpath "$1")
samples=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

room=(--scene "$samples/room/scene.rad" --apertures "$samples/room/apertures.rad" --grid "$samples/room/grid.pts")
# A coarse mesh and no refinement: this checks the plumbing, tests/simulation/test_reflections.cpp the numbers.
fast=(--components all --element-size 3 --max-refinements 0 --threads 2)
"$daylit" df "${room[@]}" "${fast[@]}" --out "$work/all.csv" --summary "$work/all.json" --quiet || fail "df on the room"
"$daylit" df "${room[@]}" --components sc --out "$work/sc.csv" --quiet || fail "df --components sc on the room"
head -1 "$work/all.csv" | grep -qx 'grid,index,x,y,z,dx,dy,dz,sc_percent,erc_percent,irc_percent,df_percent,reflection_error_estimate_percent' ||
  fail "CSV header: $(head -1 "$work/all.csv")"
head -1 "$work/sc.csv" | grep -qx 'grid,index,x,y,z,dx,dy,dz,sc_percent,df_percent' || fail "sc CSV header: $(head -1 "$work/sc.csv")"
python3 - "$work/all.csv" "$work/sc.csv" "$work/all.json" <<'PY' || fail "room values or summary"
import csv, json, math, sys
a = list(csv.DictReader(open(sys.argv[1])))
b = list(csv.DictReader(open(sys.argv[2])))
s = json.load(open(sys.argv[3]))
assert len(a) == 80 == len(b)
for r, q in zip(a, b):
    sc, erc, irc, df, err = (float(r[k]) for k in ("sc_percent", "erc_percent", "irc_percent", "df_percent",
                                                    "reflection_error_estimate_percent"))
    assert sc == float(q["sc_percent"]), (r, q)          # the same sky component, bit for bit
    assert abs(df - (sc + erc + irc)) <= 1e-15 * df, r    # one rounding of the sum
    assert irc > 0 and erc >= 0 and err > 0 and all(map(math.isfinite, (sc, erc, irc, df, err))), r
    # Sensors face up at 0.85 m and nothing lies outside but the far ground: no ERC.
    assert erc == 0, r
c = s["components"]
assert c["computed"] == ["sc", "erc", "irc"], c["computed"]
assert c["materials"]["wall_mat"]["reflectance"] == 0.5, c["materials"]
assert c["mesh"]["elements"] > 0 and c["solver"]["sweeps"] > 1
assert abs(c["energy_balance"]["relative_mismatch"]) < 1e-3, c["energy_balance"]
assert c["error"]["max_estimate_percent"] > 0
g = s["grids"][0]
for k in ("sc_percent", "erc_percent", "irc_percent", "reflection_error_estimate_percent"):
    assert k in g["components"], g["components"].keys()
# The mean IRC of this room is about 1 DF point (issue 12; DESIGN.md §4).
assert 0.5 < g["components"]["irc_percent"]["mean"] < 1.5, g["components"]["irc_percent"]
PY

# Bad input: clear errors, non-zero exit, no output files.
expect_failure() {  # name, expected text, arguments...
  local name=$1 expected=$2
  shift 2
  rm -f "$work/bad.csv" "$work/bad.json"
  if "$daylit" df "$@" --out "$work/bad.csv" --summary "$work/bad.json" --quiet 2> "$work/stderr.txt"; then
    fail "$name: accepted"
  fi
  grep -q -- "$expected" "$work/stderr.txt" || fail "$name: stderr lacks '$expected': $(cat "$work/stderr.txt")"
  [ ! -e "$work/bad.csv" ] && [ ! -e "$work/bad.json" ] || fail "$name: output left behind"
}
sed 's/^5 0.5 0.5 0.5 0 0$/5 1.2 1.2 1.2 0 0/' "$samples/room/scene.rad" > "$work/bright.rad"
expect_failure "reflectance above 1" "outside \[0, 1\]" --components all --scene "$work/bright.rad" --apertures "$samples/room/apertures.rad" \
  --grid "$samples/room/grid.pts"
sed 's/^void plastic wall_mat$/void mirror wall_mat/; s/^5 0.5 0.5 0.5 0 0$/3 0.5 0.5 0.5/' "$samples/room/scene.rad" > "$work/mirror.rad"
expect_failure "mirror" "mirror 'wall_mat'" --components all --scene "$work/mirror.rad" --apertures "$samples/room/apertures.rad" \
  --grid "$samples/room/grid.pts"
expect_failure "ground reflectance 1" "ground-reflectance" "${room[@]}" --components all --ground-reflectance 1
expect_failure "gradient with reflections" "components sc" "${room[@]}" --components all --gradient
# With --components sc a mirror is no obstacle: its reflectance is not used.
"$daylit" df --scene "$work/mirror.rad" --apertures "$samples/room/apertures.rad" --grid "$samples/room/grid.pts" \
  --components sc --out "$work/mirror-sc.csv" --quiet || fail "mirror with --components sc"
cmp -s "$work/mirror-sc.csv" "$work/sc.csv" || fail "mirror changes the sky component"

[ "$failures" -eq 0 ] && echo "room: columns, sums, summary and bad input as expected"
exit "$failures"
