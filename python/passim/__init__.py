"""passim from Python: the papers' pass programs, traces, precision studies and the cost model,
bit for bit the command line's (docs/python.md).

    >>> import passim
    >>> run = passim.run_program("pcf", filter="2x2", bits=12, scene="edges")
    >>> run.images["attenuation"].dtype, run.images["attenuation"].bits, run.levels
    (dtype('uint16'), 12, 5)

Images are numpy arrays of the plane's integer codes (rows top first, as image files and
matplotlib's imshow have them) with their width in bits as ``.bits``; ``.counters`` is the
run's counters.json as dicts and lists (docs/counters.md); studies come back as a pandas
DataFrame when pandas is installed, else as a list of dicts. The command line's errors are
raised as exceptions with its messages: ProgramError (a setting the program cannot run with),
TraceError (a trace's error, naming file:line or the call), ValueError (a bad argument).

The figures (passim.figures) need matplotlib only; the rest needs the compiled module
_passim, built with the project (pybind11).
"""
from __future__ import annotations

import json
import os

try:
    from . import _passim
except ImportError as _error:  # the figures work without it (sanitizer builds, no pybind11)
    _passim = None
    _import_error = _error

    class ProgramError(RuntimeError):
        """A setting the program cannot run with (the message names the setting and the limit)."""

    class TraceError(RuntimeError):
        """A trace's error (the message names file:line, or the apitrace call)."""
else:
    ProgramError = _passim.ProgramError
    TraceError = _passim.TraceError

__all__ = ["run_program", "run_trace", "study_precision", "cost", "programs", "profiles", "Run", "CodeImage",
           "ProgramError", "TraceError", "count_levels"]


def _core():
    if _np is None:
        import sys
        raise ImportError(f"passim's runs need numpy, which {sys.executable} does not have (Debian's python3-numpy "
                          "serves /usr/bin/python3: run passim from it)")
    if _passim is None:
        raise ImportError(f"passim's compiled module (_passim) is not available here: {_import_error}; "
                          "build the project with pybind11 (Debian: pybind11-dev python3-dev)")
    return _passim


try:
    import numpy as _np
except ImportError:  # passim.figures does not need it either
    _np = None

if _np is not None:
    class CodeImage(_np.ndarray):
        """A plane's integer codes: uint16 for widths up to 16 bits, uint32 for wider depth planes;
        rows top first; shape (height, width) or (height, width, channels).

        ``bits``: the width in bits (an int when every channel has the same width, else the tuple
        ``channel_bits``); ``plane``: "color", "rgb", "alpha", "depth" or "stencil"; ``name``: the
        image's name (final, attenuation, ...). ``unit()`` gives the codes as fractions of the
        largest code, k / (2^bits − 1), the value GL means by them (§2.14.9).
        """

        def __new__(cls, codes, name, plane, channel_bits):
            obj = _np.asarray(codes).view(cls)
            obj.name, obj.plane, obj.channel_bits = name, plane, tuple(channel_bits)
            widths = set(obj.channel_bits)
            obj.bits = obj.channel_bits[0] if len(widths) == 1 else obj.channel_bits
            return obj

        def __array_finalize__(self, obj):
            if obj is not None:
                for key in ("name", "plane", "channel_bits", "bits"):
                    setattr(self, key, getattr(obj, key, None))

        def unit(self):
            """The codes as fractions in [0, 1]: k / (2^bits − 1), per channel."""
            top = _np.array([(1 << b) - 1 for b in self.channel_bits], dtype=_np.float64)
            return _np.asarray(self, dtype=_np.float64) / (top if self.ndim == 3 else top[0])
else:
    CodeImage = None


def count_levels(codes) -> int:
    """Distinct codes, codes one apart counted as one level (the paper's 63 and 64): the
    'levels' of counters.json and the studies."""
    values = sorted(set(int(v) for v in _np.asarray(codes).ravel()))
    return sum(1 for k, v in enumerate(values) if k == 0 or v - values[k - 1] > 1)


