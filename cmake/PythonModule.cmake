# Finds what the Python module (python/) needs: the Python interpreter and
# development files, and pybind11. Sets XSHELL_WITH_PYTHON when XSHELL_PYTHON
# is on (and no sanitizer is) and both are found; the static libraries are then compiled as
# position-independent code, so that the module (a shared object) can link them.
#
# The interpreter: -DPython3_EXECUTABLE=... when given, else Debian's
# /usr/bin/python3 when it exists (a python3 earlier on PATH may lack numpy
# and scipy), else the first one found.
set(XSHELL_WITH_PYTHON OFF)
if(XSHELL_PYTHON AND (XSHELL_SANITIZE OR XSHELL_FUZZ))
  # An extension instrumented with ASan cannot load into an uninstrumented
  # python3: the sanitizer and fuzzing builds leave the module out.
  message(STATUS "xshell: the Python module is not built with sanitizers")
elseif(XSHELL_PYTHON)
  if(NOT Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "The Python of the xshell module")
  endif()
  find_package(Python3 COMPONENTS Interpreter Development.Module)
  if(Python3_FOUND)
    find_package(pybind11 2.6 CONFIG QUIET)
  endif()
  if(Python3_FOUND AND pybind11_FOUND)
    set(XSHELL_WITH_PYTHON ON)
    set(CMAKE_POSITION_INDEPENDENT_CODE ON)
    message(STATUS "xshell: Python module for ${Python3_EXECUTABLE} (pybind11 ${pybind11_VERSION})")
  elseif(NOT Python3_FOUND)
    message(WARNING "xshell: no Python 3 interpreter with development files: the Python module "
                    "is not built (install python3-dev, or -DXSHELL_PYTHON=OFF to silence this)")
  else()
    message(WARNING "xshell: pybind11 not found: the Python module is not built (install "
                    "pybind11-dev, scripts/install-deps.sh; or -DXSHELL_PYTHON=OFF to silence this)")
  endif()
endif()
