#!/usr/bin/env bash
# `daylit sun`: the example of the SPA report (NREL/TP-560-34302, Table A5.1; NREL's spa.c prints
# zenith 50.111622°, azimuth 194.340241°) as one line of JSON, the same answer for the same
# instant in another offset, and bad arguments refused with the option named and a non-zero status.
set -u
daylit=$(realpath "$1")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

vector=(--location 39.742476,-105.1786,1830.14 --pressure-hpa 820 --temperature-c 11 --delta-t-s 67)
out=$("$daylit" sun "${vector[@]}" --time 2003-10-17T12:30:30-07:00) || fail "exit status $? for the test vector"
echo "$out"
[ "$(printf '%s\n' "$out" | wc -l)" -eq 1 ] || fail "not one line"
[[ "$out" == '{"zenith_deg":'*',"azimuth_deg":'*',"elevation_deg":'*',"declination_deg":'*',"equation_of_time_min":'*',"delta_t_s":67.0}' ]] ||
  fail "keys or their order: $out"
value() { printf '%s\n' "$out" | sed -n "s/.*\"$1\":\([-0-9.eE+]*\).*/\1/p"; }
near() {  # name, value, expected, tolerance
  awk -v v="$2" -v e="$3" -v t="$4" 'BEGIN { d = v - e; if (d < 0) d = -d; exit !(v != "" && d <= t) }' ||
    fail "$1 = $2, expected $3 within $4"
}
# Half a unit of the last printed digit, plus 1e-7 for the report's JD rounding (see the unit test).
near zenith_deg "$(value zenith_deg)" 50.111622 6e-7
near azimuth_deg "$(value azimuth_deg)" 194.340241 6e-7
near declination_deg "$(value declination_deg)" -9.316179 6e-7
# Full precision: at least 15 significant digits, not printf's default 6.
[ "$(value zenith_deg | tr -d '.-' | wc -c)" -ge 16 ] || fail "zenith printed with too few digits: $(value zenith_deg)"

# The same instant in UTC and in +09:30, and a negative latitude written with '='.
same=$("$daylit" sun "${vector[@]}" --time 2003-10-17T19:30:30Z)
[ "$same" = "$out" ] || fail "UTC gives $same"
same=$("$daylit" sun "${vector[@]}" --time 2003-10-18T05:00:30+09:30)
[ "$same" = "$out" ] || fail "+09:30 gives $same"
"$daylit" sun --location=-33.87,151.21 --time 2021-12-21T12:00:00+11:00 > /dev/null || fail "southern site refused"
"$daylit" sun --location -33.87,151.21,40 --time 2021-12-21T12:00:00+11:00 > /dev/null || fail "--location -33.87,... refused"

# --site takes the site file that df and illuminance take (one meaning per option name): the sun
# at its origin, the same answer as the coordinates give.
cd "$work" || exit 1
printf '{"latitude_deg": 39.742476, "longitude_deg": -105.1786, "elevation_m": 1830.14, "north_deg": 0}\n' > site.json
from_file=$("$daylit" sun --site site.json --pressure-hpa 820 --temperature-c 11 --delta-t-s 67 --time 2003-10-17T12:30:30-07:00)
[ "$from_file" = "$out" ] || fail "--site site.json gives $from_file"

# Every refusal here is of the command line: exit status 2 (README, "Exit codes").
expect_failure() {  # name, text stderr must contain, arguments...
  local name=$1 expected=$2
  shift 2
  "$daylit" sun "$@" > stdout.txt 2> stderr.txt
  local status=$?
  local before=$failures
  [ "$status" -eq 2 ] || fail "$name: exit status $status, not 2"
  grep -q -- "$expected" stderr.txt || { fail "$name: stderr lacks '$expected':"; cat stderr.txt; }
  [ ! -s stdout.txt ] || fail "$name: printed $(cat stdout.txt)"
  [ "$failures" -ne "$before" ] || echo "ok   $name: $(head -n 1 stderr.txt)"
}
t=2003-10-17T12:30:30-07:00
expect_failure "latitude above 90" "--location.*latitude 95" --location 95,0,0 --time $t
expect_failure "longitude beyond 180" "--location.*longitude 200" --location 40,200 --time $t
expect_failure "site not numbers" "--location.*\"abc\" is not a number" --location 40,abc,0 --time $t
expect_failure "site with four numbers" "--location.*4 numbers" --location 1,2,3,4 --time $t
expect_failure "time without an offset" "--time.*UTC offset" --location 40,0 --time 2003-10-17T12:30:30
expect_failure "time that does not exist" "--time.*day 29 does not exist" --location 40,0 --time 2003-02-29T12:00Z
expect_failure "negative pressure" "--pressure-hpa" --location 40,0 --time $t --pressure-hpa -1
expect_failure "UT1 - UTC of 2 s" "--delta-ut1-s" --location 40,0 --time $t --delta-ut1-s 2
expect_failure "no time" "--time" --location 40,0
expect_failure "no observer" "--location" --time $t
expect_failure "both --location and --site" "Exactly 1 option from \[--location,--site\]" --location 40,0 --site site.json --time $t
expect_failure "a site file that does not exist" "--site.*missing.json" --site missing.json --time $t
echo "$failures failures"
[ "$failures" -eq 0 ]
