// The commands that need rendering or IPOPT (render, design) run in
// xshell-full, the same program with every library linked, installed beside
// xshell. xshell itself links only what relax and fabricate need, and so
// starts in about half the time: loading and relocating VTK's rendering
// libraries (OpenGL, X11, FreeType), IPOPT and their dependencies took 27 ms
// of every run, a tenth of a plain relaxation of manta_ray.
#pragma once

namespace xshell {

// The file name of the program with every command, beside this one.
inline constexpr const char* kFullProgramName = "xshell-full";

// Replaces this process by xshell-full beside this program, with the same
// arguments (the exit status, the output and the signals are then that
// program's). Returns only when it could not be started, with the exit
// status for that after saying why on stderr.
int run_in_full_program(char** argv);

}  // namespace xshell
