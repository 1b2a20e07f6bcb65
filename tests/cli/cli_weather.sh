#!/usr/bin/env bash
# `daylit illuminance --sky perez` with a weather hour: the hour and the site it used are stated
# (the EPW's hour-ending record, the sun at its middle, the site from the file unless --site), the
# sky is scaled to the record's diffuse horizontal illuminance, a .wea and given irradiances work,
# the Radiance clamps are named; a bad weather file fails with file:line, exit 1 and no output.
set -u
daylit=$(realpath "$1")
samples=$(realpath "$2")
data=$(realpath "$3")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

head -40 "$samples/office/grid.pts" > "$work/grid.pts"
office=(--scene "$samples/office/scene.rad" --apertures "$samples/office/apertures.rad" --grid "$work/grid.pts" --quiet)
epw="$data/chicago-ohare-tmy3-jan1-3.epw"

"$daylit" illuminance --components sc "${office[@]}" --sky perez --weather "$epw" --time 2026-01-01T12:00:00-06:00 \
  --summary "$work/epw.json" --out "$work/epw.csv" || fail "perez with an EPW hour"
python3 - "$work/epw.json" <<'PY' || fail "EPW summary"
import json, sys
s = json.load(open(sys.argv[1]))
w, p = s["weather"], s["sky"]["perez"]
assert w["record"]["line"] == 20 and w["record"]["hour"] == 12, w["record"]   # 12:00 ends the hour 11:00-12:00
assert w["hour"].startswith("01-01 11:00"), w["hour"]
assert w["sun_taken_at"].startswith("2026-01-01T11:30:00"), w["sun_taken_at"]
assert s["site"]["source"] == "weather file" and abs(s["site"]["latitude_deg"] - 41.98) < 1e-12
assert abs(s["sky"]["unobstructed_horizontal_lux"] - 16854) < 1e-9 * 16854      # the record's illuminance
assert p["diffuse_horizontal_lux_source"] == "given" and p["clamps"] == "none"
assert p["diffuse_horizontal_irradiance_w_m2"] == 144 and p["direct_normal_irradiance_w_m2"] == 521
assert s["sun"]["direct_normal_lux"] == 50467 and s["sun"]["included"]
assert 0.99 < p["radiance_145_point_sum_over_normalisation"] < 1.05
assert "policy" in w["missing_values"]
PY
head -1 "$work/epw.csv" | grep -q '^grid,index' || fail "CSV"

# A typical-year file's record from another year than --time's: the sun is taken for the year
# asked, and a notice (and the summary) says so, since `annual` takes the record's own year.
loud=(--scene "$samples/office/scene.rad" --apertures "$samples/office/apertures.rad" --grid "$work/grid.pts")
for year in 2026 1986; do
  "$daylit" illuminance --components sc "${loud[@]}" --sky perez --weather "$epw" --time "$year-01-01T12:00:00-06:00" \
    --summary "$work/year-$year.json" --out /dev/null 2> "$work/year-$year.err" || fail "perez hour asked in $year"
done
grep -q "the record is from 1986, --time asks for 2026: the sun is taken for 2026" "$work/year-2026.err" \
  || fail "no notice for a record from another year"
grep -q "the record is from" "$work/year-1986.err" && fail "a notice for a record of the year asked"
python3 - "$work/year-2026.json" <<'PY' || fail "the summary's record and sun years"
import json, sys
w = json.load(open(sys.argv[1]))["weather"]
assert w["record"]["year"] == 1986 and w["sun_year"] == 2026, w
PY

# The same hour asked in UTC picks the same record; 12:00:01 local picks the next one.
"$daylit" illuminance --components sc "${office[@]}" --sky perez --weather "$epw" --time 2026-01-01T18:00:00Z --summary "$work/utc.json" \
  --out "$work/utc.csv" || fail "perez at a UTC time"
cmp -s "$work/epw.csv" "$work/utc.csv" || fail "the same instant in UTC gave another result"
"$daylit" illuminance --components sc "${office[@]}" --sky perez --weather "$epw" --time 2026-01-01T12:00:01-06:00 --summary "$work/next.json" \
  --out /dev/null || fail "perez a second later"
python3 -c "import json,sys; assert json.load(open(sys.argv[1]))['weather']['record']['line'] == 21" "$work/next.json" ||
  fail "12:00:01 is in the hour ending 13:00"

