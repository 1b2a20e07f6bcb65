#!/usr/bin/env bash
# `daylit illuminance` on the bundled samples: under the overcast sky every sensor's sky
# illuminance is its daylight factor times E_out (the same exact closed form); with a site and a
# time the sun's position is SPA's (`daylit sun` for the same site), the summary states the sky,
# the sun and what was left out; bad arguments fail with a clear message and leave no output.
set -u
daylit=$(realpath "$1")
samples=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

office=(--scene "$samples/office/scene.rad" --apertures "$samples/office/apertures.rad" --grid "$samples/office/grid.pts")
# The sky illuminance is the sky component's: --components sc.
"$daylit" df "${office[@]}" --components sc --out "$work/df.csv" --quiet || fail "df on the office"
"$daylit" illuminance --components sc "${office[@]}" --diffuse-horizontal 10000 --out "$work/lux.csv" --summary "$work/lux.json" \
  --image "$work/lux.png" --quiet || fail "illuminance on the office"
[ -s "$work/lux.png" ] || fail "no image"
head -1 "$work/lux.csv" | grep -qx 'grid,index,x,y,z,dx,dy,dz,sky_lux,sun_lux,illuminance_lux,sky_error_bound_lux' ||
  fail "CSV header: $(head -1 "$work/lux.csv")"
# sky_lux = DF/100 · 10,000 lux, row by row, to 1e-12 relative (+1e-12 lux for zeros).
paste -d, "$work/df.csv" "$work/lux.csv" | awk -F, 'NR > 1 {
    e = $10 * 100; d = $19 - e; if (d < 0) d = -d; if (d > 1e-12 * (e < 0 ? -e : e) + 1e-12) bad++ }
  END { exit bad > 0 }' || fail "overcast illuminance is not DF times E_out"

# The city block at 17:00 on the summer solstice under a clear sky (CIE type 12) with the sun.
city=(--scene "$samples/city/scene.rad" --apertures "$samples/city/apertures.rad" --grid "$samples/city/grid.pts"
      --site "$samples/city/site.json" --context "$samples/city/buildings.geojson")
"$daylit" illuminance --components sc "${city[@]}" --sky cie-12 --time 2026-06-21T17:00:00+02:00 --diffuse-horizontal 15000 \
  --direct-normal 70000 --summary "$work/city.json" --out "$work/city.csv" --quiet || fail "illuminance on the city"
sun=$("$daylit" sun --site "$samples/city/site.json" --time 2026-06-21T17:00:00+02:00)
python3 - "$work/city.json" "$sun" <<'PY' || fail "city summary"
import json, sys
s = json.load(open(sys.argv[1])); sun = json.loads(sys.argv[2])
assert s["sun"]["position"] == "spa" and s["sun"]["included"], s["sun"]
assert abs(s["sun"]["zenith_deg"] - sun["zenith_deg"]) < 1e-9, (s["sun"], sun)
assert abs(s["sun"]["azimuth_deg"] - sun["azimuth_deg"]) < 1e-9
assert s["sky"]["model"] == "cie-12" and s["sky"]["method"] == "quadrature"
assert abs(s["sky"]["unobstructed_horizontal_lux"] - 15000) < 1e-9
assert s["context"]["min_angle_deg"] == 0.1, s["context"]
assert "kept_in_sun_beam" in s["context"], "with the sun on, the buildings in its beam are kept"
assert s["context"]["illuminance_change_bound_lux"]["sun"] == 0
assert s["components"]["computed"] == ["sky_direct", "sun_direct"]
g = s["grids"][0]
assert g["count"] > 0 and 0 <= g["share_in_direct_sun"] <= 1
assert g["illuminance_lux"]["max"] >= g["illuminance_lux"]["mean"] >= 0
PY

# Leaving out the small buildings outside the sun's beam changes nothing of the sun: at 10:00, when
# the sun reaches into the rooms, the same sun illuminance as with every visible building kept, to
# 1e-11 of the direct normal 70,000 lux (cap_clip.hpp: ~1e-13 of the disk per cut, more where the
# regions are cut into different pieces, whose seams across the disk cancel).
for min_angle in 0.1 0; do
  "$daylit" illuminance --components sc "${city[@]}" --sky cie-12 --time 2026-06-21T10:00:00+02:00 --diffuse-horizontal 15000 \
    --direct-normal 70000 --context-min-angle $min_angle --out "$work/city_$min_angle.csv" --quiet || fail "city at 10:00"
done
paste -d, "$work/city_0.1.csv" "$work/city_0.csv" | awk -F, 'NR > 1 {
    d = $10 - $22; if (d < 0) d = -d; if (d > 1e-11 * 70000) bad++; lit += $22 > 0 } END { exit bad > 0 || lit == 0 }' ||
  fail "the sun changed when small buildings outside its beam were left out"

# The quadrature path gives the same answer within the fit's per-sensor bounds.
"$daylit" illuminance --components sc "${city[@]}" --sky cie-12 --time 2026-06-21T17:00:00+02:00 --diffuse-horizontal 15000 \
  --sky-method quadrature --out "$work/cityq.csv" --quiet || fail "quadrature on the city"
"$daylit" illuminance --components sc "${city[@]}" --sky cie-12 --time 2026-06-21T17:00:00+02:00 --diffuse-horizontal 15000 \
  --sky-method fit --out "$work/cityf.csv" --quiet || fail "fit on the city"
paste -d, "$work/cityf.csv" "$work/cityq.csv" | awk -F, 'NR > 1 {
    d = $9 - $21; if (d < 0) d = -d; if (d > $12 + $24 + 1e-9) bad++ } END { exit bad > 0 }' ||
  fail "fit and quadrature differ by more than their bounds"

expect_failure() {  # name, text stderr must contain, arguments...
  local name=$1 expected=$2
  shift 2
  rm -f "$work/bad.csv"
  if "$daylit" illuminance --components sc "$@" --out "$work/bad.csv" 2> "$work/err"; then
    fail "$name: exit status 0"
  fi
  grep -q -- "$expected" "$work/err" || fail "$name: stderr lacks '$expected': $(cat "$work/err")"
  [ ! -e "$work/bad.csv" ] || fail "$name: partial output left behind"
}
expect_failure "no scale" "diffuse-horizontal" "${office[@]}"
expect_failure "time without site" "needs --site" "${office[@]}" --diffuse-horizontal 1 --time 2026-06-21T12:00:00Z
expect_failure "CIE sky without sun" "needs the sun" "${office[@]}" --diffuse-horizontal 1 --sky cie-7
expect_failure "unknown sky" "unknown sky" "${office[@]}" --diffuse-horizontal 1 --sky cie-16
expect_failure "sun at night" "below the horizon" "${city[@]}" --diffuse-horizontal 1 --sky cie-7 --time 2026-06-21T02:00:00+02:00
expect_failure "direct light without a sun" "needs the sun" "${office[@]}" --diffuse-horizontal 1 --direct-normal 1000
expect_failure "both scales" "excludes" "${office[@]}" --diffuse-horizontal 1 --zenith-luminance 1
expect_failure "zenith without azimuth" "requires" "${office[@]}" --diffuse-horizontal 1 --sun-zenith 30

[ "$failures" -eq 0 ] && echo "all illuminance checks passed"
exit $((failures > 0))
