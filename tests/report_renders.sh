#!/bin/sh
# the report of a sweep opens offline and shows every plot. Structural check: one
# HTML document, no external resource, five inline SVG charts, each well-formed XML (xmllint).
# Rendered check: every chart is rasterised by librsvg (rsvg-convert) into a non-trivial PNG.
# Usage: report_renders.sh WETROAD WORKDIR
set -eu
BIN=$1
W=$2
rm -rf "$W" && mkdir -p "$W"
export OMP_NUM_THREADS=1
"$BIN" sweep-coverage --scene default --size 16 --dx 1.875e-3 --coverages 0 0.3 0.6 --uz 3e-3 --ux 1.5e-3 \
  --steps 2 --shear-steps 2 --out "$W/sweep.h5" -q
printf 'site,mpd_mm,sn40r,speed_kmh\nA,0.4,45,64\nB,0.8,55,64\nC,1.2,52,64\n' > "$W/measured.csv"
"$BIN" report --sweep "$W/sweep.h5" --measured "$W/measured.csv" -o "$W/report.html" -q
R="$W/report.html"
head -c 15 "$R" | grep -q '<!DOCTYPE html>' || { echo "FAIL: not an HTML5 document"; exit 1; }
grep -q '</html>' "$R" || { echo "FAIL: truncated document"; exit 1; }
if grep -q 'src=' "$R"; then echo "FAIL: external resource (src=)"; exit 1; fi
if grep -o "href=['\"][^'\"#][^'\"]*" "$R" | grep -q .; then echo "FAIL: non-local link"; exit 1; fi
perl -0777 -ne 'my $n = 0; while (/(<svg.*?<\/svg>)/sg) { $n++; open(my $f, ">", "'"$W"'/chart$n.svg") or die; print $f $1; close $f }' "$R"
n=$(ls "$W"/chart*.svg | wc -l)
[ "$n" -eq 5 ] || { echo "FAIL: $n charts, expected 5"; exit 1; }
for s in "$W"/chart*.svg; do
  xmllint --noout "$s" || { echo "FAIL: $s is not well-formed"; exit 1; }
  rsvg-convert -o "${s%.svg}.png" "$s" || { echo "FAIL: $s does not render"; exit 1; }
  bytes=$(wc -c < "${s%.svg}.png")
  [ "$bytes" -gt 5000 ] || { echo "FAIL: ${s%.svg}.png is nearly empty ($bytes bytes)"; exit 1; }
done
echo "report: 5 charts, well-formed and rendered"
