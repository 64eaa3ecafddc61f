#!/usr/bin/env python3
"""The hostile-input suite (docs/hostile-input.md): traces from strangers, run by `passim run`.

Usage: run_hostile.py PASSIM [--sanitized] [--only NAME ...]

Every case of cases.json runs in a scratch copy of cases/ (symlinks, FIFOs and sparse files
are made there at run time: git stores none of them) and must
  - exit as the manifest says: 0 (the GL errors it lists reported at their lines, and no
    others), or 1 with a message naming the input (`FILE:LINE:` for a .pass, `call N` or
    `before the first call` for an apitrace trace) and holding the manifest's fragment;
  - never crash, hang (a time limit) or exceed the memory bound: the child's peak RSS
    (ru_maxrss from wait4) below its budget (--max-memory, 1 GiB by default) plus what an
    empty trace costs (the program's code and libraries, not charged to any trace). Under the
    sanitizers RSS holds shadow memory and quarantine: the memory bound is not checked there
    (--sanitized, given by CMake), every other check is;
  - on exit 1, leave its --out directory absent or empty.
"""
import argparse
import concurrent.futures
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

DEFAULT_BUDGET = 1 << 30
TIME_LIMIT = 20.0
SIZE_UNITS = {"": 1, "b": 1, "kib": 1 << 10, "kb": 1 << 10, "mib": 1 << 20, "mb": 1 << 20, "gib": 1 << 30, "gb": 1 << 30}


def budget_of(args):
    for k, a in enumerate(args):
        if a == "--max-memory":
            m = re.fullmatch(r"(\d+)\s*([a-zA-Z]*)", args[k + 1])
            return int(m.group(1)) * SIZE_UNITS[m.group(2).lower()]
    return DEFAULT_BUDGET