# A .wea of the same hours (irradiance only: the illuminances come from Perez's efficacies).
"$daylit" illuminance --components sc "${office[@]}" --sky perez --weather "$data/chicago-ohare-tmy3-jan1-3.wea" \
  --time 2026-01-01T12:00:00-06:00 --perez-clamps radiance --summary "$work/wea.json" --out /dev/null || fail "perez with a .wea"
python3 - "$work/wea.json" <<'PY' || fail ".wea summary"
import json, sys
s = json.load(open(sys.argv[1]))
p = s["sky"]["perez"]
assert s["weather"]["format"] == "wea" and s["weather"]["record"]["hour"] == 11.5
assert p["diffuse_horizontal_lux_source"] == "Perez 1990 diffuse efficacy" and p["clamps"] == "radiance"
assert s["weather"]["sun_taken_at"].startswith("2026-01-01T11:30:00")
PY

# Given irradiances and sun; --site overrides the file's site and says so.
"$daylit" illuminance --components sc "${office[@]}" --sky perez --diffuse-horizontal-irradiance 144 --direct-normal-irradiance 521 \
  --sun-zenith 65.1666 --sun-azimuth 173.57 --summary "$work/given.json" --out /dev/null || fail "perez given"
python3 -c "import json,sys; p=json.load(open(sys.argv[1]))['sky']['perez']; assert p['direct_normal_lux_source'].startswith('Perez')" \
  "$work/given.json" || fail "given irradiances: efficacy"
echo '{"latitude_deg": 41.5, "longitude_deg": -87.5, "elevation_m": 180, "north_deg": 10}' > "$work/site.json"
"$daylit" illuminance --components sc "${office[@]}" --sky perez --weather "$epw" --time 2026-01-01T12:00:00-06:00 \
  --site "$work/site.json" --summary "$work/sited.json" --out /dev/null || fail "perez with --site"
python3 -c "import json,sys; s=json.load(open(sys.argv[1]))['site']; assert s['source'] == '--site' and s['latitude_deg'] == 41.5" \
  "$work/sited.json" ||
  fail "--site not stated"

expect_failure() {  # name, text stderr must contain, arguments...
  local name=$1 expected=$2
  shift 2
  rm -f "$work/bad.csv" "$work/bad.json"
  "$daylit" illuminance --components sc "${office[@]}" "$@" --out "$work/bad.csv" --summary "$work/bad.json" 2> "$work/err"
  local rc=$?
  [ $rc -eq 1 ] || fail "$name: exit status $rc, not 1"
  grep -q -- "$expected" "$work/err" || fail "$name: stderr lacks '$expected': $(cat "$work/err")"
  [ ! -e "$work/bad.csv" ] && [ ! -e "$work/bad.json" ] || fail "$name: partial output left behind"
}
awk -F, 'NR == 15 { $15 = "lots" } { print }' OFS=, "$epw" > "$work/bad.epw"
expect_failure "bad field" "bad.epw:15: direct normal irradiance (field 15) is 'lots'" --sky perez --weather "$work/bad.epw" \
  --time 2026-01-01T12:00:00-06:00
awk -F, 'NR == 20 { $16 = "9999" } { print }' OFS=, "$epw" > "$work/missing.epw"
expect_failure "missing hour" "missing.epw:20: the direct normal or diffuse horizontal value of this hour is missing" \
  --sky perez --weather "$work/missing.epw" --time 2026-01-01T12:00:00-06:00
expect_failure "night hour" "chicago-ohare-tmy3-jan1-3.epw:11: the sun is below the horizon for the whole hour" \
  --sky perez --weather "$epw" --time 2026-01-01T03:00:00-06:00
expect_failure "no record" "no record for 01-05" --sky perez --weather "$epw" --time 2026-01-05T12:00:00-06:00
head -5 "$epw" > "$work/short.epw"
expect_failure "short header" "short.epw:6: the header ends before its COMMENTS 1 line" --sky perez --weather "$work/short.epw" \
  --time 2026-01-01T12:00:00-06:00
expect_failure "weather without perez" "read by --sky perez only" --diffuse-horizontal 1 --weather "$epw"
expect_failure "weather without time" "needs --time" --sky perez --weather "$epw"
expect_failure "perez without irradiance" "needs the hour's" --sky perez --sun-zenith 30 --sun-azimuth 180
expect_failure "weather and given values" "cannot be given with --weather" --sky perez --weather "$epw" \
  --time 2026-01-01T12:00:00-06:00 --direct-normal-irradiance 500

[ "$failures" -eq 0 ] && echo "all weather checks passed"
exit $((failures > 0))
