// FHR io — atomic output files: no partial output is ever left behind (DEVELOPERS.md standards).
#pragma once

#include <string>
#include <string_view>

namespace fhr::io {

/// Writes `bytes` to `path.tmp-<pid>` and renames it onto `path`. On any failure the temporary
/// is removed and InvalidInput(path, 0, "cannot write: <reason>") is thrown.
void write_file_atomically(const std::string& path, std::string_view bytes);

}  // namespace fhr::io
