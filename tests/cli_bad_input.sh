#!/usr/bin/env bash
# Bad input to `daylit df`: a clear message naming the file (and line), a non-zero exit status, and
# no output file left behind.
set -u
daylit=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0

cat > window.rad <<'RAD'
void polygon window 0 0 12 0 0 1  2 0 1  2 0 2  0 0 2
RAD
printf '1 2 0.85 0 0 1\n' > grid.pts

expect_failure() {  # name, expected text in stderr, arguments...
  local name=$1 expected=$2
  shift 2
  rm -f out.csv summary.json plan.png
  "$daylit" df "$@" --summary summary.json --image plan.png --quiet 2> stderr.txt
  local status=$?
  if [ "$status" -eq 0 ]; then echo "FAIL $name: exit status 0"; failures=$((failures + 1)); fi
  if ! grep -q -- "$expected" stderr.txt; then echo "FAIL $name: stderr lacks '$expected':"; cat stderr.txt; failures=$((failures + 1)); fi
  if ls out.csv summary.json plan.png .*partial* 2>/dev/null | grep -q .; then echo "FAIL $name: output left behind"; failures=$((failures + 1)); fi
  echo "ok   $name: $(head -n 1 stderr.txt)"
}

printf 'void polygon w 0 0 9 0 0 1 2 0 one 2 0 2\n' > malformed.rad
expect_failure "malformed number" "malformed.rad:1" --apertures malformed.rad --grid grid.pts --out out.csv
printf 'void polygon w\n0\n0\n6 0 0 1 2 0 1\n' > two_vertices.rad
expect_failure "fewer than 3 vertices" "two_vertices.rad:1" --apertures two_vertices.rad --grid grid.pts --out out.csv
printf 'void polygon w 0 0 9 0 0 1 2 0 NaN 2 0 2\n' > nan.rad
expect_failure "NaN coordinate" "nan.rad:1" --apertures nan.rad --grid grid.pts --out out.csv
printf '1 2 0.85 0 0 1\n1 2 inf 0 0 1\n' > inf.pts
expect_failure "infinite sensor coordinate" "inf.pts:2" --apertures window.rad --grid inf.pts --out out.csv
expect_failure "missing file" "missing.rad" --apertures missing.rad --grid grid.pts --out out.csv
: > empty.pts
expect_failure "empty grid" "empty.pts" --apertures window.rad --grid empty.pts --out out.csv
expect_failure "no apertures" "no apertures" --scene window.rad --grid grid.pts --out out.csv
printf 'void polygon bow 0 0 12 0 0 1 2 0 2.5 2 0 1 0 0 2\n' > bowtie.rad
expect_failure "self-intersecting polygon" "bowtie.rad:1" --apertures bowtie.rad --grid grid.pts --out out.csv
expect_failure "output directory missing" "no-such-dir" --apertures window.rad --grid grid.pts --out no-such-dir/x.csv

# And a good run writes all three.
"$daylit" df --apertures window.rad --grid grid.pts --out out.csv --summary summary.json --image plan.png --quiet
if [ $? -ne 0 ] || [ ! -s out.csv ] || [ ! -s summary.json ] || [ ! -s plan.png ]; then
  echo "FAIL good run"; failures=$((failures + 1))
fi
if grep -qi nan out.csv; then echo "FAIL good run printed NaN"; failures=$((failures + 1)); fi
echo "$failures failures"
[ "$failures" -eq 0 ]
