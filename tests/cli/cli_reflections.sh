#!/usr/bin/env bash
# `daylit df` with the reflected components on the room sample (4 x 5 x 3 m, 80 sensors): the CSV
# has sc, erc, irc, df and the error estimate, df = sc + erc + irc row by row, the sky component
# is that of --components sc to the last digit, the summary reports the mesh, the solver, the
# error estimate, the energy balance and the materials; bad reflectances and mirrors fail cleanly
# with no output. `daylit illuminance --components all` gives df's solution in lux, and the sun's
# first bounce matches a closed form.
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
# The window's glass reflects too (2 ∫ R μ dμ of Radiance's model for transmissivity 0.96: 0.1478).
assert abs(c["materials"]["clear_glass"]["reflectance"] - 0.1478) < 1e-4, c["materials"]
assert "diffusely" in c["materials"]["clear_glass"]["description"], c["materials"]
assert c["mesh"]["elements"] > 0 and c["solver"]["sweeps"] > 1
# The reciprocal transport (the default) conserves energy on any mesh (roundoff: 1e-15; issue 12
# asks 1e-9).
assert c["energy_balance"]["transport"]["reciprocal"] is True, c["energy_balance"]
assert abs(c["energy_balance"]["relative_mismatch"]) < 1e-9, c["energy_balance"]
assert c["energy_balance"]["transport"]["closure_residual"] < 1e-13, c["energy_balance"]["transport"]
assert c["error"]["max_estimate_percent"] > 0
# Where the time went, stage by stage: the rows, the solves and the sensors of each mesh, within
# the run's time.
stages = [x["stage"] for x in c["stages"]]
assert any("rows" in x for x in stages) and any("sensors" in x for x in stages), stages
assert all(x["wall_s"] >= 0 for x in c["stages"]) and sum(x["wall_s"] for x in c["stages"]) <= c["run_time_s"], c["stages"]
g = s["grids"][0]
for k in ("sc_percent", "erc_percent", "irc_percent", "reflection_error_estimate_percent"):
    assert k in g["components"], g["components"].keys()
# The mean IRC of this room is about 1 DF point (issue 12; DESIGN.md §4).
assert 0.5 < g["components"]["irc_percent"]["mean"] < 1.5, g["components"]["irc_percent"]
PY

# The default local rounds (--max-refinements 2): the same room from elements of size 3 refines
# where the sensors over the tolerance need it, lowers the worst estimate round by round and
# stops when it is met or the rounds are spent.
"$daylit" df "${room[@]}" --components all --element-size 3 --threads 2 --out "$work/local.csv" \
  --summary "$work/local.json" --quiet || fail "df with local rounds"
python3 - "$work/all.json" "$work/local.json" <<'PY' || fail "local rounds in the summary"
import json, sys
uniform, local = (json.load(open(p))["components"] for p in sys.argv[1:])
m, e = local["mesh"], local["error"]
by_round = m["max_error_percent_by_round"]
assert uniform["mesh"]["refinement_rounds"] == 0 and len(uniform["mesh"]["max_error_percent_by_round"]) == 1
assert 1 <= m["refinement_rounds"] <= 2 and len(by_round) == m["refinement_rounds"] + 1, m
assert by_round[0] == uniform["mesh"]["max_error_percent_by_round"][0], (by_round, uniform["mesh"])
assert by_round[-1] < by_round[0] and e["max_estimate_percent"] == by_round[-1], (by_round, e)
assert e["met"] or m["refinement_rounds"] == 2, e
assert m["elements"] > uniform["mesh"]["elements"], (m, uniform["mesh"])
assert abs(local["energy_balance"]["relative_mismatch"]) < 1e-9, local["energy_balance"]
assert any(x["stage"].startswith("round 1") for x in local["stages"]), local["stages"]
PY

# --reflection-transport collocated reports its energy mismatch, the mesh's reciprocity defect
# (not zero, and small: 4.7e-4 of the first-bounce flux at this coarse mesh), and changes the IRC
# by the order of that defect.
"$daylit" df "${room[@]}" "${fast[@]}" --reflection-transport collocated --out "$work/colloc.csv" --summary "$work/colloc.json" \
  --quiet || fail "df --reflection-transport collocated"
