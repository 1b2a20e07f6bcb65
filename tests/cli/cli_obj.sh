#!/usr/bin/env bash
# daylit df, illuminance and grid on Wavefront OBJ models (--model X.obj): the bundled room and
# office written as OBJ (tests/data/obj/make_obj_models.py) give what their .rad files give,
# sensor by sensor, in z up metres, in y up millimetres and with relative v/vt/vn indices; and bad
# OBJ files, .mtl files and maps are refused with file:line (or the JSON path), exit 1, no output.
daylit="$1"
samples="$2"
data="$3"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0
fail() { echo "FAIL $1"; failures=$((failures + 1)); }

# The largest relative difference of the *_percent (or *_lux) columns of two CSVs, sensor by
# sensor; the tolerance is 1e-12. The OBJ files hold the same decimal text as the .rad files (or
# 1000 times it, divided back to the same double), so the polygons are the same doubles and the
# runs do the same operations: measured 0, bit for bit. 1e-12 is the project's "same model"
# tolerance (the cost of a different but equally exact order of operations, such as another
# subtraction order, is a few 1e-14), so a reader change that reordered vertices would still pass
# while one that moved a coordinate by a rounding would not go unnoticed in the exact tests of
# test_obj_model.
compare() {  # what, obj.csv, rad.csv
  python3 - "$2" "$3" <<'EOF'
import csv, sys
a, b = (list(csv.DictReader(open(f))) for f in sys.argv[1:3])
assert len(a) == len(b) and len(a) > 0, (len(a), len(b))
cols = [c for c in b[0] if c.endswith("_percent") or c.endswith("_lux")]
worst = 0.0
for x, y in zip(a, b):
    assert (x["x"], x["y"], x["z"]) == (y["x"], y["y"], y["z"])
    for c in cols:
        u, v = float(x[c]), float(y[c])
        if u != v:
            worst = max(worst, abs(u - v) / max(abs(u), abs(v)))
print(f"{len(a)} sensors, {len(cols)} columns, largest relative difference {worst:.3g}")
sys.exit(0 if worst <= 1e-12 else 1)
EOF
}
check_same() {  # what, obj.csv, rad.csv
  local result
  result=$(compare "$@")
  if [ $? -ne 0 ]; then fail "$1: $result"; else echo "ok   $1: $result"; fi
}

room="$samples/room"
"$daylit" df --components sc --scene "$room/scene.rad" --apertures "$room/apertures.rad" --grid "$room/grid.pts" --out rad_sc.csv --quiet
"$daylit" df --components sc --model "$data/room.obj" --obj-materials "$data/room_map.json" --grid "$room/grid.pts" \
  --out obj_sc.csv --summary obj_sc.json 2> stderr.txt || fail "df --model room.obj"
check_same "room.obj, sky component" obj_sc.csv rad_sc.csv
grep -q "notice: .*room.obj: 7 faces (13 vertices; .*6 opaque, 1 apertures, 0 left out; read z up at 1 m per unit" stderr.txt ||
  fail "no notice of what room.obj held"
"$daylit" df --components sc --model "$data/room_yup_mm.obj" --obj-up y --obj-scale 0.001 --obj-materials "$data/room_map.json" \
  --grid "$room/grid.pts" --out obj_mm.csv --quiet || fail "df --model room_yup_mm.obj"
check_same "room_yup_mm.obj (--obj-up y --obj-scale 0.001), sky component" obj_mm.csv rad_sc.csv
"$daylit" df --components sc --model "$data/room_indices.obj" --obj-materials "$data/room_map.json" --grid "$room/grid.pts" \
  --out obj_idx.csv --quiet || fail "df --model room_indices.obj"
check_same "room_indices.obj (relative v/vt/vn), sky component" obj_idx.csv rad_sc.csv

# The whole daylight factor: the radiosity over the same surfaces with the same reflectances.
"$daylit" df --components all --scene "$room/scene.rad" --apertures "$room/apertures.rad" --grid "$room/grid.pts" --out rad_all.csv --quiet
"$daylit" df --components all --model "$data/room.obj" --obj-materials "$data/room_map.json" --grid "$room/grid.pts" \
  --out obj_all.csv --quiet || fail "df --components all --model room.obj"
