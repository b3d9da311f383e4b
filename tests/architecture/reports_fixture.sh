#!/usr/bin/env bash
# include_layers.sh on its fixture tree (violation/): exits 1 and reports
# exactly the two includes there that go up (engine core -> simulation, the
# service's store -> the command line) and the folder without a rank, not
# the include within a layer (contact -> integration) nor the one going
# down (simulation -> core).
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
out=$(bash "$here/include_layers.sh" "$here/violation")
rc=$?
printf '%s\n' "$out"
expected=(
  'engine/core/uses_simulation.hpp includes "simulation/above_core.hpp" (engine/simulation/above_core.hpp): a layer above its own'
  'scheduler/store/uses_command.hpp includes "cli/a_command.hpp" (scheduler/cli/a_command.hpp): a layer above its own'
  'scheduler/unranked/no_rank.hpp: its folder has no rank (give it one in include_layers.sh)'
)
[[ $rc -eq 1 ]] || { echo "FAIL: exit $rc, expected 1"; exit 1; }
reports=$(grep -c -e ' includes "' -e 'has no rank' <<<"$out")
[[ $reports -eq ${#expected[@]} ]] || { echo "FAIL: $reports reports, expected ${#expected[@]}"; exit 1; }
for e in "${expected[@]}"; do
  grep -qxF "$e" <<<"$out" || { echo "FAIL: missing report: $e"; exit 1; }
done
echo "ok: the two upward includes and the folder without a rank are reported"
