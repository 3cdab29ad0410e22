"""The conformance suite run against every implementation we have, and the page comparing them.

Run from the project root::

    python benchmarks/suite_runs.py                    # suite v1, quick tier (a few minutes)
    python benchmarks/suite_runs.py --tier full        # every case of v1
    python benchmarks/suite_runs.py --suite /tmp/suites/v1 --out /tmp/suite-docs

Each implementation runs ``ifgm-ref oracle --suite SUITE --tier TIER --level reference`` in
its own process, one after another, its run file written to ``OUT/suite/SLUG.jsonl``
(``OUT`` is ``docs/`` by default):

* ``ifgm``: the Python reference, in process (``--planner ifgm``);
* ``ifgm-serve``: the same served as a program (``--cmd "python -m ifgm_ref serve --planner
  ifgm"``);
* ``ifgm-serve-twist``: the same answering velocity commands (``serve --twist``);
* ``c-port``: the C port, ``examples/c``'s ``ifgm_json``, built with ``make BUILD=DIR``
  into ``--c-build`` (``examples/c/build``, ignored by git, by default; ``--no-c`` leaves it
  out, e.g. without a C compiler); it promises the reference level (``tests/test_c_port.py``);
* ``float32``, ``opposite-ties``: the faithful variants of :mod:`ifgm_ref.oracle.variants`;

and every mutant of :mod:`ifgm_ref.oracle.mutants`, known broken (held to IFGM's promises),
into ``OUT/suite/broken/SLUG.jsonl``. A broken run's first failure keeps its plot,
``OUT/suite/counterexamples/IMPLEMENTATION/CASE/world.png``, which the page links to; the
rest of the evidence (traces, the world, the report) and the later failures' folders are
deleted, and the run file's ``counterexample`` of each deleted folder set to ``null``; the
plot kept is saved again in 256 colours (a third of its size), so that what is committed
stays small and every link of the page resolves. The implementations
meant to pass write their evidence in a temporary folder, deleted likewise (their failures,
if any, are unlinked: rerun ``ifgm-ref oracle --suite`` to see them). The folders
``OUT/suite`` and ``OUT/suite/broken`` are emptied of run files first, and
``OUT/suite/counterexamples`` deleted.

Then it renders the page, ``ifgm-ref report OUT/suite/*.jsonl --broken
OUT/suite/broken/*.jsonl --out OUT --name suite-report`` (``OUT/suite-report.md``, which the
site shows, and ``.html``, gitignored in ``docs/``). ``tests/test_suite_page.py`` checks that
the committed page is what the committed runs render.

It prints, per implementation, the wall-clock seconds of its run (around the subprocess:
start-up and imports included) and its verdict counts, and the machine with its load average
before and after: the runs share the machine, and seconds measured under load are longer.
"""

from __future__ import annotations

import argparse
import json
import os
import shlex
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from ifgm_ref.apps.bench.report import machine
from ifgm_ref.oracle.mutants import MUTANTS

ROOT = Path(__file__).resolve().parent.parent
C_PORT = ROOT / "examples" / "c"
TITLE = "Conformance suite {suite}, {tier} tier: every implementation"


@dataclass(frozen=True)
class Target:
    """One implementation to run: its file's slug, the oracle's options that name it, and
    whether it is broken on purpose."""

    slug: str
    options: tuple[str, ...]
    broken: bool = False


def _python() -> str:
    """How a served planner's command line starts: ``python`` when that is this interpreter
    (a shorter, portable label on the page), else this interpreter's path."""
    found = shutil.which("python")
    same = found is not None and Path(found).resolve() == Path(sys.executable).resolve()
    return "python" if same else shlex.quote(sys.executable)


def _kebab(name: str) -> str:
    """``GapAngleSignFlipped`` -> ``gap-angle-sign-flipped``."""
    return "".join(f"-{c.lower()}" if c.isupper() else c for c in name).lstrip("-")


def targets(c_program: Path | None) -> list[Target]:
    """Every implementation, those meant to pass first, then the mutants."""
    serve = f"{_python()} -m ifgm_ref serve --planner ifgm"
    found = [
        Target("ifgm", ("--planner", "ifgm")),
        Target("ifgm-serve", ("--cmd", serve)),
        Target("ifgm-serve-twist", ("--cmd", f"{serve} --twist")),
    ]
    if c_program is not None:
        program = os.path.relpath(c_program, ROOT)  # the page's label: no machine's path
        found.append(Target("c-port", ("--cmd", program, "--promises", "ifgm")))
    for slug, name in (("float32", "Float32"), ("opposite-ties", "OppositeTies")):
        planner = f"ifgm_ref.oracle.variants:{name}"
        found.append(Target(slug, ("--planner", planner, "--promises", "ifgm")))
    for mutant in MUTANTS.values():
        planner = f"{mutant.__module__}:{mutant.__name__}"
        options = ("--planner", planner, "--promises", "ifgm")
        found.append(Target(_kebab(mutant.__name__), options, broken=True))
    return found


def build_c_port(build: Path) -> Path:
    """``make -C examples/c BUILD=build``; the protocol program's path."""
    command = ["make", "-s", "--no-print-directory", "-C", str(C_PORT), f"BUILD={build}"]
    subprocess.run(command, check=True)
    return build / "ifgm_json"


def shrink_png(path: Path) -> None:
    """Save the plot ``path`` again in 256 colours: a third of its size, the same picture."""
    from PIL import Image

    with Image.open(path) as image:
        small = image.convert("RGB").quantize(256)
    small.save(path, "PNG", optimize=True)


