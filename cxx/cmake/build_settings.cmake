# Settings shared by the libraries, the Python extension and the tests.

# std::span needs C++20 (the same standard as Debian's dolfinx 0.5.2).
set(CMAKE_CXX_STANDARD 20)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
set(CMAKE_CXX_EXTENSIONS OFF)
if(NOT CMAKE_BUILD_TYPE AND NOT CMAKE_CONFIGURATION_TYPES)
  set(CMAKE_BUILD_TYPE Release CACHE STRING "Build type" FORCE)
endif()
set(CMAKE_CXX_FLAGS_RELEASE "-O2 -DNDEBUG")

# Stop at configure time, naming the Debian package, when a dependency is
# missing (instead of an obscure find_package error or a compiler error).
function(hypercontact_missing what package)
  message(FATAL_ERROR "hypercontact: ${what} not found: install the Debian package ${package} "
                      "(apt-get install ${package}; scripts/setup.sh does)")
endfunction()
