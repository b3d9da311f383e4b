#!/usr/bin/env bash
# include_layers.sh on its fixture tree (violation/): exits 1 and reports
# exactly the one include there that goes up (core -> simulation), not the
# one within a layer (contact -> integration) nor the one going down
# (simulation -> core).
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
out=$(bash "$here/include_layers.sh" "$here/violation")
rc=$?
printf '%s\n' "$out"
expected='engine/core/uses_simulation.hpp includes "simulation/above_core.hpp" (engine/simulation/above_core.hpp): a layer above its own'
[[ $rc -eq 1 ]] || { echo "FAIL: exit $rc, expected 1"; exit 1; }
reports=$(grep -c ' includes "' <<<"$out")
[[ $reports -eq 1 ]] || { echo "FAIL: $reports reports, expected 1"; exit 1; }
grep -qxF "$expected" <<<"$out" || { echo "FAIL: not the expected report"; exit 1; }
echo "ok: the one upward include is reported"