python3 - "$work/all.csv" "$work/colloc.csv" "$work/colloc.json" <<'PY' || fail "collocated transport"
import csv, json, sys
a = list(csv.DictReader(open(sys.argv[1])))
b = list(csv.DictReader(open(sys.argv[2])))
e = json.load(open(sys.argv[3]))["components"]["energy_balance"]
assert e["transport"]["reciprocal"] is False and 0 < abs(e["relative_mismatch"]) < 1e-3, e
for r, q in zip(a, b):
    assert r["sc_percent"] == q["sc_percent"], (r, q)
    x, y = float(r["irc_percent"]), float(q["irc_percent"])
    assert x != y and abs(x - y) < 0.05 * x, (r, q)  # element size 3: a defect of a few percent
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
expect_failure "element grading 0" "element-grading" "${room[@]}" --components all --element-grading 0

# --element-grading: far elements grow as grading x distance; a smaller grading meshes the far
# surfaces (the room's back half, the walls above the sensors) finer, and the summary says so.
"$daylit" df "${room[@]}" --components all --max-refinements 0 --threads 2 --element-size 1.5 --element-grading 2 --out "$work/grading2.csv" --summary "$work/grading2.json" --quiet ||
  fail "df --element-grading 2"
"$daylit" df "${room[@]}" --components all --max-refinements 0 --threads 2 --element-size 1.5 --element-grading 0.25 --out "$work/grading025.csv" --summary "$work/grading025.json" --quiet ||
  fail "df --element-grading 0.25"
python3 - "$work/grading2.json" "$work/grading025.json" <<'PY' || fail "element grading"
import json, sys
coarse, fine = (json.load(open(f))["components"]["mesh"] for f in sys.argv[1:])
assert coarse["grading"] == 2 and fine["grading"] == 0.25, (coarse, fine)
assert fine["elements"] > coarse["elements"], (coarse["elements"], fine["elements"])
PY
# With --components sc a mirror is no obstacle: its reflectance is not used.
"$daylit" df --scene "$work/mirror.rad" --apertures "$samples/room/apertures.rad" --grid "$samples/room/grid.pts" \
  --components sc --out "$work/mirror-sc.csv" --quiet || fail "mirror with --components sc"
cmp -s "$work/mirror-sc.csv" "$work/sc.csv" || fail "mirror changes the sky component"

# The sky component alone by default (README: the radiosity is not yet fast on large models); a
# reflection option given without --components all is named in a notice as unused.
"$daylit" df "${room[@]}" --element-size 3 --out "$work/default.csv" 2> "$work/default.txt" || fail "df on the room by default"
head -1 "$work/default.csv" | grep -qx 'grid,index,x,y,z,dx,dy,dz,sc_percent,df_percent' || fail "the default is not SC alone"
grep -q -- "--element-size is not used" "$work/default.txt" || fail "no notice that --element-size is not used"
# A wall drawn whole over the window (coplanar, not cut by seams) hides it: said so, naming both.
printf 'void plastic paper 0 0 5 0.5 0.5 0.5 0 0\npaper polygon cover 0 0 12 0 0 0 4 0 0 4 0 3 0 0 3\n' > "$work/cover.rad"
"$daylit" df "${room[@]}" --scene "$work/cover.rad" --out "$work/cover.csv" 2> "$work/cover.txt" || fail "df with a covering wall"
grep -q "aperture 'window' lies in the plane of occluder 'cover' (.*cover.rad:2) and inside it" "$work/cover.txt" ||
  fail "no notice of the wall covering the window: $(cat "$work/cover.txt")"
grep -q "lies in the plane of occluder" "$work/default.txt" && fail "a notice of a covering wall on the room, whose wall has the window cut out"
# ... and so are the room's reflectances (never silently ignored).
grep -q "the reflectances of 3 materials (plastic 'ceiling_mat' 0.7, plastic 'floor_mat' 0.2, plastic 'wall_mat' 0.5) are not used" \
  "$work/default.txt" || fail "no notice that the materials' reflectances are not used: $(cat "$work/default.txt")"

