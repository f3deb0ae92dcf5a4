#!/bin/sh
# Corpus v2, gap series: the quasi-static smooth plane run at H = 20 d (B = 1,
# V = 0.0025 sqrt(N/rho_s), 24M sheared steps = 60 d of wall travel = 40 d + H), one core, nice 19.
# Re-running this script resumes it from its last checkpoint.
cd /work/dem_runs
PY=/work/main/.venv/bin/python
export PYTHONPATH=/work/main/src OMP_NUM_THREADS=1
out=plane_smooth_H20_qs
resume=""; [ -f $out/deck.lmp ] && resume="--resume"
nice -n 19 $PY -m cosserat dem run plane --out $out --wall smooth-frictional --gap-d 20 --width 30 --B 1 \
  --speed 0.0025 --settle 30000 --steps 24000000 --dump-every 10000 --restart-every 200000 --seed 1 \
  --keep-dumps $resume >> $out.log 2>&1
