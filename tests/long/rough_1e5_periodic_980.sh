#!/usr/bin/env bash
# A long check (CTest label `long`, ~5 min on one core: its own timeout, tests/CMakeLists.txt):
# rough_1e5_periodic.sh on the same 1e5 samples at about five times the load of
# rough_1e5_periodic.sh (`self_affine_profile.py 100000 1 1.4e-2 --periodic`): ~980 patches.
# Seeded from the coarse solve at its 2^21 panels (21 a sample), the
# first round's coupled solve keeps every coarse contact and converges; at 2^19 (5 a sample) the
# search lost or merged a contact in each of its first eight rounds and ended with 977 contacts,
# one real contact missing (penetrating by 7.8e-7 of the span), in 16-18 min. Measured (one core,
# another solve on the other): ok in 4.0-4.4 min, 330 MB, 979 contacts, C_f 0.0508028; the
# boundary-element solver (acceptance 1e-3, 13 s) 980 patches, C_f 0.05084 +- 2.2e-4: two of them
# one panel apart (the lighter one's load within its error) are one contact of the search.
#   bash rough_1e5_periodic_980.sh <path-to-rhabel-binary> <source-dir>
exec bash "$(dirname "$0")/rough_1e5_periodic.sh" "$1" "$2" 100000 1 1.4e-2 1500
