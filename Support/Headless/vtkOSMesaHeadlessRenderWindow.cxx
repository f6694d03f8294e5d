// SPDX-License-Identifier: BSD-3-Clause
#include "vtkOSMesaHeadlessRenderWindow.h"

#include "csmHeadless.h"

#include "vtkGenericRenderWindowInteractor.h"
#include "vtkObjectFactory.h"
#include "vtkVersionMacros.h"

#include <GL/osmesa.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>

extern "C" int csmOSMesaCheckBinding(char* message, size_t size);
void vtkRenderingOpenGL2_AutoInit_Construct();

vtkStandardNewMacro(vtkOSMesaHeadlessRenderWindow);

vtkOSMesaHeadlessRenderWindow::vtkOSMesaHeadlessRenderWindow()
{
  this->SetFrameBlitModeToNoBlit();
  this->ShowWindow = false;
  this->UseOffScreenBuffers = true;
  this->OwnContext = 1;
  this->ScreenSize[0] = 1280;
  this->ScreenSize[1] = 1024;
}

vtkOSMesaHeadlessRenderWindow::~vtkOSMesaHeadlessRenderWindow()
{
  this->Finalize();
}

std::string vtkOSMesaHeadlessRenderWindow::CheckLinkOrder()
{
  char message[1024];
  return csmOSMesaCheckBinding(message, sizeof(message)) ? std::string() : std::string(message);
}

bool vtkOSMesaHeadlessRenderWindow::CreateContext()
{
  if (this->Context)
    return true;
  if (this->Refused)
    return false;
  const std::string linkError = CheckLinkOrder();
  if (!linkError.empty())
  {
    vtkErrorMacro("OSMesa window: " << linkError);
    this->Refused = true;
    this->ReadyForRendering = false;
    return false;
  }
  // Core profile, 3.2 asked (VTK's minimum); Mesa's llvmpipe gives its highest, 4.5. The depth
  // and stencil of this default framebuffer are never used: VTK renders into its own FBOs.
  const int attributes[] = { OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS,
    8, OSMESA_ACCUM_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
    OSMESA_CONTEXT_MINOR_VERSION, 2, 0 };
  this->Context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!this->Context)
  {
    vtkErrorMacro("OSMesa window: OSMesaCreateContextAttribs gave no OpenGL 3.2 core context");
    this->Refused = true;
    this->ReadyForRendering = false;
    return false;
  }
  this->Mapped = 0;
  return true;
}

void vtkOSMesaHeadlessRenderWindow::MakeCurrent()
{
  if (!this->CreateContext())
    return;
  const int width = this->Size[0] > 0 ? this->Size[0] : 300;
  const int height = this->Size[1] > 0 ? this->Size[1] : 300;
  if (width != this->BufferSize[0] || height != this->BufferSize[1])
  {
    this->Buffer.assign(size_t(width) * size_t(height) * 4, 0);
    this->BufferSize[0] = width;
    this->BufferSize[1] = height;
  }
  else if (OSMesaGetCurrentContext() == static_cast<OSMesaContext>(this->Context))
  {
    return;
  }
  if (!OSMesaMakeCurrent(static_cast<OSMesaContext>(this->Context), this->Buffer.data(),
        GL_UNSIGNED_BYTE, width, height))
  {
    vtkErrorMacro("OSMesa window: OSMesaMakeCurrent failed");
  }
}

void vtkOSMesaHeadlessRenderWindow::PushContext()
{
  Current before;
  OSMesaContext current = OSMesaGetCurrentContext();
  before.Context = current;
  if (current)
  {
    GLint width = 0, height = 0, format = 0;
    void* buffer = nullptr;
    OSMesaGetColorBuffer(current, &width, &height, &format, &buffer);
    before.Buffer = buffer;
    before.Width = width;
    before.Height = height;
  }
  this->ContextStack.push_back(before);
  if (current != static_cast<OSMesaContext>(this->Context))
  {
    this->MakeCurrent();
  }
}

