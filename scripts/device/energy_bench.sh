#!/bin/bash
# The GPU cost of ReSTIR GI's energy fix (docs/gi/restir-gi.md, "Energy"): `bounce bench` of
# Evolve on sunroom (sun fixed at noon) and city, 1920x1080 desktop, 120 frames, for each
# program packed (PROGRAMS, default: bounce-base, the build before the fix, then bounce),
# alternated twice. Pack first (from the repository root):
#   cp BASE_BUILD/bounce /tmp/base/bounce-base
#   ../shared/device/pack.sh build/bounce /tmp/base/bounce-base
# then run from the repository root on the GPU machine with .devicepack carried.
set -u
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
source "$(dirname "${BASH_SOURCE[0]}")/evolve_rounds.sh"
# $PROGRAMS unquoted: one word a program
evolve_rounds /tmp/energy "gi-|frame \(GPU\)|error" ${PROGRAMS:-bounce-base bounce}
