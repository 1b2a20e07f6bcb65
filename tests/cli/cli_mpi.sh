#!/usr/bin/env bash
# `mpirun -n N daylit ...` (DAYLIT_MPI=ON; README "Beyond one machine: MPI"): the sensors are
# sharded over the ranks and gathered on rank 0, so every output file is byte for byte the single
# process's, whatever N (2, and 3 for blocks of unequal size): df's sky component with gradients
# and over two grids, df --components all on the room (reflections on rank 0), df --refine, more
# ranks than sensors, illuminance with the sun (and with --components all), annual (sky + sun with
# blinds that close, and with --components all) with its .npy. The summary counts the ranks, their sensors
# add up to each grid's and the counters summed over them are the single process's. A failure
# on one rank only (its own bad grid, by MPMD) fails every rank with that rank's message and no
# output; bad input read alike by every rank is reported once.
set -u
daylit=$(realpath "$1")
samples=$(realpath "$2")
data=$(realpath "$3")
mpiexec=${4:-mpiexec}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# OpenMPI refuses root without --allow-run-as-root; CI runs as root on 2 cores, and -n 3 needs
# --oversubscribe there.
launch=("$mpiexec" --oversubscribe)
[ "$(id -u)" -eq 0 ] && launch+=(--allow-run-as-root)
mpi() {  # N daylit-arguments...
  local n=$1
  shift
  "${launch[@]}" -n "$n" "$daylit" "$@"
}
same() {  # what a b: byte for byte
  cmp -s "$2" "$3" || fail "$1: $(basename "$3") differs from the single process's ($(cmp "$2" "$3" 2>&1 | head -1))"
}

office=(--scene "$samples/office/scene.rad" --apertures "$samples/office/apertures.rad" --grid "$samples/office/grid.pts"
        --threads 1)
room=(--scene "$samples/room/scene.rad" --apertures "$samples/room/apertures.rad" --grid "$samples/room/grid.pts"
      --threads 1 --quiet)

# ---- df, sky component: the office (2,400 sensors), one process against 1, 2 and 3 ranks.
"$daylit" df "${office[@]}" --quiet --out "$work/df.csv" --summary "$work/df.json" || fail "df, one process"
for n in 1 2 3; do
  mpi "$n" df "${office[@]}" --quiet --out "$work/df-$n.csv" --summary "$work/df-$n.json" || fail "df, $n ranks"
  same "df, $n ranks" "$work/df.csv" "$work/df-$n.csv"
