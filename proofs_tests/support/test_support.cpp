// Shared helpers of the test suites (see test_support.hpp).
#include "test_support.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fhr/io/read.hpp>

extern char** environ;

namespace fhr::test {
namespace fs = std::filesystem;

namespace {

struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() / ("fhr-test-" + std::to_string(::getpid()));
        fs::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

const fs::path& temp_dir() {
    static TempDir dir;
    return dir.path;
}

std::optional<std::string> existing(const fs::path& p) {
    if (fs::exists(p)) return p.string();
    return std::nullopt;
}

fs::path env_or(const char* var, const fs::path& fallback) {
    const char* v = std::getenv(var);
    return (v && *v) ? fs::path(v) : fallback;
}

const fs::path source_root() { return fs::path(FHR_SOURCE_ROOT); }

}  // namespace

TriMesh load_mesh(const std::string& path) { return io::read_mesh(path); }

std::string temp_path(std::string_view file_name) { return (temp_dir() / file_name).string(); }

std::string write_temp(std::string_view file_name, std::string_view bytes) {
    const std::string path = temp_path(file_name);
    std::ofstream f(path, std::ios::binary);
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!f) throw std::runtime_error("cannot write " + path);
    return path;
}

std::string read_file(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw std::runtime_error("cannot read " + path);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

std::string cgal_mesh(std::string_view name) {
    const fs::path folder = env_or("FHR_CGAL_MESHES", source_root() / "out/cgal-data/data/meshes");
    const std::optional<std::string> path = existing(folder / name);
    if (!path)
        throw std::runtime_error(std::string(name) + " is missing from " + folder.string() +
                                 ": ./run installs libcgal-demo and extracts its meshes there");
    return *path;
}

std::optional<std::string> shared_mesh(std::string_view name) {
    return existing(env_or("FHR_SHARED_MESHES", source_root().parent_path() / "shared/meshes") / name);
}

std::string peer_path(std::string_view name) { return (source_root() / "peers" / name).string(); }

RunResult run_fhr(const std::vector<std::string>& args) {
    const std::string out_path = temp_path("run.stdout"), err_path = temp_path("run.stderr");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> argv_s{FHR_EXE};
    argv_s.insert(argv_s.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    const auto start = std::chrono::steady_clock::now();
    pid_t pid = 0;
    if (posix_spawn(&pid, FHR_EXE, &actions, nullptr, argv.data(), environ) != 0)
        throw std::runtime_error("cannot start " FHR_EXE);
    posix_spawn_file_actions_destroy(&actions);
    int status = 0;
    ::waitpid(pid, &status, 0);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return {code, read_file(out_path), read_file(err_path), seconds};
}

}  // namespace fhr::test
