#!/usr/bin/env bash
# Writes the scene variants of docs/tradeoff.md (section 3) into target/scene/:
# the bundled cases with one modelling choice changed at a time. Run from
# the repository root.
set -euo pipefail
S=target/scene
mkdir -p $S
base=cases/brazilian-split.toml      # the 4 mm disc, rigid platens, contact
band=cases/brazilian-split-band.toml # the same, joints only within |x| <= 6 mm
paper=cases/paper/brazilian.toml     # the paper's 1.2 mm disc

# Platens glued to the disc's top and bottom node lines (x = 0): the platen
# drives move them, so the platens need no contact with the disc.
glue() { perl -0pe 's/(region = "platen_top"\nvelocity = .*\nramp_time = 1.0e-5\n)/$1drives = { group = "disc.side", box = { min = [-1e-4, 0.0199, -1.0], max = [1e-4, 1.0, 1.0] } }\n/; s/(region = "platen_bottom"\nvelocity = .*\nramp_time = 1.0e-5\n)/$1drives = { group = "disc.side", box = { min = [-1e-4, -1.0, -1.0], max = [1e-4, -0.0199, 1.0] } }\n/' "$1"; }
# Contact on crack faces only: outer surfaces are not searched.
nosurf() { sed 's/^\[contact\]$/[contact]\nsurfaces = false/' "$1"; }
# No contact at all (crack faces may then pass through each other).
nocontact() { perl -0pe 's/\[contact\]\n(.*\n)*?\n(?=# Ends earlier)//; s/\[\[contact.pairs\]\]\n.*\n.*\n\n//g' "$1"; }
# Deformable steel platens (E = 200 GPa, nu = 0.3, rho = 7850 kg/m3) pushed
# at their outer faces by velocity loads `top` and `bottom`, instead of
# rigid [[platens]].
steel() { perl -0pe 's/\[\[platens\]\]\nregion = "platen_top"\nvelocity = (.*)\nramp_time = (.*)\n/[[loads]]\nkind = "velocity"\nname = "top"\nnodes = { group = "platen_top.ymax" }\nvelocity = $1\nramp_time = $2\n/; s/\[\[platens\]\]\nregion = "platen_bottom"\nvelocity = (.*)\nramp_time = (.*)\n/[[loads]]\nkind = "velocity"\nname = "bottom"\nnodes = { group = "platen_bottom.ymin" }\nvelocity = $1\nramp_time = $2\n\n[[materials]]\nregion = "platen_top"\ndensity = 7850.0\nyoung = 200.0e9\npoisson = 0.3\ndamping_ratio = 0.05\n\n[[materials]]\nregion = "platen_bottom"\ndensity = 7850.0\nyoung = 200.0e9\npoisson = 0.3\ndamping_ratio = 0.05\n/; s/upper = "platen_top"/upper = "top"/; s/lower = "platen_bottom"/lower = "bottom"/' "$1"; }
# A jointless disc: nothing breaks, so the run goes to end_time; 5.4e-4 s is
# where the fully jointed run ends.
jointless() { sed 's/^breakable = true/breakable = false/; s/^end_time = 1.0e-3/end_time = 5.4e-4/' "$1"; }
# The paper disc for 4 us (about 200 steps) with its two frames.
short() { sed 's/^end_time = 1.0e-5/end_time = 4.0e-6/; s/^interval = 1.0e-6/interval = 4.0e-6/' "$1"; }
# Joints only within |x| <= 6 mm of the loaded diameter.
band6() { perl -0pe 's/(name = "disc"\nbreakable = true\n)/$1joints_within = [{ box = { min = [-0.006, -0.021, -0.001], max = [0.006, 0.021, 0.016] } }]\n/' "$1"; }

cp $base $S/full.toml
cp $band $S/band6.toml
sed 's/min = \[-0.006, -0.021/min = [-0.004, -0.021/; s/max = \[0.006, 0.021/max = [0.004, 0.021/; s/12 mm central band/8 mm central band/' $band > $S/band4.toml
jointless $base > $S/jointless.toml
glue $base > $S/glued.toml
glue $base | nosurf /dev/stdin > $S/glued-nosurf.toml
glue $band | nosurf /dev/stdin > $S/band6-glued-nosurf.toml
glue $base | nocontact /dev/stdin > $S/glued-nocontact.toml
steel $base > $S/steel-platens.toml
jointless $base | steel /dev/stdin > $S/jointless-steel-platens.toml

short $paper > $S/paper-full.toml
short $paper | band6 /dev/stdin > $S/paper-band6.toml
short $paper | sed 's/^breakable = true/breakable = false/' > $S/paper-jointless.toml
short $paper | glue /dev/stdin | nosurf /dev/stdin > $S/paper-glued-nosurf.toml
# One step only: the setup and the two frames every run writes.
for n in paper-full paper-band6 paper-jointless paper-glued-nosurf; do
  sed 's/^end_time = 4.0e-6/end_time = 1.0e-9/' $S/$n.toml > $S/$n-1step.toml
done

# The bundled pulled bar (weakest-link Weibull strengths), fully jointed and
# jointed only in its middle third (z from 10 to 20 mm).
cp cases/pulled-bar.toml $S/pulled.toml
perl -0pe 's/(name = "rock"\nbreakable = true\n)/$1joints_within = [{ box = { min = [-1.0, -1.0, 0.01], max = [1.0, 1.0, 0.02] } }]\n/' cases/pulled-bar.toml > $S/pulled-band.toml
