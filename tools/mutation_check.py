#!/usr/bin/env python3
"""Mutation check of the safety code (issue 12 part 8).

Applies each mutation of tools/safety_mutations.txt on its own (a deleted check, a flipped comparison, a
constant changed, a branch skipped), rebuilds what depends on the changed file, runs the tests that
should notice and prints which mutations survived. The source is restored after every mutation, also
on Ctrl-C or an error.

    tools/mutation_check.py [--build DIR] [--only ID ...] [--jobs N] [--check] [--list]

--check   only verifies that every mutation's text is found exactly once in its file (fast; the test
          suite runs it so that the list follows the code)
--build   the configured build directory to rebuild and test in (default build/release)

Exit status: 0 when every mutation was killed or carries a `survives:` reason, 1 when one survived
unexplained or did not compile, 2 for a bad mutation list or a failing baseline.
"""

from __future__ import annotations

import argparse
import dataclasses
import pathlib
import re
import signal
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
LIST = ROOT / "tools" / "safety_mutations.txt"

# Left out of every selection: real-time runs of a minute and more, and suites that never touch the
# safety code (the bad-input corpus, fuzz replays, the planner's random problems).
SLOW = r"cli\.demo_emulated|cli\.demo_preset_builds|cli\.emulate_commissioning|cli\.operator_console|bad_input|Fuzz|AxisProfileRandom"
TEST_TIMEOUT_S = 120  # a mutation that makes a test hang counts as killed by the time-out


@dataclasses.dataclass
class Mutation:
    ident: str
    line: int
    file: str = ""
    what: str = ""
    tests: str = ""
    survives: str = ""
    original: list[str] = dataclasses.field(default_factory=list)
    replacement: list[str] = dataclasses.field(default_factory=list)

    @property
    def old(self) -> str:
        return "\n".join(self.original)

    @property
    def new(self) -> str:
        return "\n".join(self.replacement)


def parse(path: pathlib.Path) -> list[Mutation]:
    mutations: list[Mutation] = []
    errors: list[str] = []
    for number, text in enumerate(path.read_text().splitlines(), start=1):
        if text.startswith("## "):
            mutations.append(Mutation(text[3:].strip(), number))
            continue
        if not text.strip() or text.startswith("#"):
            continue
        if not mutations:
            errors.append(f"{path}:{number}:1: a line before the first '## ID'")
            continue
        m = mutations[-1]
        if text.startswith("- "):
            m.original.append(text[2:])
        elif text.startswith("+ "):
            m.replacement.append(text[2:])
        elif (key := re.match(r"(file|what|tests|survives): (.*)$", text)) is not None:
            setattr(m, key.group(1), key.group(2).strip())
        else:
            errors.append(f"{path}:{number}:1: not a key, '- ' or '+ ' line: {text!r}")
    seen: set[str] = set()
    for m in mutations:
        where = f"{path}:{m.line}:1: {m.ident}"
        if m.ident in seen:
            errors.append(f"{where}: the name is used twice")
        seen.add(m.ident)
        if not m.file or not m.what or not m.original:
            errors.append(f"{where}: needs file:, what: and at least one '- ' line")
    if errors:
        raise SystemExit("\n".join(errors))
    return mutations


def stale(m: Mutation) -> str | None:
    source = ROOT / m.file
    if not source.is_file():
        return f"{m.file} does not exist"
    count = source.read_text().count(m.old)
    if count != 1:
        return f"its text is found {count} times in {m.file}, not once"
    return None


class Applied:
    """The mutation in the source for the `with` block; the original back afterwards, whatever happens."""

    def __init__(self, m: Mutation):
        self.path = ROOT / m.file
        self.mutation = m

    def __enter__(self) -> None:
        self.text = self.path.read_text()
        self.path.write_text(self.text.replace(self.mutation.old, self.mutation.new, 1))

    def __exit__(self, *exc: object) -> None:
        self.path.write_text(self.text)


def build(build_dir: pathlib.Path, jobs: int) -> tuple[bool, str]:
    r = subprocess.run(["cmake", "--build", str(build_dir), "-j", str(jobs)], capture_output=True, text=True)
    return r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]


def set_test_timeout(build_dir: pathlib.Path, seconds: str) -> bool:
    # CTest's --timeout yields to a test's TIMEOUT property, which the GoogleTest cases carry; the property
    # comes from this cache variable (written into the test lists when the tests are built), so a hung
    # mutant is ended after TEST_TIMEOUT_S and not 300 s.
    r = subprocess.run(["cmake", f"-DCELLCTL_TEST_TIMEOUT={seconds}", str(build_dir)], capture_output=True, text=True)
    if r.returncode != 0:
        print(f"cmake could not set CELLCTL_TEST_TIMEOUT={seconds} in {build_dir}:\n{r.stdout[-2000:]}{r.stderr[-2000:]}",
              file=sys.stderr)
    return r.returncode == 0


def cached_test_timeout(build_dir: pathlib.Path) -> str:
    cache = (build_dir / "CMakeCache.txt").read_text()
    found = re.search(r"^CELLCTL_TEST_TIMEOUT:STRING=(\S+)$", cache, re.M)
    return found.group(1) if found else "300"


