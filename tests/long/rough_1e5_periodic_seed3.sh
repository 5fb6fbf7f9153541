#!/usr/bin/env bash
# A long check (CTest label `long`): rough_1e5_periodic.sh on a third profile at the heavy load
# (`self_affine_profile.py 100000 3 6e-3 --periodic`, --time-limit 1200): 428 contacts. Seeded from
# the coarse solve at 2^19 panels, the coupled iteration's first steps, far from the solution, would
# shrink light contacts past zero that carry load at the solution; dropped there and added back
# where the profile penetrated, they were dropped again, round after round (`tension`, 427 contacts,
# at --time-limit 900). The search stops when it would add back a contact it dropped and searches
# again, keeping light contacts while the coupled iteration is far from the solution
# (docs/theory.md, section 7). From the seeds at 2^21 panels the first round keeps all 428. Measured
# (one core, another solve beside it): ok in 50-51 s, 428 contacts, C_f 0.0519880; the
# boundary-element solver (acceptance 1e-3) 428 patches, C_f 0.05202 +- 2.1e-4.
#   bash rough_1e5_periodic_seed3.sh <path-to-rhabel-binary> <source-dir>
exec bash "$(dirname "$0")/rough_1e5_periodic.sh" "$1" "$2" 100000 3 6e-3 1200
