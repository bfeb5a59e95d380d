// <fhr/version.hpp> — the version of the fhr library these headers belong to (spec/library.md
// LIB-5). meson.build refuses to configure when it differs from the project's version.
#pragma once

#include <string_view>

#define FHR_VERSION_MAJOR 0
#define FHR_VERSION_MINOR 1
#define FHR_VERSION_PATCH 0

namespace fhr {

/// "major.minor.patch" of the headers in use.
inline constexpr std::string_view version = "0.1.0";

}  // namespace fhr
