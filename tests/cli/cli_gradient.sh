#!/usr/bin/env bash
# `daylit df --gradient` and `--refine` on the office sample: the gradient columns agree with
# Richardson-extrapolated central differences of the daylight factor computed by daylit itself at
# displaced sensors, and refinement adds 2×2 sensors per split cell, writes them with their cell
# areas, and reports the estimated error of the grid's mean DF falling.
set -eu
daylit=$1
samples=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
dir=$samples/office
# The gradient is of the sky component: --components sc (reflections refuse --gradient).
model=(--scene "$dir/scene.rad" --apertures "$dir/apertures.rad" --components sc)

# Sensors at p (which sees the sky through the glazed window, past its reveals) and at p ± h, p ± h/2
# along each axis, h = 1e-3 m: the extrapolated differences are good to ~1e-10 (h⁴ truncation,
# rounding u·DF/h), far below the gradient's stated 1e-7.
python3 - "$work/fd.pts" <<'PY'
import sys
p, h = (3.25, 0.35, 0.85), 1e-3
rows = [p]
for a in range(3):
    for s in (h, -h, h / 2, -h / 2):
        q = list(p); q[a] += s; rows.append(q)
with open(sys.argv[1], "w") as f:
    for q in rows: f.write("%.17g %.17g %.17g 0 0 1\n" % tuple(q))
PY
"$daylit" df "${model[@]}" --grid "$work/fd.pts" --gradient --out "$work/fd.csv" --quiet
python3 - "$work/fd.csv" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert list(rows[0].keys())[-3:] == ["ddf_dx", "ddf_dy", "ddf_dz"], rows[0].keys()
df = [float(r["df_percent"]) for r in rows]
g = [float(rows[0][k]) for k in ("ddf_dx", "ddf_dy", "ddf_dz")]
h = 1e-3
fd = []
for a in range(3):
    f = df[1 + 4 * a: 5 + 4 * a]
    d1, d2 = (f[0] - f[1]) / (2 * h), (f[2] - f[3]) / h
    fd.append((4 * d2 - d1) / 3)
err = math.dist(g, fd) / math.hypot(*g)
print("DF %.6g %%, gradient %s, differences %s, relative difference %.2g" % (df[0], g, fd, err))
assert df[0] > 1 and err < 1e-7, err
PY

# Refinement of the whole grid.
"$daylit" df "${model[@]}" --grid "$dir/grid.pts" --refine --out "$work/refined.csv" --summary "$work/refined.json" \
  2> "$work/stderr.txt"
grep -q "estimated error of the mean" "$work/stderr.txt"
python3 - "$work/refined.csv" "$work/refined.json" <<'PY'
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1])))
f = json.load(open(sys.argv[2]))["grids"][0]["refinement"]
assert list(rows[0].keys())[-5:] == ["ddf_dx", "ddf_dy", "ddf_dz", "added", "cell_area"]
added = [r for r in rows if r["added"] == "1"]
split = [r for r in rows if r["added"] == "0" and float(r["cell_area"]) == 0]
assert len(rows) - len(added) == 2400
assert len(added) == f["sensors_added"] == 4 * f["cells_split"] == 4 * len(split) > 0, (len(added), f)
# The refined mean is the area-weighted mean of what the CSV says.
area = sum(float(r["cell_area"]) for r in rows)
mean = sum(float(r["cell_area"]) * float(r["df_percent"]) for r in rows) / area
assert abs(mean - f["mean_df_percent"]["after"]) <= 1e-12 * mean, (mean, f)
e = f["estimated_error_of_mean_df_percent"]
print("cells split %d, mean DF %.6f -> %.6f %%, estimated error %.3g -> %.3g %%" %
      (f["cells_split"], f["mean_df_percent"]["before"], f["mean_df_percent"]["after"], e["before"], e["after"]))
assert 0 < e["after"] < e["before"]
PY
echo "ok"
