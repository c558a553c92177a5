#!/usr/bin/env python3
"""Runs the libFuzzer targets built in a fuzz build folder (./run.sh fuzz builds it).

For each target: first every regression file under tests/fuzz/regressions/TARGET/ once
(inputs that crashed, hung or ran away before: each must now pass), then fuzzing for
SECONDS on the target's working corpus (BUILD/corpus/TARGET, kept between runs) and its
committed seeds (tests/fuzz/corpus/TARGET) with its dictionary. An input that crashes,
breaks a sanitizer check or a target's property, runs longer than 10 s or needs more than
1 GiB is written to BUILD/artifacts/TARGET/ and fails the run; keep it as a regression
file (under regressions/TARGET/) with the fix.

usage: run_fuzzers.py --build DIR [--seconds N] [--target NAME ...]
Prints per target: runs, executions per second, corpus size, and the result.
Exit 0 when every target passed, 1 when one found something, 2 when one cannot run.
"""
import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TARGETS = ["fuzz_gltf_json", "fuzz_gltf_glb", "fuzz_fbx", "fuzz_collada", "fuzz_project", "fuzz_blobtree_scene"]
# Inputs of up to 64 KiB: enough for every structure the loaders know (the seeds are
# smaller), small enough to keep executions fast.
MAX_LEN = 65536
LIMITS = ["-timeout=10", "-rss_limit_mb=1024", "-malloc_limit_mb=1024", f"-max_len={MAX_LEN}"]


def corpus_name(target):
    return target[len("fuzz_"):]


def run_corpus_once(exe, target):
    """Each seed of the target's corpus run once (no mutation); True when none fails."""
    folder = os.path.join(HERE, "corpus", corpus_name(target))
    files = sorted(os.path.join(folder, f) for f in os.listdir(folder)) if os.path.isdir(folder) else []
    out = subprocess.run([exe, *LIMITS, *files], capture_output=True, text=True) if files else None
    if out is not None and out.returncode != 0:
        print(out.stderr[-6000:])
        print(f"{target}: FAILED on a seed of its corpus (above)")
        return False
    print(f"{target}: {len(files)} corpus seeds run once: ok")
    return True


def run_regressions(exe, target):
    folder = os.path.join(HERE, "regressions", corpus_name(target))
    files = sorted(os.path.join(folder, f) for f in os.listdir(folder)) if os.path.isdir(folder) else []
    if not files:
        return True, 0
    out = subprocess.run([exe, *LIMITS, *files], capture_output=True, text=True)
    if out.returncode != 0:
        print(out.stderr[-6000:])
        print(f"{target}: FAILED on a regression file (above)")
        return False, len(files)
    return True, len(files)


def fuzz(exe, target, build, seconds):
    name = corpus_name(target)
    work = os.path.join(build, "corpus", name)
    artifacts = os.path.join(build, "artifacts", name) + "/"
    os.makedirs(work, exist_ok=True)
    os.makedirs(artifacts, exist_ok=True)
    cmd = [exe, *LIMITS, f"-max_total_time={seconds}", f"-dict={os.path.join(HERE, 'dict', name + '.dict')}",
           f"-artifact_prefix={artifacts}", "-print_final_stats=1", "-reload=0", work,
           os.path.join(HERE, "corpus", name)]
    out = subprocess.run(cmd, capture_output=True, text=True)
    log = out.stderr
    runs = re.search(r"stat::number_of_executed_units:\s*(\d+)", log)
    rate = re.search(r"stat::average_exec_per_sec:\s*(\d+)", log)
    peak = re.search(r"stat::peak_rss_mb:\s*(\d+)", log)
    corpus = len(os.listdir(work))
    if out.returncode != 0:
        print(log[-8000:])
        found = re.findall(r"Test unit written to (\S+)", log)
        print(f"{target}: FAILED after {runs.group(1) if runs else '?'} runs: "
              f"{found[0] if found else 'see the log above'}; keep it under "
              f"tests/fuzz/regressions/{name}/ with the fix")
        return False
    print(f"{target}: {runs.group(1) if runs else '?'} runs in {seconds} s, "
          f"{rate.group(1) if rate else '?'} exec/s, peak RSS {peak.group(1) if peak else '?'} MB, "
          f"working corpus {corpus} inputs: ok")
    return True


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", required=True, help="the fuzz build folder (ANIMORPH_FUZZ=ON)")
    ap.add_argument("--seconds", type=int, default=int(os.environ.get("ANIMORPH_FUZZ_SECONDS", "20")))
    ap.add_argument("--target", action="append", choices=TARGETS)
    ap.add_argument("--corpus-only", action="store_true",
                    help="run the regression files and each seed of the corpus once, without fuzzing")
    a = ap.parse_args()
    # Leaks are reported as failures, except those the suppressions file lists: third-party
    # libraries' own (libassimp's, with its reason there), never Animorph's.
    supp = os.path.join(HERE, "..", "sanitizers", "lsan.supp")
    os.environ["LSAN_OPTIONS"] = ":".join(filter(None, [os.environ.get("LSAN_OPTIONS", ""),
                                                       f"suppressions={os.path.abspath(supp)}", "print_suppressions=0"]))
    ok = True
    for target in a.target or TARGETS:
        exe = os.path.join(a.build, "tests", "fuzz", target)
        if not os.access(exe, os.X_OK):
            print(f"{target}: {exe} is not built (./run.sh fuzz builds it)")
            return 2
        passed, count = run_regressions(exe, target)
        print(f"{target}: {count} regression files: {'ok' if passed else 'FAILED'}")
        if a.corpus_only:
            ok = passed and run_corpus_once(exe, target) and ok
        else:
            ok = passed and fuzz(exe, target, a.build, a.seconds) and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
