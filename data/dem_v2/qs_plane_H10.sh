#!/bin/sh
# Corpus v2, first runs: the quasi-static rough and smooth plane pair at H = 10 d (B = 1,
# V = 0.0025 sqrt(N/rho_s), 16M sheared steps = 40 d of wall travel), one after the other on
# one core, nice 19. Re-running this script resumes both from their last checkpoints
# (a finished run is only coarse-grained again).
cd /work/dem_runs
PY=/work/main/.venv/bin/python
export PYTHONPATH=/work/main/src OMP_NUM_THREADS=1
COMMON="--gap-d 10 --width 30 --B 1 --speed 0.0025 --settle 30000 --steps 16000000 --dump-every 10000 --restart-every 200000 --seed 1 --keep-dumps"
for wall in rough smooth; do
  kind=glued-grains; [ $wall = smooth ] && kind=smooth-frictional
  out=plane_${wall}_H10_qs
  resume=""; [ -f $out/deck.lmp ] && resume="--resume"
  nice -n 19 $PY -m cosserat dem run plane --out $out --wall $kind $COMMON $resume >> $out.log 2>&1
done
