#!/usr/bin/env bash
# `daylit eval`: one answer line per query line, in order, errors as answers, blank lines skipped.
set -u
daylit=$1
out=$(printf '%s\n' \
  '{"id":1,"quantity":"moment","region":{"polygon":[[0,0,1],[1,0,1],[1,1,1],[0,1,1]],"origin":[0,0,0]}}' \
  '' \
  'not json' \
  '{"id":"b","quantity":"moment","region":{"cap":{"axis":[0,0,1],"half_angle":1}}}' \
  '{"id":{"k":3},"quantity":"moment","region":{"polygon":[[0,0,1],[1,0,1],[1,1,1],[0,1,1]],"origin":[0,0,0]},"factors":[{"axis":[0,0,1],"power":1}]}' \
  '{"id":4,"quantity":"nonsense"}' \
  '{"id":"c1","quantity":"moment","region":{"cap":{"axis":[0.6,0,0.8],"half_angle":0.3}},"clip":[0,0,1],"factors":[{"axis":[0,0,1],"power":2}]}' \
  '{"id":"c2","quantity":"moment","region":{"cap":{"axis":[1,0,0],"half_angle":0.5}},"clip":[0,0,1],"factors":[{"axis":[0,0,2],"power":3},{"axis":[3,0,0],"power":1}]}' \
  '{"id":"c3","quantity":"moment","region":{"cap":{"axis":[0,0,-1],"half_angle":2}},"clip":[0,0,1],"factors":[{"axis":[0,0,1],"power":4}]}' \
  '{"id":"c4","quantity":"moment","region":{"cap":{"axis":[0,0,1],"half_angle":0.5}},"clip":[0,0,1],"factors":[{"axis":[0,1,0],"power":1}]}' \
  '{"id":"r1","quantity":"moment","region":{"polygon":[[0,0,1],[1,0,1],[1,1,1],[0,1,1]],"origin":[0,0,0]},"denominator":{"axis":[0,0,1],"power":1}}' \
  '{"id":"r2","quantity":"moment","region":{"polygon":[[0,0,1],[1,0,1],[1,1,1],[0,1,1]],"origin":[0,0,0]},"factors":[{"axis":[1,0,0],"power":1},{"axis":[0,0,1],"power":1}],"denominator":{"axis":[0,0,2],"power":2}}' \
  '{"id":"r3","quantity":"moment","region":{"polygon":[[0,0,-1],[1,0,-1],[1,1,-1],[0,1,-1]],"origin":[0,0,0]},"denominator":{"axis":[0,0,1],"power":1}}' \
  '{"id":"r4","quantity":"moment","region":{"polygon":[[0,0,1],[1,0,1],[1,1,-1],[0,1,-1]],"origin":[0,0,0]},"denominator":{"axis":[0,0,1],"power":1}}' \
  '{"id":"r5","quantity":"moment","region":{"polygon":[[0,0,1],[1,0,1],[1,1,1],[0,1,1]],"origin":[0,0,0]},"factors":[{"axis":[0.3,0.4,0.8],"power":100},{"axis":[1,0,0],"power":1}],"denominator":{"axis":[0,0,1],"power":1}}' \
  '{"id":"r6","quantity":"moment","region":{"cap":{"axis":[0,0,1],"half_angle":0.3}},"denominator":{"axis":[0,0,1],"power":1}}' | "$daylit" eval)
