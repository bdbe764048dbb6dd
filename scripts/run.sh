#!/usr/bin/env bash
# Installs what is missing, builds Release and runs the main job: the plate
# impact of the seed paper, two plates with contact (results in results/,
# open results/plate_impact.xmf in ParaView).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
scripts/install_deps.sh
scripts/build.sh release
build/release/src/app/exdyn run input/plate_impact.yaml "$@"
