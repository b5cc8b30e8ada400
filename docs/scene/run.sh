#!/usr/bin/env bash
# Runs each variant of target/scene/ named on the command line,
# single-threaded, once per repetition FIRST..REPS (default 1..1), into
# target/scene/out/<name>-r<k>/ with femdem's summary, the report of
# /usr/bin/time -v and the load average before and after. Run from the
# repository root after docs/scene/variants.sh.
set -euo pipefail
S=target/scene
for k in $(seq ${FIRST:-1} ${REPS:-1}); do
  for n in "$@"; do
    o=$S/out/$n-r$k
    rm -rf $o && mkdir -p $o
    uptime > $o/load.txt
    /usr/bin/time -v target/release/femdem run $S/$n.toml --out $o --threads 1 > $o/summary.txt 2> $o/time.txt
    uptime >> $o/load.txt
  done
done
