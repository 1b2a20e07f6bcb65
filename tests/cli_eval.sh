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
  '{"id":4,"quantity":"nonsense"}' | "$daylit" eval)
status=$?
expected='{"id":1,"value":0.5235987755982989}
{"error":"stdin:3: invalid JSON*","id":null}
{"error":"cap regions are not supported yet","id":"b"}
{"id":{"k":3},"value":0.4352098756835516}
{"error":"unknown quantity '"'"'nonsense'"'"'","id":4}'
failures=0
[ "$status" -eq 0 ] || { echo "FAIL exit status $status"; failures=1; }
i=0
while IFS= read -r want; do
  i=$((i + 1))
  got=$(printf '%s\n' "$out" | sed -n "${i}p")
  # shellcheck disable=SC2053
  if [[ "$got" != $want ]]; then echo "FAIL line $i: got $got, expected $want"; failures=1; fi
done <<< "$expected"
[ "$(printf '%s\n' "$out" | wc -l)" -eq 5 ] || { echo "FAIL: not 5 answers"; failures=1; }
echo "$failures failures"
[ "$failures" -eq 0 ]
