// SPDX-License-Identifier: BSD-3-Clause
// csm-bench --changes: data that changes while the camera stays (csmChanges.cxx).
#pragma once

#include <string>

namespace csmChanges
{
/// Runs the mode (argv as csm-bench got it, --changes among it); returns the exit code.
int Run(int argc, char** argv, const std::string& engineModel);

/// The mode's help text.
std::string Usage();
} // namespace csmChanges
