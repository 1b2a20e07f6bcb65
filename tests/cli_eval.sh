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
  '{"id":"c4","quantity":"moment","region":{"cap":{"axis":[0,0,1],"half_angle":0.5}},"clip":[0,0,1],"factors":[{"axis":[0,1,0],"power":1}]}' | "$daylit" eval)
status=$?
# Cap values ("b", "c1"–"c3"): 2π(1 − cos 1), and 40-digit mpmath integrals over z = c·u of z^n times
# the cap's azimuthal extent (no formula shared with cap_moment.cpp), to 14–15 digits.
expected='{"id":1,"value":0.5235987755982989}
{"error":"stdin:3: invalid JSON*","id":null}
{"id":"b","value":2.88836579751364*}
{"id":{"k":3},"value":0.4352098756835516}
{"error":"unknown quantity '"'"'nonsense'"'"'","id":4}
{"id":"c1","value":0.17392288537500*}
{"id":"c2","value":0.16210103885028*}
{"id":"c3","value":0.015683495075357*}
{"error":"cap moment: the factor axis*parallel neither*","id":"c4"}'
failures=0
[ "$status" -eq 0 ] || { echo "FAIL exit status $status"; failures=1; }
i=0
while IFS= read -r want; do
  i=$((i + 1))
  got=$(printf '%s\n' "$out" | sed -n "${i}p")
  # shellcheck disable=SC2053
  if [[ "$got" != $want ]]; then echo "FAIL line $i: got $got, expected $want"; failures=1; fi
done <<< "$expected"
[ "$(printf '%s\n' "$out" | wc -l)" -eq 9 ] || { echo "FAIL: not 9 answers"; failures=1; }
echo "$failures failures"
[ "$failures" -eq 0 ]
