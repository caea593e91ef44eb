#!/usr/bin/env bash
# The plug-in seam's measures over a checkout (issue 30): files outside the voxel folders that
# name voxel types, Trace fields, Result<_, String> in library crates. Usage: counts.sh [DIR]
# (compare two checkouts, e.g. a `git worktree` of an old commit and this one).
set -u
root="${1:-.}"
cd "$root"
# production text of a Rust file: everything before its first #[cfg(test)]
prod() { awk '/^#\[cfg\(test\)\]/{exit} {print}' "$1"; }
voxel_re='\b(Morphology|VoxelState|Vsr|VoxelParams|Voxel)\b'
files=$(git ls-files 'crates/*.rs' 'python/src/*.rs' | grep '/src/' )
n_prod=0; n_all=0
for f in $files; do
  case "$f" in crates/body/*|crates/tasks/src/kinds/voxel/*|crates/tasks/src/kinds/voxel3d/*) continue;; esac
  if prod "$f" | grep -qE "$voxel_re"; then n_prod=$((n_prod+1)); if [ -n "${LIST:-}" ]; then echo "  $f"; fi; fi
  if grep -qE "$voxel_re" "$f"; then n_all=$((n_all+1)); fi
done
echo "voxel-type files outside body and voxel kind folders: production $n_prod, with test modules $n_all"
# Trace fields
tf=$(awk '/pub struct Trace \{/{on=1; next} on&&/^\}/{exit} on&&/^    pub [a-z_]+:/{n++} END{print n+0}' crates/tasks/src/outcome.rs)
echo "Trace fields: $tf"
# Result<_, String> in library crates (not cli, not python, production only)
rs=0; rss=0
for f in $(git ls-files 'crates/*.rs' | grep '/src/' | grep -v '^crates/cli/'); do
  a=$(prod "$f" | grep -oE 'Result<[^;{]*,\s*String>' | grep -vE '\(String, String\)' | wc -l)
  b=$(prod "$f" | grep -oE 'Result<[^;{]*,\s*\(String, String\)>' | wc -l)
  rs=$((rs+a)); rss=$((rss+b))
done
echo "Result<_, String> in library crates: $rs; Result<_, (String, String)>: $rss"
