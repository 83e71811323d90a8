"""How long `bash run.sh` takes, stage by stage: runs it in a checkout, stamps each line it prints
and writes the time from one stage line (`setup: [k/4] ...`, `run.sh: simulating ...`) to the next.
On a fresh machine (no .venv, no build/ in the checkout, the Debian packages not installed) this is
the first run the README speaks of; the JSON says which it was (`fresh`: neither .venv nor build/
existed when it started).

    python3 tools/first_run.py --repo CHECKOUT --json first_run.json   # plain python3: no venv yet

Prints each line of run.sh with its time since the start, then the stages; exits with run.sh's code."""

from __future__ import annotations

import argparse
import json
import os
import platform
import re
import subprocess
import sys
import time
from pathlib import Path

STAGE = re.compile(r"^(setup: \[\d/\d\] .*|run\.sh: simulating .*)$")


def os_name():
    try:
        text = Path("/etc/os-release").read_text()
    except OSError:
        return platform.platform()
    m = re.search(r'^PRETTY_NAME="?(.*?)"?$', text, re.M)
    return m.group(1) if m else platform.platform()


def stages(lines, total):
    """[(stage line, seconds)] from (seconds since the start, line) pairs; the time before the first
    stage line is its own row."""
    marks = [(t, line) for t, line in lines if STAGE.match(line)]
    out = []
    if marks and marks[0][0] > 0:
        out.append({"stage": "(before the first stage line)", "s": marks[0][0]})
    for i, (t, line) in enumerate(marks):
        end = marks[i + 1][0] if i + 1 < len(marks) else total
        out.append({"stage": line, "s": end - t})
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repo", type=Path, default=Path("."), help="the checkout to run run.sh in (default: .)")
    ap.add_argument("--json", type=Path, help="write the times here")
    args = ap.parse_args(argv)
    repo = args.repo.resolve()
    fresh = not (repo / ".venv").exists() and not (repo / "build").exists()
    t0 = time.perf_counter()
    lines = []
    with subprocess.Popen(
        ["bash", str(repo / "run.sh")], cwd=repo, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True
    ) as proc:
        for line in proc.stdout:
            t = time.perf_counter() - t0
            lines.append((t, line.rstrip("\n")))
            print(f"{t:7.1f} s  {line}", end="", flush=True)
    total = time.perf_counter() - t0
    rows = stages(lines, total)
    for r in rows:
        print(f"{r['s']:7.1f} s  {r['stage']}")
    print(f"{total:7.1f} s  in all (exit code {proc.returncode}; {'fresh' if fresh else 'not fresh'})")
    if args.json:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=repo, capture_output=True, text=True)
        report = {
            "command": "bash run.sh",
            "fresh": fresh,
            "exit_code": proc.returncode,
            "total_s": total,
            "stages": rows,
            "commit": commit.stdout.strip(),
            "date": time.strftime("%Y-%m-%d"),
            "os": os_name(),
            "cores": os.cpu_count(),
        }
        args.json.write_text(json.dumps(report, indent=1, ensure_ascii=False) + "\n")
        print(f"wrote {args.json}")
    return proc.returncode


if __name__ == "__main__":
    sys.exit(main())
