#!/usr/bin/env bash
# daylit df and illuminance on Honeybee models (--model): the model's grids by default, --grid
# instead when given, and bad models refused with the file and JSON path, exit 1, no output.
daylit="$1"
data="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0

"$daylit" df --model "$data/model_radiance_grid_views.hbjson" --out grids.csv --summary summary.json 2> stderr.txt
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
"$daylit" df --model "$data/model_radiance_grid_views.hbjson" --grid one.pts --out one.csv 2> stderr.txt
if [ $? -ne 0 ] || [ "$(wc -l < one.csv)" -ne 2 ] || ! grep -q "sensor grids are left out: --grid was given" stderr.txt; then
  echo "FAIL df --model --grid"; failures=$((failures + 1))
fi
"$daylit" illuminance --model "$data/model_radiance_grid_views.hbjson" --sky cie-overcast --diffuse-horizontal 10000 --out lux.csv --quiet
if [ $? -ne 0 ] || [ "$(wc -l < lux.csv)" -ne 401 ]; then echo "FAIL illuminance --model"; failures=$((failures + 1)); fi

expect_failure() {  # description, pattern, arguments...
  local what="$1" pattern="$2"
  shift 2
  rm -f out.csv
  "$daylit" df "$@" > stdout.txt 2> stderr.txt
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
mkdir -p empty_folder
expect_failure "a folder that is not a Radiance folder" "not a Honeybee Radiance folder" --model empty_folder --grid one.pts --out out.csv

echo "$failures failures"
[ "$failures" -eq 0 ]
