#!/bin/sh
# Run this deck with your own LAMMPS build (needs the GRANULAR package):
#   NP=64 LMP=lmp_mpi sh job.sh      (or submit it from a batch script)
cd "$(dirname "$0")"
mpirun -np "${NP:-4}" "${LMP:-lmp}" -in deck.lmp -log log.lammps
