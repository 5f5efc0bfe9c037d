#!/usr/bin/env python3
"""Run every example of README.md and docs/*.md as written, in order, from a fresh copy of the example data.

What runs (docs/measurements/ is history, not examples, and is not read):
  - every ```sh block: one command per line (a line ending in a backslash continues), comments and blank lines
    skipped; each command runs with bash -o pipefail, so `a && b` and pipes fail as a whole;
  - every ```python block: the whole block as one script, with PYTHONPATH naming the built Python package;
  - in README.md, the job table's example cells: a cell that is one code span starting with `conform `.

Where it runs: each file gets its own fresh temporary directory laid out like a clone (a copy of datasets/examples/
and datasets/real/, and a build/ folder with `conform` and `python/` linked to the built ones), and its commands run
there in the order they appear: `datasets/examples/tube_patch.ply`, `build/conform` and `PYTHONPATH=build/python`
mean what they mean from the root of a fresh clone, `conform` on PATH is the built program, and a relative output of
one example is the input of a later one in the same file. Two files run at a time (--jobs).

What does not run: a block whose fence says so, ```sh no-run (installing packages, building, several hosts; a
synopsis with [OPTIONS] is not an example: write it as ```text). Keep those few and say why in the text beside them. A cell or block whose language is
not sh or python (```text, ```json, ```cpp, ```csv) is not an example.

Usage: scripts/run_doc_examples.py [--conform build/conform] [--python-dir build/python] [--python /usr/bin/python3]
                                   [--list] [--keep] [-v] [--jobs N] [--exclude FILE.md] [FILE.md ...]
Exit 0 when every example ran with exit 0; 1 naming the file, the line, the command and its stderr for each file
whose examples stopped (the rest of that file is not run: later examples build on earlier ones); 2 on bad usage.
"""

import argparse
import concurrent.futures
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FENCE = re.compile(r"^(`{3,})\s*([A-Za-z0-9_+-]*)(.*)$")
TABLE_EXAMPLE = re.compile(r"^`(conform [^`]+)`$")
TIMEOUT_S = 300
DATA_DIRS = ("datasets/examples", "datasets/real")  # what a fresh clone has that the examples read


class Example:
    def __init__(self, path, line, kind, text, run=True):
        self.path, self.line, self.kind, self.text, self.run = path, line, kind, text, run


def sh_commands(lines, first_line):
    """The logical commands of a sh block: (line number, command), continuation lines joined."""
    commands, pending, start = [], "", None
    for offset, raw in enumerate(lines):
        line = raw.rstrip("\n")
        if not pending and (not line.strip() or line.lstrip().startswith("#")):
            continue
        if start is None:
            start = first_line + offset
        if line.endswith("\\"):
            pending += line[:-1] + " "
            continue
        commands.append((start, pending + line))
        pending, start = "", None
    if pending:
        commands.append((start, pending))
    return commands


def extract(path):
    """The examples of one markdown file, in order."""
    rel = os.path.relpath(path, REPO)
    with open(path, encoding="utf-8") as f:
        lines = f.readlines()
    examples, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            if rel == "README.md" and lines[i].startswith("|"):
                cells = [c.strip() for c in lines[i].strip().strip("|").split("|")]
                for cell in cells:
                    t = TABLE_EXAMPLE.match(cell)
                    if t:
                        examples.append(Example(rel, i + 1, "sh", t.group(1)))
            i += 1
            continue
        ticks, lang, info = m.group(1), m.group(2).lower(), m.group(3).split()
        j = i + 1
        while j < len(lines) and not lines[j].startswith(ticks):
            j += 1
        body = lines[i + 1:j]
        run = "no-run" not in info
        if lang in ("sh", "bash", "shell"):
            if run:
                for line_no, command in sh_commands(body, i + 2):
                    examples.append(Example(rel, line_no, "sh", command))
            else:
                examples.append(Example(rel, i + 1, "sh", "".join(body), run=False))
        elif lang == "python":
            examples.append(Example(rel, i + 2, "python", "".join(body), run=run))
        i = j + 1
    return examples


def make_clone(conform, python_dir):
    """A temporary directory laid out like a fresh clone with the program built."""
    root = tempfile.mkdtemp(prefix="conform-doc-examples-")
    for data in DATA_DIRS:
        shutil.copytree(os.path.join(REPO, data), os.path.join(root, data))
    os.makedirs(os.path.join(root, "build"))
    os.makedirs(os.path.join(root, "bin"))
    os.symlink(conform, os.path.join(root, "build", "conform"))
    os.symlink(conform, os.path.join(root, "bin", "conform"))
    if python_dir and os.path.isdir(python_dir):
        os.symlink(python_dir, os.path.join(root, "build", "python"))
    return root