void vtkOSMesaHeadlessRenderWindow::PopContext()
{
  if (this->ContextStack.empty())
  {
    return;
  }
  const Current before = this->ContextStack.back();
  this->ContextStack.pop_back();
  OSMesaContext target = static_cast<OSMesaContext>(before.Context);
  if (target && target != OSMesaGetCurrentContext() && before.Buffer)
  {
    // (The colour buffer's type: VTK's windows draw into GL_UNSIGNED_BYTE buffers.)
    OSMesaMakeCurrent(target, before.Buffer, GL_UNSIGNED_BYTE, before.Width, before.Height);
  }
}

void vtkOSMesaHeadlessRenderWindow::ReleaseCurrent()
{
  if (this->Context && OSMesaGetCurrentContext() == static_cast<OSMesaContext>(this->Context))
    OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
}

bool vtkOSMesaHeadlessRenderWindow::IsCurrent()
{
  return this->Context && OSMesaGetCurrentContext() == static_cast<OSMesaContext>(this->Context);
}

int vtkOSMesaHeadlessRenderWindow::SupportsOpenGL()
{
  return this->CreateContext() ? 1 : 0;
}

vtkTypeBool vtkOSMesaHeadlessRenderWindow::IsDirect()
{
  return 1;
}

void vtkOSMesaHeadlessRenderWindow::Initialize()
{
  if (!this->Initialized)
    this->OpenGLInit();
}

void vtkOSMesaHeadlessRenderWindow::OpenGLInit()
{
  this->MakeCurrent();
  if (!this->IsCurrent())
    return;
  this->Superclass::OpenGLInit();
}

void vtkOSMesaHeadlessRenderWindow::Frame()
{
  if (!this->IsCurrent())
    this->MakeCurrent();
  // vtkGenericOpenGLRenderWindow::Frame only fires an event; VTK's own frame copies the render
  // framebuffer to the display framebuffer (what a front-buffer read sees) and, with NoBlit,
  // stops there.
  this->vtkOpenGLRenderWindow::Frame();
}

void vtkOSMesaHeadlessRenderWindow::Finalize()
{
  if (!this->Context)
    return;
  this->MakeCurrent();
  this->Superclass::Finalize(); // releases the renderers' and the window's GL resources
  this->ReleaseCurrent();
  OSMesaDestroyContext(static_cast<OSMesaContext>(this->Context));
  this->Context = nullptr;
  this->Buffer.clear();
  this->BufferSize[0] = this->BufferSize[1] = 0;
  this->Initialized = false; // a later Render creates a new context and initializes it
}

void* vtkOSMesaHeadlessRenderWindow::GetGenericContext()
{
  return this->Context;
}

const char* vtkOSMesaHeadlessRenderWindow::ReportCapabilities()
{
  this->Report = std::string("Context API: ") + this->GetContextAPI() + " (no X server)\n";
  if (this->Initialized)
  {
    this->MakeCurrent();
    this->Report += this->Superclass::ReportCapabilities();
  }
  return this->Report.c_str();
}

void vtkOSMesaHeadlessRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ContextAPI: " << this->GetContextAPI() << "\n";
  os << indent << "Context: " << this->Context << "\n";
}

// ---------------------------------------------------------------------------------------------
// The object-factory overrides: vtkRenderWindow::New() makes this window, and
// vtkRenderWindowInteractor::New() a vtkGenericRenderWindowInteractor (VTK's X interactor would
// open the display when a window that has one renders, as vtkContextView's does).
namespace
{
class csmHeadlessFactory : public vtkObjectFactory
{
public:
  static csmHeadlessFactory* New()
  {
    auto* factory = new csmHeadlessFactory;
    factory->InitializeObjectBase();
    return factory;
  }
  vtkTypeMacro(csmHeadlessFactory, vtkObjectFactory);
  const char* GetVTKSourceVersion() override { return VTK_SOURCE_VERSION; }
  const char* GetDescription() override { return "OSMesa render window (no X server)"; }

protected:
  csmHeadlessFactory()
  {
    this->RegisterOverride("vtkRenderWindow", "vtkOSMesaHeadlessRenderWindow",
      "OSMesa render window (no X server)", 1, &csmHeadlessFactory::MakeWindow);
    this->RegisterOverride("vtkRenderWindowInteractor", "vtkGenericRenderWindowInteractor",
      "interactor without a windowing system", 1, &csmHeadlessFactory::MakeInteractor);
  }

