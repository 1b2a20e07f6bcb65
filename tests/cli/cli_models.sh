#!/usr/bin/env bash
# daylit df and illuminance on Honeybee models (--model): the model's grids by default, --grid
# instead when given, and bad models refused with the file and JSON path, exit 1, no output.
daylit="$1"
data="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0

"$daylit" df --components sc --model "$data/model_radiance_grid_views.hbjson" --out grids.csv --summary summary.json 2> stderr.txt
status=$?
rows=$(($(wc -l < grids.csv) - 1))
if [ "$status" -ne 0 ] || [ "$rows" -ne 400 ]; then echo "FAIL df --model: status $status, $rows rows"; cat stderr.txt; failures=$((failures + 1)); fi
if [ "$(cut -d, -f1 grids.csv | sed 1d | uniq | tr '\n' ' ')" != "Tiny_House_Zone Tiny_Garage " ]; then
  echo "FAIL df --model: grids not the model's, in its order"; failures=$((failures + 1))
fi
if ! grep -q "notice: .*2 rooms, 12 faces, 2 apertures" stderr.txt; then echo "FAIL df --model: no notice of what was read"; failures=$((failures + 1)); fi
echo "ok   df --model: $rows sensors in the model's grids"

# --grid replaces the model's grids, said so.
printf '2 2 0.8 0 0 1\n' > one.pts
"$daylit" df --components sc --model "$data/model_radiance_grid_views.hbjson" --grid one.pts --out one.csv 2> stderr.txt
if [ $? -ne 0 ] || [ "$(wc -l < one.csv)" -ne 2 ] || ! grep -q "sensor grids are left out: --grid was given" stderr.txt; then
  echo "FAIL df --model --grid"; failures=$((failures + 1))
fi
# A grid whose sensors all face away from every aperture (down, below the floor) is said so.
printf '2 2 -1 0 0 -1\n3 2 -1 0 0 -1\n' > down.pts
"$daylit" df --components sc --model "$data/model_radiance_grid_views.hbjson" --grid down.pts --out down.csv 2> stderr.txt
if ! grep -q "every sensor of grid 'down' faces away from every aperture" stderr.txt; then echo "FAIL no notice for a grid facing away"; failures=$((failures + 1)); fi
# A closed box whose only glass is a partition inside it (as a Honeybee folder files a window
# between two rooms, in scene/ with nothing marking it interior): zeros, and a notice saying why.
cat > closed.rad <<'RAD'
void plastic wall 0 0 5 .5 .5 .5 0 0
void glass partition 0 0 3 .96 .96 .96
wall polygon floor 0 0 12 0 0 0 4 0 0 4 4 0 0 4 0
wall polygon ceiling 0 0 12 0 0 3 0 4 3 4 4 3 4 0 3
wall polygon south 0 0 12 0 0 0 0 0 3 4 0 3 4 0 0
wall polygon north 0 0 12 0 4 0 4 4 0 4 4 3 0 4 3
wall polygon west 0 0 12 0 0 0 0 4 0 0 4 3 0 0 3
wall polygon east 0 0 12 4 0 0 4 0 3 4 4 3 4 4 0
partition polygon pane 0 0 12 2 1 1 2 3 1 2 3 2 2 1 2
RAD
printf '1 2 0.8 0 0 1\n1 2 1.5 1 0 0\n' > closed.pts
"$daylit" df --components sc --scene closed.rad --grid closed.pts --out closed.csv --summary closed.json 2> stderr.txt
if [ $? -ne 0 ] || [ "$(cut -d, -f10 closed.csv | sed 1d | sort -u)" != 0 ] ||
   ! grep -q "no sensor sees the sky through any of the 1 apertures" stderr.txt ||
   ! grep -q "no sensor sees the sky" closed.json; then
  echo "FAIL no notice when no sensor sees the sky"; cat stderr.txt; failures=$((failures + 1))
