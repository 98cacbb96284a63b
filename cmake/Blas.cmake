# The BLAS and LAPACK behind CHOLMOD's supernodal factorization, where a
# Newton iteration spends most of its time (dsyrk, dgemm, dtrsm, dpotrf).
# Debian's libcholmod links libblas.so.3 and liblapack.so.3, which the
# system's alternatives resolve (the reference BLAS unless changed).
#
# XSHELL_BLAS:
#   openblas (default)  OpenBLAS's OpenMP build (Debian libopenblas0-openmp).
#                       Every xshell program links it directly and finds it
#                       through its run path, so it is loaded before
#                       CHOLMOD's own dependencies and CHOLMOD uses it,
#                       whatever the alternatives say. It shares the
#                       program's OpenMP threads (OMP_NUM_THREADS).
#   system              whatever libblas.so.3 the alternatives provide.
# README, "Benchmark", has the numbers behind the default.
set(XSHELL_BLAS "openblas" CACHE STRING "BLAS for CHOLMOD: openblas or system")
set_property(CACHE XSHELL_BLAS PROPERTY STRINGS openblas system)

add_library(xshell_blas INTERFACE)
add_library(xshell::blas ALIAS xshell_blas)
if(XSHELL_BLAS STREQUAL "openblas")
  set(_openblas_dirs /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/openblas-openmp)
  find_library(XSHELL_OPENBLAS_BLAS NAMES libblas.so.3 PATHS ${_openblas_dirs} NO_DEFAULT_PATH)
  find_library(XSHELL_OPENBLAS_LAPACK NAMES liblapack.so.3 PATHS ${_openblas_dirs} NO_DEFAULT_PATH)
  if(XSHELL_OPENBLAS_BLAS AND XSHELL_OPENBLAS_LAPACK)
    get_filename_component(_openblas_dir "${XSHELL_OPENBLAS_BLAS}" DIRECTORY)
    # --no-as-needed for these two alone (--push-state): nothing in xshell
    # calls BLAS itself, and the point is the dependency; every other library
    # keeps the linker's setting (xshell links --as-needed, app/CMakeLists.txt).
    # The run path is the build tree's and the installed one.
    target_link_options(xshell_blas INTERFACE "LINKER:-rpath,${_openblas_dir}")
    target_link_libraries(xshell_blas INTERFACE "-Wl,--push-state,--no-as-needed"
      "${XSHELL_OPENBLAS_BLAS}" "${XSHELL_OPENBLAS_LAPACK}" "-Wl,--pop-state")
    message(STATUS "xshell: CHOLMOD uses OpenBLAS (${_openblas_dir})")
  else()
    message(WARNING "xshell: XSHELL_BLAS=openblas but OpenBLAS (libopenblas0-openmp) is not installed: "
                    "CHOLMOD uses the system's BLAS, whose factorizations may be 2x slower "
                    "(scripts/install-deps.sh installs it; -DXSHELL_BLAS=system silences this)")
  endif()
elseif(NOT XSHELL_BLAS STREQUAL "system")
  message(FATAL_ERROR "XSHELL_BLAS must be openblas or system, not '${XSHELL_BLAS}'")
endif()
