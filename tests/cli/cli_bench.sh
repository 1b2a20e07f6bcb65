#!/usr/bin/env bash
# `daylit bench kernels --quick`: writes its tables and plots, with a row for every case and
# method; the exact kernels are exact to roundoff and the Monte Carlo error falls as N grows.
# Then `bench scenes --quick`, `bench stiff --quick`, `bench skies --quick`, `bench rational --quick`
# `bench annual --quick`, `bench reflections --quick`, `bench pairs --quick` and `bench gradient --quick` (below).
set -u
daylit=$1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$daylit" bench kernels --quick --quiet --out "$out" || fail "exit status $?"
for f in kernels_error_vs_time.csv kernels_error_vs_time.png kernels_cost_per_edge.csv kernels_cost_per_edge.png; do
  [ -s "$out/$f" ] || fail "$f missing or empty"
done
csv=$out/kernels_error_vs_time.csv
expected='case,method,parameter,time_per_eval_s,relative_error,relative_error_bound,relative_standard_error,seeds,precision,terms,value,reference,reference_relative_error,reference_method,edges,description'
[ "$(head -n 1 "$csv")" = "$expected" ] || fail "header of $csv: $(head -n 1 "$csv")"
[ "$(head -c 8 "$out/kernels_error_vs_time.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "not a PNG"

# The first five fields hold no quotes or commas (the description comes last).
report=$(awk -F, 'NR > 1 {
    cases[$1] = 1; rows[$1 "," $2]++
    if ($2 == "exact" && !($5 < 1e-12)) print "exact error " $5 " in case " $1
    if ($2 == "exact" || $2 == "truncated") if (!($4 > 0)) print "no time for " $1 " " $2 " " $3
    if ($2 ~ /^mc_/) { err[$1 "," $2 "," $3] = $5; n[$2 "," $3] = 1 }
  }
  END {
    ncases = 0
    for (c in cases) {
      ncases++
      split("exact truncated mc_uniform mc_lobe", methods, " ")
      for (m in methods) if (!rows[c "," methods[m]]) print "no " methods[m] " rows for case " c
      best = 0
      for (m in methods) if (methods[m] ~ /^mc_/) {
        e16 = err[c "," methods[m] ",16"]; e64k = err[c "," methods[m] ",65536"]
        if (e16 == "" || e64k == "") { print "no N = 16 or 65536 row for " c " " methods[m]; continue }
        if (!(e64k < e16)) print "MC error does not fall with N: " c " " methods[m] " " e16 " -> " e64k
        if (e64k < e16 / 10) best = 1
        sum16[methods[m]] += e16 * e16; sum64k[methods[m]] += e64k * e64k
      }
      if (!best) print "neither MC method improves tenfold from N = 16 to 65536 in case " c
    }
    if (ncases < 4) print "only " ncases " cases"
    for (m in sum16) if (!(sum64k[m] < sum16[m] / 400)) print "RMS " m " error over the cases falls less than 20x: " sqrt(sum16[m]) " -> " sqrt(sum64k[m])
  }' "$csv")
[ -z "$report" ] || fail "$report"

edges=$out/kernels_cost_per_edge.csv
[ "$(head -n 1 "$edges")" = "function,edges,order,time_per_eval_s,ns_per_edge,ns_per_edge_per_order,precision" ] ||
  fail "header of $edges"
[ "$(tail -n +2 "$edges" | wc -l)" -ge 9 ] || fail "fewer than 9 cost-per-edge rows"

# `daylit bench scenes --quick`: every method on both samples; exact is the reference (zero error by
# construction), float and Monte Carlo errors are finite, Monte Carlo's falls as N grows (the
# normalised RMS error: the relative error of sensors that see a sliver of sky stays near 1 until
# N is far larger), the cubature reaches its tolerance; scaling rows and exponents for every
# dimension and mode.
start=$SECONDS
"$daylit" bench scenes --quick --quiet --samples "$(dirname "$0")/../../samples" --out "$out" || fail "bench scenes: exit status $?"
echo "bench scenes --quick: $((SECONDS - start)) s"
for f in scenes_error_vs_time.csv scenes_error_vs_time.png scenes_scaling.csv scenes_scaling.png scenes_scaling_fit.csv scenes_pairs.csv; do
  [ -s "$out/$f" ] || fail "$f missing or empty"
done
[ "$(head -c 8 "$out/scenes_error_vs_time.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "scenes plot not a PNG"
csv=$out/scenes_error_vs_time.csv
expected='sample,method,parameter,sensors,cpu_time_per_sensor_s,rms_relative_error,max_relative_error,normalised_rms_error,max_abs_error_percent,sensors_with_sky,zero_sky_sensors_nonzero,failures,work_per_sensor,wall_time_per_sensor_s,threads'
[ "$(head -n 1 "$csv")" = "$expected" ] || fail "header of $csv: $(head -n 1 "$csv")"
finite='^[0-9.]+(e[-+][0-9]+)?$'
report=$(awk -F, -v finite="$finite" 'NR > 1 {
    rows[$1 "," $2]++
    if (!($5 > 0)) print "no time for " $1 " " $2 " " $3
    if ($2 == "exact" && ($6 != 0 || $7 != 0 || $9 != 0)) print "exact is not its own reference in " $1 ": " $6
    if ($2 != "exact" && ($6 !~ finite || $8 !~ finite)) print "non-finite error for " $1 " " $2 " " $3 ": " $6 " " $8
    if ($2 == "float" && !($6 < 1e-6)) print "float geometry off by " $6 " in " $1
    if ($2 == "monte_carlo") { mc[$1 "," $3] = $8; if ($3 + 0 > nmax) nmax = $3 + 0 }
    if ($2 == "cubature") { if (!(($1) in tightest) || $3 + 0 < tightest[$1]) { tightest[$1] = $3 + 0; cub[$1] = $6 } }
    if (!($10 > 0)) print "no sensor sees sky in " $1 " " $2
  }
  END {
    split("office hall", samples, " ")
    for (i in samples) {
      s = samples[i]
      split("exact float monte_carlo cubature", methods, " ")
      for (m in methods) if (!rows[s "," methods[m]]) print "no " methods[m] " rows for " s
      if (!(mc[s ",16"] != "" && mc[s "," nmax] < mc[s ",16"] / 5)) print "Monte Carlo error does not fall with N in " s ": " mc[s ",16"] " -> " mc[s "," nmax]
      if (!(cub[s] < 100 * tightest[s])) print "cubature misses its tolerance " tightest[s] " in " s ": " cub[s]
    }
  }' "$csv")
[ -z "$report" ] || fail "$report"
scaling=$out/scenes_scaling.csv
[ "$(head -n 1 "$scaling" | cut -d, -f1-8)" = "dimension,parameter,fit_x,mode,sensors,threads,cpu_s,wall_s" ] || fail "header of $scaling"
[ "$(awk -F, 'NR > 1 && $7 > 0 { seen[$1 "," $4] = 1 } END { n = 0; for (k in seen) n++; print n }' "$scaling")" = 8 ] ||
  fail "scaling: not every dimension and mode has timed rows"
[ "$(awk -F, -v finite='^-?[0-9.]+$' 'NR > 1 && $3 ~ finite' "$out/scenes_scaling_fit.csv" | wc -l)" -eq 8 ] ||
  fail "scaling: not 8 fitted exponents"
[ "$(awk -F, 'NR > 1 && $4 > 0' "$out/scenes_pairs.csv" | wc -l)" -ge 2 ] || fail "pairs: fewer than 2 grids counted"
# The generated office floor: other rooms' windows are hidden by walls, decided without clipping
# (column 14, pairs_covered), and its largest floor is written for other builds to run.
for f in scenes_floor.csv scenes_floor_scene.rad scenes_floor_apertures.rad scenes_floor_grid.pts scenes_occluders_one_core.csv scenes_threads.csv scenes_direct.csv scenes_mpi.csv; do
  [ -s "$out/$f" ] || fail "$f missing or empty"
done
# The MPI table says why it is empty in a build without MPI (tests/cli/cli_mpi.sh checks its rows
# in one with it), and leaves none of its runs' files behind.
if ! grep -q "^# not measured: this daylit is built without DAYLIT_MPI" "$out/scenes_mpi.csv"; then
  grep -q "^none," "$out/scenes_mpi.csv" || fail "scenes_mpi.csv: neither a reason nor rows: $(cat "$out/scenes_mpi.csv")"
fi
ls "$out"/scenes_mpi_ranks_* > /dev/null 2>&1 && fail "the MPI runs' CSVs were left behind"
# The sky seen directly: the samples' enclosed grids see none of it; lifted above the roof, all.
awk -F, 'NR > 1 && ($1 == "office" || $1 == "hall") && $3 != 0 { bad = 1 } NR > 1 && $1 == "office + 40 m" && $3 != $2 { bad = 1 }
         END { exit bad }' "$out/scenes_direct.csv" || fail "scenes_direct.csv: $(cat "$out/scenes_direct.csv")"
[ "$(awk -F, 'NR > 1 && $14 > 0' "$out/scenes_floor.csv" | wc -l)" -ge 2 ] || fail "floor: no pair found hidden by walls"
"$daylit" df --components sc --scene "$out/scenes_floor_scene.rad" --apertures "$out/scenes_floor_apertures.rad" --grid "$out/scenes_floor_grid.pts" \
  --quiet --out "$out/floor_df.csv" --summary "$out/floor_df.json" || fail "df on the written floor: exit status $?"
# …with its occluders: the file's polygon count (its first line says it) all read as occluders.
python3 - "$out/scenes_floor_scene.rad" "$out/floor_df.json" <<'PY' || fail "df did not read the written floor's occluders"
import json, re, sys
written = int(re.search(r"\((\d+) polygons\)", open(sys.argv[1]).readline()).group(1))
assert json.load(open(sys.argv[2]))["scene"]["occluders"] == written > 0
PY
# Front to back gives the same regions as another partition: the sums within the kernels' bound,
# twice the glazed moments' 1e-9 (the office's window is glass: illumination/moments.cpp; the
# regions themselves are compared exactly in tests/geometry/test_visibility_random.cpp).
[ "$(awk -F, 'NR > 1 && $3 == "front_to_back" && !($10 < 2e-9)' "$out/scenes_occluders_one_core.csv" | wc -l)" -eq 0 ] ||
  fail "front to back differs from the default by 2e-9 or more"

# `daylit bench stiff --quick`: one row per case, and the exact path within each case's tolerance
# of its independent reference (float is reported, not checked: it is allowed to fail).
start=$SECONDS
"$daylit" bench stiff --quick --quiet --out "$out" || fail "bench stiff: exit status $?"
echo "bench stiff --quick: $((SECONDS - start)) s"
stiff=$out/stiff.csv
[ "$(head -n 1 "$stiff" | cut -d, -f1-6)" = "case,reference,exact,float,exact_rel_error,float_rel_error" ] || fail "header of $stiff"
[ "$(tail -n +2 "$stiff" | wc -l)" -ge 20 ] || fail "fewer than 20 stiff cases"
report=$(awk -F, 'NR > 1 && !($5 <= $8) { print "exact off by " $5 " (tolerance " $8 ") in " $1 }' "$stiff")
[ -z "$report" ] || fail "$report"

# `daylit bench skies --quick`: both paths on two skies, with finite errors; the cubature at its
# tighter tolerance (1e-8) within 1e-6 of the 1e-13 reference.
start=$SECONDS
"$daylit" bench skies --quick --quiet --samples "$(dirname "$0")/../../samples" --out "$out" || fail "bench skies: exit status $?"
echo "bench skies --quick: $((SECONDS - start)) s"
skies=$out/skies_error_vs_time.csv
[ -s "$out/skies_error_vs_time.png" ] || fail "no skies plot"
[ "$(awk -F, 'NR > 1 && $3 == "fit" && $6 ~ /^[0-9.e+-]+$/' "$skies" | wc -l)" -eq 2 ] || fail "skies: not 2 fit rows"
report=$(awk -F, 'NR > 1 && $3 == "cubature" && $4 == 1e-08 && !($6 <= 1e-6) { print "cubature off by " $6 " on type " $1 }' "$skies")
[ -z "$report" ] || fail "$report"
[ "$(tail -n +2 "$out/skies_e_out.csv" | wc -l)" -eq 2 ] || fail "skies: E_out rows"

# `daylit bench rational --quick`: the special functions and both rational-moment paths. GSL's Cl2
# and eq. 36 are exact to roundoff; Grosjean within 3e-6; the exact path within 1e-12 of the
# 512-node reference, the semi-analytic one at 32 nodes as well; every degree row has an estimate.
start=$SECONDS
"$daylit" bench rational --quick --quiet --out "$out" || fail "bench rational: exit status $?"
echo "bench rational --quick: $((SECONDS - start)) s"
for f in rational_special_functions.csv rational_special_functions.png rational_moments_error_vs_time.csv \
         rational_moments_error_vs_time.png rational_cost_per_edge.png rational_luminaire_degree.csv; do
  [ -s "$out/$f" ] || fail "$f missing or empty"
done
special=$out/rational_special_functions.csv
[ "$(head -n 1 "$special")" = "function,method,parameter,time_per_eval_s,max_error,rms_error,error_kind" ] || fail "header of $special"
report=$(awk -F, 'NR > 1 {
    if (!($4 > 0)) print "no time for " $1 " " $2
    if ($1 == "cl2" && ($2 == "gsl" || $2 == "series") && !($5 < 2e-15)) print $2 " Cl2 off by " $5
    if ($1 == "cl2" && $2 == "grosjean" && !($5 < 3e-6)) print "Grosjean off by " $5
    if ($1 == "lambda" && $2 == "eq36_series" && !($6 < 1e-13)) print "Lambda by eq. 36 off by " $6 " (RMS)"
  }' "$special")
[ -z "$report" ] || fail "$report"
moments=$out/rational_moments_error_vs_time.csv
[ "$(head -n 1 "$moments")" = "n,edges,method,parameter,time_per_eval_s,ns_per_edge,relative_error,relative_error_estimate,precision" ] ||
  fail "header of $moments"
report=$(awk -F, 'NR > 1 {
    if (!($5 > 0)) print "no time for n = " $1 " " $3 " " $4
    if ($3 == "exact" && !($7 < 1e-12)) print "exact path off by " $7 " at n = " $1
    if ($3 == "semi_analytic" && $4 == 32 && !($7 < 1e-12)) print "semi-analytic (32 nodes) off by " $7 " at n = " $1
    rows[$3]++
  }
  END { if (rows["exact"] < 6 || rows["semi_analytic"] < 12 || rows["cubature"] < 1) print "missing rows" }' "$moments")
[ -z "$report" ] || fail "$report"
[ "$(awk -F, 'NR > 1 && $4 ~ /^[0-9.e+-]+$/ && $4 < 1e-10' "$out/rational_luminaire_degree.csv" | wc -l)" -ge 12 ] ||
  fail "rational_luminaire_degree.csv: fewer than 12 rows within 1e-10"

# `daylit bench annual --quick`: a row for every case and method; the exact path's error falls with
# the basis degree, exact patches' with MF, the sampled coefficients' with N; exact patches beat
# sampled ones at MF 1.
start=$SECONDS
root="$(dirname "$0")/../.."
"$daylit" bench annual --quick --quiet --samples "$root/samples" --weather "$root/tests/data/chicago-ohare-tmy3-jan1-3.epw" \
  --out "$out" || fail "bench annual: exit status $?"
echo "bench annual --quick: $((SECONDS - start)) s"
for f in annual_error_vs_time.csv annual_error_vs_time.png; do [ -s "$out/$f" ] || fail "$f missing or empty"; done
csv=$out/annual_error_vs_time.csv
expected='case,method,parameter,sensors,sky_hours,cpu_s_per_sensor,sky_cpu_s,rms_normalised_error,p95_relative_error,flipped_300lx_share,da300_difference_points'
[ "$(head -n 1 "$csv")" = "$expected" ] || fail "header of $csv: $(head -n 1 "$csv")"
python3 - "$csv" <<'PY' || fail "bench annual rows"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
for case in ("office", "hall"):
    r = {(x["method"], x["parameter"]): float(x["rms_normalised_error"]) for x in rows if x["case"] == case}
    assert r[("reference", "degree 48; circumsolar 1e-9")] == 0
    assert r[("exact", "degree 32; circumsolar 1e-06")] < r[("exact", "degree 8; circumsolar 1e-06")], r
    assert r[("exact", "degree 32; circumsolar 1e-06")] < 1e-6, r
    assert r[("patches_exact", "MF:4")] < r[("patches_exact", "MF:1")], r
    assert r[("sampled", "MF:1; 1024 rays")] < r[("sampled", "MF:1; 64 rays")], r
    assert r[("patches_exact", "MF:1")] < r[("sampled", "MF:1; 1024 rays")], r
    assert all(float(x["cpu_s_per_sensor"]) > 0 for x in rows if x["case"] == case)
PY

# `daylit bench reflections --quick`: a row for every case, N and B, with finite errors and times;
# on the closed-form cases the error falls from N = 16 to 256 and stays within 5 standard errors
# (seeded, so deterministic); in the side-lit room the runs' errors are their truncation and noise
# (below); the references per sensor add up (DF = SC + ERC + IRC).
start=$SECONDS
"$daylit" bench reflections --quick --quiet --samples "$(dirname "$0")/../../samples" --out "$out" || fail "bench reflections: exit status $?"
echo "bench reflections --quick: $((SECONDS - start)) s"
for f in reflections_error_vs_time.csv reflections_error_vs_time.png reflections_reference.csv reflections_reference_bounces.csv; do
  [ -s "$out/$f" ] || fail "$f missing or empty"
done
[ "$(head -c 8 "$out/reflections_error_vs_time.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "reflections plot not a PNG"
csv=$out/reflections_error_vs_time.csv
expected='case,method,samples,bounces,sensors,cpu_s_per_sensor,reflected_rms_error_percent,reflected_normalised_rms_error,erc_rms_error_percent,irc_rms_error_percent,standard_error_rms_percent,reference,reference_standard_error_rms_percent'
[ "$(head -n 1 "$csv")" = "$expected" ] || fail "header of $csv: $(head -n 1 "$csv")"
# The radiosity's two rows per case (samples = elements): exact to roundoff on the canopy (a
# uniform exitance, one bounce: linear elements carry it exactly), falling with refinement on the
# open-ceiling box.
report=$(awk -F, -v finite="$finite" 'NR > 1 {
    if (!($6 > 0)) print "no time for " $1 " " $2 " N = " $3 " B = " $4
    for (i = 7; i <= 11; i++) if ($i !~ finite) print "non-finite field " i " for " $1 " N = " $3 " B = " $4 ": " $i
    if ($2 == "radiosity") {
      radiosity[$1]++
      if (radiosity[$1] == 1) coarse[$1] = $7; else fine[$1] = $7
      next
    }
    rows[$1]++
    if ($4 + 0 > bmax) bmax = $4 + 0
    err[$1 "," $3 "," $4] = $7; se[$1 "," $3 "," $4] = $11; ref[$1] = $12
  }
  END {
    split("canopy open_ceiling_box office room_4x5x3", cases, " ")
    for (i in cases) if (rows[cases[i]] != 6) print rows[cases[i]] + 0 " path tracer rows for " cases[i] " (expected 6)"
    for (i in cases) if (radiosity[cases[i]] != 2) print radiosity[cases[i]] + 0 " radiosity rows for " cases[i] " (expected 2)"
    if (!(coarse["canopy"] < 1e-12 && fine["canopy"] < 1e-12)) print "canopy: radiosity off by " coarse["canopy"] ", " fine["canopy"]
    if (!(fine["open_ceiling_box"] < 0.5 * coarse["open_ceiling_box"])) print "open_ceiling_box: radiosity error does not fall: " coarse["open_ceiling_box"] " -> " fine["open_ceiling_box"]
    split("canopy open_ceiling_box", exact, " ")
    for (i in exact) {
      c = exact[i]
      if (ref[c] != "closed form") print c ": reference " ref[c]
      if (!(err[c ",256," bmax] < err[c ",16," bmax])) print c ": error does not fall with N: " err[c ",16," bmax] " -> " err[c ",256," bmax]
      if (!(err[c ",256," bmax] < 5 * se[c ",256," bmax])) print c ": error " err[c ",256," bmax] " beyond 5 sigma " se[c ",256," bmax]
    }
    if (ref["room_4x5x3"] !~ /^path tracer/) print "room_4x5x3: reference " ref["room_4x5x3"]
  }' "$csv")
[ -z "$report" ] || fail "$report"
# The side-lit room has no closed form: its reference is a long path-traced run (B = 8) with its
# standard errors and the IRC it carries per bounce. Beyond the first bounce lies about half of
# the IRC there (well above the reference's noise), and each short run's error is what its
# truncation and its noise allow: for B = 1, the RMS of (truncated part + noise) lies within the
# RMS noise of the RMS truncated part (the triangle inequality), taken 5 standard errors wide; for
# B = 8 (the reference's own truncation) the error is noise alone. The standard errors, not a
# ratio of two noisy errors, set the margins: the path tracer's sample path changes with the
# last bit of a libm result (another compiler or optimisation level), and its standard errors
# with it (0.046 and 0.23 per cent at N = 256, B = 1, measured at -O3 and -O1).
python3 - "$csv" "$out/reflections_reference.csv" "$out/reflections_reference_bounces.csv" <<'PY' || fail "bench reflections: room_4x5x3 against its reference"
import csv, math, sys
runs = {(r["samples"], r["bounces"]): r for r in csv.DictReader(open(sys.argv[1]))
        if r["case"] == "room_4x5x3" and r["method"] == "path_tracer"}
reference = [r for r in csv.DictReader(open(sys.argv[2])) if r["case"] == "room_4x5x3"]
bounces = [r for r in csv.DictReader(open(sys.argv[3])) if r["case"] == "room_4x5x3"]
rms = lambda values: math.sqrt(sum(v * v for v in values) / len(values))
reference_noise = rms([math.hypot(float(r["erc_se"]), float(r["irc_se"])) for r in reference])
beyond = {}
for r in bounces:
    if int(r["bounce"]) >= 2:
        beyond[r["index"]] = beyond.get(r["index"], 0) + float(r["erc_percent"]) + float(r["irc_percent"])
irc = sum(float(r["irc_percent"]) for r in reference)
assert len(beyond) == len(reference) == 20, (len(beyond), len(reference))
assert sum(beyond.values()) > 0.4 * irc, ("beyond the first bounce", sum(beyond.values()), "of the IRC", irc)
truncated = rms(list(beyond.values()))
assert truncated > 20 * reference_noise, (truncated, reference_noise)
one, eight = runs[("256", "1")], runs[("256", "8")]
error, noise = float(one["reflected_rms_error_percent"]), float(one["standard_error_rms_percent"])
assert abs(error - truncated) <= 5 * (noise + reference_noise), ("B = 1", error, "truncation", truncated, noise, reference_noise)
error, noise = float(eight["reflected_rms_error_percent"]), float(eight["standard_error_rms_percent"])
assert error <= 5 * (noise + reference_noise), ("B = 8", error, noise, reference_noise)
PY
report=$(awk -F, 'NR > 1 {
    n++
    d = $9 + $11 + $13 - $15; if (d < 0) d = -d
    if (d > 1e-4 * ($15 > 1 ? $15 : 1)) print "DF is not SC + ERC + IRC in " $1 " sensor " $2
    if ($1 == "room_4x5x3" && !($13 > 0)) print "no IRC at room_4x5x3 sensor " $2
  }
  END { if (n != 34) print n " reference rows (expected 34)" }' "$out/reflections_reference.csv")
[ -z "$report" ] || fail "$report"

# `daylit bench pairs --quick`: a row per case and mode; the rational reference computes in rationals
# (every pair but those decided before clipping), and nothing else needs them on these samples.
start=$SECONDS
"$daylit" bench pairs --quick --quiet --samples "$(dirname "$0")/../../samples" --out "$out" || fail "bench pairs: exit status $?"
echo "bench pairs --quick: $((SECONDS - start)) s"
[ "$(head -n 1 "$out/pairs.csv")" = "case,mode,pairs,us_per_pair,share_clipped,share_rational" ] || fail "pairs.csv header"
report=$(awk -F, 'NR > 1 { rows++; if (!($4 > 0)) print "no time: " $0
    if ($2 == "rational" && !($6 > 0)) print "rational mode without rationals: " $0
    if ($2 != "rational" && $6 != 0) print "rationals needed: " $0 }
  END { if (rows != 9) print rows " rows (expected 9)" }' "$out/pairs.csv")
[ -z "$report" ] || fail "bench pairs: $report"

# `daylit bench gradient --quick`: six rows, each with two positive times.
"$daylit" bench gradient --quick --quiet --samples "$(dirname "$0")/../../samples" --out "$out" || fail "bench gradient: exit status $?"
report=$(awk -F, 'NR > 1 { rows++; if (!($(NF-2) > 0 && $(NF-1) > 0)) print "no time: " $0 } END { if (rows != 6) print rows " rows (expected 6)" }' "$out/gradient.csv")
[ -z "$report" ] || fail "bench gradient: $report"

echo "$failures failures"
[ "$failures" -eq 0 ]
