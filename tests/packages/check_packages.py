#!/usr/bin/env python3
"""Checks that run.sh installs everything the build and the tests use.

A package a developer installed by hand (or that a machine image happened to
have) hides a missing install step: the build and CI stay green on that
machine and a fresh Debian machine cannot build. This check asks the build
and the system what was really used and who owns it:

  * every system header the compiler read (ninja's dependency log),
  * every shared library the executables link (ldd),
  * every program the build and the tests run (PROGRAMS below),
  * every Python module the test scripts import, with the interpreter CMake chose,
  * the data files the tests read from Debian packages (DATA_FILES below),

maps each to its Debian package (dpkg's file lists) and fails when that
package is neither in run.sh's *_PACKAGES lists nor a dependency of one of
them (recursively, Depends and Pre-Depends only), nor part of every Debian
system (Essential or Priority: required).

usage: check_packages.py --source DIR --build DIR [--run-sh FILE] [--drop PKG ...]
  --run-sh FILE  the run.sh whose lists are checked (default: SOURCE/run.sh)
  --drop PKG     check as if run.sh did not list PKG (the check's own test)
Exit 0: all found; 1: something is not installed by run.sh; 2: cannot tell;
77: the build is not a ninja build (no dependency log to read).
"""
import argparse
import ast
import os
import re
import subprocess
import sys

# Programs the build and the tests run, and what runs them.
PROGRAMS = {
    "cmake": "the build (run.sh)",
    "ninja": "the build (run.sh)",
    "c++": "the build (CMake's compiler)",
    "pkg-config": "the build (CMakeLists.txt: imgui)",
    "glslangValidator": "the build (shaders)",
    "ctest": "./run.sh test",
    "xvfb-run": "GUI tests (tests/gui/gui_driver.py)",
    "Xvfb": "GUI tests (started by xvfb-run)",
    "xauth": "GUI tests (xvfb-run)",
    "xdotool": "GUI tests (input and window search)",
    "import": "GUI tests (ImageMagick screenshots)",
    "convert": "GUI tests (ImageMagick pixel reads)",
    "compare": "GUI tests (ImageMagick image comparison)",
    "node": "glTF-Validator test (tests/cli/validate_demo.sh)",
    "npm": "glTF-Validator test (installs gltf-validator)",
    "timeout": "glTF-Validator test",
    "blender": "export test (imports the animated glTF headless)",
    "vdb_print": "VDB export test (tests/cli/export_checks.py vdb)",
    "ffmpeg": "animorph-cli bake --mp4 and farm assemble --mp4 (playblast encoding)",
    "ffprobe": "playblast tests (frame count and size of the mp4)",
    "clang++": "fuzz targets (./run.sh fuzz, ./run.sh test: tests/fuzz)",
    "munged": "farm test (tests/cli/farm_slurm_check.py: MUNGE for the test's Slurm cluster)",
    "slurmctld": "farm test (the test's Slurm controller)",
    "slurmd": "farm test (the test's Slurm node)",
    "sbatch": "farm test (animorph-cli farm slurm --submit)",
    "squeue": "farm test (waits for the jobs)",
    "sinfo": "farm test (waits for the node)",
    "scontrol": "farm test (job states)",
    "scancel": "farm test (cancels what is left at the end)",
}

# Runtime libraries clang links into the fuzz targets, looked up in clang's runtime folder.
CLANG_RUNTIMES = {
    "libclang_rt.fuzzer-x86_64.a": "fuzz targets (-fsanitize=fuzzer)",
    "libclang_rt.asan-x86_64.a": "fuzz targets (-fsanitize=address)",
    "libclang_rt.ubsan_standalone-x86_64.a": "fuzz targets (-fsanitize=undefined)",
}

# Files from Debian packages that the tests open by path.
DATA_FILES = {
    "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json": "GPU and GUI tests (lavapipe's Vulkan driver)",
    "/usr/share/assimp/models/glTF2": "import tests (real exporters' glTF files)",
}


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


def listed_packages(run_sh):
    """The words of every NAME_PACKAGES=( ... ) array in run.sh."""
    text = open(run_sh).read()
    pkgs = []
    for m in re.finditer(r"^[A-Z_]*PACKAGES=\(([^)]*)\)", text, re.M):
        body = re.sub(r"#.*", "", m.group(1))
        pkgs += [w for w in body.split() if re.fullmatch(r"[a-z0-9][a-z0-9.+-]+", w)]
    return sorted(set(pkgs))


def dependency_closure(pkgs):
    """pkgs and everything they depend on, recursively (Depends and Pre-Depends)."""
    out = run(["apt-cache", "depends", "--recurse", "--no-recommends", "--no-suggests", "--no-conflicts",
               "--no-breaks", "--no-replaces", "--no-enhances", *pkgs])
    if out.returncode != 0:
        sys.exit(f"check-packages: apt-cache depends failed (run 'apt-get update' once?):\n{out.stderr}")
    names = set()
    for line in out.stdout.splitlines():
        if line and not line[0].isspace():
            names.add(line.strip().strip("<>").split(":")[0])
    return names


