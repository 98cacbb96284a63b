# IPOPT (Debian coinor-libipopt-dev), the inverse design's optimizer
# (integrators/optimization/). Only libipopt itself is linked: its own
# dependencies (MUMPS, LAPACK, BLAS) come with the shared library, and the
# extra link directories that pkg-config lists for static links would hide
# the OpenBLAS that cmake/Blas.cmake puts first.
find_path(XSHELL_IPOPT_INCLUDE_DIR IpTNLP.hpp PATH_SUFFIXES coin coin-or REQUIRED)
find_library(XSHELL_IPOPT_LIBRARY ipopt REQUIRED)
add_library(xshell_ipopt INTERFACE)
add_library(xshell::ipopt ALIAS xshell_ipopt)
target_include_directories(xshell_ipopt SYSTEM INTERFACE "${XSHELL_IPOPT_INCLUDE_DIR}")
# What Debian's ipopt.pc adds to the compile flags.
target_compile_definitions(xshell_ipopt INTERFACE HAVE_CSTDDEF)
target_link_libraries(xshell_ipopt INTERFACE "${XSHELL_IPOPT_LIBRARY}")
