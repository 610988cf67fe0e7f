#!/usr/bin/env python3
"""Runs the commands of a docs page's ```sh fences as a reader would, from a scratch copy of the root.

Each line of a fence is one command, run from the repository root after `bash deploy/setup.sh`
(a leading `bash deploy/setup.sh && ` is dropped: the build under test stands for it). A line
ending in `# slow` is listed and skipped; one ending in `# until Ctrl-C` must still be running after
a few seconds and exit 0 on SIGINT; every other line must exit 0 within the time limit. Outputs
land in a scratch folder whose entries link to the repository's, so the checkout stays clean.
"""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

SETUP_PREFIX = "bash deploy/setup.sh && "


def commands(page):
    """(line number, command, kind) for every command in the page's sh fences."""
    found = []
    in_fence = False
    pending = ""
    pending_line = 0
    with open(page, encoding="utf-8") as f:
        for number, raw in enumerate(f, 1):
            line = raw.rstrip("\n")
            if re.match(r"^\s*```", line):
                in_fence = (not in_fence) and line.strip() in ("```sh", "```bash", "```shell")
                continue
            if not in_fence:
                continue
            stripped = line.strip()
            if not pending and (not stripped or stripped.startswith("#")):
                continue
            if not pending:
                pending_line = number
            if stripped.endswith("\\"):
                pending += stripped[:-1] + " "
                continue
            command = pending + stripped
            pending = ""
            kind = "run"
            if re.search(r"#\s*slow\b", command):
                kind = "slow"
            elif re.search(r"#\s*until Ctrl-C", command):
                kind = "server"
            if command.startswith(SETUP_PREFIX):
                command = command[len(SETUP_PREFIX):]
            elif command.startswith("bash deploy/setup.sh"):
                kind = "setup"
            found.append((pending_line, command, kind))
    return found


def scratch_root(repo, build):
    """A folder whose entries link to the repository's, with build/ linked to the build under test."""
    root = tempfile.mkdtemp(prefix="rovctl-docs-")
    for name in os.listdir(repo):
        if name in (".git", "build") or name.startswith("build-"):
            continue
        os.symlink(os.path.join(repo, name), os.path.join(root, name))
    os.symlink(build, os.path.join(root, "build"))
    return root


def run_server(command, cwd, settle_s):
    proc = subprocess.Popen(["bash", "-c", command], cwd=cwd, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, start_new_session=True, text=True)
    time.sleep(settle_s)
    if proc.poll() is not None:
        out = proc.stdout.read()
        return False, f"exited {proc.returncode} before Ctrl-C:\n{out}"
    os.killpg(proc.pid, signal.SIGINT)
    try:
        out, _ = proc.communicate(timeout=20)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        out, _ = proc.communicate()
        return False, f"still running 20 s after Ctrl-C:\n{out}"
    # bash -c hands the line to rovctl; rovctl's own exit code on SIGINT is what the reader sees.
    if proc.returncode != 0:
        return False, f"exit {proc.returncode} after Ctrl-C:\n{out}"
    return True, ""


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repo", required=True, help="the repository root")
    parser.add_argument("--build", required=True, help="the build folder that ./build stands for")
    parser.add_argument("--page", default="docs/getting-started.md", help="page, from the root")
    parser.add_argument("--timeout-s", type=float, default=300, help="limit for one command")
    parser.add_argument("--settle-s", type=float, default=5, help="how long a server runs first")
    args = parser.parse_args()

    page = os.path.join(args.repo, args.page)
    if not os.path.isfile(page):
        print(f"{args.page}: no such page under {args.repo}", file=sys.stderr)
        return 2
    found = commands(page)
    if not any(kind in ("run", "server") for _, _, kind in found):
        print(f"{args.page}: no command to run in its sh fences", file=sys.stderr)
        return 1

    root = scratch_root(os.path.abspath(args.repo), os.path.abspath(args.build))
    passed = failed = skipped = 0
    try:
        for number, command, kind in found:
            where = f"{args.page}:{number}"
            if kind in ("slow", "setup"):
                print(f"SKIP {where}: {command}  ({kind}: not run here)")
                skipped += 1
                continue
            start = time.monotonic()
            if kind == "server":
                ok, why = run_server(command, root, args.settle_s)
            else:
                try:
                    done = subprocess.run(["bash", "-c", command], cwd=root, capture_output=True,
                                          text=True, timeout=args.timeout_s)
                    ok = done.returncode == 0
                    why = f"exit {done.returncode}:\n{done.stdout[-3000:]}{done.stderr[-3000:]}"
                except subprocess.TimeoutExpired:
                    ok, why = False, f"still running after {args.timeout_s:.0f} s"
            took = time.monotonic() - start
            if ok:
                print(f"PASS {where} ({took:.1f} s): {command}")
                passed += 1
            else:
                print(f"FAIL {where} ({took:.1f} s): {command}\n{why}")
                failed += 1
    finally:
        shutil.rmtree(root, ignore_errors=True)
    print(f"{passed} passed, {failed} failed, {skipped} skipped")
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
