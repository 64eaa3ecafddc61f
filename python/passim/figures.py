"""passim's figures, drawn by matplotlib (docs/studies.md, "Figures").

The passim command runs this module (python3 -m passim.figures) to draw a study's figures and
the demo's figure7.png; the HTML report takes its SVGs from here too. It needs matplotlib (and
numpy) only, not passim's compiled module.

    python3 -m passim.figures study STUDY_DIR [--out DIR] [--formats png,svg,pdf]
    python3 -m passim.figures figure7 MANIFEST.json OUT.png

Every figure has its axes titled with units, markers on every series, a legend naming each
series (below the axes, in as many rows as the series need), integer ticks where the variable
is an integer and a logarithmic axis where the values span decades. The files are the same
bytes on every run (no dates; fixed SVG ids).
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle
    from matplotlib.ticker import MaxNLocator
except ImportError as error:  # the passim command turns exit status 3 into its message
    print(f"passim figures: matplotlib is not installed ({error}); Debian: apt-get install python3-matplotlib",
          file=sys.stderr)
    sys.exit(3)

plt.rcParams.update({
    "svg.hashsalt": "passim",   # the same element ids on every run
    "svg.fonttype": "none",     # text stays text: searchable, and the report's test reads it
    "font.size": 10,
    "axes.grid": True,
    "grid.alpha": 0.35,
    "lines.linewidth": 1.6,
    "lines.markersize": 5,
    "figure.dpi": 100,
})
_METADATA = {"png": {"Software": None}, "svg": {"Date": None}, "pdf": {"CreationDate": None, "ModDate": None}}
_MARKERS = ["o", "s", "^", "D", "v", "P", "X", "<", ">", "p", "h", "*"]

# Columns of study.json's rows (docs/studies.md defines each, with its unit).
BITS = "color_bits"


_DPI = [100]  # raster figures' resolution (--dpi)


def _save(fig, base: str, formats) -> list:
    written = []
    for fmt in formats:
        path = f"{base}.{fmt}"
        tmp = os.path.join(os.path.dirname(path) or ".", f".tmp-{os.path.basename(path)}")
        fig.savefig(tmp, format=fmt, metadata=_METADATA[fmt], bbox_inches="tight", dpi=_DPI[0])
        os.replace(tmp, path)  # whole or not at all, as passim's other files
        written.append(path)
    plt.close(fig)
    return written


def _style(k: int, n: int):
    """Series k of n: a colour from a qualitative map (tab10, tab20 past 10 series, then a
    sequential one), a marker of its own."""
    if n <= 10:
        colour = plt.get_cmap("tab10")(k % 10)
    elif n <= 20:
        colour = plt.get_cmap("tab20")(k % 20)
    else:
        colour = plt.get_cmap("viridis")(k / max(1, n - 1))
    return {"color": colour, "marker": _MARKERS[k % len(_MARKERS)]}


def _legend(ax, n: int):
    """The legend below the axes, in up to four columns: any number of series fits (the saved
    figure grows to hold it)."""
    if n <= 1:
        return
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=min(4, n), fontsize=9, frameon=False)


def _scale(ax, values, axis="y"):
    """Logarithmic where the positive values span more than a decade and a half (symlog when
    zeros occur: counts of pixels); linear otherwise."""
    positive = [v for v in values if v > 0]
    if len(positive) < 2 or max(positive) / min(positive) < 30:
        return "linear"
    setter = ax.set_yscale if axis == "y" else ax.set_xscale
    if len(positive) == len(values):
        setter("log")
        return "log"
    setter("symlog", linthresh=1.0)
    return "symlog"


def _integer_axis(axis):
    axis.set_major_locator(MaxNLocator(integer=True))


def _counts_axis(ax, values):
    """A linear axis of counts: from zero (a count's natural origin), with integer ticks — at
    least a few, even when every value is the same."""
    ax.set_ylim(0, max(3, max(values, default=0) * 1.08))
    _integer_axis(ax.yaxis)


def _label(ax, x: str, y: str, title: str = ""):
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    ax.xaxis.label.set_gid("x-title")  # the report's test finds the titles by these ids
    ax.yaxis.label.set_gid("y-title")
    if title:
        ax.set_title(title, fontsize=10)


def describe(sweep: dict) -> str:
    """"pcf 2×2 on edges (160×120)"; no footprint for programs without one."""
    f = int(sweep.get("filter", 0))
    program = sweep["program"] + (f" {f}×{f}" if f > 1 else "")
    if sweep["program"] == "mdsm" and int(sweep.get("depths", 1)) > 1:
        program += f", {sweep['depths']} depths"
    return f"{program} on {sweep['scene']} ({sweep['width']}×{sweep['height']})"


def _varying(rows, keys):
    return [k for k in keys if len({r[k] for r in rows}) > 1]


def _series_name(row, keys) -> str:
    names = {"depth_bits": "depth {} bits", "bias_8bit_steps": "bias {:g}", "map_size": "map {}²",
             BITS: "{} bits"}
    return ", ".join(names[k].format(row[k]) for k in keys)


def _groups(rows, keys):
    """Rows grouped by the values of `keys`, in sweep order."""
    groups = {}
    for r in rows:
        groups.setdefault(tuple(r[k] for k in keys), []).append(r)
    return list(groups.values())


# Metrics against the colour width: (file, y title, value, integer-valued).
def _misclassified(r):
    return r["lit_but_shadowed"] + r["shadowed_but_lit"]


METRICS = [
    ("error_vs_bits", "mean |attenuation error| (fraction of full shadow)", lambda r: r["mean_abs_error"], False,
     "mean absolute error against the algorithm in double precision"),
    ("precision_vs_bits", "precision (bits, −log₂ relative RMS error)", lambda r: r["precision_bits"], False,
     "precision against the algorithm in double precision"),
    ("levels_vs_bits", "shadow levels (distinct attenuation values)", lambda r: r["levels"], True,
     "shadow levels"),
    ("misclassified_vs_bits", "misclassified pixels (count)", _misclassified, True,
     "misclassified pixels against the double-precision reference"),
    ("light_leaks_vs_bits", "light leaks: shadowed pixels left lit (count)", lambda r: r["exact_shadowed_but_lit"],
     True, "light leaks against the exact shadow test"),
    ("self_shadowing_vs_bits", "self-shadowed pixels (count)", lambda r: r["exact_self_shadowed"], True,
     "self-shadowing (acne) against the exact shadow test"),
]


def plot_against_bits(rows, sweep, out_dir, formats, name, y_title, value, integer, title) -> list:
    others = _varying(rows, ["depth_bits", "bias_8bit_steps", "map_size"])
    groups = _groups(rows, others)
    fig, ax = plt.subplots(figsize=(7, 4.2))
    values = []
    for k, g in enumerate(groups):
        ys = [value(r) for r in g]
        values += ys
        ax.plot([r[BITS] for r in g], ys, label=_series_name(g[0], others) or "all points", **_style(k, len(groups)))
    scale = _scale(ax, values)
    _integer_axis(ax.xaxis)
    if integer and scale == "linear":
        _counts_axis(ax, values)
    _label(ax, "colour width (bits per channel)", y_title, f"{describe(sweep)}: {title}")
    _legend(ax, len(groups))
    return _save(fig, os.path.join(out_dir, name), formats)


def plot_against_bias(rows, sweep, out_dir, formats) -> list:
    """Self-shadowing (the exact test's acne) against the bias, one series per width (and per
    other swept setting)."""
    others = _varying(rows, [BITS, "depth_bits", "map_size"])
    groups = _groups(rows, others)
    fig, ax = plt.subplots(figsize=(7, 4.2))
    values = []
    for k, g in enumerate(groups):
        ys = [r["exact_self_shadowed"] for r in g]
        values += ys
        ax.plot([r["bias_8bit_steps"] for r in g], ys, label=_series_name(g[0], others), **_style(k, len(groups)))
    if _scale(ax, values) == "linear":
        _counts_axis(ax, values)
    _label(ax, "depth bias (8-bit steps of depth)", "self-shadowed pixels (count)",
           f"{describe(sweep)}: self-shadowing against the bias")
    _legend(ax, len(groups))
    return _save(fig, os.path.join(out_dir, "self_shadowing_vs_bias"), formats)


def plot_headline(rows, sweep, out_dir, formats) -> list:
    """The 8-vs-12-bit claim as measured: misclassified pixels, light leaks and self-shadowing
    against the bias, 8 bits beside 12 (one series per width and other swept setting)."""
    pair = [r for r in rows if r[BITS] in (8, 12)]
    others = _varying(pair, ["depth_bits", "map_size"])
    panels = [("misclassified pixels (count)", _misclassified, "misclassified (against the reference)"),
              ("light leaks (count)", lambda r: r["exact_shadowed_but_lit"], "light leaks (shadowed left lit)"),
              ("self-shadowed pixels (count)", lambda r: r["exact_self_shadowed"], "self-shadowing (acne)")]
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.0), layout="constrained")
    groups = _groups(pair, [BITS] + others)
    for ax, (y_title, value, title) in zip(axes, panels):
        values = []
        for k, g in enumerate(groups):
            ys = [value(r) for r in g]
            values += ys
            ax.plot([r["bias_8bit_steps"] for r in g], ys, label=_series_name(g[0], [BITS] + others),
                    **_style(k, len(groups)))
        if _scale(ax, values) == "linear":
            _counts_axis(ax, values)
        _label(ax, "depth bias (8-bit steps of depth)", y_title, title)
        if len({r["bias_8bit_steps"] for r in pair}) == 1:  # one bias: a point per width
            b = pair[0]["bias_8bit_steps"]
            ax.set_xlim(b - 1, b + 1)
    axes[1].legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=min(4, len(groups)), fontsize=9,
                   frameon=False)
    fig.suptitle(f"{describe(sweep)}: 8 against 12 bits", fontsize=11)
    return _save(fig, os.path.join(out_dir, "8_vs_12_bits"), formats)


def plot_edge_strip(rows, sweep, study_dir, out_dir, formats) -> list:
    """Each point's magnified shadow edge (edge-<index>.png), a row per setting other than the
    width, a column per width, each labelled."""
    present = [r for r in rows if os.path.exists(os.path.join(study_dir, f"edge-{r['index']}.png"))]
    if not present:
        return []
    others = _varying(present, ["depth_bits", "bias_8bit_steps", "map_size"])
    groups = _groups(present, others)
    columns = max(len(g) for g in groups)
    first = plt.imread(os.path.join(study_dir, f"edge-{present[0]['index']}.png"))
    h, w = first.shape[:2]
    cell = 1.9  # inches per cell's width
    fig, axes = plt.subplots(len(groups), columns, figsize=(cell * columns, cell * h / w * len(groups) + 0.9),
                             squeeze=False)
    for gi, g in enumerate(groups):
        for ci in range(columns):
            ax = axes[gi][ci]
            ax.set_xticks([])
            ax.set_yticks([])
            ax.grid(False)
            if ci >= len(g):
                ax.axis("off")
                continue
            r = g[ci]
            ax.imshow(plt.imread(os.path.join(study_dir, f"edge-{r['index']}.png")), interpolation="nearest")
            ax.set_title(f"{r[BITS]} bits", fontsize=10)
            if ci == 0 and others:
                ax.set_ylabel(_series_name(r, others), fontsize=9)
    fig.suptitle(f"{describe(sweep)}: one shadow edge per point (each pixel 4×4)", fontsize=11)
    return _save(fig, os.path.join(out_dir, "edge_strip"), formats)


def study_figures(study_dir: str, out_dir: str, formats) -> list:
    with open(os.path.join(study_dir, "study.json")) as f:
        study = json.load(f)
    sweep, rows = study["sweep"], study["rows"]
    os.makedirs(out_dir, exist_ok=True)
    written = []
    widths = {r[BITS] for r in rows}
    if {8, 12} <= widths:
        written += plot_headline(rows, sweep, out_dir, formats)
    for name, y_title, value, integer, title in METRICS:
        written += plot_against_bits(rows, sweep, out_dir, formats, name, y_title, value, integer, title)
    if len({r["bias_8bit_steps"] for r in rows}) > 1:
        written += plot_against_bias(rows, sweep, out_dir, formats)
    written += plot_edge_strip(rows, sweep, study_dir, out_dir, formats)
    return written


def figure7(manifest_path: str, out_path: str) -> list:
    """The demo's figure: per variant and width its final image (reduced), the inset outlined in
    red, and under it the inset magnified, each labelled "(a) shadow map, 8 bits" as the paper's
    Figure 7 labels its panels (a)-(h)."""
    with open(manifest_path) as f:
        m = json.load(f)
    panels, inset = m["panels"], m["inset"]
    rows = sorted({p["bits"] for p in panels})
    columns = max(sum(1 for p in panels if p["bits"] == b) for b in rows)
    fig = plt.figure(figsize=(4.1 * columns, 5.7 * len(rows)), layout="constrained")
    grid = fig.add_gridspec(2 * len(rows), columns)
    for k, p in enumerate(panels):
        r, c = rows.index(p["bits"]), [q for q in panels if q["bits"] == p["bits"]].index(p)
        image = plt.imread(p["image"])
        height = image.shape[0]
        top = height - inset["y"] - inset["height"]  # the manifest's inset is in window coordinates
        full, zoom = fig.add_subplot(grid[2 * r, c]), fig.add_subplot(grid[2 * r + 1, c])
        full.imshow(image, interpolation="antialiased")
        full.add_patch(Rectangle((inset["x"] - 0.5, top - 0.5), inset["width"], inset["height"], fill=False,
                                 edgecolor="red", linewidth=1.5))
        zoom.imshow(image[top:top + inset["height"], inset["x"]:inset["x"] + inset["width"]], interpolation="nearest")
        letter = chr(ord("a") + k)
        full.set_title(f"({letter}) {p['variant']}, {p['bits']} bits", fontsize=13, loc="left")
        zoom.set_title(f"inset magnified, {p['levels']} shadow levels", fontsize=10, loc="left")
        for ax in (full, zoom):
            ax.set_xticks([])
            ax.set_yticks([])
            ax.grid(False)
    fig.suptitle(m.get("title", "Figure 7"), fontsize=14)
    base, ext = os.path.splitext(out_path)
    return _save(fig, base, [ext.lstrip(".") or "png"])


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python3 -m passim.figures", description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="what", required=True)
    s = sub.add_parser("study", help="a study's figures from its study.json and edge images")
    s.add_argument("study_dir")
    s.add_argument("--out", help="where to write them (default: the study's folder)")
    s.add_argument("--formats", default="png,svg,pdf", help="comma-separated: png, svg, pdf")
    s.add_argument("--dpi", type=int, default=100, help="pixels per inch of PNG files (default 100)")
    f = sub.add_parser("figure7", help="the demo's figure from its manifest")
    f.add_argument("manifest")
    f.add_argument("out")
    f.add_argument("--dpi", type=int, default=100, help="pixels per inch of a PNG (default 100)")
    args = parser.parse_args(argv)
    _DPI[0] = args.dpi
    if args.what == "study":
        formats = [x for x in args.formats.split(",") if x]
        for x in formats:
            if x not in _METADATA:
                parser.error(f"--formats: {x!r} is not one of png, svg, pdf")
        written = study_figures(args.study_dir, args.out or args.study_dir, formats)
    else:
        written = figure7(args.manifest, args.out)
    for path in written:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
