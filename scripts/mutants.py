#!/usr/bin/env python3
"""Mutation sweep: does the test suite notice a wrong formula?

tests/mutants.json lists mutants: small edits of the kind a real bug would be (a pdf off by a factor, a missing
cosine or selection probability, MIS weights that no longer sum to one, a sample drawn from the wrong
distribution). This script copies the working tree (tracked and untracked, not ignored files) to a scratch
directory, builds it once (Release, no LTO) and checks that the tests pass there; then, for each mutant, it applies
the edit, rebuilds, runs ctest (stopping at the first failure) and restores the file. A mutant is KILLED when a
test fails and SURVIVED when every test passes.

A mutant with a "survive" entry changes only the variance of an estimator (or nothing at all); the entry says why,
and its survival is expected. Any other survivor is a hole in the tests. A mutant whose "old" text no longer occurs
exactly once in its file is STALE (the code moved on), and one that does not compile is NO-BUILD: both mean the
list needs an update. Exit status: 0 when every mutant without "survive" was killed, 1 otherwise, 2 when the
unmutated copy does not build or pass its tests.

Not part of scripts/test.sh: the whole list takes five hours or more on 2 cores (1.7 to 2.1 minutes a mutant in the
sixth to ninth batches: each is rebuilt and linked, and a survivor runs every test). docs/testing.md has the results.
"""
import argparse, filecmp, json, os, pathlib, re, shutil, signal, subprocess, sys, time

# Tests of the command line's input handling, outputs, interruption, speed, diff and compare: minutes of run time
# spent on what surrounds the formulas (the regression renders, warptest and every library test still run).
DEFAULT_EXCLUDE = "cli_malformed|cli_outputs|cli_interrupt|cli_prefetch|cli_bench|cli_diff|cli_compare"
ROOT = pathlib.Path(__file__).resolve().parent.parent


def run(cmd, cwd, log):
    log.write(f"$ {' '.join(cmd)}\n")
    log.flush()
    return subprocess.run(cmd, cwd=cwd, stdout=log, stderr=subprocess.STDOUT).returncode


def first_failure(log_path):
    """The name of the first test ctest reported as failed in the log."""
    for line in open(log_path, errors="replace"):
        if re.search(r"\*\*\*(Failed|Timeout|Exception)|\(Subprocess aborted\)|\(SEGFAULT\)", line):
            m = re.search(r"Test\s+#\d+:\s+(\S+)", line)
            return m.group(1) if m else line.strip()
    return "(see the log)"


