#!/usr/bin/env python3
"""Runs every command README.md and docs/*.md show, so the docs stay true.

A command is a line of a code block (indented four spaces or fenced) that starts with
`build/passim` or `build/bench/passim_bench` (continuation lines ending in `\\` joined, a
trailing `# comment` dropped). Each runs in a scratch folder that holds `build` (this build),
`traces` and `tests` (the source's) and the stand-ins the docs name (`my.pass`, `prog.trace`,
`bunny.obj`, ...), in the order the docs give them, and must exit 0. tests/doc_commands.json
makes a command small where the docs name a large job (arguments appended or replaced), or
says why one cannot run here (a cluster); an entry whose command the docs no longer show is an
error, so the list cannot go stale. The GoogleTest names the docs cite (`Suite.Name`) must exist.

usage: doc_commands.py SOURCE_DIR BUILD_DIR SCRATCH_DIR
"""
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

PREFIXES = ("build/passim", "build/bench/passim_bench")


def doc_files(src):
    return [src / "README.md"] + sorted((src / "docs").glob("*.md"))


def commands_in(path):
    """(command, line) for each documented command; blocks after a '**Needs' paragraph are skipped."""
    out, lines = [], path.read_text(encoding="utf-8").splitlines()
    fenced, needs, prev_blank, i = False, False, True, 0
    while i < len(lines):
        line = lines[i]
        if line.strip().startswith("```"):
            fenced = not fenced
            i += 1
            continue
        in_block = fenced or line.startswith("    ")
        if not in_block and line.strip() and prev_blank:  # a new paragraph
            needs = line.lstrip().startswith("**Needs")
        prev_blank = not line.strip()
        text = line.strip()
        if in_block and text.startswith(PREFIXES) and not needs:
            start = i + 1
            while text.endswith("\\") and i + 1 < len(lines):
                i += 1
                text = text[:-1].rstrip() + " " + lines[i].strip()
            text = re.sub(r"\s+#.*$", "", text)
            out.append((text, f"{path.name}:{start}"))
        i += 1
    return out


def cited_tests(src):
    names = set()
    for f in doc_files(src):
        for m in re.finditer(r"`([A-Z][A-Za-z0-9]*\.[A-Z][A-Za-z0-9]*)`", f.read_text(encoding="utf-8")):
            if m.group(1) != "Suite.Name":
                names.add(m.group(1))
    return names


def setup_scratch(src, build, scratch):
    if scratch.exists():
        shutil.rmtree(scratch)
    scratch.mkdir(parents=True)
    (scratch / "build").symlink_to(build.resolve())
    for d in ("traces", "tests", "scripts"):
        (scratch / d).symlink_to((src / d).resolve())
    # Stand-ins for the files the docs name as examples.
    shutil.copy(src / "traces/masked-multipass.pass", scratch / "my.pass")
    shutil.copy(src / "traces/masked-multipass.expected.json", scratch / "my.expected.json")
    shutil.copy(src / "tests/data/apitrace/blend_masks.trace", scratch / "prog.trace")
    (scratch / "bunny.obj").write_text(
        "# a tetrahedron standing in for the bunny\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
        "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")


def main():
    src, build, scratch = (Path(a) for a in sys.argv[1:4])
    config = json.loads((src / "tests/doc_commands.json").read_text(encoding="utf-8"))
    overrides = config["commands"]
    found, failures = [], []
    for f in doc_files(src):
        found += commands_in(f)
    shown = {c for c, _ in found}
    for c in overrides:
        if c not in shown:
            failures.append(f"tests/doc_commands.json names a command no doc shows any more: {c}")
    setup_scratch(src, build, scratch)
    env = dict(os.environ, PATH=f"{scratch / 'build'}:{os.environ.get('PATH', '')}")
    ran = skipped = 0
    for command, where in found:
        o = overrides.get(command, {})
        if "skip" in o:
            skipped += 1
            print(f"skip {where}: {command}  ({o['skip']})")
            continue
        run = command
        for old, new in o.get("replace", []):
            run = run.replace(old, new)
        run = (run + " " + o.get("append", "")).strip()
        for pre in o.get("before", []):
            subprocess.run(pre, shell=True, cwd=scratch, env=env, check=True, capture_output=True)
        r = subprocess.run(run, shell=True, cwd=scratch, env=env, capture_output=True, text=True, timeout=600)
        ran += 1
        status = "ok" if r.returncode == 0 else f"exit {r.returncode}"
        print(f"{status:>7} {where}: {run}")
        if r.returncode != 0:
            failures.append(f"{where}: `{command}` exited {r.returncode}:\n{r.stderr[-2000:]}")
    # The tests the docs cite by name.
    listed = "".join(subprocess.run([str(binary), "--gtest_list_tests"], capture_output=True, text=True,
                                    check=True).stdout
                     for binary in (build / "tests/passim_tests", build / "tests/passim_osmesa_check")
                     if binary.exists())
    have, suite = set(), ""
    for line in listed.splitlines():
        if not line.startswith(" "):
            suite = line.split("#")[0].strip().rstrip(".").split("/")[-1]
        else:
            have.add(f"{suite}.{line.split('#')[0].strip().split('/')[0]}")
    for name in sorted(cited_tests(src)):
        if name not in have and not any(h.startswith(name.split(".")[0] + ".") and h.split(".")[1].startswith(name.split(".")[1]) for h in have):
            failures.append(f"the docs cite the test {name}, which does not exist")
    print(f"{ran} documented commands ran, {skipped} skipped, {len(cited_tests(src))} cited tests checked")
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
