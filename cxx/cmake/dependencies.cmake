# The libraries' dependencies, each with the Debian package that provides it. The kernels need
# Eigen (and nanoflann, privately); the assembly also needs PETSc (pkg-config PETSc) and MPI.
find_package(Eigen3 3.4 QUIET NO_MODULE)
if(NOT Eigen3_FOUND)
  hypercontact_missing("Eigen 3.4 or newer (Eigen3Config.cmake)" libeigen3-dev)
endif()
# The header itself, and the package's target (nanoflannConfig.cmake) that the kernels link.
find_path(NANOFLANN_INCLUDE_DIR nanoflann.hpp)
find_package(nanoflann QUIET CONFIG)
if(NOT NANOFLANN_INCLUDE_DIR OR NOT nanoflann_FOUND)
  hypercontact_missing("nanoflann (nanoflannConfig.cmake; k-d trees of the contact search)"
                       libnanoflann-dev)
endif()
# PETSc's headers include mpi.h; the C++ bindings of MPI are not used.
set(MPI_CXX_SKIP_MPICXX TRUE)
find_package(MPI QUIET COMPONENTS CXX)
if(NOT MPI_FOUND)
  hypercontact_missing("MPI for C++" libopenmpi-dev)
endif()
find_package(PkgConfig QUIET)
if(NOT PKG_CONFIG_FOUND)
  hypercontact_missing("pkg-config (it finds PETSc)" pkg-config)
endif()
pkg_check_modules(PETSC QUIET IMPORTED_TARGET PETSc)
if(NOT PETSC_FOUND)
  hypercontact_missing("PETSc (PETSc.pc for pkg-config)" petsc-dev)
endif()