check_same "room.obj, --components all" obj_all.csv rad_all.csv
"$daylit" df --components all --model "$data/room_yup_mm.obj" --obj-up y --obj-scale 0.001 --obj-materials "$data/room_map.json" \
  --grid "$room/grid.pts" --out obj_mm_all.csv --quiet || fail "df --components all --model room_yup_mm.obj"
check_same "room_yup_mm.obj, --components all" obj_mm_all.csv rad_all.csv

office="$samples/office"
"$daylit" df --components sc --scene "$office/scene.rad" --apertures "$office/apertures.rad" --grid "$office/grid.pts" --out office_rad.csv --quiet
"$daylit" df --components sc --model "$data/office.obj" --obj-materials "$data/office_map.json" --grid "$office/grid.pts" \
  --out office_obj.csv --quiet || fail "df --model office.obj"
check_same "office.obj, sky component" office_obj.csv office_rad.csv

"$daylit" illuminance --components sc --scene "$room/scene.rad" --apertures "$room/apertures.rad" --grid "$room/grid.pts" \
  --sky cie-overcast --diffuse-horizontal 10000 --out lux_rad.csv --quiet
"$daylit" illuminance --components sc --model "$data/room.obj" --obj-materials "$data/room_map.json" --grid "$room/grid.pts" \
  --sky cie-overcast --diffuse-horizontal 10000 --out lux_obj.csv --quiet || fail "illuminance --model room.obj"
check_same "illuminance on room.obj" lux_obj.csv lux_rad.csv

# Without a map the glass's d = 0.12 makes an aperture of constant transmittance 0.88, said so.
"$daylit" df --components sc --model "$data/room.obj" --grid "$room/grid.pts" --out nomap.csv 2> stderr.txt || fail "df without a map"
grep -q "transparent in the .mtl are apertures of constant transmittance: 'clear_glass' 0.88 (d 0.12)" stderr.txt ||
  fail "no notice of the transparent material"

# daylit grid on the OBJ's floor gives the .rad's grid.
mkdir -p grids_obj grids_rad
"$daylit" grid --model "$data/room_yup_mm.obj" --obj-up y --obj-scale 0.001 --out grids_obj --quiet || fail "grid --model room_yup_mm.obj"
"$daylit" grid --scene "$room/scene.rad" --out grids_rad --quiet
cmp -s grids_obj/floor.pts grids_rad/floor.pts || fail "grid --model room.obj differs from grid --scene"
printf '{"materials": {"wall_mat": {"role": "opaque", "floor": true}}}' > walls_as_floor.json
"$daylit" grid --model "$data/room.obj" --obj-materials walls_as_floor.json --out grids_obj > /dev/null 2> stderr.txt
[ $? -eq 1 ] && grep -q "not horizontal" stderr.txt || fail "grid: a wall marked floor is not refused"
echo "ok   daylit grid --model X.obj"

expect_failure() {  # description, status, pattern, arguments...
  local what="$1" expected="$2" pattern="$3"
  shift 3
  rm -f out.csv out.json
  "$daylit" df --components sc "$@" --out out.csv --summary out.json > stdout.txt 2> stderr.txt
  local status=$?
  if [ "$status" -ne "$expected" ] || ! grep -q -- "$pattern" stderr.txt || [ -e out.csv ] || [ -e out.json ]; then
    fail "$what: status $status"
    cat stderr.txt
  else
    echo "ok   $what"
  fi
}
cp "$data/room.mtl" .
sed 's/^v 4.0 5.0 3.0$/v 4.0 5.0 3.O/' "$data/room.obj" > bad_number.obj
expect_failure "a bad number" 1 "bad_number.obj:14: expected a number for the z coordinate of vertex 7, found '3.O'" \
  --model bad_number.obj --grid "$room/grid.pts"
sed 's/^f 4 3 7 6$/f 4 3 7 16/' "$data/room.obj" > bad_index.obj
expect_failure "a face index out of range" 1 "bad_index.obj:19: vertex index 16 is out of range: 8 vertices are defined before this line" \
  --model bad_index.obj --grid "$room/grid.pts"
sed 's/^mtllib room.mtl$/mtllib gone.mtl/' "$data/room.obj" > no_mtl.obj
expect_failure "a missing .mtl" 1 "no_mtl.obj:2: mtllib 'gone.mtl': cannot read .*gone.mtl, and 7 faces take their material from it" \
  --model no_mtl.obj --grid "$room/grid.pts"
