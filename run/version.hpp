#pragma once

#include "run/commit.hpp"  // kCommit, generated at build time by run/commit.cmake

namespace granjet {
// From the CMake project version, so there is one place to bump it.
inline constexpr const char* kVersion = GRANJET_VERSION;
}  // namespace granjet
