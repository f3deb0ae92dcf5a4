#!/bin/sh
# Issue 18 item 4, the layer position: plane shear WITHOUT gravity (B = 0), H = 10 d, a ROUGH
# MOVING upper wall (glued-grains) and a SMOOTH FIXED lower wall (smooth-frictional, delta = 13.9
# deg), V = 0.0025 sqrt(N/rho_s), 20M sheared steps (50 d of wall travel = 40 d + H), one core,
# nice 19, checkpoints every 200k steps. The Cosserat model puts the layer at the fixed smooth
# wall; mu(I) and NGF (uniform stress) shear the gap uniformly. Code: a snapshot of the layer
# branch (commit in plane_layer_H10_qs.src/COMMIT). Re-running this script resumes the run from
# its last checkpoint (a finished run is only coarse-grained again).
cd /work/dem_runs
PY=/work/main/.venv/bin/python
export PYTHONPATH=/work/dem_runs/plane_layer_H10_qs.src OMP_NUM_THREADS=1
out=plane_layer_H10_qs
resume=""; [ -f $out/deck.lmp ] && resume="--resume"
nice -n 19 $PY -m cosserat dem run plane --out $out --wall glued-grains \
  --wall-lower smooth-frictional --wall-upper glued-grains --gap-d 10 --width 30 --B 0 \
  --speed 0.0025 --settle 30000 --steps 20000000 --dump-every 10000 --restart-every 200000 \
  --seed 1 --keep-dumps $resume >> $out.log 2>&1