def base_system():
    """Installed packages that every Debian system has: Essential, or Priority required."""
    out = run(["dpkg-query", "-W", "-f", "${Package} ${Essential} ${Priority}\n"])
    base = set()
    for line in out.stdout.splitlines():
        parts = line.split()
        if len(parts) >= 2 and ("yes" in parts[1:] or "required" in parts[1:]):
            base.add(parts[0])
    return base


class Owners:
    """Which installed package owns a path, from dpkg's file lists (one read, no dpkg -S per file)."""

    def __init__(self):
        self.owner = {}
        self.by_basename = {}
        info = "/var/lib/dpkg/info"
        for name in os.listdir(info):
            if not name.endswith(".list"):
                continue
            pkg = name[:-5].split(":")[0]
            with open(os.path.join(info, name), errors="replace") as f:
                for path in f:
                    path = path.rstrip("\n")
                    self.owner.setdefault(path, set()).add(pkg)
                    if "/bin/" in path or "/sbin/" in path:
                        self.by_basename.setdefault(os.path.basename(path), set()).add(pkg)

    def module_owners(self, name):
        """Packages shipping a Python package or module of that name anywhere (a program's own Python)."""
        tails = (f"/{name}/__init__.py", f"/{name}.py")
        found = set()
        for path, pkgs in self.owner.items():
            if path.endswith(tails):
                found |= pkgs
        return found

    def of(self, path):
        """The packages owning path, trying it as given, resolved, and across the /usr merge."""
        candidates = {path, os.path.realpath(path)}
        for p in list(candidates):
            if p.startswith("/usr/"):
                candidates.add(p[4:])
            else:
                candidates.add("/usr" + p)
        found = set()
        for p in candidates:
            found |= self.owner.get(p, set())
        return found


# Modules compiled into Blender's own executable (no file ships them): a script that Blender runs
# headless imports them, and the blender package is what provides them.
BLENDER_BUILTIN_MODULES = {m: {"blender"} for m in ("bmesh", "mathutils", "bgl", "gpu", "aud", "bl_math",
                                                     "imbuf", "idprop", "freestyle", "bpy_types")}


def system_headers(build, source):
    out = run(["ninja", "-C", build, "-t", "deps"])
    if out.returncode != 0:
        sys.exit(f"check-packages: 'ninja -t deps' failed in {build}:\n{out.stderr}")
    roots = (os.path.realpath(source) + "/", os.path.realpath(build) + "/")
    headers = set()
    for line in out.stdout.splitlines():
        if line.startswith(" "):
            p = line.strip()
            if os.path.isabs(p) and not os.path.realpath(p).startswith(roots):
                headers.add(p)
    return headers


def executables(build):
    exes = []
    for d, _, files in os.walk(build):
        if "CMakeFiles" in d:
            continue
        for f in files:
            p = os.path.join(d, f)
            if f.startswith("animorph") and os.access(p, os.X_OK) and not f.endswith((".py", ".sh")):
                with open(p, "rb") as fh:
                    if fh.read(4) == b"\x7fELF":
                        exes.append(p)
    return sorted(exes)


def linked_libraries(exes):
    libs = {}
    for exe in exes:
        for line in run(["ldd", exe]).stdout.splitlines():
            m = re.search(r"=>\s*(/\S+)", line) or re.match(r"\s*(/\S+)\s+\(", line)
            if m:
                libs.setdefault(m.group(1), os.path.basename(exe))
    return libs


def python_of(build):
    try:
        for line in open(os.path.join(build, "CMakeCache.txt")):
            if re.match(r"_?Python3_EXECUTABLE:[A-Z]+=", line):
                return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return None


def test_imports(source):
    """Top-level modules the scripts under tests/ import, less the tests' own modules."""
    names, own = set(), set()
    for d, _, files in os.walk(os.path.join(source, "tests")):
        if "node_modules" in d:
            continue
        for f in files:
            if f.endswith(".py"):
                own.add(f[:-3])
                try:
                    tree = ast.parse(open(os.path.join(d, f)).read())
                except SyntaxError:
                    continue
                for node in ast.walk(tree):
                    if isinstance(node, ast.Import):
                        names |= {a.name.split(".")[0] for a in node.names}
                    elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                        names.add(node.module.split(".")[0])
    return sorted(names - own)


