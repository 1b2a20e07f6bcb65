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
# A grid whose sensors all face away from every aperture (up, above the roof) is said so.
printf '2 2 100 0 0 1\n3 2 100 0 0 1\n' > down.pts
"$daylit" df --components sc --model "$data/model_radiance_grid_views.hbjson" --grid down.pts --out down.csv 2> stderr.txt
if ! grep -q "every sensor of grid 'down' faces away from every aperture" stderr.txt; then echo "FAIL no notice for a grid facing away"; failures=$((failures + 1)); fi
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
echo "ok   daylit grid"

echo "$failures failures"
[ "$failures" -eq 0 ]
