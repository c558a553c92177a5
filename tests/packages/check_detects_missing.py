#!/usr/bin/env python3
"""The package check's own test: with a package left out of run.sh's lists, the check fails and
names what the build or the tests use from it. libxrandr-dev (its header reached through GLFW's
native-access header) was the package a fresh Debian machine lacked; xdotool is a program only the
GUI tests run.
usage: check_detects_missing.py CHECK SOURCE BUILD"""
import subprocess
import sys

check, source, build = sys.argv[1:4]
failed = False


def expect(drop, needles):
    global failed
    out = subprocess.run([sys.executable, check, "--source", source, "--build", build, "--drop", drop],
                         capture_output=True, text=True)
    if out.returncode == 77:
        print(out.stdout, end="")
        sys.exit(77)
    text = out.stdout + out.stderr
    missing = [n for n in needles if n not in text]
    if out.returncode != 1 or missing:
        print(f"FAIL: without {drop}: exit {out.returncode}, expected 1 naming {needles}; missing {missing}\n{text}")
        failed = True
    else:
        lines = [l for l in text.splitlines() if l.startswith("MISSING") and drop in l]
        print(f"ok: without {drop} the check fails: {lines[0] if lines else ''}")


expect("libxrandr-dev", ["X11/extensions/Xrandr.h", "package libxrandr-dev is not installed by run.sh"])
expect("xdotool", ["program xdotool", "package xdotool is not installed by run.sh", "GUI tests"])
sys.exit(1 if failed else 0)
