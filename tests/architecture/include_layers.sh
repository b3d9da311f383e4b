#!/usr/bin/env bash
# No folder includes a folder ranked above it. The ranks, bottom up:
#   engine:  core -> model -> contact, integration, generators -> solver ->
#            simulation -> io, analysis
#   results: evaluation (envelopes, compliance, summary, price, report) ->
#            planning (the planner, time-step policy, cost model, ladder,
#            the rung runner: it evaluates the runs it plans)
#   scheduler, the service: core -> store, study -> queue -> workers,
#            shards -> query (reads of the store)
#   the front ends on top: cli (the vsi commands) and http (vsi serve's
#            routes, which call the same command functions)
# A quoted include "a/b.hpp" is the file of that name under engine/,
# results/ or scheduler/; a name under two of them is reported too (which
# one the compiler takes depends on the includer's target). A source in a
# folder without a rank is reported: a new folder takes its place here.
# Folders of one rank may include each other.
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
    results/envelopes/* | results/compliance/* | results/summary/* | results/price/* | results/report/*) layer=6 ;;
    results/planning/*) layer=7 ;;
    scheduler/core/*) layer=8 ;;
    scheduler/store/* | scheduler/study/*) layer=9 ;;
    scheduler/queue/*) layer=10 ;;
    scheduler/workers/* | scheduler/shards/*) layer=11 ;;
    scheduler/query/*) layer=12 ;;
    scheduler/cli/* | scheduler/http/*) layer=13 ;;
    *) layer=-1 ;;
  esac
}

up=0
mapfile -t sources < <(find engine results scheduler \( -name '*.cpp' -o -name '*.hpp' \) -type f 2>/dev/null | sort)
((${#sources[@]} > 0)) || { echo "no sources under $(pwd)" >&2; exit 2; }
for file in "${sources[@]}"; do
  rank "$file"
  if ((layer < 0)); then
    echo "$file: its folder has no rank (give it one in include_layers.sh)"
    up=1
  fi
done
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
