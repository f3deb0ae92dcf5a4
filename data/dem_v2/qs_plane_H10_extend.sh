#!/bin/sh
# After qs_plane_H10.sh: the rough H = 10 d run finished 16M steps quasi-static but its gap was
# still shrinking (steadiness: dilation z = -3.59); continue it to the design's 20M steps
# (50 d of wall travel). Re-running this script resumes it from its last checkpoint.
cd /work/dem_runs
PY=/work/main/.venv/bin/python
export PYTHONPATH=/work/main/src OMP_NUM_THREADS=1
nice -n 19 $PY -m cosserat dem run plane --out plane_rough_H10_qs --wall glued-grains \
  --gap-d 10 --width 30 --B 1 --speed 0.0025 --settle 30000 --steps 20000000 \
  --dump-every 10000 --restart-every 200000 --seed 1 --keep-dumps --resume \
  >> plane_rough_H10_qs.log 2>&1
