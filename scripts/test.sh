#!/usr/bin/env bash
# Sets everything up (scripts/setup.sh) and runs all tests: C++ (ctest, then the example
# examples/assemble_contact built against the installed C++ package),
# Python serial, the MPI-marked Python tests under mpirun -n 2, and the
# convergence-robustness subset again under a second OpenBLAS kernel.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
ctest --test-dir build --output-on-failure
# The C++ package as a C++ user gets it: installed, and a program built against the installed copy.
rm -rf build/install build/example
cmake --install build --prefix build/install > /dev/null
cmake -S examples/assemble_contact -B build/example -DCMAKE_PREFIX_PATH="$PWD/build/install" > /dev/null
cmake --build build/example
build/example/assemble_contact
.venv/bin/python -m pytest -q -p no:cacheprovider tests
mpirun -n 2 --allow-run-as-root --oversubscribe \
  .venv/bin/python -m pytest -q -p no:cacheprovider -m mpi tests
# OpenBLAS picks its kernels by processor, and their rounding differs: a
# convergence result must not be a property of one kernel. Sandybridge runs on
# any x86-64 processor with AVX, whatever this machine's own kernel is.
if grep -qw avx /proc/cpuinfo 2>/dev/null; then
  OPENBLAS_CORETYPE=Sandybridge .venv/bin/python -m pytest -q -p no:cacheprovider \
    tests/behaviour/test_robustness.py tests/verification/test_punch_friction.py tests/verification/test_friction.py \
    tests/verification/test_friction_block.py tests/verification/test_surface_friction.py \
    tests/behaviour/test_step_control.py tests/behaviour/test_contact_protocol.py tests/hard \
    tests/behaviour/test_inverted_elements.py tests/unit/test_stall_test.py tests/behaviour/test_predictor.py \
    tests/verification/test_oring.py tests/verification/test_limit_points.py tests/verification/test_continuation_deformable.py \
    tests/verification/test_self_contact.py tests/verification/test_tube_collapse.py \
    tests/verification/test_rounded_box.py tests/behaviour/test_inertia.py tests/verification/test_facet_integration.py \
    tests/verification/test_quadratic_surface_contact.py tests/verification/test_smooth_master.py
fi