def run_tests(build_dir: pathlib.Path, selection: str, jobs: int) -> tuple[bool, list[str], int]:
    """Runs the selection; returns (all passed, the failed tests' names, how many ran)."""
    r = subprocess.run(
        ["ctest", "--test-dir", str(build_dir), "-j", str(jobs), "-R", selection, "-E", SLOW,
         "--timeout", str(TEST_TIMEOUT_S)],
        capture_output=True, text=True)
    failed = re.findall(r"^\s*\d+ - (\S+)", r.stdout.split("The following tests FAILED:")[-1], re.M) \
        if "The following tests FAILED:" in r.stdout else []
    ran = re.search(r"tests passed, \d+ tests failed out of (\d+)", r.stdout)
    total = int(ran.group(1)) if ran else 0
    return r.returncode == 0 and total > 0, failed, total


def interrupted(*_: object) -> None:
    # A SIGTERM (a CI time-out, `kill`) ends the check like Ctrl-C: the source is restored on the way out.
    raise KeyboardInterrupt


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default="build/release", help="configured build directory (default build/release)")
    ap.add_argument("--only", nargs="*", default=[], help="mutation names to apply (default: all)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--check", action="store_true", help="only check that every mutation applies")
    ap.add_argument("--list", action="store_true", help="print the mutations and exit")
    args = ap.parse_args()

    mutations = parse(LIST)
    if args.only:
        unknown = set(args.only) - {m.ident for m in mutations}
        if unknown:
            print(f"unknown mutation(s): {', '.join(sorted(unknown))}", file=sys.stderr)
            return 2
        mutations = [m for m in mutations if m.ident in args.only]
    problems = [(m, why) for m in mutations if (why := stale(m))]
    for m, why in problems:
        print(f"{LIST}:{m.line}:1: mutation {m.ident}: {why}", file=sys.stderr)
    if problems:
        return 2
    if args.list or args.check:
        for m in mutations:
            print(f"{m.ident:42} {m.file:40} {m.what}")
        print(f"{len(mutations)} mutations, each found once in its file")
        return 0

    build_dir = (ROOT / args.build).resolve()
    signal.signal(signal.SIGTERM, interrupted)
    if not (build_dir / "CMakeCache.txt").is_file():
        print(f"{build_dir} is not a configured build directory (cmake --preset release first)", file=sys.stderr)
        return 2
    timeout_before = cached_test_timeout(build_dir)
    if not set_test_timeout(build_dir, str(TEST_TIMEOUT_S)):
        return 2
    try:
        return judge(mutations, build_dir, args.jobs)
    finally:
        # The source is unmutated again here; the rebuild also writes the old time-out into the test lists.
        set_test_timeout(build_dir, timeout_before)
        build(build_dir, args.jobs)


def judge(mutations: list[Mutation], build_dir: pathlib.Path, jobs: int) -> int:
    """Builds and tests the unmutated code, then each mutation; prints the table."""
    ok, log = build(build_dir, jobs)
    if not ok:
        print(f"the unmutated code does not build in {build_dir}:\n{log}", file=sys.stderr)
        return 2
    selections = sorted({m.tests or "." for m in mutations})
    for selection in selections:
        passed, failed, ran = run_tests(build_dir, selection, jobs)
        if not passed:
            print(f"baseline: tests '{selection}' fail without any mutation ({ran} ran; failed: {failed}); "
                  "a mutation could not be judged", file=sys.stderr)
            return 2

    rows = []
    started = time.monotonic()
    try:
        for n, m in enumerate(mutations, start=1):
            print(f"[{n}/{len(mutations)}] {m.ident}: {m.what}", flush=True)
            with Applied(m):
                built, log = build(build_dir, jobs)
                if not built:
                    rows.append((m, "does not compile", log.strip().splitlines()[-1:] or [""]))
                    continue
                passed, failed, ran = run_tests(build_dir, m.tests or ".", jobs)
            if not passed:
                rows.append((m, "killed", failed[:2] or [f"({ran} tests ran)"]))
            else:
                rows.append((m, "survived (explained)" if m.survives else "SURVIVED", [m.survives or f"{ran} tests passed"]))
    except KeyboardInterrupt:
        print("interrupted: the source is restored; rebuilding it", file=sys.stderr)
        return 1

    print()
    print(f"{'mutation':42} {'result':20} evidence")
    for m, result, evidence in rows:
        print(f"{m.ident:42} {result:20} {', '.join(evidence)}")
    killed = sum(1 for _, r, _ in rows if r == "killed")
    explained = sum(1 for _, r, _ in rows if r == "survived (explained)")
    bad = [m.ident for m, r, _ in rows if r in ("SURVIVED", "does not compile")]
    print(f"\n{len(rows)} mutations: {killed} killed, {explained} survived with a reason, {len(bad)} survived "
          f"or did not compile ({', '.join(bad) or 'none'}); {time.monotonic() - started:.0f} s")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
