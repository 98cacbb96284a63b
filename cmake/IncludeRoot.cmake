# The one-way include rule: src/ is the model and includes only itself;
# integrators/ and io/ include src/; app/, bench/ and the tests include all.
# Each folder is reachable as "<folder>/..." only through an include root of
# its own in the build tree (a directory holding one link named <folder> to
# the source folder), which only the targets allowed to see it get. So
# `#include "io/config.hpp"` from src/ or integrators/ fails to compile
# (tests/include_rule checks that it does).

# xshell_include_root(TARGET FOLDER): TARGET's users may include
# "FOLDER/...".
function(xshell_include_root target folder)
  set(root "${CMAKE_BINARY_DIR}/include_roots/${folder}")
  if(NOT EXISTS "${root}/${folder}")
    file(MAKE_DIRECTORY "${root}")
    file(CREATE_LINK "${CMAKE_SOURCE_DIR}/${folder}" "${root}/${folder}" SYMBOLIC)
  endif()
  target_include_directories(${target} PUBLIC "${root}")
endfunction()
