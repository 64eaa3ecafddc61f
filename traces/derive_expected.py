#!/usr/bin/env python3
"""Writes traces/fig7-*.expected.json for the Figure 7 traces.

The image hashes are regression locks: taken from a run (counters.json given on the
command line), checked elsewhere by the programs' tests (levels on the edges scene, the
same-samples transcription check). Every counter listed is derived here by hand from
the program's structure (docs/programs.md), not copied from the run:
pixel rectangles W*H, map copies M*M, convolution taps M*M*9, accumulation W*H per
operation, clears per plane, ramp and texture bits at their internal widths.

usage: derive_expected.py PROGRAM FILTER BITS counters.json > NAME.expected.json
"""
import json
import sys

W, H, M = 800, 600, 512


def sized(bits):
    return 4 if bits <= 4 else 8 if bits <= 8 else 12 if bits <= 12 else 16


def passes(program, n, bits):
    px, mp = W * H, M * M
    out = [{"label": "(unmarked)",
            "counters": {"pixels_transferred": 2 ** bits, "texture_bits_written": 2 ** bits * sized(bits)}}]
    rgba_copy = {"pixels_read": mp, "texture_bits_written": mp * 4 * sized(bits)}
    camera = {"label": "camera depth", "counters": {"clears": 1, "clear_pixels": 2 * px}}
    test = {"label": "shadow test", "counters": {}}
    count = {"label": "count", "counters": {"pixels_transferred": px, "pixels_read": px, "pixels_drawn": px,
                                            "color_table_lookups": px, "pixels_color_matrix": px,
                                            "fragments_generated": px}}
    if program == "shadow-map":
        out += [{"label": "shadow map", "counters": {"clears": 1, "clear_pixels": 2 * mp}},
                {"label": "copy to texture", "counters": {"pixels_read": mp, "texture_bits_written": mp * sized(bits)}},
                camera, test,
                {"label": "threshold", "counters": {"pixels_transferred": px, "pixels_read": px, "pixels_drawn": px,
                                                    "fragments_generated": px}}]
    elif program == "pcf":  # 2x2: one RGBA map of four channel passes
        for c in "RGBA":
            out.append({"label": f"shadow map 0 {c}",
                        "counters": {"clears": 1, "clear_pixels": (2 if c == "R" else 1) * mp}})
        out += [{"label": "copy to texture", "counters": rgba_copy}, camera, test, count]
    else:  # fast-pcf
        phases = 4 if n == 4 else 1
        out.append({"label": "shadow map", "counters": {"clears": 1, "clear_pixels": 2 * mp}})
        for _ in range(phases):
            out.append({"label": "copy to texture (packing convolution)",
                        "counters": dict(rgba_copy, pixels_convolved=mp, convolution_taps=9 * mp)})
        for p in range(phases):
            out += [camera, test, count]
            if phases > 1:
                out.append({"label": "accumulate",
                            "counters": {"accum_load_pixels" if p == 0 else "accum_accum_pixels": px}})
        if phases > 1:
            out.append({"label": "accumulate", "counters": {"accum_return_pixels": px}})
    out.append({"label": "final", "counters": {"clears": 1, "clear_pixels": px}})
    return out


def main():
    program, n, bits, counters = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
    run = json.load(open(counters))
    expected = {
        "_comment": "Image hashes: regression locks (checked by tests/programs_test.cpp through levels and the "
                    "same-samples reference). Counters: derived by hand in traces/derive_expected.py.",
        "images": {img["name"]: img["hash"] for img in run["images"]},
        "passes": passes(program, n, bits),
        "gl_errors": 0,
    }
    json.dump(expected, sys.stdout, indent=1)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
