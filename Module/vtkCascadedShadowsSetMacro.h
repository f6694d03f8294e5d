// SPDX-License-Identifier: BSD-3-Clause
/**
 * vtkSetFiniteClampMacro: vtkSetClampMacro for floating-point options that refuses values that
 * are not finite. vtkSetClampMacro lets NaN through (every comparison with NaN is false); here
 * NaN and infinity get one error message and the option keeps its value.
 */
#ifndef vtkCascadedShadowsSetMacro_h
#define vtkCascadedShadowsSetMacro_h

#include "vtkSetGet.h"

#include <cmath> // for std::isfinite

#define vtkSetFiniteClampMacro(name, type, min, max)                                               \
  virtual void Set##name(type _arg)                                                                \
  {                                                                                                \
    if (!std::isfinite(_arg))                                                                      \
    {                                                                                              \
      vtkErrorMacro(<< "Set" #name "(" << _arg << "): not a finite number; keeping "               \
                    << this->name);                                                                \
      return;                                                                                      \
    }                                                                                              \
    const type _clamped = _arg < (min) ? (min) : (_arg > (max) ? (max) : _arg);                    \
    if (this->name != _clamped)                                                                    \
    {                                                                                              \
      this->name = _clamped;                                                                       \
      this->Modified();                                                                            \
    }                                                                                              \
  }

/// GetLastFrame<name>(): one field of the last frame's statistics (this->Statistics), for
/// Python, which cannot read the struct.
#define vtkCascadedShadowsStatisticMacro(name, type)                                               \
  virtual type GetLastFrame##name() const                                                          \
  {                                                                                                \
    return this->Statistics.name;                                                                  \
  }

#endif