def prune(run_file: Path, out: Path, *, keep_first: bool) -> None:
    """Delete the evidence of ``run_file``'s failures but, with ``keep_first``, the first
    failure's ``world.png``; set each deleted folder's ``counterexample`` to ``null``.

    Every line but those changed is kept as the oracle wrote it."""
    base = run_file.parent
    lines = run_file.read_text().splitlines()
    seen_failure = False
    for k, line in enumerate(lines):
        record = json.loads(line)
        failed = record.get("type") == "case" and record.get("verdict") == "fail"
        first, seen_failure = failed and not seen_failure, seen_failure or failed
        if record.get("type") != "case" or record.get("counterexample") is None:
            continue
        folder = (base / record["counterexample"]).resolve()
        plot = folder / "world.png"
        if keep_first and first and plot.is_file():
            for path in folder.iterdir():  # the plot only
                if path != plot:
                    shutil.rmtree(path) if path.is_dir() else path.unlink()
            shrink_png(plot)
            continue
        if folder.is_relative_to(out.resolve()):
            shutil.rmtree(folder, ignore_errors=True)
        record["counterexample"] = None
        lines[k] = json.dumps(record)
    run_file.write_text("\n".join(lines) + "\n")


def _remove_empty_folders(top: Path) -> None:
    for folder in sorted(top.rglob("*"), key=lambda p: len(p.parts), reverse=True):
        if folder.is_dir() and not any(folder.iterdir()):
            folder.rmdir()


def run(target: Target, args: argparse.Namespace, folders: dict[str, Path]) -> dict[str, object]:
    """Run ``target``'s suite run in its own process; its summary line, plus the wall clock."""
    run_file = (folders["broken"] if target.broken else folders["runs"]) / f"{target.slug}.jsonl"
    with tempfile.TemporaryDirectory(prefix="suite-evidence-") as scratch:
        artifacts = folders["counterexamples"] if target.broken else Path(scratch)
        command = [
            sys.executable, "-m", "ifgm_ref", "oracle",
            "--suite", args.suite, "--tier", args.tier, "--level", "reference",
            *target.options,
            "--results", str(run_file), "--artifacts", str(artifacts),
            "--timeout", str(args.timeout),
        ]  # fmt: skip
        started = time.perf_counter()
        done = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
        wall = time.perf_counter() - started
        if done.returncode not in (0, 1) or not run_file.is_file():
            sys.exit(f"{target.slug}: exit status {done.returncode}\n{done.stderr}")
        prune(run_file, folders["out"], keep_first=target.broken)
    summary = json.loads(run_file.read_text().splitlines()[-1])
    return {**summary, "wall": wall, "file": run_file}


def main() -> None:
    """Run every implementation, prune the evidence, render the page; print the times."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--suite", default="v1", help="suite version or folder (default v1)")
    parser.add_argument("--tier", choices=("quick", "full"), default="quick")
    parser.add_argument(
        "--out", type=Path, default=ROOT / "docs", help="where suite/ and the page go (docs)"
    )
    parser.add_argument(
        "--c-build", type=Path, default=C_PORT / "build",
        help="where the C port is built (default: examples/c/build, as its README builds it; "
        "ignored by git)",
    )  # fmt: skip
    parser.add_argument("--no-c", action="store_true", help="leave the C port out")
    parser.add_argument("--timeout", type=float, default=10.0, help="per-reply timeout, s")
    parser.add_argument("--title", help=f"the page's title (default: '{TITLE}')")
    args = parser.parse_args()

    out = args.out.resolve()
    folders = {"out": out, "runs": out / "suite", "broken": out / "suite" / "broken"}
    folders["counterexamples"] = out / "suite" / "counterexamples"
    for folder in (folders["runs"], folders["broken"]):
        folder.mkdir(parents=True, exist_ok=True)
        for old in folder.glob("*.jsonl"):
            old.unlink()
    shutil.rmtree(folders["counterexamples"], ignore_errors=True)

    c_program = None if args.no_c else build_c_port(args.c_build.resolve())
    print(f"machine: {machine()}")
    print(f"suite {args.suite}, tier {args.tier}, level reference; runs one after another")
    rows = []
    for target in targets(c_program):
        s = run(target, args, folders)
        counts = ", ".join(f"{s[v]} {v}" for v in ("pass", "fail", "skip", "error") if s[v])
        lines = [json.loads(line) for line in Path(str(s["file"])).read_text().splitlines()]
        failed = [r["id"] for r in lines if r.get("verdict") in ("fail", "error")]
        if target.broken:
            verdict = "caught" if not s["ok"] else "NOT CAUGHT"
        else:
            verdict = "ok" if s["ok"] else "NOT OK"
        shown = ", ".join(failed[:4]) + (f" and {len(failed) - 4} more" if failed[4:] else "")
        load = " ".join(f"{v:.2f}" for v in os.getloadavg())
        print(
            f"{target.slug:26} {s['wall']:7.1f} s wall ({s['seconds']:.1f} s in cases), "
            f"{counts}: {verdict}{f' by {shown}' if failed else ''} [load {load}]",
            flush=True,
        )
        rows.append(s)
    _remove_empty_folders(folders["counterexamples"])

    suite = str(rows[0]["suite"])
    title = args.title or TITLE.format(suite=suite, tier=args.tier)
    runs = sorted(str(p.relative_to(out)) for p in folders["runs"].glob("*.jsonl"))
    broken = sorted(str(p.relative_to(out)) for p in folders["broken"].glob("*.jsonl"))
    page = [sys.executable, "-m", "ifgm_ref", "report", *runs]
    page += [a for path in broken for a in ("--broken", path)]
    page += ["--out", ".", "--name", "suite-report", "--title", title]
    subprocess.run(page, cwd=out, check=True)
    load = " ".join(f"{v:.2f}" for v in os.getloadavg())
    print(f"wrote {out / 'suite-report.md'} and .html; load average now {load}")


if __name__ == "__main__":
    main()