fi
# ... and none where sensors see the sky (the model's own grids, first run above).
if grep -q "no sensor sees the sky" summary.json; then echo "FAIL notice of no sky where sensors see it"; failures=$((failures + 1)); fi
# A double-sided glass shade drawn as two coincident polygons facing opposite ways (Honeybee's
# tree crowns), beyond a window: filtered once, as the shade alone, and said so.
cat > shade.rad <<'RAD'
void glass window 0 0 3 .7 .7 .7
void glass leaves 0 0 3 .5 .5 .5
window polygon w 0 0 12 0 2 1 2 2 1 2 2 2.2 0 2 2.2
leaves polygon front 0 0 12 -0.5 3.5 0.8 1.2 3.5 0.8 1.2 3.5 3 -0.5 3.5 3
RAD
{ cat shade.rad; printf 'leaves polygon back 0 0 12 -0.5 3.5 3 1.2 3.5 3 1.2 3.5 0.8 -0.5 3.5 0.8\n'; } > shade2.rad
printf '1 -1.5 0.85 0 0 1\n0.5 0 0.85 0 1 0\n' > shade.pts
"$daylit" df --components sc --scene shade.rad --grid shade.pts --out shade.csv --quiet
"$daylit" df --components sc --scene shade2.rad --grid shade.pts --out shade2.csv 2> stderr.txt
if [ "$(cut -d, -f10 shade.csv)" != "$(cut -d, -f10 shade2.csv)" ] || ! grep -q "pane 'back' and pane 'front' .* lie in one plane and overlap" stderr.txt; then
  echo "FAIL a shade drawn twice in one plane is not filtered once, or not said so"; cat stderr.txt; paste -d' ' shade.csv shade2.csv; failures=$((failures + 1))
fi
# ... nor reflected twice: the copy lies within the first and reflects nothing.
"$daylit" df --components all --scene shade.rad --grid shade.pts --out shade.csv --quiet
"$daylit" df --components all --scene shade2.rad --grid shade.pts --out shade2.csv 2> stderr.txt
if [ "$(cut -d, -f9-12 shade.csv)" != "$(cut -d, -f9-12 shade2.csv)" ] || ! grep -q "1 such pane lies within the first and reflects nothing" stderr.txt; then
  echo "FAIL a shade drawn twice reflects twice, or is not said so"; cat stderr.txt; paste -d' ' shade.csv shade2.csv; failures=$((failures + 1))
fi
"$daylit" illuminance --components sc --model "$data/model_radiance_grid_views.hbjson" --sky cie-overcast --diffuse-horizontal 10000 --out lux.csv --quiet
if [ $? -ne 0 ] || [ "$(wc -l < lux.csv)" -ne 401 ]; then echo "FAIL illuminance --model"; failures=$((failures + 1)); fi

# Honeybee's results layout beside the CSV: one DF per line per grid, and grids_info.json.
mkdir -p res
"$daylit" df --components sc --model "$data/model_radiance_grid_views.hbjson" --results res --out - --quiet > stdout.csv
if [ $? -ne 0 ] || [ -e ./- ] || [ "$(wc -l < stdout.csv)" -ne 401 ]; then echo "FAIL --out - to standard output"; failures=$((failures + 1)); fi
if [ "$(wc -l < res/Tiny_Garage.res)" -ne 200 ] || [ "$(grep Tiny_Garage stdout.csv | cut -d, -f10)" != "$(cat res/Tiny_Garage.res)" ]; then
  echo "FAIL --results: Tiny_Garage.res is not the CSV's df_percent"; failures=$((failures + 1))
fi
if [ "$(python3 -c 'import json; print([(g["identifier"], g["count"]) for g in json.load(open("res/grids_info.json"))])')" != \
     "[('Tiny_House_Zone', 200), ('Tiny_Garage', 200)]" ]; then echo "FAIL --results: grids_info.json"; failures=$((failures + 1)); fi
"$daylit" df --components sc --model "$data/model_radiance_grid_views.hbjson" --out ./- --quiet
if [ "$(wc -l < ./-)" -ne 401 ]; then echo "FAIL --out ./- writes a file named -"; failures=$((failures + 1)); fi
echo "ok   --results, --out - and --out ./-"
"$daylit" df --components sc --model "$data/model_radiance_grid_views.hbjson" --median-diffuse-lux 10000 --summary en.json --out /dev/null --quiet
if [ "$(python3 -c 'import json; g = json.load(open("en.json"))["grids"][0]["en17037_df_method"]; print(g["levels"][0]["target_df_percent"], g["levels"][0]["minimum_target_df_percent"], g["level_met"] in ("none", "minimum", "medium", "high"))')" != "3.0 1.0 True" ]; then
  echo "FAIL --median-diffuse-lux: no EN 17037 block"; failures=$((failures + 1))
fi

