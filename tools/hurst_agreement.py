#!/usr/bin/env python3
"""Checks that sylva's Hurst fit of real elevation models agrees with an independent one.

For each model, runs `SYLVA terrain --analyse MODEL --report DIR` and
`tools/variogram_fit.py MODEL --json` (written apart, sharing no code or constants), prints
a table of the two H and their lag windows, and exits 1 if any pair differs by more than
the tolerance (0.1, the real-land issue's).

usage: tools/hurst_agreement.py SYLVA_BINARY MODEL... [--tolerance T]
(needs numpy, and tifffile for .tif models, in the Python that runs it)
"""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))


def main(argv):
    tolerance = 0.1
    if "--tolerance" in argv:
        i = argv.index("--tolerance")
        tolerance = float(argv[i + 1])
        del argv[i : i + 2]
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    sylva, models = argv[0], argv[1:]
    worst = 0.0
    print(f"{'model':34} {'sylva H':>8} {'(metres)':>16} {'independent H':>14} {'(samples)':>10} {'diff':>7}")
    for model in models:
        with tempfile.TemporaryDirectory() as report:
            subprocess.run(
                [sylva, "terrain", "--analyse", model, "--report", report, "--quiet"],
                check=True,
            )
            with open(os.path.join(report, "analysis.json"), encoding="utf-8") as f:
                ours = json.load(f)
        theirs = json.loads(
            subprocess.run(
                [sys.executable, os.path.join(HERE, "variogram_fit.py"), model, "--json"],
                check=True,
                capture_output=True,
                text=True,
            ).stdout
        )
        diff = ours["hurst"] - theirs["hurst"]
        worst = max(worst, abs(diff))
        lo, hi = ours["variogram_fit"]["scale_range_m"]
        a, b = theirs["lags_samples"]
        print(
            f"{os.path.basename(model):34} {ours['hurst']:8.3f} {lo:7.0f}..{hi:<7.0f} "
            f"{theirs['hurst']:14.3f} {a:4d}..{b:<4d} {diff:+7.3f}"
        )
    print(f"largest difference {worst:.3f} (tolerance {tolerance})")
    return 0 if worst <= tolerance else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
