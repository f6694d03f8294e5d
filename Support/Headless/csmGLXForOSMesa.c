// SPDX-License-Identifier: BSD-3-Clause
/* GL entry points for an OSMesa context in a GLX-only VTK (Debian's VTK 9.1).
 *
 * Debian's VTK loads GL through Debian's GLEW, a GLX build: glewInit() takes every entry point,
 * glGetString included, from glXGetProcAddressARB, which glvnd answers with stubs that dispatch
 * to the current *GLX* context. An OSMesa context is current only in Mesa's own libglapi, so
 * GLEW finds "Missing GL version" and VTK later calls a null pointer. This library, linked into
 * the executable ahead of libGLX/libGL/libOpenGL, takes glXGetProcAddress[ARB]: while an OSMesa
 * context is current it answers with OSMesaGetProcAddress (Mesa's stubs, which dispatch to the
 * current Mesa context), otherwise it passes the call on to glvnd. It also answers the three
 * GLX calls glewInit ends with (glxewInit) for a dummy display: glXGetCurrentDisplay,
 * glXQueryVersion (1.4) and glXGetClientString (""). libOSMesa, linked just after it, supplies
 * the GL 1.x functions VTK calls directly (glViewport, glReadPixels, ...), again through libglapi.
 *
 * csmOSMesaCheckBinding() says whether the process really binds these names that way.
 */
#define _GNU_SOURCE
#include <GL/osmesa.h>
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

#define CSM_EXPORT __attribute__((visibility("default")))

typedef void (*csmProc)(void);
typedef struct _XDisplay Display; /* as in Xlib.h: only passed through */

/* What glxewInit gets as "the current display" while an OSMesa context is current; never
 * dereferenced (GLEW passes it back to glXQueryVersion and glXGetClientString, below). */
static char csmDummyDisplay[16];
#define CSM_DUMMY ((Display*)csmDummyDisplay)

static void* csmNext(const char* name)
{
  return dlsym(RTLD_NEXT, name);
}

static Display* csmFakeGetCurrentDisplay(void)
{
  return CSM_DUMMY;
}

static csmProc csmGetProcAddress(const char* procName, const char* which)
{
  if (!procName)
    return NULL;
  if (OSMesaGetCurrentContext())
  {
    if (strcmp(procName, "glXGetCurrentDisplay") == 0)
      return (csmProc)csmFakeGetCurrentDisplay;
    if (strncmp(procName, "glX", 3) == 0)
      return NULL; /* no GLX behind an OSMesa context */
    return (csmProc)OSMesaGetProcAddress(procName);
  }
  csmProc (*next)(const unsigned char*) = (csmProc(*)(const unsigned char*))csmNext(which);
  return next ? next((const unsigned char*)procName) : NULL;
}

CSM_EXPORT csmProc glXGetProcAddressARB(const unsigned char* procName)
{
  return csmGetProcAddress((const char*)procName, "glXGetProcAddressARB");
}

CSM_EXPORT csmProc glXGetProcAddress(const unsigned char* procName)
{
  return csmGetProcAddress((const char*)procName, "glXGetProcAddress");
}

CSM_EXPORT Display* glXGetCurrentDisplay(void)
{
  if (OSMesaGetCurrentContext())
    return CSM_DUMMY;
  Display* (*next)(void) = (Display * (*)(void)) csmNext("glXGetCurrentDisplay");
  return next ? next() : NULL;
}

CSM_EXPORT int glXQueryVersion(Display* display, int* major, int* minor)
{
  if (display == CSM_DUMMY)
  {
    if (major)
      *major = 1;
    if (minor)
      *minor = 4;
    return 1;
  }
  int (*next)(Display*, int*, int*) = (int (*)(Display*, int*, int*))csmNext("glXQueryVersion");
  return next ? next(display, major, minor) : 0;
}

CSM_EXPORT const char* glXGetClientString(Display* display, int name)
{
  if (display == CSM_DUMMY)
    return "";
  typedef const char* (*GetClientString)(Display*, int);
  GetClientString next = (GetClientString)csmNext("glXGetClientString");
  return next ? next(display, name) : NULL;
}

/* The object (shared library or executable) that defines the first `name` in the process's
 * global lookup order, i.e. what GLEW and VTK are bound to; NULL base when none. */
static const void* csmDefiningObject(const char* name, const char** file)
{
  Dl_info info;
  void* symbol = dlsym(RTLD_DEFAULT, name);
  *file = "(nowhere)";
  if (!symbol || !dladdr(symbol, &info))
    return NULL;
  *file = info.dli_fname;
  return info.dli_fbase;
}

CSM_EXPORT int csmOSMesaCheckBinding(char* message, size_t size)
{
  static const char* const ours[] = { "glXGetProcAddressARB", "glXGetProcAddress",
    "glXGetCurrentDisplay", "glXQueryVersion", "glXGetClientString" };
  static const char* const mesa[] = { "glGetString", "glViewport", "glReadPixels", "glClear" };
  static const char* const advice =
    ": link libcsm_headless and libOSMesa into the executable ahead of libGLX, libGL and "
    "libOpenGL (CMake: csm_link_osmesa_window(<target>); README, \"Headless\")";
  Dl_info self, osmesa;
  const char* file = NULL;
  size_t i;
  if (!dladdr((void*)csmFakeGetCurrentDisplay, &self) ||
    !dladdr((void*)OSMesaGetCurrentContext, &osmesa))
  {
    snprintf(message, size, "cannot locate libcsm_headless or libOSMesa in this process");
    return 0;
  }
  for (i = 0; i < sizeof(ours) / sizeof(ours[0]); ++i)
    if (csmDefiningObject(ours[i], &file) != self.dli_fbase)
    {
      snprintf(message, size, "%s binds to %s, not to %s%s", ours[i], file, self.dli_fname, advice);
      return 0;
    }
  for (i = 0; i < sizeof(mesa) / sizeof(mesa[0]); ++i)
    if (csmDefiningObject(mesa[i], &file) != osmesa.dli_fbase)
    {
      snprintf(
        message, size, "%s binds to %s, not to %s%s", mesa[i], file, osmesa.dli_fname, advice);
      return 0;
    }
  snprintf(message, size, "GLX entry points from %s, GL from %s", self.dli_fname, osmesa.dli_fname);
  return 1;
}
