#!/usr/bin/env bash
# Animorph: install what is missing, build, run.
#   ./run.sh                 build and open the editor on the demo project
#   ./run.sh test [--asan]   build and run every test (GUI tests under xvfb-run when there is no DISPLAY)
#   ./run.sh build [--asan]  build only
#   ./run.sh cli ARGS...     build and run animorph-cli
#   ./run.sh bench ARGS...   build and run animorph-cli bench
#   ./run.sh fuzz [SECONDS] [TARGET...]  build the libFuzzer targets (clang, ASan+UBSan, in
#                            build-fuzz/) and fuzz each for SECONDS (default 60); see tests/fuzz/
set -euo pipefail
cd "$(dirname "$(readlink -f "$0")")"
ROOT=$PWD

# Every package whose headers, libraries or programs the build or the tests use: the test
# "packages: run.sh installs every header, ..." (tests/packages/) fails naming what is missing.
# libxrandr-dev: GLFW's native-access header (X11 presentation) includes X11/extensions/Xrandr.h.
# ffmpeg: animorph-cli bake --mp4 encodes the playblast with it (and the test reads it with ffprobe).
# libopenvdb-dev: the .vdb level sets (engine/core/io/vdb_export.cpp); its headers include Boost's
# (libboost-dev), which it does not depend on.
# libassimp-dev: FBX, Collada and OBJ characters (engine/core/io/assimp_import.cpp).
BUILD_PACKAGES=(build-essential cmake ninja-build pkg-config
  libimgui-dev libglfw3-dev libglm-dev libvulkan-dev mesa-vulkan-drivers
  glslang-tools libtinygltf-dev nlohmann-json3-dev libstb-dev libtbb-dev
  libx11-dev libxext-dev libxrandr-dev ffmpeg libopenvdb-dev libboost-dev libassimp-dev)
# nodejs, npm: the Khronos glTF-Validator (an npm package) checks the glTF files we write;
# blender (with python3-numpy, which its glTF importer needs) imports them in the export test.
# slurm-wlm (slurmctld, slurmd, the client commands) and munge: the farm test starts a one-node
# Slurm cluster on localhost and bakes the demo on it (animorph-cli farm slurm).
# libopenvdb-tools: vdb_print reads the .vdb files back in the export test.
# assimp-utils: the `assimp` command writes the reference (pre-transformed) meshes the FBX /
# Collada import tests compare against.
TEST_PACKAGES=(catch2 vulkan-validationlayers xvfb xauth xdotool imagemagick
  assimp-testmodels assimp-utils python3 nodejs blender python3-numpy slurm-wlm munge libopenvdb-tools)
# clang and its runtimes (libFuzzer, ASan, UBSan: libclang-rt-dev) build the fuzz targets
# (tests/fuzz), which ./run.sh test runs too.
FUZZ_PACKAGES=(clang libclang-rt-dev)
# Installed only when no program of the same name is on PATH: a Node.js package from outside
# Debian (NodeSource's) ships its own npm and conflicts with Debian's.
TEST_PROGRAM_PACKAGES=(npm)

say() { printf '\033[1m[animorph]\033[0m %s\n' "$*" >&2; }

missing_packages() {
  local p
  for p in "$@"; do
    if [ "$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null)" != "installed" ]; then
      printf '%s\n' "$p"
    fi
  done
}

