#!/bin/sh
# Issue 55, bar 4: the speed constant Sp predicted by the wet-at-speed model (hysteresis friction
# under the E274 water film) over the thesis's datasets A-C, with both E274 tyres, against PIARC's
# regression Sp = 14.2 + 89.7 MPD (ASTM E1960). One hysteresis roughness sweep per dataset and
# tyre (300 x 300 surfaces, REALIZATIONS realizations each, flash temperature on), then a table
# per sweep: MPD, predicted SN40 and Sp (median over realizations), E1960's Sp, their ratio, and
# the film's drain time against the time under the tyre at 64 km/h.
# Usage: scripts/validate-speed-constant.sh [BIN] [OUT] [REALIZATIONS]
set -eu
BIN=${1:-build/bin/wetroad}
OUT=${2:-build/validate-speed-constant}
REAL=${3:-10}
mkdir -p "$OUT"
for tyre in e274-ribbed e274-smooth; do
  for ds in A B C; do
    f="$OUT/$ds-$tyre"
    rm -rf "$f.h5" "$f.h5.runs"
    start=$(date +%s)
    "$BIN" sweep-roughness --dataset "$ds" --realizations "$REAL" --model hysteresis --flash-temperature --test "$tyre" \
      --out "$f.h5" --json "$f.json" -q
    echo "dataset $ds, $tyre: $(( $(date +%s) - start )) s"
  done
done
python3 - "$OUT" <<'PY'
import json, sys, statistics, glob, os, math
out = sys.argv[1]
for path in sorted(glob.glob(os.path.join(out, "*.json"))):
    j = json.load(open(path))
    groups = {}
    for r in j["runs"]:
        if r.get("status") != "ok": continue
        groups.setdefault(r["label"], []).append(r)
    print(f"\n{os.path.basename(path)[:-5]}")
    print(f"  {'surfaces':<14} {'MPD mm':>7} {'SN40':>6} {'Sp model':>9} {'Sp E1960':>9} {'ratio':>6} {'drain ms':>9} {'patch ms':>9}")
    for label, rs in groups.items():
        mpd = statistics.median(1e3 * r["mpd"] for r in rs)
        sn = statistics.median(r["contact"]["sn"] for r in rs)
        sps = [r["contact"]["sp_kmh"] if r["contact"]["sp_kmh"] is not None else math.inf for r in rs]
        sp = statistics.median(sps)
        dr = [r["contact"]["drain_time"] if r["contact"]["drain_time"] is not None else math.inf for r in rs]
        e = 14.2 + 89.7 * mpd
        print(f"  {label:<14} {mpd:7.3f} {sn:6.1f} {sp:9.0f} {e:9.1f} {sp / e:6.2f} {1e3 * statistics.median(dr):9.3g} "
              f"{1e3 * rs[0]['contact']['patch_time']:9.3g}")
PY