status=$?
# Cap values ("b", "c1"–"c3"): 2π(1 − cos 1), and 40-digit mpmath integrals over z = c·u of z^n times
# the cap's azimuthal extent (no formula shared with cap_moment.cpp), to 14–15 digits.
# Rational moments ("r1", "r2", "r5"): 30-digit mpmath quadrature over the unit square at z = 1,
# e.g. r1 = ∫∫ dx dy/(1 + x² + y²), r5 = ∫∫ (0.3x + 0.4y + 0.8)^100 x (1 + x² + y²)^-51.5; "r3" is
# r1's region below the plane (the sign of (d·u)^1); "r4" crosses d·u = 0, where they diverge.
expected='{"id":1,"value":0.5235987755982989}
{"error":"stdin:3: invalid JSON*","id":null}
{"id":"b","value":2.88836579751364*}
{"id":{"k":3},"value":0.4352098756835516}
{"error":"unknown quantity '"'"'nonsense'"'"'","id":4}
{"id":"c1","value":0.17392288537500*}
{"id":"c2","value":0.16210103885028*}
{"id":"c3","value":0.015683495075357*}
{"error":"cap moment: the factor axis*parallel neither*","id":"c4"}
{"id":"r1","value":0.63951035187031*}
{"id":"r2","value":0.055723659639283*}
{"id":"r3","value":-0.63951035187031*}
{"error":"*strictly on one side*diverges","id":"r4"}
{"id":"r5","value":6.96406586360*e-05}
{"error":"*polygon regions only","id":"r6"}'
failures=0
# The answers, line by line, against glob patterns, and their count.
check_answers() {  # what, answers, patterns (one per line), count
  local i=0 want got
  while IFS= read -r want; do
    i=$((i + 1))
    got=$(printf '%s\n' "$2" | sed -n "${i}p")
    # shellcheck disable=SC2053
    if [[ "$got" != $want ]]; then echo "FAIL $1 line $i: got $got, expected $want"; failures=1; fi
  done <<< "$3"
  [ "$(printf '%s\n' "$2" | wc -l)" -eq "$4" ] || { echo "FAIL: not $4 $1 answers"; failures=1; }
}
[ "$status" -eq 0 ] || { echo "FAIL exit status $status"; failures=1; }
check_answers moment "$out" "$expected" 15
# Irradiance queries: a 1 × 2 luminaire at z = 1.5 seen from (0.3, 0.4, 0.2), uniform (M = 2), behind a
# plate whose edge cuts its shadow across it, and with M = 1 + x/2 − y/4; then the errors (origin in the
# luminaire's plane asked for a gradient, a zero normal, a degree above the limit, a bad exitance).
# References from tests/data/irradiance_gradient_reference.py (Howell's formula and 40-digit mpmath
# quadrature, differentiated numerically), to 13–14 digits.
lum='"luminaire":[[0,0,1.5],[1,0,1.5],[1,2,1.5],[0,2,1.5]],"origin":[0.3,0.4,0.2],"normal":[0,0,1]'
irr=$(printf '%s\n' \
  '{"id":"u","quantity":"irradiance",'"$lum"',"exitance":{"uniform":2},"gradient":true}' \
  '{"id":"v","quantity":"irradiance",'"$lum"',"exitance":{"uniform":2}}' \
  '{"id":"o","quantity":"irradiance",'"$lum"',"exitance":{"uniform":2},"occluders":[[[-3,-3,0.75],[0.5,-3,0.75],[0.5,5,0.75],[-3,5,0.75]]],"gradient":true}' \
  '{"id":"l","quantity":"irradiance",'"$lum"',"exitance":{"polynomial":[{"coef":1,"powers":[0,0,0]},{"coef":0.5,"powers":[1,0,0]},{"coef":-0.25,"powers":[0,1,0]}]},"gradient":true}' \
  '{"id":"e1","quantity":"irradiance","luminaire":[[0,0,1.5],[1,0,1.5],[1,2,1.5],[0,2,1.5]],"origin":[3,0.4,1.5],"normal":[-1,0,0],"exitance":{"uniform":2},"gradient":true}' \
  '{"id":"e2","quantity":"irradiance","luminaire":[[0,0,1.5],[1,0,1.5],[1,2,1.5],[0,2,1.5]],"origin":[0.3,0.4,0.2],"normal":[0,0,0],"exitance":{"uniform":2}}' \
  '{"id":"e3","quantity":"irradiance",'"$lum"',"exitance":{"polynomial":[{"coef":1,"powers":[17,0,0]}]}}' \
  '{"id":"e4","quantity":"irradiance",'"$lum"',"exitance":{"uniform":2,"polynomial":[]}}' | "$daylit" eval)
[ $? -eq 0 ] || { echo "FAIL irradiance exit status"; failures=1; }
irr_expected='{"gradient":\[0.1304224997740*,0.2235623482397*,0.4223374883540*\],"id":"u","value":0.4294174805954*}
{"id":"v","value":0.4294174805954*}
{"gradient":\[0.6055425925974*,0.03921787817433*,-0.1365355028397*\],"id":"o","value":0.07892231932360*}
{"gradient":\[0.08451122982021*,0.09820921582500*,0.2285427864166*\],"id":"l","value":0.2249520140870*}
{"error":"the origin lies in the luminaire*plane*","id":"e1"}
{"error":"normal must be non-zero","id":"e2"}
{"error":"exitance.polynomial\[0\]*degree above*","id":"e3"}
{"error":"exitance must be*","id":"e4"}'
check_answers irradiance "$irr" "$irr_expected" 8
echo "$failures failures"
[ "$failures" -eq 0 ]
