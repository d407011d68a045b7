#!/usr/bin/env python3
"""Runs clang-tidy (the checks of .clang-tidy) on the library's, the command's and the Python module's sources and
fails (exit 1) on a finding that .clang-tidy-baseline does not list: the findings the tree had when the check was
introduced are listed there per file and check, to be fixed over time; a new one fails `make test`.

  scripts/check-tidy.py BUILD_DIR                 BUILD_DIR has compile_commands.json (the clang build: build/asan)
  scripts/check-tidy.py BUILD_DIR --write-cache   the same, and records every source's findings in
                                                  .clang-tidy-cache (commit it with the change, once it passes)
  scripts/check-tidy.py BUILD_DIR --update        rewrite the baseline (and the cache) from the current findings

clang-tidy takes about 10 CPU seconds a source (most of CI's time once), so each source's findings are kept in
.clang-tidy-cache under a key: a hash of what can change them (clang-tidy's version, .clang-tidy, the compile command,
the source and every header of the tree it includes). A source whose key is recorded is not checked again; any
change to it, to a header it includes, to its flags or to the checks runs clang-tidy on it. A source clang cannot
compile fails the check (exit 2) rather than passing unread.
"""
import concurrent.futures
import hashlib
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BASELINE = ROOT / ".clang-tidy-baseline"
CACHE = ROOT / ".clang-tidy-cache"
FINDING = re.compile(r"^(/[^:]+):(\d+):(\d+): warning: .* \[([a-z0-9.,-]+)\]$")


def fail(message, code=2):
    print(f"check-tidy: {message}", file=sys.stderr)
    sys.exit(code)


def relative(path):
    """A path of the tree relative to its root (compile commands and clang name files absolutely), else None."""
    try:
        return Path(os.path.normpath(path)).relative_to(ROOT).as_posix()
    except ValueError:
        return None


def sources(build):
    """The sources to check (the library's, the command's and the Python module's, as this build compiles them) and
    their commands."""
    commands = {}
    for entry in json.loads((build / "compile_commands.json").read_text()):
        name = relative(Path(entry["directory"], entry["file"]))
        if name:
            commands[name] = entry
    tracked = subprocess.run(["git", "ls-files", "libs/*/src/*.cpp", "apps/*.cpp", "python/src/*.cpp"], cwd=ROOT, check=True,
                             capture_output=True, text=True).stdout.split()
    # A source of a disabled option (the window without SDL2) has no command and is not checked.
    return {name: commands[name] for name in tracked if name in commands}


def key(tidy_version, checks, entry):
    """The hash of what decides a source's findings, or None when its includes cannot be listed."""
    argv = shlex.split(entry["command"]) if "command" in entry else list(entry["arguments"])
    # The command without its output: the headers it includes (-MM lists the user headers, not the system ones).
    flags, skip = [], False
    for arg in argv:
        if skip:
            skip = False
        elif arg == "-o":
            skip = True
        elif arg != "-c" and not arg.startswith("-o"):
            flags.append(arg)
    deps = subprocess.run(flags + ["-MM", "-MG", "-MF", "-"], cwd=entry["directory"], capture_output=True, text=True)
    if deps.returncode != 0:
        return None
    files = sorted({relative(Path(entry["directory"], f)) or f
                    for f in deps.stdout.replace("\\\n", " ").split(":", 1)[1].split()})
    h = hashlib.sha256()
    h.update(tidy_version.encode())
    h.update(checks)
    h.update(" ".join(flags).replace(str(ROOT), "<root>").encode())  # the same key in any checkout
    for name in files:
        path = ROOT / name
        h.update(name.encode())
        h.update(path.read_bytes() if path.is_file() else b"(absent)")
    return h.hexdigest()


def run_tidy(tidy, build, name):
    """The findings clang-tidy reports in the tree's files for one source, as sorted 'file check line:col' strings."""
    result = subprocess.run([tidy, "-p", str(build), "--quiet", f"--header-filter=^{ROOT}/(libs|apps|python)/", name],
                            cwd=ROOT, capture_output=True, text=True)
    if result.returncode != 0:
        errors = [line for line in result.stdout.splitlines() if ": error: " in line]
        fail("clang-tidy could not check every file:\n" + "\n".join(errors[:20] or [f"{name}: clang-tidy failed"]))
    found = set()
    for line in result.stdout.splitlines():
        m = FINDING.match(line)
        if m and relative(m[1]):
            found.add(f"{relative(m[1])} {m[4]} {m[2]}:{m[3]}")
    return sorted(found)


def main():
    args = sys.argv[1:]
    if not args or args[0].startswith("-"):
        fail("usage: check-tidy.py BUILD_DIR [--write-cache | --update]")
    build = Path(args[0]).resolve()
    mode = args[1] if len(args) > 1 else ""
    if mode not in ("", "--write-cache", "--update"):
        fail(f"unknown option {mode}; usage: check-tidy.py BUILD_DIR [--write-cache | --update]")
    tidy = shutil.which("clang-tidy-14") or shutil.which("clang-tidy")
    if not tidy:
        fail("clang-tidy not found (scripts/install-deps.sh installs it)")
    if not (build / "compile_commands.json").is_file():
        fail(f"no {build}/compile_commands.json (configure it first)")
    version = subprocess.run([tidy, "--version"], capture_output=True, text=True, check=True).stdout
    checks = (ROOT / ".clang-tidy").read_bytes()
    cache = json.loads(CACHE.read_text()) if CACHE.is_file() else {}
    todo = sources(build)

    with concurrent.futures.ThreadPoolExecutor(os.cpu_count() or 1) as pool:
        keys = dict(zip(todo, pool.map(lambda name: key(version, checks, todo[name]), todo)))
        stale = [name for name in todo if not keys[name] or cache.get(name, {}).get("key") != keys[name]]
        fresh = dict(zip(stale, pool.map(lambda name: run_tidy(tidy, build, name), stale)))
    findings = {name: fresh[name] if name in fresh else cache[name]["findings"] for name in todo}

    # Findings in the tree's headers count once, however many sources include them.
    unique = {f for found in findings.values() for f in found}
    counts = Counter(" ".join(f.split()[:2]) for f in unique)
    total = sum(counts.values())
    print(f"check-tidy: {len(stale)} of {len(todo)} sources checked, {len(todo) - len(stale)} unchanged since "
          f".clang-tidy-cache")

    if mode in ("--update", "--write-cache"):
        # Each source's findings, new ones too: a failing run need not check its sources again once they are fixed.
        recorded = {name: {"key": keys[name], "findings": findings[name]} for name in sorted(todo) if keys[name]}
        CACHE.write_text(json.dumps(recorded, indent=1) + "\n")
        print(f"check-tidy: .clang-tidy-cache records {len(recorded)} sources")
    if mode == "--update":
        BASELINE.write_text("".join(f"{k} {n}\n" for k, n in sorted(counts.items())))
        print(f"check-tidy: baseline rewritten ({total} findings)")
    else:
        allowed = {}
        for line in BASELINE.read_text().splitlines():
            file, check, n = line.split()
            allowed[f"{file} {check}"] = int(n)
        new = [f"  {k.split()[0]}: {n} {k.split()[1]} finding(s), the baseline allows {allowed.get(k, 0)}"
               for k, n in sorted(counts.items()) if n > allowed.get(k, 0)]
        if new:
            fail(f"new clang-tidy findings (run clang-tidy -p {args[0]} FILE to see them; fix them):\n" + "\n".join(new),
                 1)
        print(f"check-tidy: no new findings ({total} listed in .clang-tidy-baseline remain)")


if __name__ == "__main__":
    main()
