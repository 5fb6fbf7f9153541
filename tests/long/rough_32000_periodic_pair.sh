#!/usr/bin/env bash
# A long check (CTest label `long`): rough_1e5_periodic.sh on a periodic self-affine profile of
# 32000 samples at load 6e-3 (`self_affine_profile.py 32000 1 6e-3 --periodic`): 240 patches, two of
# them ~5e-6 apart (the boundary-element solver's [0.573360, 0.573402] and [0.573407, 0.573502]).
# Its first round converges to a contact with a negative pressure inside, which the search moves an
# edge of; from the Jacobian kept by the round before, the next round closed that pair below 1e-4 of
# a contact length, merged it, the merged contact was negative inside again, and the search cycled
# until its time limit (not_converged with 239 contacts, 120 s); the round after such a repair now
# differences a new Jacobian (coupled_newton.cpp, memo_serves). Measured (one core, another solve
# beside it): ok in 15 s, 240 contacts, C_f 0.0395440; the boundary-element solver (acceptance 1e-3)
# 240 patches.
#   bash rough_32000_periodic_pair.sh <path-to-rhabel-binary> <source-dir>
exec bash "$(dirname "$0")/rough_1e5_periodic.sh" "$1" "$2" 32000 1 6e-3
