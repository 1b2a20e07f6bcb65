#!/usr/bin/env bash
# The bundled samples run in every geometry mode and give finite daylight factors: exact and float
# agree to roundoff on these well-conditioned scenes, and the certified exact path reproduces the
# all-rational reference (on every 40th sensor: the reference is slow).
set -eu
# These checks are of the sky component (geometry modes against each other), so they run with
# --components sc; the reflected components have tests/cli/cli_reflections.sh.
daylit=$1
samples=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# label, csv a, csv b, bound: fails if the largest difference relative to max(|b|, 1e-6 %) exceeds
# bound. (Where the exact sky component is 0, the float path may leave slivers of ~1e-16 %: counted.)
largest_difference() {
  paste -d, "$2" "$3" | tail -n +2 | awk -F, -v label="$1" -v bound="$4" '
    { d = $10 - $20; if (d < 0) d = -d; b = $20 < 0 ? -$20 : $20; r = d / (b > 1e-6 ? b : 1e-6); if (r > m) m = r
      if (($10 == 0) != ($20 == 0)) slivers++ }
    END { printf "%s: largest relative difference %.3g; zero in one and not the other at %d sensors\n", label, m, slivers
          if (m > bound) exit 1 }'
}

# label, exact CSV, then df's arguments less --apertures, --geometry and --out: the exact path
# against the all-rational one. Behind glass the moments are held to 1e-9 relative
# (illumination/moments.cpp: the glass's polynomial is a fit, good to ~1e-3), so two partitions
# of one region may differ by twice that; the geometry itself is compared to 1e-12 with the
# apertures open (void), where both are exact to roundoff.
exact_against_rational() {
  local label=$1 exact=$2 apertures=$3
  shift 3
  "$daylit" df --components sc "$@" --apertures "$apertures" --geometry rational --out "$work/$label-rational.csv" --quiet
  if grep -q "^void glass" "$apertures"; then
    largest_difference "$label exact/rational (glazed)" "$exact" "$work/$label-rational.csv" 2e-9
    sed 's/^[a-z_]* polygon /void polygon /' "$apertures" > "$work/$label-open.rad"
    for geometry in exact rational; do
      "$daylit" df --components sc "$@" --apertures "$work/$label-open.rad" --geometry "$geometry" \
        --out "$work/$label-open-$geometry.csv" --quiet
    done
    largest_difference "$label exact/rational (open)" "$work/$label-open-exact.csv" "$work/$label-open-rational.csv" 1e-12
  else
    largest_difference "$label exact/rational" "$exact" "$work/$label-rational.csv" 1e-12
  fi
}

for sample in office hall; do
  dir=$samples/$sample
  awk 'NR % 40 == 1' "$dir/grid.pts" > "$work/$sample-subset.pts"
  for geometry in exact float; do
    grid=$dir/grid.pts
    "$daylit" df --components sc --scene "$dir/scene.rad" --apertures "$dir/apertures.rad" --grid "$grid" \
      --geometry "$geometry" --out "$work/$sample-$geometry.csv" --summary "$work/$sample-$geometry.json" --quiet
    if grep -qi nan "$work/$sample-$geometry.csv"; then echo "NaN in $sample ($geometry)"; exit 1; fi
  done
  "$daylit" df --components sc --scene "$dir/scene.rad" --apertures "$dir/apertures.rad" --grid "$work/$sample-subset.pts" \
    --out "$work/$sample-subset-exact.csv" --quiet
  largest_difference "$sample exact/float" "$work/$sample-exact.csv" "$work/$sample-float.csv" 1e-9
  exact_against_rational "$sample" "$work/$sample-subset-exact.csv" "$dir/apertures.rad" --scene "$dir/scene.rad" \
    --grid "$work/$sample-subset.pts"
done

# The city sample: neighbours from GeoJSON placed by the site file. The summary counts what was
# placed and left out, the certified path still reproduces the rational reference, and --context
# without --site is refused.
dir=$samples/city
city=(--scene "$dir/scene.rad" --apertures "$dir/apertures.rad" --site "$dir/site.json" --context "$dir/buildings.geojson")
"$daylit" df --components sc "${city[@]}" --grid "$dir/grid.pts" --out "$work/city.csv" --summary "$work/city.json" --quiet
for expected in '"buildings_read": 11' '"placed": 4' '"holding_the_model": 1' '"below_the_horizon": 1' \
                '"behind_the_apertures": 3' '"smaller_than_min_angle": 2'; do
  grep -q "$expected" "$work/city.json" || { echo "city summary lacks $expected"; exit 1; }
