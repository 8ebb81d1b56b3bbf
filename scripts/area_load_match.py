"""Compare two models' normal-load curves at the same A/A0 (used by the bench-fem-kappa scripts).

A fitted low-pressure kappa depends on the loads it was fitted at: A/A0 / sigma* falls with the
load (on a 100 x 100 patch from 3.0 at 1.4 % contact to 2.3 at 10 %), so two models pressed to
different loads must be compared point by point, at the same contact fraction.
"""


def normal_points(run):
    """(A/A0, A/A0 / sigma*) of the converged normal steps of a `contact --json` record."""
    return [(s["area_fraction"], s["area_fraction"] / s["sigma_star"]) for s in run["steps"]
            if s["ux"] == 0 and s["converged"] and s["sigma_star"] > 0]


def interpolate(curve, area):
    """A/A0 / sigma* of `curve` (rising A/A0) at `area`, linear between its points; None outside."""
    for (a0, k0), (a1, k1) in zip(curve, curve[1:]):
        if a0 <= area <= a1:
            return k0 + (k1 - k0) * (area - a0) / (a1 - a0)
    return None


def matched(run, reference):
    """[(A/A0, run's A/A0 / sigma*, reference's at that A/A0 or None)] over the run's normal steps."""
    curve = normal_points(reference)
    return [(a, k, interpolate(curve, a)) for a, k in normal_points(run)]
