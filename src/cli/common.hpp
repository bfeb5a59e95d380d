// FHR cli — what every subcommand shares: argument parsing, loading a mesh through the strict
// readers and builder (spec/mesh.md), and writing a mesh by its file extension.
#pragma once

#include <exception>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <fhr/core/build.hpp>
#include <fhr/core/trimesh.hpp>

namespace fhr::cli {

/// `fhr CMD positional... --flag --key value`. Unknown options are usage errors (exit 2).
class Args {
public:
    /// \param flags   options without a value (e.g. "json")
    /// \param valued  options that take one value (e.g. "faces")
    Args(const std::vector<std::string>& argv, const std::vector<std::string>& flags,
         const std::vector<std::string>& valued);
    const std::vector<std::string>& positional() const { return positional_; }
    /// The single positional argument `what` (e.g. "MESH"); a usage error when there is not exactly one.
    const std::string& single_positional(const std::string& what) const;
    bool flag(const std::string& name) const { return flags_.count(name) != 0; }
    std::optional<std::string> get(const std::string& name) const;
    const std::string& require(const std::string& name) const;
    long long integer(const std::string& name, long long fallback, long long min, long long max) const;
    double real(const std::string& name, double fallback, double min, double max) const;

private:
    std::vector<std::string> positional_;
    std::map<std::string, bool> flags_;
    std::map<std::string, std::string> values_;
};

/// A usage error: InvalidInput without a file (exit code 2).
[[noreturn]] void usage_error(const std::string& what);

/// spec/cli.md's exit code for an exception the library threw (LIB-2): 2 InvalidInput, 3
/// PartitionFailure, 4 NumericalFailure, 70 InternalError or anything else (a bug).
int exit_code_of(const std::exception& e);

/// Prints `fhr: warning: <line>` for each warning of a build.
void print_warnings(const BuildLog& log);

/// Reads and validates a mesh (read_soup + build_trimesh); warnings go to stderr.
TriMesh load_mesh(const std::string& path, const BuildOptions& options);

/// Writes a mesh in the format of the path's extension (.off, .obj, .ply), atomically.
void save_mesh(const std::string& path, const TriMesh& mesh);

int run_info(const std::vector<std::string>& args);
int run_generate(const std::vector<std::string>& args);
int run_convert(const std::vector<std::string>& args);
int run_decimate(const std::vector<std::string>& args);
int run_attach(const std::vector<std::string>& args);
int run_geodesic(const std::vector<std::string>& args);

}  // namespace fhr::cli
