#!/usr/bin/env bash
# Installs everything hypercontact needs on Debian 12, builds the C++ library
# and its Python extension, and installs the package into .venv.
# Quick when everything is already there.
set -euo pipefail
cd "$(dirname "$0")/.."

# Every package the build (CMakeLists.txt), the tests, a run and bench/ use;
# CMake names the one that is missing if this list is not installed.
PACKAGES=(
  # build: compilers and tools, C++ headers and libraries
  cmake g++ make pkg-config
  libnanoflann-dev libeigen3-dev petsc-dev libopenmpi-dev pybind11-dev libgtest-dev libdolfinx-dev
  # Python: FEniCSx 0.5.2 (with ufl, basix, ffcx, cffi), PETSc and MPI bindings, pybind11 for the extension
  python3-dolfinx python3-petsc4py python3-mpi4py python3-pybind11 python3-numpy
  # the typed scene schema (hypercontact.scene: pydantic 1.10)
  python3-pydantic
  # a run: meshes, results and pictures
  python3-gmsh python3-meshio python3-h5py python3-matplotlib python3-scipy python3-pil
  # MPI runs (mpirun), the BLAS, tests and the virtual environment
  openmpi-bin libopenblas0-pthread python3-pytest python3-venv python3-setuptools python3-wheel
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build.log 2>&1 || { cat build.log; exit 1; }
cmake --build build -j2 >> build.log 2>&1 || { cat build.log; exit 1; }

if [ ! -x .venv/bin/python ]; then
  /usr/bin/python3 -m venv --system-site-packages .venv
fi
if ! .venv/bin/python -c "import hypercontact._cpp, hypercontact.forms, hypercontact.scenes" 2>/dev/null; then
  .venv/bin/pip install -q --no-build-isolation --no-deps -e .
fi
echo "setup: ready (.venv/bin/hypercontact)"
