#!/usr/bin/env bash
# The cost of everything before the first step (mesh, joints, model, the
# stable-step estimate): `femdem check`, single-threaded, on each variant
# named, REPS times, into target/scene/setup/<name>-r<k>.txt.
set -euo pipefail
S=target/scene
mkdir -p $S/setup
for k in $(seq 1 ${REPS:-1}); do
  for n in "$@"; do
    /usr/bin/time -v target/release/femdem check $S/$n.toml --threads 1 > /dev/null 2> $S/setup/$n-r$k.txt
  done
done