class Run:
    """A finished run of a program or a trace.

    images    name -> CodeImage (final, attenuation, shadowmap..., or a trace's @output images)
    counters  counters.json as dicts and lists: settings, passes, total, images, gl_errors, ...
    levels    shadow levels of the attenuation image (None for a trace without one)
    options   the settings it ran with
    """

    def __init__(self, core_run, options):
        self._run = core_run
        self.options = dict(options)
        self.counters = json.loads(core_run.report())
        self.levels = core_run.levels()
        self.images = {}
        for name, plane, bits, codes in core_run.images():
            if plane == "color" and len(bits) == 4 and bits[3] == 0:  # no alpha plane
                codes, bits = codes[..., :3], bits[:3]
            self.images[name] = CodeImage(codes, name, plane, bits)

    def cost(self, profile: str = "octane-vpro8") -> dict:
        """This run's counters on a modelled machine (see passim.cost)."""
        return cost(self, profile)

    def __repr__(self):
        what = self.options.get("program") or self.options.get("trace")
        return f"<passim.Run {what}: images {sorted(self.images)}, levels {self.levels}>"


def _filter(value) -> int:
    """None, 2, "2" or "2x2" -> 2 (0: the program's default)."""
    if value is None:
        return 0
    if isinstance(value, int):
        return value
    text = str(value)
    parts = text.lower().split("x")
    if len(parts) > 2 or not all(p.strip().isdigit() for p in parts) or len(set(parts)) != 1:
        raise ValueError(f"filter={value!r}: expected NxN (square), e.g. '2x2'")
    return int(parts[0])


def _size(value):
    if isinstance(value, str):
        parts = value.lower().split("x")
        if len(parts) != 2 or not all(p.isdigit() for p in parts):
            raise ValueError(f"size={value!r}: expected 'WIDTHxHEIGHT', e.g. '800x600'")
        value = tuple(int(p) for p in parts)
    width, height = value
    return int(width), int(height)


# Keyword arguments of run_program and study_precision beyond the named ones, as the
# program's option fields (the command line's --texture-bits, --no-jitter, ...).
_PROGRAM_KEYWORDS = {"profile": "profile", "depths": "depths", "accum_bits": "accum_bits",
                     "texture_bits": "texture_bits", "table_bits": "table_bits", "linear": "linear",
                     "jitter": "jitter", "seed": "seed", "sampling": "sampling",
                     "intermediates": "intermediates"}


def _program_options(more: dict, where: str) -> dict:
    options = {}
    for key, value in more.items():
        if key == "size":
            options["width"], options["height"] = _size(value)
        elif key in ("width", "height"):
            options[key] = int(value)
        elif key in _PROGRAM_KEYWORDS:
            options[_PROGRAM_KEYWORDS[key]] = value
        else:
            known = ", ".join(sorted(list(_PROGRAM_KEYWORDS) + ["size", "width", "height"]))
            raise TypeError(f"{where}() got an unexpected keyword argument {key!r} (also accepted: {known})")
    return options


def run_program(name: str, *, filter=None, bits: int = 12, depth_bits: int = 24, map: int | None = None,
                scene: str = "paper", bias: float | None = None, threads: int = 1, **more) -> Run:
    """Runs one of the papers' pass programs (passim program --list; programs()) for one frame.

    filter      the footprint, "2x2" or 2 (None: the program's default)
    bits        colour width of every channel, 4-16
    depth_bits  depth-buffer width
    map         shadow-map size, a power of two (None: the scene's, 512 for paper and edges,
                1024 for fig8)
    scene       "paper", "fig8", "edges" or an .obj file
    bias        depth bias in steps of the depth encoding at this width (None: one 8-bit step,
                the same depth at every width)
    threads     threads of rasterization: the same bits and counters at any number
    more        profile, size ("800x600" or (w, h)), depths, accum_bits, texture_bits,
                table_bits, linear, jitter, seed, sampling, intermediates

    The double-precision references (reeves, shader-pcf, mdsm-ref) run too: their one image is
    the attenuation, and their counters are reference.json's.
    """
    options = dict(_program_options(more, "run_program"), filter=_filter(filter), color_bits=int(bits),
                   depth_bits=int(depth_bits), map_size=int(map or 0), scene=str(scene),
                   bias=None if bias is None else float(bias), threads=int(threads))
    run = _core().run_program(str(name), options)
    return Run(run, dict(options, program=name))


