# VTK: Debian's libvtk9-dev, or the VTK that ParaView ships (paraview-dev).
#
# On Debian bookworm python3-paraview (pvpython, pvbatch) conflicts with
# python3-vtk9, on which libvtk9-dev depends: a machine with ParaView's Python
# has no libvtk9-dev. paraview-dev carries ParaView's own VTK (9.2, libraries
# libvtk*-pv5.11.so, headers in include/paraview-5.11) with a CMake package of
# its own in lib/<arch>/cmake/paraview-<version>/vtk, whose targets have the
# usual names (VTK::CommonCore, ...). xshell builds against either.
#
# XSHELL_VTK_FROM_PARAVIEW:
#   AUTO (default)  libvtk9-dev when found, else ParaView's VTK.
#   OFF             libvtk9-dev only.
#   ON              ParaView's VTK only (also when libvtk9-dev is installed).
# ParaView's VTK is looked for under CMAKE_PREFIX_PATH (the variable, then the
# environment's) and the system prefixes (/usr, /usr/local); VTK_DIR set by
# hand wins over them.
#
# Sets VTK_LIBRARIES (the components below) and XSHELL_VTK_SOURCE
# ("libvtk9-dev" or "ParaView").
set(XSHELL_VTK_FROM_PARAVIEW "AUTO" CACHE STRING "Build against ParaView's VTK (paraview-dev): AUTO, ON or OFF")
set_property(CACHE XSHELL_VTK_FROM_PARAVIEW PROPERTY STRINGS AUTO ON OFF)

set(_xshell_vtk_components CommonCore CommonDataModel IOXML FiltersCore IOImage RenderingCore RenderingOpenGL2
  FiltersSources RenderingAnnotation RenderingFreeType)

# The directories holding ParaView's vtk-config.cmake, newest version first.
function(_xshell_paraview_vtk_dirs out)
  set(dirs)
  string(REPLACE ":" ";" env_prefixes "$ENV{CMAKE_PREFIX_PATH}")
  foreach(prefix IN LISTS CMAKE_PREFIX_PATH env_prefixes CMAKE_SYSTEM_PREFIX_PATH)
    file(GLOB found "${prefix}/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/paraview-*/vtk/vtk-config.cmake"
      "${prefix}/lib/cmake/paraview-*/vtk/vtk-config.cmake")
    list(SORT found COMPARE NATURAL ORDER DESCENDING)
    foreach(file IN LISTS found)
      get_filename_component(dir "${file}" DIRECTORY)
      list(APPEND dirs "${dir}")
    endforeach()
  endforeach()
  set(${out} ${dirs} PARENT_SCOPE)
endfunction()

if(XSHELL_VTK_FROM_PARAVIEW STREQUAL "OFF" OR (VTK_DIR AND NOT XSHELL_VTK_FROM_PARAVIEW STREQUAL "ON"))
  # libvtk9-dev, the VTK_DIR given, or the one a previous configure found.
  find_package(VTK 9 REQUIRED COMPONENTS ${_xshell_vtk_components})
else()
  if(XSHELL_VTK_FROM_PARAVIEW STREQUAL "AUTO")
    find_package(VTK 9 QUIET COMPONENTS ${_xshell_vtk_components})
  endif()
  if(NOT VTK_FOUND)
    _xshell_paraview_vtk_dirs(_xshell_paraview_dirs)
    if(NOT _xshell_paraview_dirs)
      message(FATAL_ERROR "xshell: no VTK (XSHELL_VTK_FROM_PARAVIEW=${XSHELL_VTK_FROM_PARAVIEW}): no ParaView VTK "
        "(lib/<arch>/cmake/paraview-*/vtk) under CMAKE_PREFIX_PATH or the system prefixes. Install libvtk9-dev, "
        "or paraview-dev when ParaView's Python (python3-paraview) is installed (scripts/install-deps.sh chooses), "
        "or set VTK_DIR.")
    endif()
    unset(VTK_DIR CACHE)
    find_package(VTK 9 REQUIRED COMPONENTS ${_xshell_vtk_components} PATHS ${_xshell_paraview_dirs} NO_DEFAULT_PATH)
  endif()
endif()

if(VTK_DIR MATCHES "/cmake/paraview-[^/]*/vtk$")
  set(XSHELL_VTK_SOURCE "ParaView")
else()
  set(XSHELL_VTK_SOURCE "libvtk9-dev")
endif()
message(STATUS "xshell: VTK ${VTK_VERSION} from ${XSHELL_VTK_SOURCE} (${VTK_DIR})")
