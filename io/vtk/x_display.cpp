#include "x_display.hpp"

#include <X11/Xlib.h>

#include <cstdlib>
#include <string>

#include "render_error.hpp"

namespace xshell {

bool display_variable_set() {
  const char* name = std::getenv("DISPLAY");
  return name != nullptr && name[0] != '\0';
}

XDisplay::XDisplay() {
  if (!display_variable_set())
    throw RenderError(
        "render: no X display (DISPLAY is not set); VTK here renders through X even off "
        "screen -- run the command under `xvfb-run -a`");
  display_ = XOpenDisplay(nullptr);
  if (display_ == nullptr)
    throw RenderError("render: cannot open X display '" + std::string(std::getenv("DISPLAY")) +
                      "'; run the command under `xvfb-run -a`");
}

XDisplay::~XDisplay() {
  if (display_ != nullptr) XCloseDisplay(static_cast<Display*>(display_));
}

}  // namespace xshell
