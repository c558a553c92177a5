#!/usr/bin/env bash
# Validates the glTF files written by `animorph-cli make-demo` (and the
# committed resources/demo) with the Khronos glTF-Validator. The npm package
# is installed on demand into tests/tools/node_modules (git-ignored); when
# Node or the package is unavailable the test is skipped (exit 77).
# usage: validate_demo.sh CLI TOOLS_DIR RESOURCES_DIR
set -uo pipefail
cli=$1 tools=$2 resources=$3
command -v node >/dev/null 2>&1 || { echo "node not installed: skipped"; exit 77; }
if [ ! -f "$tools/node_modules/gltf-validator/package.json" ]; then
  command -v npm >/dev/null 2>&1 || { echo "npm not installed: skipped"; exit 77; }
  if ! (cd "$tools" && timeout 180 npm install --no-audit --no-fund --loglevel=error >/dev/null 2>&1); then
    echo "npm install gltf-validator failed (offline?): skipped"
    exit 77
  fi
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$cli" make-demo "$tmp" >/dev/null || { echo "make-demo failed"; exit 1; }
node "$tools/validate_gltf.js" "$tmp/creature.glb" "$tmp/gear.glb" "$resources/creature.glb" "$resources/gear.glb"
