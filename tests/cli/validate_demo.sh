#!/usr/bin/env bash
# Validates the glTF files written by `animorph-cli make-demo` (and the
# committed resources/demo) with the Khronos glTF-Validator. The npm package
# is installed on demand into tests/tools/node_modules (git-ignored); when
# Node or the package is unavailable the test is skipped (exit 77).
# usage: validate_demo.sh CLI TOOLS_DIR RESOURCES_DIR
set -uo pipefail
cli=$1 tools=$2 resources=$3
"$tools/install_validator.sh" "$tools" || exit $?
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$cli" make-demo "$tmp" >/dev/null || { echo "make-demo failed"; exit 1; }
node "$tools/validate_gltf.js" "$tmp/creature.glb" "$tmp/gear.glb" "$resources/creature.glb" "$resources/gear.glb"
