// SPDX-License-Identifier: BSD-3-Clause
// csmHeadless for a window program (csm-demo): the program links the system's GL as any VTK
// program does, and neither libcsm_headless nor libOSMesa. Run with --offscreen (and CSM_HEADLESS
// not "x"), it executes itself again, before main(), with libcsm_headless and libOSMesa in
// LD_PRELOAD: they then come first in the symbol lookup, as csm_link_osmesa_window's link order
// puts them (README, "Headless"), and vtkRenderWindow::New() makes the OSMesa window. The
// functions below find the preloaded library with dlsym; without it, VTK's own window.
#include "csmHeadless.h"

#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <cstdlib>
#include <cstring>
#include <string>

namespace
{
// Set while the program runs again with the library preloaded: the LD_PRELOAD it had before
// ("-" for none), restored at once so that the programs it starts do not inherit ours.
const char* const kSavedPreload = "CSM_HEADLESS_SAVED_LD_PRELOAD";

using UseFunction = int (*)(int);
using UsingFunction = int (*)();

UseFunction LoadedUse()
{
  return reinterpret_cast<UseFunction>(dlsym(RTLD_DEFAULT, "csmHeadlessUseOSMesa"));
}

UsingFunction LoadedUsing()
{
  return reinterpret_cast<UsingFunction>(dlsym(RTLD_DEFAULT, "csmHeadlessUsingOSMesa"));
}

bool Readable(const std::string& path)
{
  return !path.empty() && access(path.c_str(), R_OK) == 0;
}

/// libcsm_headless: beside the installed program (bin/../lib), else in the build tree.
std::string HeadlessLibrary()
{
  char exe[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof(exe) - 1);
  if (n > 0)
  {
    exe[n] = '\0';
    std::string dir(exe);
    dir.erase(dir.rfind('/') + 1);
    const std::string installed = dir + CSM_HEADLESS_LIBRARY_FROM_BIN;
    if (Readable(installed))
      return installed;
  }
  return Readable(CSM_HEADLESS_LIBRARY_BUILT) ? CSM_HEADLESS_LIBRARY_BUILT : std::string();
}

bool OSMesaTurnedOff()
{
  const char* choice = std::getenv("CSM_HEADLESS");
  return choice && (std::strcmp(choice, "x") == 0 || std::strcmp(choice, "glx") == 0);
}

// glibc calls an executable's constructors with main()'s arguments.
__attribute__((constructor)) void PreloadForOffscreen(int argc, char** argv, char**)
{
  if (const char* saved = std::getenv(kSavedPreload))
  {
    // Running again: give back the caller's LD_PRELOAD (the libraries are loaded now).
    if (std::strcmp(saved, "-") == 0)
      unsetenv("LD_PRELOAD");
    else
      setenv("LD_PRELOAD", saved, 1);
    unsetenv(kSavedPreload);
    return;
  }
  if (LoadedUse() || OSMesaTurnedOff() || argc < 2 || !argv)
    return;
  bool offscreen = false;
  for (int i = 1; i < argc && argv[i]; ++i)
    offscreen = offscreen || std::strcmp(argv[i], "--offscreen") == 0;
  const std::string library = offscreen ? HeadlessLibrary() : std::string();
  if (library.empty())
    return;
  const char* before = std::getenv("LD_PRELOAD");
  std::string preload = library + ":" + CSM_OSMESA_SONAME;
  if (before && *before)
    preload += std::string(":") + before;
  setenv(kSavedPreload, before && *before ? before : "-", 1);
  setenv("LD_PRELOAD", preload.c_str(), 1);
  execv("/proc/self/exe", argv);
  // Not executed again: go on with VTK's own window (it says when it needs a display).
  if (before)
    setenv("LD_PRELOAD", before, 1);
  else
    unsetenv("LD_PRELOAD");
  unsetenv(kSavedPreload);
}
}

namespace csmHeadless
{
bool Available()
{
  return LoadedUse() || (!HeadlessLibrary().empty());
}

bool UseOSMesa(bool use)
{
  UseFunction loaded = LoadedUse();
  return loaded ? loaded(use ? 1 : 0) != 0 : false;
}

bool UsingOSMesa()
{
  UsingFunction loaded = LoadedUsing();
  return loaded ? loaded() != 0 : false;
}
}