MODULE_PROBE = """
import importlib.util, sys
for name in sys.argv[1:]:
    try:
        spec = importlib.util.find_spec(name)
    except Exception:
        spec = None
    origin = "missing" if spec is None else (spec.origin or "namespace")
    print(name + "\\t" + origin)
"""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--build", required=True)
    ap.add_argument("--run-sh")
    ap.add_argument("--drop", action="append", default=[])
    a = ap.parse_args()
    source, build = os.path.abspath(a.source), os.path.abspath(a.build)
    run_sh = a.run_sh or os.path.join(source, "run.sh")

    if not os.path.exists(os.path.join(build, ".ninja_deps")):
        print(f"check-packages: {build} is not a ninja build (no .ninja_deps): cannot list the headers; skipped")
        return 77
    listed = [p for p in listed_packages(run_sh) if p not in a.drop]
    if not listed:
        print(f"check-packages: found no NAME_PACKAGES=( ... ) lists in {run_sh}")
        return 2
    allowed = dependency_closure(listed) | base_system()
    owners = Owners()
    problems = []

    def judge(kind, what, path, why):
        pkgs = owners.of(path)
        if not pkgs:
            problems.append(f"{kind} {what}: {path} belongs to no Debian package ({why}); "
                            f"a fresh machine will not have it")
        elif not pkgs & allowed:
            names = ", ".join(sorted(pkgs))
            problems.append(f"{kind} {what}: package {names} is not installed by run.sh, nor a dependency "
                            f"of a package it installs ({why}); add {sorted(pkgs)[0]} to a list in run.sh")
        return bool(pkgs & allowed)

    headers = system_headers(build, source)
    for h in sorted(headers):
        judge("header", h, h, "read by the build")

    exes = executables(build)
    libs = linked_libraries(exes)
    for lib, exe in sorted(libs.items()):
        judge("library", os.path.basename(lib), lib, f"linked by {exe}")

    for prog, why in PROGRAMS.items():
        # The packages that ship a program of that name, and the owner of the one on PATH (through
        # Debian's alternatives: /usr/bin/c++ -> /etc/alternatives/c++ -> g++-12's file).
        # /usr/bin/PROG is looked at too when PATH finds another first (a /usr/local/bin/convert),
        # and through its alternatives link (/usr/bin/convert -> ... -> convert-im6.q16).
        pkgs = set(owners.by_basename.get(prog, set()))
        where = run(["sh", "-c", f"command -v {prog}"]).stdout.strip()
        for path in (where, f"/usr/bin/{prog}", f"/usr/sbin/{prog}"):
            if path and os.path.exists(path):
                pkgs |= owners.of(path)
        if pkgs & allowed:
            continue
        if pkgs:
            problems.append(f"program {prog}: package {', '.join(sorted(pkgs))} is not installed by run.sh, nor "
                            f"a dependency of a package it installs ({why}); add it to a list in run.sh")
        elif where:
            problems.append(f"program {prog}: found only at {where}, which no Debian package installs ({why})")
        else:
            problems.append(f"program {prog}: not installed ({why})")

    for path, why in DATA_FILES.items():
        judge("file", path, path, why)

    runtime_dir = run(["sh", "-c", "clang++ --print-runtime-dir 2>/dev/null"]).stdout.strip()
    for name, why in CLANG_RUNTIMES.items():
        path = os.path.join(runtime_dir, name)
        if runtime_dir and os.path.exists(path):
            judge("file", path, path, why)
        else:
            problems.append(f"file {name}: not in clang's runtime folder '{runtime_dir}' ({why})")

    py = python_of(build)
    modules = test_imports(source)
    if not py:
        problems.append("python: the build has no Python3_EXECUTABLE (CMakeCache.txt); the tests need one")
    elif judge("program", "python3", py, "the interpreter CMake chose for the tests"):
        out = run([py, "-c", MODULE_PROBE, *modules])
        for line in out.stdout.splitlines():
            name, origin = line.split("\t", 1)
            if origin in ("built-in", "frozen"):
                continue
            if origin == "missing":
                # Not for this interpreter: a module of a program's own Python (Blender's bpy) counts
                # when a package that run.sh installs ships it.
                shipped = owners.module_owners(name) or BLENDER_BUILTIN_MODULES.get(name, set())
                if not shipped:
                    problems.append(f"python module {name}: not importable by {py}, and no Debian package "
                                    f"ships it (imported by tests/)")
                elif not shipped & allowed:
                    problems.append(f"python module {name}: package {', '.join(sorted(shipped))} is not "
                                    f"installed by run.sh (imported by tests/)")
            elif not os.path.realpath(origin).startswith(source + "/"):
                judge("python module", name, origin, "imported by tests/")

    print(f"check-packages: {len(listed)} packages listed in {os.path.relpath(run_sh, source)}, "
          f"{len(allowed)} with their dependencies and the base system; checked {len(headers)} headers, "
          f"{len(libs)} libraries of {len(exes)} executables, {len(PROGRAMS)} programs, "
          f"{len(DATA_FILES) + len(CLANG_RUNTIMES)} data paths, {len(modules)} Python modules")
    for p in problems:
        print("MISSING " + p)
    if problems:
        print(f"check-packages: {len(problems)} thing(s) the build or the tests use that run.sh does not install")
        return 1
    print("check-packages: run.sh installs everything the build and the tests use")
    return 0


if __name__ == "__main__":
    sys.exit(main())
