// Shared helpers of the test suites: temporary files, the real meshes, running the fhr command.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fhr/core/trimesh.hpp>

namespace fhr::test {

/// Reads and validates a mesh file with the strict reader and builder (default options).
TriMesh load_mesh(const std::string& path);

/// A fresh path inside this process's temporary directory (removed at exit).
std::string temp_path(std::string_view file_name);

/// Writes `bytes` to temp_path(file_name) and returns the path.
std::string write_temp(std::string_view file_name, std::string_view bytes);

/// Reads a whole file (throws std::runtime_error if it cannot).
std::string read_file(const std::string& path);

/// Path of a mesh from libcgal-demo's data/meshes (extracted by ./run into out/cgal-data, or the
/// folder named by $FHR_CGAL_MESHES). libcgal-demo is a Debian package that ./run installs and
/// extracts: a missing mesh is a broken set-up, never a case to skip.
/// \throws std::runtime_error naming the mesh, where it was looked for and what provides it.
std::string cgal_mesh(std::string_view name);

/// Path of an optional mesh, not distributed, in ../shared/meshes (or $FHR_SHARED_MESHES), or nullopt.
std::optional<std::string> shared_mesh(std::string_view name);

/// How a test case that needs an optional mesh of ../shared/meshes says it ran nothing: its warning
/// starts with this, and run_suites.py counts the case as skipped, never as passed.
inline constexpr const char* optional_data_absent = "optional data absent: ";

/// The path of shared_mesh(name), or — when it is absent — a skip: the warning above, and the test
/// case returns. For use in a Catch2 TEST_CASE's body.
#define FHR_SHARED_MESH_OR_SKIP(path, name)                                                          \
    const std::optional<std::string> path##_found = fhr::test::shared_mesh(name);                    \
    if (!path##_found) {                                                                             \
        WARN(std::string(fhr::test::optional_data_absent) + (name) + " is not in ../shared/meshes"); \
        return;                                                                                      \
    }                                                                                                \
    const std::string& path = *path##_found

/// A program of peers/ (the adapters of other programs, and fhr's own: peers/fhr-param).
std::string peer_path(std::string_view name);

struct RunResult {
    int exit_code;    ///< the process's exit status, or 128+signal when it was killed
    std::string out;  ///< everything it wrote to stdout
    std::string err;  ///< everything it wrote to stderr
    double seconds;   ///< wall-clock time
};

/// Runs the built `fhr` executable with `args` (no shell involved) and collects its output.
RunResult run_fhr(const std::vector<std::string>& args);

}  // namespace fhr::test
