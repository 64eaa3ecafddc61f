"""The README's notebook example runs as printed and gives Figure 7's level table: the levels
each variant's sampling allows (docs/programs.md, "Levels"): the shadow map 2 (lit, shadowed),
PCF 2x2 and fast PCF 2x2 5 (0-4 of 4 samples), fast PCF 4x4 17 (sums s/16, s = 0..16), at 8 and
at 12 bits."""
import contextlib
import io
import re


def test_readme_example_prints_the_level_table(source_dir):
    readme = (source_dir / "README.md").read_text()
    block = re.search(r"<!-- python-example: figure7-levels[^>]*-->\n```python\n(.*?)```", readme, re.S).group(1)
    assert len(block.strip().splitlines()) <= 10  # ten lines, as a notebook cell
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(block, "README.md", "exec"), {})
    lines = out.getvalue().strip().splitlines()
    table = {m.group(1).strip(): (int(m.group(2)), int(m.group(3)))
             for m in (re.match(r"(.+?)\s+(\d+)\s+(\d+)$", line) for line in lines) if m}
    assert table.pop("bits") == (8, 12)  # the header: the two widths
    assert table == {"shadow map": (2, 2), "PCF 2x2": (5, 5), "fast PCF 2x2": (5, 5), "fast PCF 4x4": (17, 17)}
