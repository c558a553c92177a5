#!/usr/bin/env bash
# Installs the Khronos glTF-Validator (npm gltf-validator) into TOOLS_DIR/node_modules
# (git-ignored) unless it is there already.
# usage: install_validator.sh TOOLS_DIR
# Exit 0 when it is ready; 77 (the tests' "skipped") with a message when Node or
# npm is missing or the registry cannot be reached.
set -uo pipefail
tools=$1
command -v node >/dev/null 2>&1 || { echo "node not installed: skipped"; exit 77; }
[ -f "$tools/node_modules/gltf-validator/package.json" ] && exit 0
command -v npm >/dev/null 2>&1 || { echo "npm not installed: skipped"; exit 77; }
if ! (cd "$tools" && timeout 180 npm install --no-audit --no-fund --loglevel=error >/dev/null 2>&1); then
  echo "npm install gltf-validator failed (offline?): skipped"
  exit 77
fi