done
awk 'NR % 20 == 1' "$dir/grid.pts" > "$work/city-subset.pts"
"$daylit" df --components sc "${city[@]}" --grid "$work/city-subset.pts" --out "$work/city-subset-exact.csv" --quiet
exact_against_rational city "$work/city-subset-exact.csv" "$dir/apertures.rad" --scene "$dir/scene.rad" --site "$dir/site.json" \
  --context "$dir/buildings.geojson" --grid "$work/city-subset.pts"
if "$daylit" df --components sc --scene "$dir/scene.rad" --apertures "$dir/apertures.rad" --grid "$dir/grid.pts" \
     --context "$dir/buildings.geojson" --out "$work/no-site.csv" --quiet 2> "$work/no-site.err"; then
  echo "city: --context without --site was accepted"; exit 1
fi
grep -q "needs --site" "$work/no-site.err" && [ ! -e "$work/no-site.csv" ]
echo "city: context counts as expected, exact/rational agree, --context without --site refused"

# Sensors that see the sky directly (outdoors, or in a model open to the sky) get a notice naming
# how many, and their grid the sky seen past every surface. The office's grid has none; the same
# grid with two sensors above the roof and one beside the building facing out has those three (and
# the sensor facing down, none): above the roof the whole sky (SC 100 %), facing west 30 m from
# the building the unobstructed vertical sky component (3π + 8)/(14π) = 39.6177 % (SKY.md).
dir=$samples/office
"$daylit" df --components sc --scene "$dir/scene.rad" --apertures "$dir/apertures.rad" --grid "$dir/grid.pts" \
  --out "$work/office-sky.csv" 2> "$work/office-sky.err"
if grep -q "see the sky directly" "$work/office-sky.err"; then echo "office: sensors said to see the sky directly"; exit 1; fi
{ head -n 3 "$dir/grid.pts"; echo "5 5 40 0 0 1"; echo "2 3 45 0.6 0 0.8"; echo "-30 5 1 -1 0 0"; echo "5 5 40 0 0 -1"; } > "$work/outdoors.pts"
"$daylit" df --components sc --scene "$dir/scene.rad" --apertures "$dir/apertures.rad" --grid "$work/outdoors.pts" \
  --out "$work/outdoors.csv" 2> "$work/outdoors.err"
grep -q "3 of the 7 sensors of grid 'outdoors' see the sky directly" "$work/outdoors.err" ||
  { echo "outdoor sensors not noticed:"; cat "$work/outdoors.err"; exit 1; }
python3 - "$work/outdoors.csv" "$dir/grid.pts" "$work/office-sky.csv" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
sc = [float(r["sc_percent"]) for r in rows]
indoors = [float(r["sc_percent"]) for r in csv.DictReader(open(sys.argv[3]))][:3]
vsc = 100 * (3 * math.pi + 8) / (14 * math.pi)
# Closed forms to roundoff (a few sums over the faces of the box around the model); the sensors
# indoors keep their values bit for bit (the grid's direct view adds nothing where it is empty).
assert abs(sc[3] - 100) < 1e-9 and abs(sc[5] - vsc) < 1e-9 * vsc, sc
assert sc[6] == 0 and 0 < sc[4] < 100, sc
assert sc[:3] == indoors, (sc[:3], indoors)
PY
echo "office: no sensor sees the sky directly; three placed outdoors are noticed and see the whole sky"

# Without any aperture a grid that sees the sky directly still gets it (a street of windowless
# buildings): facing away from the one wall, the unobstructed vertical sky component; facing it,
# less. A grid that sees no sky at all is still refused for want of apertures.
printf 'void plastic w 0 0 5 .4 .4 .4 0 0\nw polygon b 0 0 12  0 10 0  20 10 0  20 10 8  0 10 8\n' > "$work/street.rad"
printf '10 0 1.5 0 -1 0\n10 0 1.5 0 1 0\n' > "$work/street.pts"
"$daylit" df --components sc --scene "$work/street.rad" --grid "$work/street.pts" --out "$work/street.csv" --quiet
python3 - "$work/street.csv" <<'PY'
import csv, math, sys
sc = [float(r["sc_percent"]) for r in csv.DictReader(open(sys.argv[1]))]
vsc = 100 * (3 * math.pi + 8) / (14 * math.pi)
assert abs(sc[0] - vsc) < 1e-9 * vsc and 0 < sc[1] < vsc - 1, sc
PY
printf '10 5 1.5 0 0 -1\n' > "$work/down.pts"
if "$daylit" df --components sc --scene "$work/street.rad" --grid "$work/down.pts" --out "$work/down.csv" 2> "$work/down.err" ||
   ! grep -q "no apertures open to the sky" "$work/down.err" || [ -e "$work/down.csv" ]; then
  echo "street: a grid seeing no sky, without apertures, not refused"; exit 1
fi
echo "street without apertures: the sky seen directly on a facade, closed form to roundoff"