def run(command, cwd, limit=TIME_LIMIT):
    """Runs `command`; returns (exit status or -signal, stdout, stderr, seconds, peak RSS in bytes, timed out)."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        start = time.monotonic()
        child = subprocess.Popen(command, cwd=cwd, stdout=out, stderr=err, stdin=subprocess.DEVNULL,
                                 start_new_session=True)
        timed_out = []

        def kill():
            timed_out.append(True)
            os.killpg(child.pid, signal.SIGKILL)

        timer = threading.Timer(limit, kill)
        timer.start()
        _, status, usage = os.wait4(child.pid, 0)
        timer.cancel()
        child.returncode = 0  # reaped here, not by Popen
        seconds = time.monotonic() - start
        code = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        return (code, out.read().decode("utf-8", "replace"), err.read().decode("utf-8", "replace"), seconds,
                usage.ru_maxrss * 1024, bool(timed_out))


def prepare(work, setup):
    """What git cannot store, made in the scratch copy."""
    side = os.path.join(work, "side_files")
    if setup == "symlink_out":
        os.symlink("../../cases.json", os.path.join(side, "link_out.bin"))
    elif setup == "fifo":
        os.mkfifo(os.path.join(side, "fifo.bin"))
    elif setup == "symlink_in_to_fifo":
        os.mkfifo(os.path.join(side, "fifo2.bin"))
        os.symlink("fifo2.bin", os.path.join(side, "link_fifo.bin"))
    elif setup == "symlink_dev_null":
        os.symlink("/dev/null", os.path.join(side, "null.obj"))
    elif setup == "sparse_2gib":
        with open(os.path.join(side, "sparse.bin"), "wb") as f:
            f.truncate(2 << 30)
    elif setup == "long_comment":  # one 64 MiB line
        with open(os.path.join(work, "syntax", "long_comment.pass"), "w") as f:
            f.write("passim-trace 1\n@framebuffer 8x8\n# " + "x" * (64 << 20) + "\nglClear(GL_COLOR_BUFFER_BIT)\n"
                    "@output c\n")
    elif setup == "long_array":  # 16 Mi array elements in 32 MiB of text
        with open(os.path.join(work, "syntax", "long_array.pass"), "w") as f:
            f.write("passim-trace 1\n@framebuffer 8x8\nglEnableClientState(GL_VERTEX_ARRAY)\n"
                    "glVertexPointer(2, GL_FLOAT, 0, {" + "0," * (16 << 20) + "0})\nglDrawArrays(GL_TRIANGLES, 0, 3)\n"
                    "@output c\n")
    elif setup:
        raise ValueError(f"unknown setup '{setup}'")


def line_of(path, fragment):
    with open(path, encoding="latin-1") as f:
        for number, line in enumerate(f, 1):
            if fragment in line:
                return number
    raise ValueError(f"{path}: no line holds '{fragment}'")


def check(case, passim, work, baseline, sanitized):
    """The failures of one case (an empty list when it passes)."""
    name = case["file"]
    out = os.path.join(work, "out", name.replace("/", "_"))
    args = case.get("args", [])
    code, _, err, seconds, rss, timed_out = run([passim, "run", name, "--out", out] + args, work)
    failures = []
    if timed_out:
        return [f"did not finish within {TIME_LIMIT:.0f} s"], seconds, rss
    if code != case["exit"]:
        failures.append(f"exit {code}, expected {case['exit']}")
    apitrace = name.endswith(".trace") and "line" not in case and "line_of" not in case
    if case["exit"] == 1:
        if apitrace:
            where = "before the first call" if case.get("call") == "before" else f"call {case.get('call')}"
            if "call" in case and f"{name}: {where}: " not in err:
                failures.append(f"the message does not name '{name}: {where}'")
            elif "call" not in case and f"{name}: " not in err:
                failures.append(f"the message does not name '{name}'")
        else:
            line = line_of(os.path.join(work, name), case["line_of"]) if "line_of" in case else case["line"]
            if f"{name}:{line}: " not in err:
                failures.append(f"the message does not name '{name}:{line}'")
        if case["message"] not in err:
            failures.append(f"the message lacks '{case['message']}'")
        if os.path.isdir(out) and os.listdir(out):
            failures.append(f"a failed run left {sorted(os.listdir(out))} in its --out directory")
    else:
        want = set()
        for fragment, error in case.get("gl_errors", []):
            alternatives = error.split("|")
            line = f"call {fragment}" if apitrace else line_of(os.path.join(work, name), fragment)
            sep = ": " if apitrace else ":"
            found = [e for e in alternatives if f"{name}{sep}{line}: {e} raised by" in err]
            if not found:
                failures.append(f"no {error} reported at {name}{sep}{line}")
            want.update(f"{name}{sep}{line}: {e} raised by" for e in alternatives)
        for reported in re.findall(r"^(.*?: GL_[A-Z_]+ raised by)", err, re.M):
            if reported not in want:
                failures.append(f"unexpected GL error: {reported}")
        if not os.path.exists(os.path.join(out, "counters.json")):
            failures.append("a successful run wrote no counters.json")
    bound = budget_of(args) + baseline
    if not sanitized and rss > bound:
        failures.append(f"peak RSS {rss >> 20} MiB, over the bound of {bound >> 20} MiB")
    if failures:
        failures.append("stderr: " + err.strip()[-600:])
    return failures, seconds, rss


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("passim")
    parser.add_argument("--sanitized", action="store_true", help="a sanitizer build: RSS is not bounded")
    parser.add_argument("--only", nargs="*", default=None)
    parser.add_argument("--jobs", type=int, default=2)
    options = parser.parse_args()
    passim = os.path.abspath(options.passim)
    with open(os.path.join(HERE, "cases.json")) as f:
        cases = json.load(f)["cases"]
    if options.only:
        cases = [c for c in cases if any(o in c["file"] for o in options.only)]
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="passim-hostile-") as scratch:
        work = os.path.join(scratch, "cases")
        shutil.copytree(os.path.join(HERE, "cases"), work, symlinks=True)
        shutil.copy(os.path.join(HERE, "cases.json"), scratch)
        for c in cases:
            prepare(work, c.get("setup"))
            if c.get("generate"):  # before any child starts: a child's RSS counts this process's at fork
                import make_apitrace  # needs python3-snappy (scripts/install-deps.sh --test)
                os.makedirs(os.path.join(work, os.path.dirname(c["file"])), exist_ok=True)
                with open(os.path.join(work, c["file"]), "wb") as f:
                    f.write(make_apitrace.CASES[c["generate"]]())
        with open(os.path.join(work, "empty.pass"), "w") as f:
            f.write("passim-trace 1\n@framebuffer 8x8\n")
        baseline = run([passim, "run", "empty.pass", "--out", os.path.join(work, "out", "empty")], work)[4]
        with concurrent.futures.ThreadPoolExecutor(options.jobs) as pool:
            results = list(pool.map(lambda c: (c, check(c, passim, work, baseline, options.sanitized)), cases))
    failed = 0
    for c, result in results:
        failures, seconds, rss = result
        status = "FAIL" if failures else "ok"
        print(f"{status:4} {c['file']:52} exit {c['exit']}  {seconds:5.2f} s  {rss >> 20:5} MiB")
        for f in failures:
            print("       " + f.replace("\n", "\n       "))
        failed += bool(failures)
    memory = "not checked (sanitizer build: RSS holds shadow memory)" if options.sanitized else \
        f"peak RSS bounded by each budget + {baseline >> 20} MiB (an empty trace's)"
    print(f"\n{len(results) - failed} of {len(results)} hostile cases pass in {time.monotonic() - start:.1f} s; "
          f"memory: {memory}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
