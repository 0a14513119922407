#!/usr/bin/env bash
# Sets everything up (scripts/setup.sh) and runs all tests: C++ (ctest),
# Python serial, and the MPI-marked Python tests under mpirun -n 2.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
ctest --test-dir build --output-on-failure
.venv/bin/python -m pytest -q -p no:cacheprovider tests
mpirun -n 2 --allow-run-as-root --oversubscribe \
  .venv/bin/python -m pytest -q -p no:cacheprovider -m mpi tests
