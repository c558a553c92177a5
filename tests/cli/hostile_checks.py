#!/usr/bin/env python3
"""End-to-end checks of animorph-cli info on hostile and careless input.

usage: hostile_checks.py CLI
  Every file is generated here: a project nesting 20,000 BlobTree frames, a
  glTF whose extras nest 15,000 arrays, a 250-byte glTF declaring 2^26
  vertices, a folder and a FIFO named as files, assets naming /dev/zero and a
  FIFO, integers beyond 32 bits. Each must end with a clear error naming the
  path, within seconds, without a crash and without a large allocation (the
  peak resident memory of that child process alone, from wait4)."""
import json
import os
import signal
import subprocess
import sys
import tempfile
import threading
import time

FAILURES = []


def check(ok, what):
    if not ok:
        FAILURES.append(what)
        print("FAIL:", what)


def run_measured(argv, timeout):
    """Runs argv; returns (CompletedProcess or None when it ran past timeout, seconds, peak resident
    MiB of that child alone). The peak is the child's own ru_maxrss from wait4 on its pid (the
    RUSAGE_CHILDREN total only ever grows: a child smaller than an earlier one would read as 0)."""
    start = time.monotonic()
    p = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    out = {}
    readers = [threading.Thread(target=lambda k, f: out.__setitem__(k, f.read()), args=(k, f))
               for k, f in (("stdout", p.stdout), ("stderr", p.stderr))]
    for t in readers:
        t.start()
    killer = threading.Timer(timeout, p.kill)
    killer.start()
    _, status, usage = os.wait4(p.pid, 0)
    killer.cancel()
    seconds = time.monotonic() - start
    p.returncode = os.waitstatus_to_exitcode(status)  # reaped here: Popen must not wait for it again
    for t in readers:
        t.join()
    p.stdout.close()
    p.stderr.close()
    if seconds >= timeout and p.returncode == -signal.SIGKILL:
        return None, seconds, usage.ru_maxrss / 1024
    return subprocess.CompletedProcess(argv, p.returncode, out["stdout"], out["stderr"]), seconds, usage.ru_maxrss / 1024


def info(cli, *args, timeout=20):
    """Runs info; returns (completed process, seconds, peak MiB of this child)."""
    r, seconds, mib = run_measured([cli, "info", *args], timeout)
    if r is None:
        check(False, f"info {' '.join(args)} did not finish within {timeout} s")
        return None, timeout, 0
    return r, seconds, mib


def refused(cli, path, expected, max_seconds=5, max_mib=300):
    r, seconds, mib = info(cli, path)
    if r is None:
        return
    what = f"info {path}: exit {r.returncode}, {seconds:.2f} s, {mib:.0f} MiB, stderr {r.stderr.strip()[:300]!r}"
    check(r.returncode == 1, what + " (expected exit 1, not a crash)")
    check(path in r.stderr, what + " (the error names the path as given)")
    check(expected in r.stderr, what + f" (expected {expected!r})")
    check(seconds < max_seconds, what + f" (took more than {max_seconds} s)")
    check(mib < max_mib, what + f" (more than {max_mib} MiB)")
    check(mib > 0, what + " (no peak memory read for this child)")
    print(f"info {os.path.basename(path)}: exit {r.returncode}, {seconds:.2f} s, peak {mib:.1f} MiB")


def nested_frames(depth):
    head = "".join('{"id":%d,"type":"frame","children":[' % i for i in range(depth))
    leaf = '{"id":%d,"type":"point","params":{"center":[0,0,0],"radius":1}}' % depth
    return head + leaf + "]}" * depth


def write(path, text):
    with open(path, "w") as f:
        f.write(text)
    return path


def project(actors, **extra):
    doc = {"format": "animorph", "version": 1, "actors": actors}
    doc.update(extra)
    return json.dumps(doc)


def main():
    cli = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        deep = write(os.path.join(tmp, "deep.animorph"),
                     '{"format":"animorph","version":1,"actors":[{"id":"b","kind":"blobtree","blobtree":{"root":'
                     + nested_frames(20000) + "}}]}")
        refused(cli, deep, "nesting deeper than 256 levels")

        gltf = ('{"extras":' + "[" * 15000 + "]" * 15000 +
                ',"asset":{"version":"2.0"},"nodes":[{"name":"n"}]}')
        refused(cli, write(os.path.join(tmp, "deep.gltf"), gltf), "nesting deeper than 256 levels")

        tiny = write(os.path.join(tmp, "tiny.gltf"),
                     '{"asset":{"version":"2.0"},"accessors":[{"componentType":5126,"count":67108864,"type":"VEC3"}],'
                     '"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}]}')
        refused(cli, tiny, "decoding budget", max_seconds=3, max_mib=150)

        wrapped = write(os.path.join(tmp, "wrapped.gltf"),
                        '{"asset":{"version":"2.0"},"accessors":[{"bufferView":4294967295,"componentType":5126,'
                        '"count":3,"type":"VEC3"}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],'
                        '"nodes":[{"mesh":0}]}')
        refused(cli, wrapped, "accessors[0].bufferView: 4294967295 is out of range")

        folder = os.path.join(tmp, "folder.glb")
        os.mkdir(folder)
        refused(cli, folder, "is a directory, not a regular file")
        fifo = os.path.join(tmp, "pipe.glb")
        os.mkfifo(fifo)
        refused(cli, fifo, "is a FIFO (named pipe), not a regular file")

        newer = write(os.path.join(tmp, "newer.animorph"), project([], version=4294967297))
        refused(cli, newer, "version 4294967297 is newer than this Animorph understands")
        frames = write(os.path.join(tmp, "frames.animorph"), project([], timeline={"frame_end": 2**32}))
        refused(cli, frames, "timeline.frame_end: 4294967296 is out of range")
        fps = write(os.path.join(tmp, "fps.animorph"), project([], timeline={"fps": 1e-300}))
        refused(cli, fps, "timeline.fps: must be in [0.1, 1000]")

        # Assets that are not files: the project loads, each actor reports its error.
        assets = write(os.path.join(tmp, "assets.animorph"),
                       project([{"id": "zero", "asset": "/dev/zero"}, {"id": "pipe", "asset": "pipe.glb"},
                                {"id": "dir", "asset": "folder.glb"}]))
        r, seconds, _ = info(cli, assets, "--json")
        if r is not None:
            check(r.returncode == 0 and seconds < 5, f"info on a project with special assets: exit {r.returncode}, "
                  f"{seconds:.2f} s, {r.stderr.strip()[:300]!r}")
            errors = {a["id"]: a.get("error", "") for a in json.loads(r.stdout or '{"actors":[]}')["actors"]}
            check("/dev/zero: is a character device" in errors.get("zero", ""), f"/dev/zero asset: {errors}")
            check("pipe.glb: is a FIFO" in errors.get("pipe", ""), f"FIFO asset: {errors}")
            check("folder.glb: is a directory" in errors.get("dir", ""), f"folder asset: {errors}")
    if FAILURES:
        sys.exit(1)
    print("ok")


if __name__ == "__main__":
    main()