# `daylit illuminance --components all`: under the overcast sky at 10,000 lux diffuse horizontal,
# ERC and IRC in lux are df's percentages times 100 (the same solution, scaled), and the total is
# sky + sun + ERC + IRC.
"$daylit" illuminance "${room[@]}" "${fast[@]}" --sky cie-overcast --diffuse-horizontal 10000 --out "$work/lux.csv" \
  --summary "$work/lux.json" --quiet || fail "illuminance --components all on the room"
python3 - "$work/lux.csv" "$work/all.csv" "$work/lux.json" <<'PY' || fail "illuminance reflections against df"
import csv, json, sys
lux = list(csv.DictReader(open(sys.argv[1])))
df = list(csv.DictReader(open(sys.argv[2])))
assert len(lux) == len(df) == 80
for l, d in zip(lux, df):
    for a, b in (("erc_lux", "erc_percent"), ("irc_lux", "irc_percent")):
        assert abs(float(l[a]) - 100 * float(d[b])) <= 1e-12 * max(100 * float(d[b]), 1e-300) + 1e-9, (a, l[a], d[b])
    # The estimate is written to 3 significant digits.
    e, p = float(l["reflection_error_estimate_lux"]), 100 * float(d["reflection_error_estimate_percent"])
    assert abs(e - p) <= 5e-3 * p, (e, p)
    total = sum(float(l[k]) for k in ("sky_lux", "sun_lux", "erc_lux", "irc_lux"))
    assert abs(float(l["illuminance_lux"]) - total) <= 1e-12 * total, l
c = json.load(open(sys.argv[3]))["components"]
assert c["computed"] == ["sky_direct", "erc", "irc"], c["computed"]
assert c["illuminance_lux_is"] == "sky_lux + sun_lux + erc_lux + irc_lux"
PY

# The sun's first bounce, against a closed form: a 2 x 2 m plate (rho = 0.5) lit by the sun alone
# (zenith 30°, 100,000 lux direct normal, no sky), seen from above by sensors facing down. The
# plate's top is lit uniformly, M = rho E_dn cos 30°, and reflects once onto the sensors:
# E = M F, F Howell's factor from the point to the plate (four rectangles about its foot). A
# far opening at 30 m stands in for the apertures daylit asks for; it lies behind every sensor
# (void: a hole, which reflects nothing, where a glass pane would send a little sun back).
cat > "$work/plate.rad" <<'RAD'
void plastic grey
0
0
5 0.5 0.5 0.5 0 0
grey polygon plate
0
0
12 -1 -1 0  1 -1 0  1 1 0  -1 1 0
RAD
cat > "$work/skylight.rad" <<'RAD'
void polygon far_skylight
0
0
12 30 0 5  30.1 0 5  30.1 0.1 5  30 0.1 5
RAD
printf '0 0 1 0 0 -1\n0.5 0.3 0.4 0 0 -1\n' > "$work/plate.pts"
"$daylit" illuminance --components all --scene "$work/plate.rad" --apertures "$work/skylight.rad" --grid "$work/plate.pts" \
  --sky uniform --diffuse-horizontal 0 --sun-zenith 30 --sun-azimuth 0 --direct-normal 100000 --out "$work/plate.csv" \
  --quiet || fail "illuminance with the sun on the plate"
python3 - "$work/plate.csv" <<'PY' || fail "sun-lit plate against Howell's factor"
import csv, math, sys
def howell(a, b, c):  # point under the corner of an a x b rectangle at distance c (parallel)
    x, y = a / c, b / c
    return (x / math.sqrt(1 + x * x) * math.atan(y / math.sqrt(1 + x * x)) +
            y / math.sqrt(1 + y * y) * math.atan(x / math.sqrt(1 + y * y))) / (2 * math.pi)
m = 0.5 * 1e5 * math.cos(math.radians(30))
for r in csv.DictReader(open(sys.argv[1])):
    x, y, h = float(r["x"]), float(r["y"]), float(r["z"])
    f = howell(1 - x, 1 - y, h) + howell(1 + x, 1 - y, h) + howell(1 - x, 1 + y, h) + howell(1 + x, 1 + y, h)
    # A uniform exitance is what linear elements carry exactly and the transport is exact: the
    # only error is roundoff (1e-12 allows for the sums over the mesh's elements).
    assert abs(float(r["irc_lux"]) - m * f) <= 1e-12 * m * f, (r["irc_lux"], m * f)
    assert float(r["sky_lux"]) == 0 and float(r["sun_lux"]) == 0 and float(r["erc_lux"]) == 0, r
