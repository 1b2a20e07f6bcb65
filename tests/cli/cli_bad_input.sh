#!/usr/bin/env bash
# Bad input to `daylit df`: a clear message naming the file (and line), a non-zero exit status, and
# no output file left behind; never a crash, a sanitizer report or a hang. Then what must work:
# repeated vertices and sensors on occluders; millions of lines in bounded memory; and `daylit
# eval` on garbage (answered line by line, errors naming file:line). The reader-level matrix is
# tests/geometry/test_bad_input.cpp.
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

# A clean failure: a status of 1 (input that cannot be used) or 2 (a command line that cannot be
# parsed), README "Exit codes" — not 0, not a signal, not the timeout's 124, not an internal
# error's 3 — and no sanitizer report.
clean_failure_status() {  # name, status
  if { [ "$2" -ne 1 ] && [ "$2" -ne 2 ]; } || grep -q -e "Sanitizer" -e "runtime error" stderr.txt; then
    echo "FAIL $1: exit status $2"; head -n 5 stderr.txt; failures=$((failures + 1))
  fi
}

expect_failure() {  # name, expected text in stderr, arguments...
  local name=$1 expected=$2
  shift 2
  rm -f out.csv summary.json plan.png
  timeout 120 "$daylit" df --components sc "$@" --summary summary.json --image plan.png --quiet 2> stderr.txt
  local status=$?
  clean_failure_status "$name" "$status"
  if LC_ALL=C grep -q '[^[:print:][:space:]]' stderr.txt; then echo "FAIL $name: unprintable bytes in stderr"; failures=$((failures + 1)); fi
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
# (A sensor that sees the sky directly needs none: this one faces down.)
printf '1 2 0.85 0 0 -1\n' > down.pts
expect_failure "no apertures" "no apertures" --scene window.rad --grid down.pts --out out.csv
# No sensors at all (neither --grid nor --model) is a command line that cannot be run: exit 2.
"$daylit" df --components sc --apertures window.rad --out out.csv --quiet 2> stderr.txt
status=$?
[ "$status" -eq 2 ] || { echo "FAIL no --grid or --model: exit status $status, not 2"; failures=$((failures + 1)); }
grep -q -- "--grid or --model" stderr.txt || { echo "FAIL no --grid or --model: stderr"; cat stderr.txt; failures=$((failures + 1)); }
[ ! -e out.csv ] || { echo "FAIL no --grid or --model: output left behind"; failures=$((failures + 1)); }
printf 'void polygon bow 0 0 12 0 0 1 2 0 2.5 2 0 1 0 0 2\n' > bowtie.rad
expect_failure "self-intersecting polygon" "bowtie.rad:1" --apertures bowtie.rad --grid grid.pts --out out.csv
expect_failure "output directory missing" "no-such-dir" --apertures window.rad --grid grid.pts --out no-such-dir/x.csv

# Truncated files, binary garbage (deterministic bytes, NUL included), huge numbers, NaN and Inf,
# warped and degenerate polygons.
printf 'void polygon w\n0\n0\n12\n0 0 1\n2 0 1\n2 0' > truncated.rad
expect_failure "file truncated inside a primitive" "truncated.rad:1:" --apertures truncated.rad --grid grid.pts --out out.csv
printf '1 2 0.85 0 0 1\n1 2 0.85 0 0' > truncated.pts
expect_failure "grid truncated inside a line" "truncated.pts:2:" --apertures window.rad --grid truncated.pts --out out.csv
perl -e 'srand(7); print map { chr(int(rand(256))) } 1 .. 4096' > garbage.rad
expect_failure "binary garbage scene" "garbage.rad:[0-9]*:" --scene garbage.rad --apertures window.rad --grid grid.pts --out out.csv
perl -e 'srand(8); print map { chr(int(rand(256))) } 1 .. 4096' > garbage.pts
expect_failure "binary garbage grid" "garbage.pts:[0-9]*:" --apertures window.rad --grid garbage.pts --out out.csv
printf '1 2 0.85 0 0 1\n1 2 0.85 0 0 1\0 3\n' > nul.pts
expect_failure "NUL byte in a grid" "nul.pts:2:.*x00" --apertures window.rad --grid nul.pts --out out.csv
printf 'void polygon w 0 0 12\n0 0 1\n2 0 1\n2 0 2\n0 0 1e308\n' > huge.rad
expect_failure "coordinate beyond 1e12" "huge.rad:5:.*beyond 1e12" --apertures huge.rad --grid grid.pts --out out.csv
printf 'void polygon w 0 0 12 0 0 1 2 0 1 2 0 2 0 0 1e400\n' > overflow.rad
expect_failure "number beyond double" "overflow.rad:1:.*out of range" --apertures overflow.rad --grid grid.pts --out out.csv
printf 'void glass g 0 0 3 1e308 1e308 1e308\ng polygon w 0 0 12 0 0 1 2 0 1 2 0 2 0 0 2\n' > glass.rad
expect_failure "glass transmissivity 1e308" "glass.rad:1:.*transmissivity" --apertures glass.rad --grid grid.pts --out out.csv
printf '1 2 0.85 0 0 1\n1e308 2 0.85 0 0 1\n' > huge.pts
expect_failure "sensor beyond 1e12" "huge.pts:2:.*beyond 1e12" --apertures window.rad --grid huge.pts --out out.csv
printf '1 2 0.85 0 0 -Infinity\n' > ninf.pts
expect_failure "-Infinity direction" "ninf.pts:1:.*non-finite" --apertures window.rad --grid ninf.pts --out out.csv
printf 'void polygon warp 0 0 12 0 0 1 2 0 1 2 0.01 2 0 0 2\n' > warp.rad
expect_failure "non-planar polygon (beyond 1e-4 of its extent)" "warp.rad:1:.*not planar" --apertures warp.rad --grid grid.pts --out out.csv
printf 'void polygon line 0 0 9 0 0 1 1 0 1 3 0 1\n' > line.rad
expect_failure "zero-area polygon" "line.rad:1:.*zero area" --scene line.rad --apertures window.rad --grid grid.pts --out out.csv
printf 'void plastic black 0 0 5 0 0 0 0 0\nblack polygon star 0 0 15 0 0 0 2 0 3 4 0 0 0 0 2 4 0 2\n' > star.rad
expect_failure "self-intersecting occluder" "star.rad:2:" --scene star.rad --apertures window.rad --grid grid.pts --out out.csv

# And a good run writes all three.
"$daylit" df --components sc --apertures window.rad --grid grid.pts --out out.csv --summary summary.json --image plan.png --quiet
if [ $? -ne 0 ] || [ ! -s out.csv ] || [ ! -s summary.json ] || [ ! -s plan.png ]; then
  echo "FAIL good run"; failures=$((failures + 1))
fi
if grep -qi nan out.csv; then echo "FAIL good run printed NaN"; failures=$((failures + 1)); fi

# The plan image's scale: a range whose bottom is not below its top, or a log scale from 0, is
# refused before any work; the scale options without --image are a command-line error.
expect_failure "image range upside down" "--image-range 5 1: the bottom must be below the top" --apertures window.rad --grid grid.pts \
  --out out.csv --image-range 5 1
expect_failure "log image from 0" "a log scale needs a bottom above 0" --apertures window.rad --grid grid.pts --out out.csv \
  --image-scale log --image-range 0 10
"$daylit" df --components sc --apertures window.rad --grid grid.pts --out out.csv --image-contours 1 --quiet 2> stderr.txt
status=$?
if [ $status -ne 2 ] || ! grep -q -- "--image-contours requires --image" stderr.txt; then
  echo "FAIL --image-contours without --image: status $status"; cat stderr.txt; failures=$((failures + 1))
fi
"$daylit" df --components sc --apertures window.rad --grid grid.pts --out out.csv --summary summary.json --image log.png \
  --image-scale log --image-range 0.1 100 --image-contours 1 2 5 --quiet
if [ $? -ne 0 ] || [ ! -s log.png ]; then echo "FAIL log image with contours"; failures=$((failures + 1)); fi

# Repeated consecutive vertices are dropped with a notice, and change nothing; a sensor on an
# occluder polygon (a table top, in its plane) sees what it would without it.
printf 'void polygon window 0 0 21 0 0 1  2 0 1  2 0 1  2 0 2  0 0 2  0 0 2  0 0 1\n' > repeats.rad
"$daylit" df --components sc --apertures repeats.rad --grid grid.pts --out repeats.csv 2> stderr.txt
if ! grep -q "notice: repeats.rad:1: dropped repeated consecutive vertices" stderr.txt; then
  echo "FAIL repeated vertices: no notice"; cat stderr.txt; failures=$((failures + 1))
fi
"$daylit" df --components sc --apertures window.rad --grid grid.pts --out plain.csv --quiet
if [ "$(cut -d, -f2- repeats.csv)" != "$(cut -d, -f2- plain.csv)" ]; then echo "FAIL repeated vertices change the result"; failures=$((failures + 1)); fi
printf 'void plastic black 0 0 5 0 0 0 0 0\nblack polygon table 0 0 12 0 0.5 0.85  2 0.5 0.85  2 3 0.85  0 3 0.85\n' > table.rad
"$daylit" df --components sc --scene table.rad --apertures window.rad --grid grid.pts --out table.csv --quiet
# The sensor stands in the open beside the window: it sees the whole sky directly (SC 100 %), past
# the box around the model, which the table enlarges: the same regions in other pieces, so equal
# to roundoff (1e-12), not bit for bit.
if ! paste -d, table.csv plain.csv | awk -F, 'NR > 1 { d = $9 - $19; if (d < 0) d = -d; if (d > 1e-12 * $19 || $19 != $19 || $9 < 99.9999999999) bad = 1 } END { exit bad }'; then
  echo "FAIL sensor on a table top"; failures=$((failures + 1))
fi
echo "ok   repeated vertices and sensors on occluders"

# Millions of lines. Memory must stay proportional to the sensors (the grid is streamed, not
# held as text): the growth of the peak from 20,000 to 2 million sensors below 200 bytes per added
# sensor (measured: 149 MB peak for 2 million sensors in the normal build, 7 MB at start-up).
# Growth, not the peak, because under ASan the start-up alone now takes 426 MB (`daylit
# --version`; the sanitizer build links OpenImageIO at start, see cli/CMakeLists.txt), as eval's
# check below does; ASan's quarantine is capped so that the bound holds under the sanitizers too.
# A file that is not a grid fails at its first line without being read to the end; a bad last
# line is named.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}quarantine_size_mb=16"
lines=2000000
awk -v n=$lines 'BEGIN { for (i = 0; i < n; ++i) printf "%d.%d %d.%d 0.85 0 0 -1\n", i % 1000, i % 7, int(i / 1000) % 1000, i % 11 }' > big.pts
if [ -x /usr/bin/time ]; then
  head -n 20000 big.pts > small.pts
  /usr/bin/time -f '%M' -o rss_small.txt timeout 300 "$daylit" df --components sc --apertures window.rad --grid small.pts --quiet > small.csv 2> stderr.txt
  small_kb=$(tail -n 1 rss_small.txt)
  /usr/bin/time -f '%M' -o rss.txt timeout 300 "$daylit" df --components sc --apertures window.rad --grid big.pts --quiet > big.csv 2> stderr.txt
  status=$?
  rss_kb=$(tail -n 1 rss.txt)
  bound_kb=$(( (200 * (lines - 20000)) / 1024 + small_kb ))
  rows=$(wc -l < big.csv)
  if [ "$status" -ne 0 ] || [ "$rows" -ne $((lines + 1)) ]; then echo "FAIL 2 million sensors: status $status, $rows rows"; failures=$((failures + 1)); fi
  if [ "$rss_kb" -gt "$bound_kb" ]; then echo "FAIL 2 million sensors: peak RSS $rss_kb kB > $bound_kb kB"; failures=$((failures + 1)); fi
  echo "ok   2 million sensors: peak RSS $rss_kb kB (bound $bound_kb kB)"
else
  echo "skip 2 million sensors: /usr/bin/time is missing (scripts/setup.sh installs it)"
fi
rm -f big.csv
perl -e 'srand(9); print map { chr(int(rand(256))) } 1 .. 64' > huge_garbage.pts
cat big.pts >> huge_garbage.pts
start=$(date +%s)
expect_failure "2 million lines of garbage fail at the first" "huge_garbage.pts:[0-9]:" --apertures window.rad --grid huge_garbage.pts --out out.csv
if [ $(( $(date +%s) - start )) -gt 10 ]; then echo "FAIL garbage grid: not fast"; failures=$((failures + 1)); fi
printf '1 2 0.85 0 0 x\n' >> big.pts
expect_failure "bad line 2000001 of a grid" "big.pts:2000001:" --apertures window.rad --grid big.pts --out out.csv
awk -v n=$lines 'BEGIN { for (i = 1; i < n; ++i) print "# comment line " i; print "void instance tree 1 tree.oct 0 0" }' > big.rad
expect_failure "unsupported primitive at line 2000000" "big.rad:2000000:.*instance" --scene big.rad --apertures window.rad --grid grid.pts --out out.csv
rm -f big.pts big.rad huge_garbage.pts

# Numeric options: NaN, infinity and values out of range are refused in one line that names the
# option and the range (CLI11's own checks let "nan" through and print DBL_MAX in 309 digits).
expect_failure "NaN tolerance" "reflection-tolerance: nan is not a finite number > 0" --apertures window.rad --grid grid.pts --out out.csv --reflection-tolerance nan
expect_failure "zero element size" "element-size: 0 is not a finite number > 0" --apertures window.rad --grid grid.pts --out out.csv --element-size 0
expect_failure "infinite ground reflectance" "ground-reflectance: inf is not a finite number in \\[0, 0.999999\\]" --apertures window.rad --grid grid.pts --out out.csv --ground-reflectance inf
expect_failure "negative threads" "threads: -1 is not a finite number >= 0" --apertures window.rad --grid grid.pts --out out.csv --threads -1
if grep -q "179769313486" stderr.txt; then echo "FAIL negative threads: DBL_MAX printed"; failures=$((failures + 1)); fi

# `daylit eval` on garbage: every line answered in order (one line each, the run goes on),
# errors about the text naming file and line; a line over 1 MiB is refused without being kept;
# 2 million lines in bounded memory.
query='{"id":1,"quantity":"moment","region":{"polygon":[[0,0,1],[1,0,1],[1,1,1],[0,1,1]],"origin":[0,0,0]}}'
{
  echo "$query"
  perl -e 'srand(10); print map { chr } grep { $_ != 10 } map { int(rand(256)) } 1 .. 200'; echo
  printf '{"id":2,"quantity":"moment","region":{"polygon":[[0,0,1e400],[1,0,1],[1,1,1]],"origin":[0,0,0]}}\n'
  printf '{"id":3,"quantity":5}\n'
  printf '{"id":4,"x":"\xff\xfe"}\n'
  perl -e 'print "[" x 100000, "]" x 100000, "\n"'
  perl -e 'print "{\"id\":5,\"pad\":\"", "x" x 1100000, "\"}\n"'
  printf '%s' "$query"
} > garbage.jsonl
timeout 60 "$daylit" eval garbage.jsonl > answers.jsonl 2> stderr.txt
status=$?
if [ "$status" -ne 0 ] || grep -q -e "Sanitizer" -e "runtime error" stderr.txt; then echo "FAIL eval garbage: status $status"; cat stderr.txt; failures=$((failures + 1)); fi
answers=$(wc -l < answers.jsonl)
if [ "$answers" -lt 8 ]; then echo "FAIL eval garbage: $answers answers"; failures=$((failures + 1)); fi
for expected in '"value":0.52359877559829' 'garbage.jsonl:2: invalid JSON' 'garbage.jsonl:3: invalid JSON.*1e400' \
                 '"id":3' 'garbage.jsonl:5: invalid JSON' 'garbage.jsonl:6: invalid query.*nested' 'garbage.jsonl:7: line longer'; do
  if ! grep -q -- "$expected" answers.jsonl; then echo "FAIL eval garbage: no answer matching $expected"; failures=$((failures + 1)); fi
done
if [ "$(tail -n 1 answers.jsonl | grep -c '"value"')" -ne 1 ]; then echo "FAIL eval garbage: the last query was not answered"; failures=$((failures + 1)); fi
echo "ok   eval garbage: $answers answers"
# Bounded memory is judged by growth: the peak RSS of 2 million lines over that of 20,000 lines of
# the same kind. The sanitizers' own start-up (about 130 MB under ASan, 7 MB without) cancels, and
# 40 MB is ASan's capped quarantine (16 MB) and allocator caches with room to spare (measured:
# 28 MB under ASan, 0 without), while keeping as little as 20 bytes per line would add 40 MB.
measure_eval_peak_rss() {  # lines; sets peak_rss_kb
  awk -v n="$1" -v q="$query" 'BEGIN { for (i = 0; i < n; ++i) print (i % 10000 == 0 ? q : "") }' > big.jsonl
  /usr/bin/time -f '%M' -o rss.txt timeout 300 "$daylit" eval big.jsonl > answers.jsonl 2> stderr.txt
  local status=$?
  if [ "$status" -ne 0 ] || [ "$(wc -l < answers.jsonl)" -ne $(($1 / 10000)) ]; then echo "FAIL eval $1 lines: status $status"; failures=$((failures + 1)); fi
  peak_rss_kb=$(tail -n 1 rss.txt)
}
if [ -x /usr/bin/time ]; then
  measure_eval_peak_rss 20000
  small_rss_kb=$peak_rss_kb
  measure_eval_peak_rss $lines
  rss_kb=$peak_rss_kb
  growth_kb=$((rss_kb - small_rss_kb))
  if [ "$growth_kb" -gt $((40 * 1024)) ]; then echo "FAIL eval 2 million lines: peak RSS grew by $growth_kb kB"; failures=$((failures + 1)); fi
  echo "ok   eval 2 million lines: peak RSS $rss_kb kB, $growth_kb kB over 20,000 lines"
fi
rm -f big.jsonl answers.jsonl

# Outputs that are not plain files. A FIFO (as /dev/null or /dev/stdout are devices) is written
# in place, not replaced by a renamed file: as root, renaming onto /dev/null turned it into a
# plain file. A symbolic link keeps linking and the file it names gets the results.
mkfifo out.fifo
cat out.fifo > fifo.txt &
reader=$!
"$daylit" df --components sc --scene window.rad --apertures window.rad --grid grid.pts --out out.fifo --quiet 2> stderr.txt
status=$?
# The reader ends at the writer's end of file; had daylit replaced the FIFO, it would wait forever.
for _ in $(seq 50); do kill -0 "$reader" 2> /dev/null || break; sleep 0.1; done
kill "$reader" 2> /dev/null
wait "$reader" 2> /dev/null
if [ "$status" -ne 0 ] || [ ! -p out.fifo ] || ! grep -q "^grid,index" fifo.txt; then
  echo "FAIL --out to a FIFO: status $status; still a FIFO: $([ -p out.fifo ] && echo yes || echo no)"; failures=$((failures + 1))
fi
mkdir results && ln -s results/df.csv link.csv
"$daylit" df --components sc --scene window.rad --apertures window.rad --grid grid.pts --out link.csv --quiet 2> stderr.txt
status=$?
if [ "$status" -ne 0 ] || [ ! -L link.csv ] || ! grep -q "^grid,index" results/df.csv; then
  echo "FAIL --out to a symbolic link: status $status; still a link: $([ -L link.csv ] && echo yes || echo no)"; failures=$((failures + 1))
fi
"$daylit" df --components sc --scene window.rad --apertures window.rad --grid grid.pts --out results --quiet 2> stderr.txt
status=$?
clean_failure_status "--out to a directory" "$status"
grep -q "results: is a directory" stderr.txt || { echo "FAIL --out to a directory: $(head -n 1 stderr.txt)"; failures=$((failures + 1)); }
echo "$failures failures"
[ "$failures" -eq 0 ]
