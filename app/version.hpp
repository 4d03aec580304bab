#pragma once

namespace granjet {
// From the CMake project version, so there is one place to bump it.
inline constexpr const char* kVersion = GRANJET_VERSION;
}  // namespace granjet
