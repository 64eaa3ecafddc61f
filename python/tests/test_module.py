"""passim's Python module against values derived independently of it: the level counts the
programs' algorithms allow, the golden hashes of the example traces (FNV-1a 64 over the codes,
recomputed here), the cost model's definition recomputed from its stage times."""
import json
import sys

import numpy as np
import pytest

import passim


def fnv1a64(codes, bytes_per_code):
    """FNV-1a 64 over the codes, bottom row first, `bytes_per_code` little-endian bytes each
    (README, "Reading counters.json"): written here from the FNV definition, not from passim."""
    h = 0xcbf29ce484222325
    for c in codes:
        for b in range(bytes_per_code):
            h ^= (int(c) >> (8 * b)) & 0xFF
            h = (h * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    return f"{h:016x}"


def test_acceptance_one_liner():
    # The acceptance: `print(r.images['attenuation'].dtype, r.levels)` prints "uint16 5".
    r = passim.run_program("pcf", filter="2x2", bits=12, scene="edges")
    att = r.images["attenuation"]
    assert f"{att.dtype} {r.levels}" == "uint16 5"
    assert att.bits == 12 and att.shape == (600, 800)
    assert int(att.max()) <= 4095  # codes of a 12-bit plane
    # PCF 2x2 counts 0-4 of 4 samples: 5 levels at most (docs/programs.md); recounted from the array.
    assert passim.count_levels(att) == 5
    assert r.counters["program"]["levels"] == 5


@pytest.mark.parametrize("program,filter,levels", [("shadow-map", None, 2), ("pcf", "3x3", 10), ("fast-pcf", "4x4", 17),
                                                    ("mdsm", "2x2", 5)])
def test_levels_are_the_samples_plus_one(program, filter, levels):
    # n·k samples per pixel give n·k + 1 levels (docs/programs.md, "Levels"): all occur on edges.
    r = passim.run_program(program, filter=filter, bits=8, scene="edges", size="320x240")
    assert r.levels == levels
    assert passim.count_levels(r.images["attenuation"]) == levels


def test_trace_images_are_the_codes_bottom_row_first_in_the_hash(source_dir):
    expected = json.load(open(source_dir / "traces" / "lit-scene.expected.json"))
    r = passim.run_trace(source_dir / "traces" / "lit-scene.pass")
    final = r.images["final"]
    assert final.dtype == np.uint16 and final.bits == 12 and final.shape == (120, 160, 4)
    # The golden hash: every code of the plane, bottom row first, two bytes a colour code.
    assert fnv1a64(np.asarray(final)[::-1].ravel(), 2) == expected["images"]["final"]
    for key, value in expected["total"].items():
        assert r.counters["total"][key] == value
    depth = r.images["depth"]
    assert depth.dtype == np.uint32 and depth.bits == 24
    assert fnv1a64(depth[::-1].ravel(), 4) == expected["images"]["depth"]  # four bytes a depth code


def test_code_image_keeps_its_width():
    r = passim.run_program("shadow-map", bits=6, scene="edges", size="160x120")
    att = r.images["attenuation"]
    assert att.bits == 6 and att[10:20, 10:20].bits == 6
    unit = att.unit()
    assert unit.dtype == np.float64 and unit.max() <= 1.0
    assert np.array_equal(np.round(unit * 63).astype(np.uint16), np.asarray(att))


def test_errors_are_the_command_lines(tmp_path):
    with pytest.raises(passim.ProgramError, match="no-such-program"):
        passim.run_program("no-such-program")
    with pytest.raises(passim.ProgramError):
        passim.run_program("fast-pcf", filter="3x3", scene="edges", size="64x48")
    with pytest.raises(ValueError, match="NxN"):
        passim.run_program("pcf", filter="2x3")
    with pytest.raises(TypeError, match="colour"):
        passim.run_program("pcf", colour=12)
    with pytest.raises(passim.TraceError, match="missing.pass"):
        passim.run_trace(tmp_path / "missing.pass")
    bad = tmp_path / "bad.pass"
    bad.write_text("passim-trace 1\n@framebuffer 8x8 color=8\nglEnable(GL_NOT_AN_ENUM)\n")
    with pytest.raises(passim.TraceError, match=r"bad.pass:3"):
        passim.run_trace(bad)
    with pytest.raises(ValueError, match="no cost rates"):
        passim.cost(passim.run_program("shadow-map", scene="edges", size="64x48"), profile="ideal")


def test_cost_is_each_pass_slowest_stage_plus_overhead():
    run = passim.run_program("fast-pcf", filter="2x2", bits=12, scene="edges", size="320x240")
    c = passim.cost(run, "octane-vpro8")
    total = 0.0
    for p in c["passes"]:
        stages = p["stages"]
        slowest = max(s["seconds"] for s in stages.values())
        assert p["seconds"] == pytest.approx(slowest + p["overhead"], rel=1e-12)
        if p["bound"]:
            assert stages[p["bound"]]["seconds"] == slowest
        total += p["seconds"]
    assert c["seconds"] == pytest.approx(total, rel=1e-12)
    assert c["fps"] == pytest.approx(1.0 / total, rel=1e-12)
    assert run.cost() == c


def test_study_rows(monkeypatch):
    rows = passim.study_precision("pcf", filter="2x2", scene="edges", size="160x120", bits="8,12", bias=[0, 1], jobs=2)
    import pandas
    assert isinstance(rows, pandas.DataFrame)
    assert list(rows["color_bits"]) == [8, 12, 8, 12]
    assert list(rows["bias_8bit_steps"]) == [0, 0, 1, 1]
    assert set(rows["levels"]) == {5}
    assert "wrong_pixels" in rows.columns and "max_abs_error" not in rows.columns
    # Without pandas: a list of dicts, the same rows.
    monkeypatch.setitem(sys.modules, "pandas", None)
    plain = passim.study_precision("pcf", filter="2x2", scene="edges", size="160x120", bits=[8, 12], bias=[0, 1])
    assert isinstance(plain, list) and [r["color_bits"] for r in plain] == [8, 12, 8, 12]
    assert [r["levels"] for r in plain] == list(rows["levels"])
    with pytest.raises(ValueError, match="4..16"):
        passim.study_precision("pcf", bits=[3])