done
python3 - "$work/df.json" "$work/df-1.json" "$work/df-2.json" "$work/df-3.json" <<'PY' || fail "df summaries"
import json, sys
one, n1, n2, n3 = (json.load(open(p)) for p in sys.argv[1:])
assert "mpi" not in one and "mpi" not in n1, "one rank: the summary is the single process's"
for s, n in ((n2, 2), (n3, 3)):
    m = s["mpi"]
    assert m["ranks"] == n and len(m["per_rank"]) == n, m
    g = s["grids"][0]
    assert sum(r["sensors"] for r in m["per_rank"]) == g["count"] == 2400, m["per_rank"]
    assert m["grids"][0]["sensors_per_rank"] == [2400 // n] * n, m["grids"][0]
    assert all(t >= 0 for t in m["grids"][0]["compute_time_s_per_rank"]) and len(m["grids"][0]["compute_time_s_per_rank"]) == n
    assert all(r["threads"] == 1 and r["host"] for r in m["per_rank"]), m["per_rank"]
    assert abs(m["compute_time_s_sum"] - sum(r["compute_time_s"] for r in m["per_rank"])) < 1e-9
    # Counters summed over the ranks are the single process's; so are the statistics.
    assert g["left_out"] == one["grids"][0]["left_out"], (g["left_out"], one["grids"][0]["left_out"])
    assert g["df_percent"] == one["grids"][0]["df_percent"] and g["uniformity"] == one["grids"][0]["uniformity"]
PY

# Only rank 0 speaks: the glass notice and the grid's line once, not once per rank.
mpi 2 df "${office[@]}" --out "$work/talk.csv" 2> "$work/talk.err" || fail "df, 2 ranks, not quiet"
[ "$(grep -c '^notice: glass' "$work/talk.err")" -eq 1 ] || fail "notices not once: $(cat "$work/talk.err")"
[ "$(grep -c '^grid: 2400 sensors' "$work/talk.err")" -eq 1 ] || fail "grid line not once: $(cat "$work/talk.err")"

# ---- df with gradients, over two grids (the room's 80 sensors and the office's): blocks of 27,
# 27 and 26 with 3 ranks, grids gathered in their order.
two=(--scene "$samples/room/scene.rad" --apertures "$samples/room/apertures.rad" --grid "$samples/room/grid.pts"
     --grid "$samples/office/grid.pts" --threads 1 --quiet --gradient)
"$daylit" df "${two[@]}" --out "$work/grad.csv" || fail "df --gradient, one process"
for n in 2 3; do
  mpi "$n" df "${two[@]}" --out "$work/grad-$n.csv" --summary "$work/grad-$n.json" || fail "df --gradient, $n ranks"
  same "df --gradient over two grids, $n ranks" "$work/grad.csv" "$work/grad-$n.csv"
done
python3 - "$work/grad-3.json" <<'PY' || fail "two grids' summary"
import json, sys
m = json.load(open(sys.argv[1]))["mpi"]
assert [g["sensors_per_rank"] for g in m["grids"]] == [[27, 27, 26], [800, 800, 800]], m["grids"]
assert [r["sensors"] for r in m["per_rank"]] == [827, 827, 826], m["per_rank"]
PY

# ---- df --components all on the room: the sky component sharded, the reflections on rank 0.
"$daylit" df "${room[@]}" --components all --out "$work/all.csv" --summary "$work/all.json" || fail "df all, one process"
mpi 2 df "${room[@]}" --components all --out "$work/all-2.csv" --summary "$work/all-2.json" || fail "df all, 2 ranks"
same "df --components all, 2 ranks" "$work/all.csv" "$work/all-2.csv"
python3 - "$work/all.json" "$work/all-2.json" <<'PY' || fail "df all summary"
import json, sys
one, two = (json.load(open(p)) for p in sys.argv[1:])
assert two["mpi"]["ranks"] == 2 and "reflected components" in two["mpi"]["not_sharded"]
assert two["grids"][0]["components"] == one["grids"][0]["components"]
# Wall times differ between any two runs; the stages' names and order must not.
for s in (one, two):
    del s["components"]["run_time_s"]
    s["components"]["stages"] = [stage["stage"] for stage in s["components"]["stages"]]
assert two["components"] == one["components"]  # mesh, solver, energy balance, error: rank 0's, as one process's
PY

# ---- df --refine (the added sensors on rank 0), and more ranks than sensors (a rank with none).
"$daylit" df "${room[@]}" --refine --out "$work/refine.csv" || fail "df --refine, one process"
mpi 2 df "${room[@]}" --refine --out "$work/refine-2.csv" || fail "df --refine, 2 ranks"
same "df --refine, 2 ranks" "$work/refine.csv" "$work/refine-2.csv"
head -2 "$samples/room/grid.pts" > "$work/two.pts"
few=(--scene "$samples/room/scene.rad" --apertures "$samples/room/apertures.rad" --grid "$work/two.pts" --threads 1 --quiet)
"$daylit" df "${few[@]}" --out "$work/few.csv" || fail "df on 2 sensors, one process"
mpi 3 df "${few[@]}" --out "$work/few-3.csv" --summary "$work/few-3.json" || fail "df on 2 sensors, 3 ranks"
same "df on 2 sensors, 3 ranks" "$work/few.csv" "$work/few-3.csv"
python3 -c 'import json, sys; assert json.load(open(sys.argv[1]))["mpi"]["grids"][0]["sensors_per_rank"] == [1, 1, 0]' \
  "$work/few-3.json" || fail "2 sensors over 3 ranks: not blocks of 1, 1, 0"

# ---- a grid that sees the sky directly (sensors above and beside the office, facing up and out):
# each rank's block keeps the grid's direct view (SensorGrid::sees_sky_directly), with gradients.
{ head -n 5 "$samples/office/grid.pts"; echo "5 5 40 0 0 1"; echo "2 3 45 0.6 0 0.8"; echo "-30 5 1 -1 0 0"; } > "$work/outdoors.pts"
out=(--scene "$samples/office/scene.rad" --apertures "$samples/office/apertures.rad" --grid "$work/outdoors.pts"
     --threads 1 --quiet --gradient)
"$daylit" df "${out[@]}" --out "$work/outdoors.csv" || fail "df outdoors, one process"
mpi 3 df "${out[@]}" --out "$work/outdoors-3.csv" || fail "df outdoors, 3 ranks"
same "df on a grid that sees the sky directly, 3 ranks" "$work/outdoors.csv" "$work/outdoors-3.csv"
python3 -c 'import csv, sys; r = list(csv.DictReader(open(sys.argv[1]))); assert float(r[5]["sc_percent"]) > 99.9, r[5]' \
  "$work/outdoors-3.csv" || fail "outdoors: the sensor above the roof lacks the sky"

# ---- illuminance: a CIE clear sky (cubature per region) and the sun on the office.
lux=("${office[@]}" --quiet --sky cie-12 --sun-zenith 40 --sun-azimuth 200 --direct-normal 70000 --diffuse-horizontal 15000)
"$daylit" illuminance "${lux[@]}" --out "$work/lux.csv" --summary "$work/lux.json" || fail "illuminance, one process"
mpi 2 illuminance "${lux[@]}" --out "$work/lux-2.csv" --summary "$work/lux-2.json" || fail "illuminance, 2 ranks"
same "illuminance with the sun, 2 ranks" "$work/lux.csv" "$work/lux-2.csv"
python3 - "$work/lux.json" "$work/lux-2.json" <<'PY' || fail "illuminance summary"
import json, sys
one, two = (json.load(open(p)) for p in sys.argv[1:])
assert two["mpi"]["ranks"] == 2 and sum(r["sensors"] for r in two["mpi"]["per_rank"]) == 2400
g1, g2 = one["grids"][0], two["grids"][0]
assert g2["left_out"] == g1["left_out"] and g2["illuminance_lux"] == g1["illuminance_lux"]
assert g2["share_in_direct_sun"] == g1["share_in_direct_sun"] > 0
assert two["sky"]["quadrature_evaluations"] == one["sky"]["quadrature_evaluations"] > 0
assert two["sky"]["sky_error_bound_lux_max"] == one["sky"]["sky_error_bound_lux_max"]
PY

# illuminance --components all: the room lit by the sky and the sun, reflections on rank 0
# (coarse elements, to keep it short).
sunlit=("${room[@]}" --components all --element-size 1.8 --sky cie-12 --sun-zenith 40 --sun-azimuth 200
        --direct-normal 70000 --diffuse-horizontal 15000)
"$daylit" illuminance "${sunlit[@]}" --out "$work/lux-all.csv" || fail "illuminance --components all, one process"
mpi 2 illuminance "${sunlit[@]}" --out "$work/lux-all-2.csv" || fail "illuminance --components all, 2 ranks"
same "illuminance --components all, 2 ranks" "$work/lux-all.csv" "$work/lux-all-2.csv"

# ---- annual: sharded too (README). The room (80 sensors) over three January days: sky + sun,
# whose LM-83 blinds close in some hours (the rule counts the whole grid's lit sensors, summed over
# the ranks: a block's own count would close them in other hours), and with --components all
# (coarse elements, to keep it short). CSV, .npy and the summary's results are the single
# process's at 1, 2 and 3 ranks (3: blocks of 27, 27 and 26 sensors).
year=("${room[@]}" --weather "$data/chicago-ohare-tmy3-jan1-3.epw")
for case in sky all; do
  args=("${year[@]}")
  [ "$case" = all ] && args+=(--components all --element-size 1.8)
  "$daylit" annual "${args[@]}" --out "$work/year-$case.csv" --hourly "$work/year-$case.npy" \
    --summary "$work/year-$case.json" || fail "annual $case, one process"
  for n in 1 2 3; do
    mpi "$n" annual "${args[@]}" --out "$work/year-$case-$n.csv" --hourly "$work/year-$case-$n.npy" \
      --summary "$work/year-$case-$n.json" || fail "annual $case, $n ranks"
    same "annual $case, $n ranks" "$work/year-$case.csv" "$work/year-$case-$n.csv"
    same "annual $case --hourly, $n ranks" "$work/year-$case.npy" "$work/year-$case-$n.npy"
  done
  python3 - "$case" "$work/year-$case.json" "$work/year-$case-1.json" "$work/year-$case-2.json" \
    "$work/year-$case-3.json" <<'PY' || fail "annual $case summaries"
import json, sys
case = sys.argv[1]
one, n1, n2, n3 = (json.load(open(p)) for p in sys.argv[2:])
def results(s):  # the summary less its run times and the mpi object
    if isinstance(s, dict):
        return {k: results(v) for k, v in s.items() if k != "mpi" and not k.startswith("run_time")}
    if isinstance(s, list):
        return [results(v) for v in s]
    return s
assert "mpi" not in one and "mpi" not in n1, "one rank: the summary is the single process's"
g = one["grids"][0]
assert g["count"] == 80 and sum(b["hours_closed"] for b in g["blinds"]) > 0, ("the blinds never close", g["blinds"])
assert isinstance(g["reflected"], dict) == (case == "all"), g["reflected"]
for s, n in ((n1, 1), (n2, 2), (n3, 3)):
    assert results(s) == results(one), [k for k in results(one) if results(one)[k] != results(s).get(k)]
    if n == 1:
        continue
    m = s["mpi"]
    assert m["ranks"] == n and len(m["per_rank"]) == n, m
    assert m["grids"][0]["sensors_per_rank"] == [80 // n + (r < 80 % n) for r in range(n)], m["grids"][0]
    assert "AnnualSky" in m["not_sharded"] and "blinds" in m["sharded"], m
PY
done

# ---- Failures. Rank 1 alone reads a bad grid (MPMD: each rank its own command line), after rank
# 0 has started computing: every rank exits 1, rank 0 prints rank 1's message, and no file is written.
printf '0 0 0.8 0 0 1\n1 2 x 0 0 1\n' > "$work/bad.pts"
bad1=(--scene "$samples/room/scene.rad" --apertures "$samples/room/apertures.rad" --threads 1 --quiet
      --out "$work/fail.csv" --summary "$work/fail.json")
"${launch[@]}" -n 1 "$daylit" df "${bad1[@]}" --grid "$samples/room/grid.pts" : -n 1 "$daylit" df "${bad1[@]}" --grid "$work/bad.pts" \
  > "$work/fail.out" 2> "$work/fail.err"
status=$?
[ "$status" -ne 0 ] || fail "a failing rank 1: exit status 0"
grep -q "^error: .*bad.pts:2: .*\[MPI rank 1 of 2\]" "$work/fail.err" || fail "rank 1's message: $(cat "$work/fail.err")"
[ ! -e "$work/fail.csv" ] && [ ! -e "$work/fail.json" ] || fail "a failed run left output"
# Every rank reads the same bad grid: one message, as one process gives it, and exit 1.
mpi 2 df "${bad1[@]}" --grid "$work/bad.pts" 2> "$work/fail2.err"
status=$?
[ "$status" -eq 1 ] || fail "bad input on every rank: exit $status, not 1"
[ "$(grep -c '^error: ' "$work/fail2.err")" -eq 1 ] || fail "bad input on every rank: not one message: $(cat "$work/fail2.err")"
grep -q "^error: .*bad.pts:2: expected a number" "$work/fail2.err" || fail "bad input message: $(cat "$work/fail2.err")"
# Rank 0 cannot write after the last exchange: every rank exits non-zero, no partial output.
mpi 2 df "${room[@]}" --out "$work/fail.csv" --summary "$work/no/such/dir/s.json" 2> "$work/fail3.err"
[ $? -ne 0 ] || fail "rank 0's write failure: exit status 0"
grep -q "^error: .*no/such/dir" "$work/fail3.err" || fail "write failure message: $(cat "$work/fail3.err")"
[ ! -e "$work/fail.csv" ] || fail "a failed write left the CSV"

# ---- The scaling report's MPI table (`daylit bench scenes`, issue 13 part 4): df alone and under
# mpirun -n 1 and -n 2, one thread each, the CSVs byte for byte the same.
"$daylit" bench scenes --quick --quiet --samples "$samples" --out "$work/bench" > /dev/null || fail "bench scenes --quick"
python3 - "$work/bench/scenes_mpi.csv" <<'PY' || fail "scenes_mpi.csv: $(cat "$work/bench/scenes_mpi.csv")"
import csv, sys
lines = open(sys.argv[1]).read().splitlines()
assert lines[0].startswith("# the office with the most boxes of the scaling"), lines[0]
rows = list(csv.DictReader(lines[1:]))
assert [r["ranks"] for r in rows] == ["none", "1", "2"], rows
assert all(r["identical_to_one_process"] == "yes" and float(r["wall_s"]) > 0 for r in rows), rows
PY

if [ "$failures" -gt 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "mpi: all checks passed"
