#!/usr/bin/env python3
"""The octane-vpro8 profile's fitted cost rates, and how well they predict (docs/cost-model.md).

Runs `passim report cost --paper --json`, which fits the free rates (the ones no published
figure gives: triangles, plain pixel path, scale/bias, colour table and matrix, clears, texture
loads, per-pass overhead) with passim's own seeded search (fit_rates, reports/cost.cpp) and
predicts each of the paper's six published frame rates held out (fitted to the other five).
Prints the rates fitted to Figure 7's four (the profile's; to copy into pipeline/profile.cpp
when the model changes), the rates fitted to all six, and the held-out misses. One search,
in C++: this script only reads its result. Needs only Python 3.

usage: tools/fit_vpro_rates.py build/passim
"""
import json
import subprocess
import sys

UNITS = {"triangles": (1e6, "M/s"), "pixels": (1e6, "M/s"), "scale_bias": (1e6, "M/s"), "color_table": (1e6, "M/s"),
         "clear": (1e9, "G pixels/s"), "texture_load_bytes": (1e6, "MB/s"), "pass_overhead": (1e-6, "us")}


def main():
    passim = sys.argv[1] if len(sys.argv) > 1 else "build/passim"
    out = subprocess.run([passim, "report", "cost", "--paper", "--json", "--profile", "octane-vpro8"], check=True,
                         capture_output=True, text=True).stdout
    report = json.loads(out)
    for name, fit in report["fits"].items():
        print(f"fitted to {'Figure 7' if name == 'figure7' else 'all six published rates'}: "
              f"margin {100 * fit['margin']:+.1f} % (negative: outside a range)")
        for key, (scale, unit) in UNITS.items():
            print(f"  {key} = {fit[key] / scale:.3g} {unit}")
    print("held out (each rate predicted by the rates fitted to the other five):")
    for row in report["rows"]:
        print(f"  {row['what']:<34} published {row['published_low']:g}-{row['published_high']:g}: "
              f"{row['held_out']:.2f} fps ({100 * row['held_out_miss']:+.0f} %)")


if __name__ == "__main__":
    main()
