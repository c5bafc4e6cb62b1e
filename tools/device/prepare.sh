#!/usr/bin/env bash
# Fills .devlibs/ for the GPU machine (shared/device/README.md beside the checkouts): the shared
# prepare.sh, given the Debian runtime packages that Photon's binaries link beyond its own list
# (run `ldd` on what you carry after adding a dependency, and name its package here). Each is
# linked in there only where the machine lacks that library. From the project root:
#   tools/device/prepare.sh [more-debian-packages ...]
#   libisal2: PNG files' deflate (ISA-L); libopenexr-3-1-30, libimath-3-1-29: EXR files (OpenEXR);
#   libmeshoptimizer2d: meshopt-compressed glTF.
set -euo pipefail
cd "$(git rev-parse --show-toplevel)"
exec ../shared/device/prepare.sh libisal2 libopenexr-3-1-30 libimath-3-1-29 libmeshoptimizer2d "$@"
