#!/bin/sh
# Runs a Blender headless script that writes test material into a directory (a CTest fixture).
# usage: blender_fixture.sh SCRIPT OUT_DIR ; exit 77 (skipped) when Blender is not installed,
# non-zero when the script fails (--python-exit-code: Blender itself would exit 0).
command -v blender >/dev/null 2>&1 || { echo "blender is not installed: skipped"; exit 77; }
rm -rf "$2"
exec blender -b --factory-startup --python-exit-code 1 -P "$1" -- "$2"
