#!/usr/bin/env bash
# No layer includes a layer above it. The layers, bottom up:
#   core -> model -> contact, integration, generators -> solver ->
#   simulation -> io, analysis -> results -> scheduler
# (engine/<layer>, results/*, scheduler/*). A quoted include "a/b.hpp" is
# the file of that name under engine/, results/ or scheduler/; a name
# under two of them is reported too (which one the compiler takes depends
# on the includer's target).
# Folders of one layer may include each other.
#
#   tests/architecture/include_layers.sh SOURCE_ROOT
#
# Prints every include that goes up and exits 1 if there is one.
set -euo pipefail
[[ $# -eq 1 && -d $1 ]] || { echo "usage: include_layers.sh SOURCE_ROOT" >&2; exit 2; }
cd "$1"

# Sets `layer` to the rank of file $1 (no subshell: this runs per include).
rank() {
  case $1 in
    engine/core/*) layer=0 ;;
    engine/model/*) layer=1 ;;
    engine/contact/* | engine/integration/* | engine/generators/*) layer=2 ;;
    engine/solver/*) layer=3 ;;
    engine/simulation/*) layer=4 ;;
    engine/io/* | engine/analysis/*) layer=5 ;;
    results/*) layer=6 ;;
    scheduler/*) layer=7 ;;
    *) layer=-1 ;;
  esac
}

up=0
mapfile -t sources < <(find engine results scheduler \( -name '*.cpp' -o -name '*.hpp' \) -type f 2>/dev/null | sort)
((${#sources[@]} > 0)) || { echo "no sources under $(pwd)" >&2; exit 2; }
# Every quoted include of every source, one "file:included" a line.
while IFS=: read -r file included; do
  target=""
  for root in engine results scheduler; do
    [[ -f $root/$included ]] || continue
    if [[ -n $target ]]; then
      echo "$file includes \"$included\": both $target and $root/$included (rename one)"
      up=1
    fi
    target=$root/$included
  done
  [[ -n $target ]] || continue  # a system or third-party header
  rank "$file"
  from=$layer
  rank "$target"
  if ((layer > from)); then
    echo "$file includes \"$included\" ($target): a layer above its own"
    up=1
  fi
done < <(grep -HoP '^\s*#\s*include\s+"\K[^"]+' "${sources[@]}" || true)
echo "${#sources[@]} files read"
exit $up