  static vtkObject* MakeInteractor() { return vtkGenericRenderWindowInteractor::New(); }

  /// A window that cannot work is refused here, with the reason, before any GL call.
  static vtkObject* MakeWindow()
  {
    const std::string linkError = vtkOSMesaHeadlessRenderWindow::CheckLinkOrder();
    if (!linkError.empty())
    {
      std::fprintf(stderr, "error: OSMesa render window refused: %s\n", linkError.c_str());
      std::exit(2);
    }
    return vtkOSMesaHeadlessRenderWindow::New();
  }
};

csmHeadlessFactory* Factory = nullptr;
const std::pair<const char*, const char*> Overrides[] = { { "vtkRenderWindow",
                                                            "vtkOSMesaHeadlessRenderWindow" },
  { "vtkRenderWindowInteractor", "vtkGenericRenderWindowInteractor" } };

bool UseOSMesaWindow(bool use)
{
  if (use)
  {
    if (!Factory)
    {
      Factory = csmHeadlessFactory::New();
      vtkObjectFactory::RegisterFactory(Factory);
    }
  }
  for (const auto& o : Overrides)
  {
    if (use)
    {
      vtkObjectFactory::SetAllEnableFlags(0, o.first); // VTK's X window and interactor off
      Factory->SetEnableFlag(1, o.first, o.second);
    }
    else
    {
      vtkObjectFactory::SetAllEnableFlags(1, o.first);
      if (Factory)
        Factory->SetEnableFlag(0, o.first, o.second);
    }
  }
  return Factory && Factory->GetEnableFlag("vtkRenderWindow", "vtkOSMesaHeadlessRenderWindow");
}

bool UsingOSMesaWindow()
{
  return Factory && Factory->GetEnableFlag("vtkRenderWindow", "vtkOSMesaHeadlessRenderWindow");
}

// Registered when libcsm_headless is loaded. The factories registered before it (VTK's OpenGL
// one is registered here first) get their window and interactor overrides disabled; those
// registered later come after it in VTK's lookup: the order of static initializers does not
// matter.
struct Registration
{
  Registration()
  {
    vtkRenderingOpenGL2_AutoInit_Construct();
    const char* choice = std::getenv("CSM_HEADLESS");
    const bool x = choice && (std::strcmp(choice, "x") == 0 || std::strcmp(choice, "glx") == 0);
    UseOSMesaWindow(!x);
  }
  ~Registration()
  {
    if (Factory)
    {
      vtkObjectFactory::UnRegisterFactory(Factory);
      Factory->Delete();
      Factory = nullptr;
    }
  }
} registration;
}

namespace csmHeadless
{
bool Available()
{
  return true;
}

bool UseOSMesa(bool use)
{
  return UseOSMesaWindow(use);
}

bool UsingOSMesa()
{
  return UsingOSMesaWindow();
}
}

// The same for a program that does not link this library and finds it loaded (csmHeadless.h,
// csmHeadlessPreload.cxx: the window programs, which get it through LD_PRELOAD).
extern "C" __attribute__((visibility("default"))) int csmHeadlessUseOSMesa(int use)
{
  return UseOSMesaWindow(use != 0) ? 1 : 0;
}

extern "C" __attribute__((visibility("default"))) int csmHeadlessUsingOSMesa()
{
  return UsingOSMesaWindow() ? 1 : 0;
}
