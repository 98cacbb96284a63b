// An open connection to the X server named by $DISPLAY, owned (RAII).
//
// Debian's VTK renders through GLX only, even off screen, and its
// vtkXOpenGLRenderWindow calls abort() when it cannot open the display. So
// the renderer opens the display itself first, where a failure is a clean
// RenderError, and hands the connection to VTK (vtkRenderWindow::
// SetDisplayId), which then does not close it. Xlib stays out of this header
// (its macros clash with VTK's and Eigen's names).
#pragma once

namespace xshell {

class XDisplay {
 public:
  // Throws RenderError when $DISPLAY is unset or empty, or when its server
  // does not answer (e.g. a stale DISPLAY after an ssh session ended).
  XDisplay();
  XDisplay(const XDisplay&) = delete;
  XDisplay& operator=(const XDisplay&) = delete;
  ~XDisplay();

  // The Xlib Display*, as VTK takes it.
  void* handle() const { return display_; }

 private:
  void* display_ = nullptr;
};

// Whether $DISPLAY is set and non-empty (it says nothing of the server).
bool display_variable_set();

}  // namespace xshell
