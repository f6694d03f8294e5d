// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkOSMesaHeadlessRenderWindow
 * @brief A render window over an OSMesa context: renders with no X server and no display, in a
 * GLX-only VTK (Debian's VTK 9.1).
 *
 * A vtkGenericOpenGLRenderWindow whose context the window creates itself with
 * OSMesaCreateContextAttribs (core profile, 3.2 asked; Mesa's llvmpipe gives 4.5). VTK renders
 * into its own framebuffers as in any offscreen window; nothing is blitted to the OSMesa buffer
 * (frame blit mode NoBlit). It needs the executable to bind GL entry points through
 * libcsm_headless and libOSMesa (see csmGLXForOSMesa.c): CMake's csm_link_osmesa_window(target)
 * links both ahead of glvnd's libraries, and this window refuses to render, with a message that
 * says so, when the binding is wrong.
 *
 * Linked that way, `vtkRenderWindow::New()` returns this window (an object-factory override
 * registered when libcsm_headless loads); csmHeadless::UseOSMesa(false) turns the override off
 * (VTK's X window again), CSM_HEADLESS=x in the environment too.
 */
#ifndef vtkOSMesaHeadlessRenderWindow_h
#define vtkOSMesaHeadlessRenderWindow_h

#include "vtkGenericOpenGLRenderWindow.h"

#include <string>
#include <vector>

class __attribute__((visibility("default"))) vtkOSMesaHeadlessRenderWindow
  : public vtkGenericOpenGLRenderWindow
{
public:
  static vtkOSMesaHeadlessRenderWindow* New();
  vtkTypeMacro(vtkOSMesaHeadlessRenderWindow, vtkGenericOpenGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// "OSMesa": the API of this window's context (no GLX, no X server).
  const char* GetContextAPI() const { return "OSMesa"; }

  /// Empty when this process binds the GL entry points as this window needs (GLX lookups to
  /// libcsm_headless, GL 1.x functions to libOSMesa); else what is wrong and how to link.
  static std::string CheckLinkOrder();

  /// Creates the context (once) and initializes OpenGL (GLEW, VTK's state) in it.
  void Initialize() override;
  void OpenGLInit() override;
  void MakeCurrent() override;
  void ReleaseCurrent() override;
  bool IsCurrent() override;
  /// This window's context made current for a while (VTK releases a mapper's buffers in the
  /// window that made them when another window draws it), and the context current before, with
  /// its buffer, made current again after.
  void PushContext() override;
  void PopContext() override;
  int SupportsOpenGL() override;
  vtkTypeBool IsDirect() override;
  /// VTK's frame (render framebuffer to display framebuffer), no blit to the OSMesa buffer.
  void Frame() override;
  /// Releases VTK's graphics resources in this context, then destroys the context.
  void Finalize() override;
  void* GetGenericContext() override;
  /// VTK's report, after a line naming the context API.
  const char* ReportCapabilities() override;

protected:
  vtkOSMesaHeadlessRenderWindow();
  ~vtkOSMesaHeadlessRenderWindow() override;

private:
  bool CreateContext();

  void* Context = nullptr;           // OSMesaContext
  std::vector<unsigned char> Buffer; // the context's own colour buffer (RGBA), never read
  int BufferSize[2] = { 0, 0 };
  bool Refused = false; // wrong link order or no context: reported once, nothing rendered
  struct Current
  {
    void* Context = nullptr; // OSMesaContext
    void* Buffer = nullptr;
    int Width = 0, Height = 0;
  };
  std::vector<Current> ContextStack; // PushContext()'s
  std::string Report;

  vtkOSMesaHeadlessRenderWindow(const vtkOSMesaHeadlessRenderWindow&) = delete;
  void operator=(const vtkOSMesaHeadlessRenderWindow&) = delete;
};

#endif
