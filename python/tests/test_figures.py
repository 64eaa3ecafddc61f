"""The figures (python/passim/figures.py) on studies made up here: every figure has its axes
titled, more than two tick labels, a legend naming every series — also with 20 series, where the
hand-drawn plots of old lost their legends and aborted — and the same bytes when drawn again."""
import json
import re

import pytest

from passim import figures


def make_study(folder, widths, biases, maps=(512,)):
    rows = []
    for m in maps:
        for b in biases:
            for bits in widths:
                k = len(rows)
                rows.append({"index": k, "color_bits": bits, "depth_bits": 24, "map_size": m, "bias_8bit_steps": b,
                             "levels": 5, "mean_abs_error": 0.5 ** bits, "wrong_pixels": 1000 >> (bits // 2),
                             "precision_bits": bits / 3, "lit_but_shadowed": 10 * bits, "shadowed_but_lit": 4000 >> bits,
                             "self_shadowed": 9 * bits, "exact_lit_but_shadowed": 100 + bits,
                             "exact_shadowed_but_lit": int(5000 / (1 + b) / bits), "exact_self_shadowed": int(900 * bits / (1 + b)),
                             "surfaces": 400000, "depth_step_world": 2.0 ** -bits})
    sweep = {"program": "pcf", "scene": "edges", "profile": "ideal", "filter": 2, "depths": 1, "width": 160,
             "height": 120, "seed": 1, "color_bits": list(widths), "depth_bits": [24], "bias_8bit_steps": list(biases),
             "map_sizes": list(maps), "id": "test", "points": len(rows)}
    (folder / "study.json").write_text(json.dumps({"sweep": sweep, "shard": "1/1", "rows": rows}))
    return rows


def svg_texts(path):
    return re.findall(r"<text[^>]*>([^<]*)</text>", path.read_text())


def test_every_figure_has_titles_ticks_and_a_legend(tmp_path):
    make_study(tmp_path, [4, 6, 8, 10, 12, 16], [0, 0.5, 1])
    written = figures.study_figures(str(tmp_path), str(tmp_path), ["svg"])
    names = {p.rsplit("/", 1)[-1] for p in written}
    for name in ["8_vs_12_bits", "error_vs_bits", "precision_vs_bits", "levels_vs_bits", "misclassified_vs_bits",
                 "light_leaks_vs_bits", "self_shadowing_vs_bits", "self_shadowing_vs_bias"]:
        assert f"{name}.svg" in names, name
        svg = (tmp_path / f"{name}.svg").read_text()
        assert 'id="x-title"' in svg and 'id="y-title"' in svg, name
        texts = svg_texts(tmp_path / f"{name}.svg")
        assert "bits" in svg or "bias" in svg
        assert len(re.findall(r'<g id="xtick_\d+">', svg)) > 2 and len(re.findall(r'<g id="ytick_\d+">', svg)) > 2, name
        assert "−log2" not in " ".join(texts)  # the minus and the subscript are real glyphs (−log₂)
    # Series are named by the setting that varies: "bias 0.5", not "all".
    assert "bias 0.5" in svg_texts(tmp_path / "error_vs_bits.svg")
    # Widths are integers: no tick at 8.5 bits.
    ticks = [t for t in svg_texts(tmp_path / "levels_vs_bits.svg") if re.fullmatch(r"[0-9.]+", t)]
    assert all("." not in t for t in ticks)
    # The error spans decades: a logarithmic axis (tick labels as powers of ten).
    assert "10" in " ".join(svg_texts(tmp_path / "error_vs_bits.svg"))


def test_twenty_series_keep_their_legend(tmp_path):
    biases = [round(0.1 * k, 1) for k in range(20)]
    rows = make_study(tmp_path, [8, 12], biases)
    sweep = json.loads((tmp_path / "study.json").read_text())["sweep"]
    figures.plot_against_bits(rows, sweep, str(tmp_path), ["svg"], *figures.METRICS[0])
    texts = svg_texts(tmp_path / "error_vs_bits.svg")
    for b in biases:
        assert f"bias {b:g}" in texts


def test_the_files_are_the_same_bytes_again(tmp_path):
    rows = make_study(tmp_path, [8, 12], [0, 1])
    sweep = json.loads((tmp_path / "study.json").read_text())["sweep"]
    formats = ["png", "svg", "pdf"]
    for out in ("a", "b"):
        (tmp_path / out).mkdir()
        figures.plot_against_bits(rows, sweep, str(tmp_path / out), formats, *figures.METRICS[0])
    for fmt in formats:
        a = (tmp_path / "a" / f"error_vs_bits.{fmt}").read_bytes()
        assert a == (tmp_path / "b" / f"error_vs_bits.{fmt}").read_bytes(), fmt
        assert a.startswith({"png": b"\x89PNG", "svg": b"<?xml", "pdf": b"%PDF"}[fmt])
