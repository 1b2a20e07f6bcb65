#!/usr/bin/env bash
# The bundled samples run, exactly and in floating point, and give finite daylight factors.
set -eu
daylit=$1
samples=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for sample in office hall; do
  dir=$samples/$sample
  for geometry in exact float; do
    "$daylit" df --scene "$dir/scene.rad" --apertures "$dir/apertures.rad" --grid "$dir/grid.pts" \
      --geometry "$geometry" --out "$work/$sample-$geometry.csv" --summary "$work/$sample-$geometry.json" --quiet
    if grep -qi nan "$work/$sample-$geometry.csv"; then echo "NaN in $sample ($geometry)"; exit 1; fi
  done
  # Exact and float agree to roundoff on these well-conditioned scenes (largest relative deviation).
  paste -d, "$work/$sample-exact.csv" "$work/$sample-float.csv" | tail -n +2 | awk -F, -v s="$sample" '
    { d = $10 - $20; if (d < 0) d = -d; r = d / ($10 > 1e-300 ? $10 : 1); if (r > m) m = r }
    END { printf "%s: largest relative exact/float difference %.3g\n", s, m; if (m > 1e-9) exit 1 }'
done
