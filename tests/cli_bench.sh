#!/usr/bin/env bash
# `daylit bench kernels --quick`: writes its tables and plots, with a row for every case and
# method; the exact kernels are exact to roundoff and the Monte Carlo error falls as N grows.
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

echo "$failures failures"
[ "$failures" -eq 0 ]
