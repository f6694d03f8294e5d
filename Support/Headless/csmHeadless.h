// SPDX-License-Identifier: BSD-3-Clause
// Which window vtkRenderWindow::New() makes in the programs of this project (tests, csm-demo,
// csm-bench). Built with CSM_OSMESA (the default where libosmesa6-dev is installed), the tests and
// csm-bench link libcsm_headless, whose object factory makes it a vtkOSMesaHeadlessRenderWindow:
// rendering with no X server. csm-demo links the system's GL and gets libcsm_headless preloaded
// for --offscreen (csmHeadlessPreload.cxx). Without it, or after UseOSMesa(false), it is VTK's
// own (X/GLX) window.
#ifndef csmHeadless_h
#define csmHeadless_h

namespace csmHeadless
{
/// True when this executable has the OSMesa window: linked with it, or (csm-demo) loaded or
/// found for --offscreen (built with CSM_OSMESA).
bool Available();

/// From now on vtkRenderWindow::New() makes the OSMesa window (true; the default when available,
/// unless CSM_HEADLESS=x is set in the environment) or VTK's own X window (false). Returns
/// whether the OSMesa window is in use afterwards.
bool UseOSMesa(bool use);

/// Whether vtkRenderWindow::New() makes the OSMesa window now.
bool UsingOSMesa();
}

#endif