PY

# trans in a scene file is a pane of its total transmittance (1 − spec)·τ·grey, wherever it is
# filed: a veil in front of the window, larger than every view through it, scales every sensor's
# sky component by T (constant panes multiply exactly); Radiance's air boundary (trans 1 1 1 0 0 1 1)
# changes nothing. The notice states the transmittance, the diffuse part taken as clear and what
# it reflects (which the reflected components use; this run is of the sky component).
veil() {
  printf 'void trans veil\n0\n0\n7 %s\n\nveil polygon sheet\n0\n0\n12\n-50 -0.5 -50\n50 -0.5 -50\n50 -0.5 60\n-50 -0.5 60\n' "$1" > "$2"
}
veil "0.5 0.5 0.5 0.1 0 0.6 0.3" "$work/veil.rad"
veil "1 1 1 0 0 1 1" "$work/air.rad"
"$daylit" df "${room[@]}" --scene "$work/veil.rad" --out "$work/veil.csv" 2> "$work/veil.txt" || fail "df with a trans veil"
"$daylit" df "${room[@]}" --scene "$work/air.rad" --out "$work/air.csv" --quiet || fail "df with an air boundary"
grep -q "veil.rad:1: trans 'veil': a pane of transmittance 0.2700, its diffuse part (0.1890) treated as clear; it reflects 0.2800, which the reflected components send back diffusely" \
  "$work/veil.txt" || fail "no notice of the trans pane: $(cat "$work/veil.txt")"
python3 - "$work/sc.csv" "$work/veil.csv" "$work/air.csv" <<'PY' || fail "trans panes do not scale the sky component"
import csv, sys
base, veil, air = (list(csv.DictReader(open(f))) for f in sys.argv[1:])
for b, v, a in zip(base, veil, air):
    sc = float(b["sc_percent"])
    # T = (1 − 0.1)·0.6·0.5. The veil's view through the window counts T_w·T_v·E and takes back
    # the window's own count T_w·E of the same directions (PaneView), each a sum of the glass's
    # degree-12 polynomial moments, whose coefficients cancel: measured 4e-12, held to 1e-10.
    assert abs(float(v["sc_percent"]) - 0.27 * sc) <= 1e-10 * sc, (b, v)
    assert abs(float(a["sc_percent"]) - sc) <= 1e-12 * sc, (b, a)
PY

# `daylit bench trace`: the path tracer on the same room, df's columns with standard errors; every
# 10th sensor, 16,384 paths. df's default solution and the trace agree within 5 standard errors
# plus df's own error estimate at every sensor (the chance that a correct pair fails one of 8 such
# checks is below 1e-5; the two are independent codes).
awk 'NR % 10 == 1' "$samples/room/grid.pts" > "$work/tenth.pts"
"$daylit" df --scene "$samples/room/scene.rad" --apertures "$samples/room/apertures.rad" --grid "$work/tenth.pts" \
  --components all --out "$work/tenth.csv" --quiet || fail "df on every 10th sensor"
"$daylit" bench trace --scene "$samples/room/scene.rad" --apertures "$samples/room/apertures.rad" --grid "$work/tenth.pts" \
  --paths 16384 --out "$work/trace" --quiet || fail "bench trace"
python3 - "$work/tenth.csv" "$work/trace/trace.csv" <<'PY' || fail "bench trace against df --components all"
import csv, sys
d, t = (list(csv.DictReader(open(f))) for f in sys.argv[1:])
assert len(d) == len(t) == 8
for a, b in zip(d, t):
    assert [a[k] for k in ("grid", "index", "x", "y")] == [b[k] for k in ("grid", "index", "x", "y")], (a, b)
    for k in ("sc", "erc", "irc", "df"):
        allowance = 5 * float(b[k + "_se"]) + (float(a["reflection_error_estimate_percent"]) if k != "sc" else 0) + 1e-9
        assert abs(float(a[k + "_percent"]) - float(b[k + "_percent"])) <= allowance, (k, a, b)
PY

[ "$failures" -eq 0 ] && echo "room: columns, sums, summary and bad input as expected"
exit "$failures"