expect_failure() {  # description, pattern, arguments...
  local what="$1" pattern="$2"
  shift 2
  rm -f out.csv
  "$daylit" df --components sc "$@" > stdout.txt 2> stderr.txt
  local status=$?
  if [ "$status" -ne 1 ] || ! grep -q -- "$pattern" stderr.txt || [ -e out.csv ]; then
    echo "FAIL $what: status $status"; cat stderr.txt; failures=$((failures + 1))
  else
    echo "ok   $what"
  fi
}
sed 's/"boundary": \[/"outline": [/' "$data/model_5vertex_sub_faces.hbjson" > broken.hbjson
expect_failure "HBJSON without a boundary" "broken.hbjson: rooms\[0\].faces\[0\].geometry: missing \"boundary\"" \
  --model broken.hbjson --grid one.pts --out out.csv
printf '{"type": "Model",\n"rooms": [\n' > truncated.hbjson
expect_failure "truncated HBJSON" "truncated.hbjson:2: JSON syntax error" --model truncated.hbjson --grid one.pts --out out.csv
expect_failure "a model without grids" "has no sensor grids: give --grid" --model "$data/model_5vertex_sub_faces.hbjson" --out out.csv
expect_failure "only interior windows" "no apertures" --model "$data/model_5vertex_sub_faces_interior.hbjson" --grid one.pts --out out.csv
expect_failure "a results folder that does not exist" "no-such-folder: results folder does not exist" \
  --model "$data/model_radiance_grid_views.hbjson" --results no-such-folder --out out.csv
mkdir -p empty_folder
expect_failure "a folder that is not a Radiance folder" "not a Honeybee Radiance folder" --model empty_folder --grid one.pts --out out.csv

# daylit grid: the model's rooms' floors as .pts, and a .rad floor by hand (4 x 3, spacing 1,
# offset 0.5: centres x = 1, 2, 3 and y = 1, 2 at 0.85).
mkdir -p grids
"$daylit" grid --model "$data/model_5vertex_sub_faces.hbjson" --out grids --quiet
if [ $? -ne 0 ] || [ "$(wc -l < grids/TinyHouseZone.pts)" -lt 10 ]; then echo "FAIL grid --model"; failures=$((failures + 1)); fi
"$daylit" df --components sc --model "$data/model_5vertex_sub_faces.hbjson" --grid grids/TinyHouseZone.pts --out grid_df.csv --quiet
if [ $? -ne 0 ]; then echo "FAIL df on the generated grid"; failures=$((failures + 1)); fi
printf 'void plastic f 0 0 5 .2 .2 .2 0 0\nf polygon floor 0 0 12 0 0 0 4 0 0 4 3 0 0 3 0\n' > floor.rad
"$daylit" grid --scene floor.rad --spacing 1 --out grids --quiet
if [ "$(awk '{printf "%s,%s,%s;", $1, $2, $3}' grids/floor.pts)" != "1,1,0.84999999999999998;2,1,0.84999999999999998;3,1,0.84999999999999998;1,2,0.84999999999999998;2,2,0.84999999999999998;3,2,0.84999999999999998;" ]; then
  echo "FAIL grid --scene: $(cat grids/floor.pts)"; failures=$((failures + 1))
fi
"$daylit" grid --scene floor.rad --out no-such-dir > /dev/null 2> stderr.txt
if [ $? -ne 1 ] || ! grep -q "no-such-dir: output directory does not exist" stderr.txt; then echo "FAIL grid: missing folder"; failures=$((failures + 1)); fi
# An attic (Honeybee's multiroom sample: a gable roof down to its floor's edges): the sensors at
# 0.85 m near the eaves stand above the roof, outside the room; they are left out (72 of 324),
# so that no sensor of its grid sees the sky directly.
"$daylit" grid --model "$data/model_complete_multiroom_radiance.hbjson" --out grids 2> stderr.txt > /dev/null
if [ "$(wc -l < grids/Attic.pts)" -ne 252 ] || ! grep -q "room 'Attic': 72 of its 324 sensors lie outside it" stderr.txt ||
   grep -q "lie outside" <(grep -v "'Attic'" stderr.txt); then
  echo "FAIL grid --model: the attic's sensors above its roof: $(cat stderr.txt)"; failures=$((failures + 1))
fi
"$daylit" df --components sc --model "$data/model_complete_multiroom_radiance.hbjson" --grid grids/Attic.pts --out attic.csv 2> stderr.txt
if grep -q "see the sky directly" stderr.txt; then echo "FAIL the attic's grid sees the sky directly"; failures=$((failures + 1)); fi
echo "ok   daylit grid"


