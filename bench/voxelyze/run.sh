#!/usr/bin/env bash
# Side by side with Voxelyze (issue 34): builds Voxelyze from its public source and a driver of
# our own (walker.cpp) that runs the same 3D walker as vsrlab's `--example walker3d`, then runs
# both and prints their lines. Needs a Voxelyze checkout: VOXELYZE_SRC (default: the snapshot
# the `fetch` tool brings to /work/.mirror/jonhiller+Voxelyze/repo, read with git).
#   bench/voxelyze/run.sh [seconds] [quadruped|box6] [off|on (collisions)]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
seconds="${1:-2}"
body="${2:-quadruped}"
collisions="${3:-off}"
src="${VOXELYZE_SRC:-/work/.mirror/jonhiller+Voxelyze/repo}"
build="$root/target/voxelyze"
mkdir -p "$build"
if [ ! -f "$build/walker" ] || [ "$here/walker.cpp" -nt "$build/walker" ]; then
    if [ -d "$src/.git" ] || git -C "$src" rev-parse --git-dir > /dev/null 2>&1; then
        rm -rf "$build/src" && mkdir -p "$build/src"
        git -C "$src" archive HEAD include src | tar -x -C "$build/src"
    else
        cp -r "$src/include" "$src/src" "$build/src/"
    fi
    # the mesh renderer (OpenGL) is not used; without PARDISO_5 the static solver needs no PARDISO
    srcs=$(ls "$build"/src/src/*.cpp | grep -v VX_MeshRender)
    g++ -O3 -std=c++11 -w -I"$build/src/include" $srcs "$here/walker.cpp" -o "$build/walker"
fi
"$build/walker" "$seconds" "$body" "$collisions"
cargo run --quiet --release -p vsrlab-physics3d --example walker3d "$seconds" "$body" "$collisions"