sed 's/^Kd 0.5 0.5 0.5$/Kd 0.5 0,5 0.5/' room.mtl > bad.mtl
sed 's/^mtllib room.mtl$/mtllib bad.mtl/' "$data/room.obj" > bad_mtl.obj
expect_failure "a bad number in the .mtl" 1 "bad.mtl:13: expected a number for the green value of Kd, found '0,5'" \
  --model bad_mtl.obj --grid "$room/grid.pts"
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0.2\nv 2 0 0\nv 0 1 0\nf 1 2 4 3 5\n' > warped.obj
expect_failure "a warped pentagon" 1 "warped.obj:6: face 'warped#1' is not planar" --model warped.obj --grid "$room/grid.pts"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > no_window.obj
expect_failure "no aperture" 1 "no_window.obj: no face is an aperture" --model no_window.obj --grid "$room/grid.pts"
expect_failure "an OBJ without --grid" 1 "an OBJ model carries no sensor grids: give --grid" --model "$data/room.obj"
printf '{"materials": {"wall_mat": {"role": "wall"}}}' > bad_role.json
expect_failure "a map with an unknown role" 1 "bad_role.json: materials.wall_mat.role: unknown role 'wall'" \
  --model "$data/room.obj" --obj-materials bad_role.json --grid "$room/grid.pts"
expect_failure "an OBJ given as a .rad scene" 1 "this is a Wavefront OBJ model .* give it with --model" \
  --scene "$data/room.obj" --apertures "$room/apertures.rad" --grid "$room/grid.pts"
expect_failure "--obj-scale without an OBJ model" 2 "--obj-scale.* applies to an OBJ model" \
  --scene "$room/scene.rad" --apertures "$room/apertures.rad" --grid "$room/grid.pts" --obj-scale 0.001
expect_failure "--obj-up x" 2 "--obj-up" --model "$data/room.obj" --grid "$room/grid.pts" --obj-up x
expect_failure "--obj-scale 0" 2 "--obj-scale" --model "$data/room.obj" --grid "$room/grid.pts" --obj-scale 0

# A Radiance `mesh` primitive, read from the OBJ it was compiled from (obj2mesh; daylit does not
# read the .rtm), placed by its transform arguments: an overhang above the room's window gives
# what the same overhang written as a polygon gives, byte for byte (the transform is exact here).
printf 'v 0 0 0\nv 0 1 0\nv 3 1 0\nv 3 0 0\nusemtl shade_mat\nf 1 2 3 4\n' > overhang.obj
{ cat "$samples/room/scene.rad"; printf 'void plastic shade_mat 0 0 5 .3 .3 .3 0 0\n'
  printf 'void mesh overhang 5 overhang.rtm -t 0.5 -1 2.6 0 0\n'; } > with_mesh.rad
{ cat "$samples/room/scene.rad"; printf 'void plastic shade_mat 0 0 5 .3 .3 .3 0 0\n'
  printf 'shade_mat polygon overhang.0 0 0 12 0.5 -1 2.6 0.5 0 2.6 3.5 0 2.6 3.5 -1 2.6\n'; } > with_polygon.rad
for s in mesh polygon; do
  "$daylit" df --scene "with_$s.rad" --apertures "$samples/room/apertures.rad" --grid "$samples/room/grid.pts" \
    --components all --element-size 3 --max-refinements 0 --threads 2 --out "overhang_$s.csv" 2> "stderr_$s.txt" ||
    fail "df with the overhang as a $s"
done
cmp -s overhang_mesh.csv overhang_polygon.csv || fail "a mesh's faces differ from the same polygon's"
grep -q "mesh 'overhang' read from its OBJ source overhang.obj: 1 face, transformed" stderr_mesh.txt ||
  fail "no notice of the mesh's OBJ source"
"$daylit" df --scene <(printf 'void mesh far 1 elsewhere.rtm 0 0\n') --apertures "$samples/room/apertures.rad" \
  --grid "$samples/room/grid.pts" --out none.csv 2> stderr.txt
if [ $? -ne 1 ] || [ -e none.csv ] || ! grep -q "elsewhere.obj" stderr.txt; then fail "a mesh without its OBJ"; fi
echo "ok   mesh primitives from their OBJ source"

echo "$failures failures"
[ "$failures" -eq 0 ]