def run_file(path, examples, args):
    """Runs one file's examples in order in its own clone; returns (examples run, failures, log lines)."""
    log = []
    root = make_clone(args.conform, args.python_dir)
    env = dict(os.environ)
    env["PATH"] = os.path.join(root, "bin") + os.pathsep + env.get("PATH", "")
    # files run side by side share the cores: one OpenMP thread each then (conform's results do not depend on it)
    env.setdefault("OMP_NUM_THREADS", "1" if args.jobs > 1 else "2")
    failures, ran = [], 0
    have_python = os.path.isdir(os.path.join(args.python_dir, "conform"))
    try:
        for ex in examples:
            if not ex.run:
                continue
            if not have_python and (ex.kind == "python" or "build/python" in ex.text):
                log.append("  %s:%d not run: the Python package is not built (%s)" % (ex.path, ex.line, args.python_dir))
                continue
            started = time.monotonic()
            if ex.kind == "sh":
                cmd = ["bash", "-o", "pipefail", "-c", ex.text]
                run_env = env
            else:
                cmd = [args.python, "-"]
                run_env = dict(env, PYTHONPATH=os.path.join(root, "build", "python"))
            try:
                proc = subprocess.run(cmd, cwd=root, env=run_env, input=ex.text if ex.kind == "python" else None,
                                      stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=TIMEOUT_S)
                code, err = proc.returncode, proc.stderr
            except subprocess.TimeoutExpired as e:
                code, err = "timeout", "timed out after %d s\n%s" % (TIMEOUT_S, e.stderr or "")
            ran += 1
            seconds = time.monotonic() - started
            if args.verbose:
                log.append("  %s:%d %.1f s %s" % (ex.path, ex.line, seconds, ex.text.splitlines()[0][:100]))
            if code != 0:
                tail = "\n".join(err.strip().splitlines()[-15:])
                failures.append("%s:%d: exit %s: %s\n%s" % (ex.path, ex.line, code, ex.text.strip(), tail))
                break  # the later examples of this file build on this one
    finally:
        if args.keep:
            log.append("kept %s for %s" % (root, path))
        else:
            shutil.rmtree(root, ignore_errors=True)
    return ran, failures, log


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="*", help="markdown files (default: README.md and docs/*.md)")
    parser.add_argument("--conform", default=os.path.join(REPO, "build", "conform"), help="the built program")
    parser.add_argument("--python-dir", default=os.path.join(REPO, "build", "python"),
                        help="the built Python package's parent (PYTHONPATH)")
    parser.add_argument("--python", default="/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable,
                        help="the interpreter the Python package was built for")
    parser.add_argument("--list", action="store_true", help="list the examples, run nothing")
    parser.add_argument("--keep", action="store_true", help="keep the temporary directories")
    parser.add_argument("-v", "--verbose", action="store_true", help="print every example with its time")
    parser.add_argument("--exclude", action="append", default=[], metavar="FILE.md",
                        help="a file whose examples are known not to run yet (named in the summary); repeatable")
    parser.add_argument("-j", "--jobs", type=int, default=2,
                        help="files run at the same time, each in its own directory (default 2)")
    args = parser.parse_args()
    args.conform = os.path.abspath(args.conform)
    args.python_dir = os.path.abspath(args.python_dir)
    if not os.access(args.conform, os.X_OK):
        print("run_doc_examples: %s is not an executable (build the conform target)" % args.conform, file=sys.stderr)
        return 2
    files = [os.path.abspath(f) for f in args.files] or (
        [os.path.join(REPO, "README.md")] + sorted(
            os.path.join(REPO, "docs", f) for f in os.listdir(os.path.join(REPO, "docs")) if f.endswith(".md")))

    excluded = {os.path.abspath(os.path.join(REPO, f)) for f in args.exclude}
    for path in sorted(excluded & set(files)):
        print("%-22s excluded: its examples are known not to run yet (--exclude)" % os.path.relpath(path, REPO))
    files = [f for f in files if f not in excluded]

    started = time.monotonic()
    total_run, total_skipped, failures, work = 0, 0, [], []
    for path in files:
        examples = extract(path)
        skipped = [ex for ex in examples if not ex.run]
        total_skipped += len(skipped)
        if args.list:
            for ex in examples:
                print("%s:%d %s%s" % (ex.path, ex.line, "" if ex.run else "[no-run] ",
                                      ex.text.strip().splitlines()[0] if ex.text.strip() else ""))
        elif any(ex.run for ex in examples):
            work.append((path, examples, len(skipped)))

    def timed(item):
        file_started = time.monotonic()
        return run_file(item[0], item[1], args) + (time.monotonic() - file_started,)

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        for (path, _, skipped), (ran, file_failures, log, seconds) in zip(work, pool.map(timed, work)):
            total_run += ran
            failures += file_failures
            for line in log:
                print(line)
            print("%-22s %2d run, %d not run, %s, %.1f s" % (os.path.relpath(path, REPO), ran, skipped,
                  "FAILED" if file_failures else "ok", seconds))
    if args.list:
        return 0
    for failure in failures:
        print("\nFAILED " + failure, file=sys.stderr)
    print("%d examples run, %d blocks not run (no-run), %d failed, %.1f s"
          % (total_run, total_skipped, len(failures), time.monotonic() - started))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
