// The VTK encoding that a configuration's "output" asks for ("format",
// "compression"), for every .vtp file a run writes.
#pragma once

#include "io/config.hpp"
#include "io/vtk/write_options.hpp"

namespace xshell {

WriteOptions vtk_write_options(const OutputOptions& output);

}  // namespace xshell
