#!/usr/bin/env bash
# A long check (CTest label `long`): rough_1e5_periodic.sh on the same 1e5 samples at twice the
# load (`self_affine_profile.py 100000 1 6e-3 --periodic`): 443 patches, many narrower than a
# sample spacing, which a coupled solve from coarse seeds known to a panel can starve. Measured
# (one core, another solve beside it): ok in 51-58 s, 260 MB, C_f 0.0515588; the boundary-element
# solver (acceptance 1e-3, 6 s) 443 patches, C_f 0.051540 +- 1.8e-4.
#   bash rough_1e5_periodic_heavy.sh <path-to-rhabel-binary> <source-dir>
exec bash "$(dirname "$0")/rough_1e5_periodic.sh" "$1" "$2" 100000 1 6e-3