def copy_tree(dest):
    """Copies the working tree's tracked and untracked, not ignored files to dest. Only files whose content differs
    are copied, with a fresh time, so that a rerun rebuilds what changed (a file left mutated by an interrupted run
    is restored and rebuilt); files that left the tree are removed from the copy."""
    listed = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "-z"], cwd=ROOT, check=True,
                            capture_output=True).stdout.decode().split("\0")
    files = {f for f in listed if f and (ROOT / f).is_file()}
    if dest.exists():
        for p in list(dest.rglob("*")):
            rel = p.relative_to(dest).as_posix()
            if p.is_file() and not rel.startswith(("build/", ".git/")) and rel not in files:
                p.unlink()
    for f in sorted(files):
        src, dst = ROOT / f, dest / f
        if dst.is_file() and filecmp.cmp(src, dst, shallow=False):
            continue
        dst.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(src, dst)
        shutil.copymode(src, dst)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--work", default="/tmp/lumis-mutants", help="scratch directory, kept between runs (default "
                    "%(default)s)")
    ap.add_argument("--only", nargs="+", metavar="ID", help="run only these mutants")
    ap.add_argument("--list", action="store_true", help="list the mutants and exit")
    ap.add_argument("--check", action="store_true", help="only check the list against the source (a ctest, in "
                    "seconds): each mutant's text occurs exactly once in its file and changes it; exit 1 otherwise")
    ap.add_argument("--exclude", default=DEFAULT_EXCLUDE, help="ctest -E regex (default: %(default)s)")
    ap.add_argument("--timeout", type=int, default=240, help="per-test timeout in seconds (default 240)")
    args = ap.parse_args()
    # A kill restores the mutated file like Ctrl-C does (and the next run's copy repairs any file left mutated).
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))

    mutants = json.loads((ROOT / "tests" / "mutants.json").read_text())
    ids = [m["id"] for m in mutants]
    if len(ids) != len(set(ids)):
        sys.exit("mutants.py: tests/mutants.json has a duplicate id")
    if args.check:
        problems = []
        for m in mutants:
            path = ROOT / m["file"]
            n = path.read_text().count(m["old"]) if path.is_file() else -1
            if n != 1:
                problems.append(f"{m['id']}: its text occurs {n} times in {m['file']}" if n >= 0
                                else f"{m['id']}: no file {m['file']}")
            elif m["old"] == m["new"]:
                problems.append(f"{m['id']}: changes nothing")
        for p in problems:
            print(f"STALE {p}", file=sys.stderr)
        print(f"mutants.py --check: {len(mutants)} mutants, {len(problems)} stale")
        return 1 if problems else 0
    if args.list:
        for m in mutants:
            extra = f"  (expected to survive: {m['survive']})" if m.get("survive") else ""
            print(f"{m['id']:26} {m['file']:30} {m['bug']}{extra}")
        return 0
    if args.only:
        unknown = sorted(set(args.only) - set(ids))
        if unknown:
            print(f"mutants.py: unknown mutant {', '.join(unknown)} (--list lists them)", file=sys.stderr)
            return 2
        mutants = [m for m in mutants if m["id"] in args.only]

    work = pathlib.Path(args.work).resolve()
    src, logs = work / "lumis", work / "logs"
    logs.mkdir(parents=True, exist_ok=True)
    copy_tree(src)
    shared = (ROOT.parent / "shared").resolve()
    if shared.is_dir() and not (work / "shared").exists():
        (work / "shared").symlink_to(shared)  # tests find the glTF sample models at ../shared
    # --output-on-failure: each mutant's log (--work/logs/ID.txt) shows what the first failing test said.
    ctest = ["ctest", "--test-dir", "build", "-j", str(os.cpu_count() or 2), "--stop-on-failure", "--output-on-failure",
             "--timeout", str(args.timeout), "-E", args.exclude]
    build = ["ninja", "-C", "build"]
    print(f"building and testing the unmutated copy in {src} ...", flush=True)
    with open(logs / "baseline.txt", "w") as log:
        ok = (run(["cmake", "-S", ".", "-B", "build", "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release", "-DLUMIS_LTO=OFF"],
                  src, log) == 0 and run(build, src, log) == 0 and run(ctest, src, log) == 0)
    if not ok:
        print(f"mutants.py: the unmutated copy does not build or pass: {logs / 'baseline.txt'}", file=sys.stderr)
        return 2

    counts, holes = {}, []
    print(f"{'mutant':26} {'result':8} {'s':>4}  first failing test, or why it may survive", flush=True)
    for m in mutants:
        path, t0 = src / m["file"], time.time()
        text = path.read_text()
        n = text.count(m["old"])
        if n != 1:
            status, detail = "STALE", f"its text occurs {n} times in {m['file']}"
        else:
            log_path = logs / f"{m['id']}.txt"
            try:
                path.write_text(text.replace(m["old"], m["new"]))
                with open(log_path, "w") as log:
                    if run(build, src, log) != 0:
                        status, detail = "NO-BUILD", str(log_path)
                    elif run(ctest, src, log) != 0:
                        status, detail = "KILLED", first_failure(log_path)
                    else:
                        status, detail = "SURVIVED", ""
            finally:
                path.write_text(text)  # a fresh time: the next build recompiles what the mutant touched
        if m.get("survive"):
            detail += (" " if detail else "") + f"(expected to survive: {m['survive']})"
        elif status != "KILLED":
            holes.append(m["id"])
        counts[status] = counts.get(status, 0) + 1
        print(f"{m['id']:26} {status:8} {time.time() - t0:4.0f}  {detail}", flush=True)
    with open(logs / "restore.txt", "w") as log:
        run(build, src, log)  # leave the copy built unmutated for the next run
    print(", ".join(f"{k.lower()} {v}" for k, v in sorted(counts.items())) + f" of {len(mutants)} mutants")
    if holes:
        print(f"not killed: {' '.join(holes)}")
    return 1 if holes else 0


if __name__ == "__main__":
    sys.exit(main())