ensure_packages() {
  local missing
  mapfile -t missing < <(missing_packages "$@")
  [ ${#missing[@]} -eq 0 ] && return 0
  say "installing missing Debian packages: ${missing[*]}"
  local SUDO=()
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
      SUDO=(sudo -n)
    elif command -v sudo >/dev/null 2>&1 && [ -t 0 ]; then
      SUDO=(sudo)
    else
      say "these packages are missing and I am not root and cannot sudo:"
      say "  apt-get install -y ${missing[*]}"
      say "run that as root, then ./run.sh again."
      exit 1
    fi
  fi
  export DEBIAN_FRONTEND=noninteractive
  if ! "${SUDO[@]}" apt-get install -y --no-install-recommends "${missing[@]}"; then
    say "apt-get install failed; refreshing package lists and trying again"
    "${SUDO[@]}" apt-get update
    "${SUDO[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
  fi
}

build() {
  local dir=$1; shift
  local generator=()
  command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
  # The tests' scripts run with Debian's python3 (installed above), not whichever python3 comes
  # first on PATH: what a fresh machine has is what the tests use here too.
  [ -x /usr/bin/python3 ] && set -- -DPython3_EXECUTABLE=/usr/bin/python3 "$@"
  if [ ! -f "$dir/CMakeCache.txt" ]; then
    cmake -S "$ROOT" -B "$dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "$@"
  else
    cmake -S "$ROOT" -B "$dir" "$@" >/dev/null
  fi
  cmake --build "$dir" -j"$(nproc)"
}

# The fuzz targets: animorph_core and tests/fuzz only, built with clang in their own folder.
build_fuzz() {
  CXX=clang++ build "$ROOT/build-fuzz" -DANIMORPH_FUZZ=ON -DANIMORPH_BUILD_TESTS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo
}

asan=0
cmd=${1:-run}
[ $# -gt 0 ] && shift
args=()
for a in "$@"; do
  if [ "$a" = "--asan" ]; then asan=1; else args+=("$a"); fi
done
BUILD_DIR=$ROOT/build
BUILD_FLAGS=()
if [ $asan -eq 1 ]; then
  BUILD_DIR=$ROOT/build-asan
  # -O1 -g1 (line tables for the reports' stacks): a lighter build than -O2 -g on a small machine,
  # and -O1 is the level AddressSanitizer's documentation advises.
  BUILD_FLAGS=(-DANIMORPH_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG")
fi

case "$cmd" in
  run)
    ensure_packages "${BUILD_PACKAGES[@]}" catch2
    build "$BUILD_DIR" "${BUILD_FLAGS[@]}"
    project=${args[0]:-$ROOT/resources/demo/demo.animorph}
    if [ -z "${DISPLAY:-}" ] && [ -z "${WAYLAND_DISPLAY:-}" ]; then
      say "no DISPLAY: the editor needs a window. Either run it under a virtual X server:"
      say "  xvfb-run -a ./run.sh"
      say "or use the headless CLI:"
      say "  $BUILD_DIR/app/animorph-cli --help"
      exit 2
    fi
    exec "$BUILD_DIR/app/animorph" "$project"
    ;;
  build)
    ensure_packages "${BUILD_PACKAGES[@]}" catch2
    build "$BUILD_DIR" "${BUILD_FLAGS[@]}"
    ;;
  test)
    ensure_packages "${BUILD_PACKAGES[@]}" "${TEST_PACKAGES[@]}" "${FUZZ_PACKAGES[@]}"
    for p in "${TEST_PROGRAM_PACKAGES[@]}"; do
      command -v "$p" >/dev/null 2>&1 || ensure_packages "$p"
    done
    build_fuzz
    build "$BUILD_DIR" "${BUILD_FLAGS[@]}" -DANIMORPH_FUZZ_BUILD_DIR="$ROOT/build-fuzz"
    export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$(mktemp -d /tmp/animorph-xdg.XXXXXX)}
    chmod 700 "$XDG_RUNTIME_DIR" 2>/dev/null || true
    export ANIMORPH_VALIDATION=1
    if [ $asan -eq 1 ]; then
      # Leaks are reported when each instrumented process exits; the suppressions name only
      # third-party libraries' own allocations, each with its reason (tests/sanitizers/lsan.supp).
      export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
      export LSAN_OPTIONS=suppressions=$ROOT/tests/sanitizers/lsan.supp:print_suppressions=0
      export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
    fi
    # The tests that could not run (a tool, package or shared asset missing) are listed with their
    # reasons after the run: a skip proves nothing. ctest's own exit status is kept.
    junit="$BUILD_DIR/Testing/ctest-junit.xml"
    rm -f "$junit"
    status=0
    ctest --test-dir "$BUILD_DIR" --output-on-failure -j"$(nproc)" --timeout 600 --output-junit "$junit" \
      "${args[@]}" || status=$?
    [ -f "$junit" ] && python3 "$ROOT/tests/tools/list_skipped_tests.py" "$junit" || true
    exit $status
    ;;
  cli)
    ensure_packages "${BUILD_PACKAGES[@]}" catch2
    build "$BUILD_DIR" "${BUILD_FLAGS[@]}" >/dev/null
    exec "$BUILD_DIR/app/animorph-cli" "${args[@]}"
    ;;
  bench)
    ensure_packages "${BUILD_PACKAGES[@]}" catch2
    build "$BUILD_DIR" "${BUILD_FLAGS[@]}" >/dev/null
    exec "$BUILD_DIR/app/animorph-cli" bench "${args[@]}"
    ;;
  fuzz)
    ensure_packages "${BUILD_PACKAGES[@]}" "${FUZZ_PACKAGES[@]}" python3
    build_fuzz
    seconds=60
    if [ ${#args[@]} -gt 0 ] && [[ ${args[0]} =~ ^[0-9]+$ ]]; then seconds=${args[0]}; args=("${args[@]:1}"); fi
    targets=()
    for t in "${args[@]}"; do targets+=(--target "$t"); done
    exec /usr/bin/python3 "$ROOT/tests/fuzz/run_fuzzers.py" --build "$ROOT/build-fuzz" --seconds "$seconds" "${targets[@]}"
    ;;
  *)
    say "unknown command '$cmd'. Use: ./run.sh [run|build|test|cli|bench|fuzz] [--asan]"
    exit 2
    ;;
esac