# The two paths agree: each HBJSON against the Radiance folder Honeybee's own translator wrote
# from it (folders/: model-to-rad-folder, see README.md), on the grids `daylit grid` lays on its
# floors (grid_views: the model's own grids, read from each). The readers share nothing but the
# .rad semantics, so this checks the HBJSON reader's modifier rules, punching, holes (holes: a
# window with a hole, open to the sky), doors, interior windows and dynamic states (first state:
# an electrochromic window, a trans tree, a light shelf) against Honeybee's. Allowance 1e-9
# relative: the geometry is the same doubles (Python's repr round-trips), but polygons and seam
# vertices come in another order, so the exact visibility cuts the regions otherwise (measured
# differences at most 2e-12); any difference of meaning is far above it (a face moved by 2 cm:
# 3e-2 relative). Honeybee moves one face of each pair shared by two rooms 2 x tolerance into its
# room (afn: NorthRoom..Face1 to y = 10.02; dynamic_states: Tiny_Garage_Left to x = 5.02): those
# two are compared with that face put back, and as translated they must differ (it is seen).
agree() {  # model, "components", extra df arguments...; returns 1 if they differ, 2 if a run failed
  local name="$1" components="$2" folder="$data/folders/$1"
  shift 2
  local grid=()
  if [ "$name" != model_radiance_grid_views ]; then
    mkdir -p "g_$name"
    "$daylit" grid --model "$data/$name.hbjson" --out "g_$name" --quiet
    cat "g_$name"/*.pts > "$name.pts"
    grid=(--grid "$name.pts")
  fi
  if [ -d "moved_$name" ]; then folder="moved_$name"; fi
  "$daylit" df --components "$components" --model "$data/$name.hbjson" "${grid[@]}" "$@" --out hbjson.csv --quiet &&
    "$daylit" df --components "$components" --model "$folder" "${grid[@]}" "$@" --out folder.csv --quiet || {
    echo "FAIL $name: a run failed"; return 2; }
  python3 - hbjson.csv folder.csv "$name" <<'PY'
import csv, sys
a, b = (list(csv.DictReader(open(p))) for p in sys.argv[1:3])
columns = [c for c in ("sc_percent", "erc_percent", "irc_percent", "df_percent") if c in a[0]]
assert len(a) == len(b) > 0 and all(x["grid"] == y["grid"] and x["x"] == y["x"] for x, y in zip(a, b)), "sensors differ"
worst = max(abs(float(x[c]) - float(y[c])) / max(abs(float(x[c])), 1e-300) if float(x[c]) or float(y[c]) else 0.0
            for x, y in zip(a, b) for c in columns)
print(("ok  " if worst <= 1e-9 else "FAIL") + f" {sys.argv[3]}: HBJSON and Honeybee's folder agree at {len(a)} sensors ({', '.join(columns)}): worst {worst:.1e}")
sys.exit(worst > 1e-9)
PY
}
for name in model_5vertex_sub_faces model_complete_multiroom_radiance model_radiance_grid_views model_complete_holes; do
  agree "$name" sc || failures=$((failures + 1))
done
"$daylit" df --components sc --model "$data/folders/model_complete_holes" --grid model_complete_holes.pts --out /dev/null 2> stderr.txt
if ! grep -q "1 holes in 1 apertures or doors taken as openings of transmittance 1" stderr.txt; then echo "FAIL holes: no notice"; failures=$((failures + 1)); fi
# The reflected components too: the same materials and reflectances from both.
agree model_complete_holes all --element-size 3 --max-refinements 0 || failures=$((failures + 1))
for moved in model_energy_afn:10.02:10.0 model_radiance_dynamic_states:5.02:5.0; do
  IFS=: read -r name from to <<< "$moved"
  agree "$name" sc > /dev/null
  if [ $? -ne 1 ]; then echo "FAIL $name: as translated (its face moved) the paths should differ"; failures=$((failures + 1)); fi
  cp -r "$data/folders/$name" "moved_$name"
  sed -i "s/\b${from//./\\.} /$to /g" "moved_$name/model/scene/envelope.rad"
  agree "$name" sc || failures=$((failures + 1))
done

echo "$failures failures"
[ "$failures" -eq 0 ]