def run_trace(path, *, strict: bool = False, max_memory: int | None = None, allow_files=(), profile=None,
              bits=None, depth_bits=None, stencil_bits=None, accum_bits=None, size=None, snapshot=None,
              snapshot_at=None) -> Run:
    """Replays a .pass trace (or an apitrace .trace) as `passim run` does.

    strict, max_memory (bytes), allow_files (folders side files may come from) as the command's
    --strict, --max-memory, --allow-files. For apitrace traces only: profile, bits, depth_bits,
    stencil_bits, accum_bits, size, snapshot (apitrace's call sets, e.g. "frame"), snapshot_at
    ("flush"); a .pass trace states its settings in its header.
    """
    path = os.fspath(path)
    options = {"strict": bool(strict), "allow_files": [os.fspath(f) for f in allow_files]}
    if max_memory is not None:
        options["max_memory"] = int(max_memory)
    apitrace_only = {"profile": profile, "color_bits": bits, "depth_bits": depth_bits,
                     "stencil_bits": stencil_bits, "accum_bits": accum_bits, "snapshot": snapshot}
    given = {k: v for k, v in apitrace_only.items() if v is not None}
    if size is not None:
        given["width"], given["height"] = _size(size)
    if snapshot_at is not None:
        if snapshot_at != "flush":
            raise ValueError("snapshot_at takes 'flush'")
        given["snapshot_at_flush"] = True
    if given and path.endswith(".pass"):
        raise ValueError(f"{', '.join(sorted(given))}: for apitrace traces; a .pass trace states its settings "
                         "in its header")
    options.update(given)
    return Run(_core().run_trace(path, options), dict(options, trace=path))


def _int_list(value, what: str) -> list:
    """4, [8, 12], range(4, 17), "4-16" or "4-8,12" -> a list of ints."""
    if value is None:
        return []
    if isinstance(value, int):
        return [value]
    if isinstance(value, str):
        out = []
        for item in value.split(","):
            a, _, b = item.partition("-")
            if not a.strip().isdigit() or (b and not b.strip().isdigit()):
                raise ValueError(f"{what}={value!r}: expected numbers and ranges like '4-16' or '8,12'")
            out.extend(range(int(a), int(b or a) + 1))
        return out
    return [int(v) for v in value]


def _float_list(value) -> list:
    if value is None:
        return []
    if isinstance(value, (int, float)):
        return [float(value)]
    if isinstance(value, str):
        return [float(v) for v in value.split(",")]
    return [float(v) for v in value]


def study_precision(name: str, *, filter=None, bits="4-16", depth_bits=None, bias=None, map=None,
                    scene: str = "paper", jobs: int = 1, **more):
    """A precision study (docs/studies.md), as `passim study precision` runs it: the program at
    every point of the sweep, measured against its double-precision reference.

    bits        colour widths: "4-16", "8,12", [8, 12] or range(4, 17)
    depth_bits  depth widths (None: 24)
    bias        biases in 8-bit steps of depth, the same depth at every width (None: one step)
    map         shadow-map sizes (None: the scene's)
    jobs        points run at a time (the rows do not depend on it)
    more        size, profile, depths and the program's other settings (see run_program)

    Returns the study.json rows, one per point in sweep order (bits fastest, then depth, bias,
    map): a pandas DataFrame when pandas is installed, else a list of dicts. Their columns are
    study.csv's (docs/studies.md defines each, with its unit).
    """
    base = dict(_program_options(more, "study_precision"), filter=_filter(filter), scene=str(scene))
    color_bits = _int_list(bits, "bits")
    for b in color_bits:
        if not 4 <= b <= 16:
            raise ValueError(f"bits={bits!r}: values must lie in 4..16")
    maps = _int_list(map, "map")
    for m in maps:
        if m < 1 or m & (m - 1):
            raise ValueError(f"map {m}: a power of two")
    biases = _float_list(bias)
    if any(not b >= 0 for b in biases):
        raise ValueError(f"bias={bias!r}: non-negative numbers of 8-bit steps")
    text = _core().study(str(name), base, color_bits, _int_list(depth_bits, "depth_bits"), biases, maps, int(jobs))
    rows = json.loads(text)["rows"]
    try:
        import pandas
    except ImportError:
        return rows
    return pandas.DataFrame(rows)


def cost(run: Run, profile: str = "octane-vpro8") -> dict:
    """The cost model (docs/cost-model.md) of a run's passes on a modelled machine, as
    `passim report cost --json` gives it: per pass the bounding stage and its seconds, every
    stage's work and seconds; the frame's seconds and fps. The run keeps its own widths: to cost
    a program at the machine's width, run it at that width (profiles() gives each one's)."""
    return json.loads(_core().cost(run._run, str(profile)))


def programs() -> list:
    """The programs run_program knows: (name, the paper's section, summary, is a reference)."""
    return [tuple(p) for p in _core().programs()]


def profiles() -> list:
    """The machine profiles: (name, colour width, has cost rates)."""
    return [tuple(p) for p in _core().profiles()]
