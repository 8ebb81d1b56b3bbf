#!/usr/bin/python3
"""MPD of wetroad against captif-slp (Waka Kotahi's ISO 13473-1:2019 implementation, checked by
its authors against the VTI reference MPDs of the ERPUG profiles to 0.1 %), on synthetic laser
texture records: 1.8 m at 0.0375 mm, clustered dropouts, spikes. Hand-run validation, not part of
`make test`; results in docs/validation.md.

Usage: CAPTIF=/path/to/captif-slp-checkout scripts/compare-mpd-captif.py build/bin/wetroad [N]
Needs Debian's python3-numpy, -scipy, -pandas, -matplotlib, -pydantic, -psutil; captif-slp's
pyrsona (file parsing) and unsync (parallel reads) are not used and are stubbed.
"""
import json, os, subprocess, sys, tempfile, types

import numpy as np
import pandas as pd

sys.modules.setdefault("pyrsona", types.SimpleNamespace(BaseStructure=object))
sys.modules.setdefault("unsync", types.SimpleNamespace(unsync=lambda f=None, **k: f if f else (lambda g: g)))
sys.path.insert(0, os.environ["CAPTIF"])
from captif_slp import Reading  # noqa: E402

DX_MM = 0.0375


def record(seed, n=48000):
    rng = np.random.default_rng(seed)
    x = np.arange(n) * DX_MM
    z = np.zeros(n)
    # Self-affine texture: random-phase waves from 0.3 to 60 mm, amplitude ~ wavelength^0.8.
    for lam in np.geomspace(0.3, 60, 120):
        z += 0.035 * lam ** 0.8 * np.sin(2 * np.pi * x / lam + rng.uniform(0, 2 * np.pi)) * rng.uniform(0.5, 1.5)
    z *= rng.uniform(0.4, 1.6) / z.std()
    z += 0.5 * np.sin(2 * np.pi * x / 900 + rng.uniform(0, 6))  # unevenness
    drop = np.zeros(n, bool)
    for start in rng.integers(0, n, size=400):  # ~10 % dropouts in runs
        drop[start:start + rng.integers(1, 25)] = True
    spikes = rng.integers(0, n, size=30)
    z[spikes] += rng.choice([-6, 6], size=30)
    z[drop] = np.nan
    return x, np.round(z, 4)


def wetroad_mpd(binary, z, method):
    with tempfile.TemporaryDirectory() as d:
        txt = os.path.join(d, "p.txt")
        np.savetxt(txt, z[None, :], fmt="%.4f")
        out = os.path.join(d, "p.json")
        subprocess.run([binary, "analyze", txt, "--dx", str(DX_MM * 1e-3), "--unit", "mm", "--keep-plates",
                        "--mpd-method", method, "--json", out, "-q"], check=True)
        j = json.load(open(out))
        return j["mpd"] * 1e3, j["mpd_detail"]


def captif_mpd(x, z, continuous):
    trace = pd.DataFrame({"distance_mm": x, "relative_height_mm": z})
    r = Reading.from_trace(trace, evaluation_length_m=10.0 if continuous else None)
    m = r.mpd()
    return float(m["mpd"].iloc[0] if hasattr(m, "iloc") else m["mpd"]), r


def main():
    binary = sys.argv[1]
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 10
    worst = {"spot": 0.0, "continuous": 0.0}
    print(f"{'seed':>4} {'method':>10} {'wetroad mm':>11} {'captif mm':>10} {'diff %':>8} {'segments':>9}")
    for seed in range(count):
        x, z = record(seed)
        for method in ("spot", "continuous"):
            w, detail = wetroad_mpd(binary, z, method)
            c, _ = captif_mpd(x, z, method == "continuous")
            d = 100 * (w - c) / c
            worst[method] = max(worst[method], abs(d))
            print(f"{seed:>4} {method:>10} {w:>11.6f} {c:>10.6f} {d:>8.4f} "
                  f"{detail['valid_segments']:>4}/{detail['segments']}")
    print("largest |difference|: " + ", ".join(f"{k} {v:.4f} %" for k, v in worst.items()))


if __name__ == "__main__":
    main()
