// FHR bench — reading + validating a mesh, the first stage every run pays.
// Usage: bench_io MESH [RUNS]. Prints the median and minimum wall time of read_soup +
// build_trimesh over RUNS runs (default 7), and the peak memory the first load added, per
// triangle. Goals: horse ≤ 60 ms, ≤ 300 bytes per triangle.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/io/read.hpp>

namespace {

// The peak resident size of this process image: VmHWM of /proc/self/status. Not getrusage's
// ru_maxrss, which Linux carries across execve, so that a child of a large parent (the Python
// bench driver) starts with the parent's peak and a load's growth is hidden below it.
long peak_rss_bytes() {
    std::FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return 0;
    char line[256];
    long kib = 0;
    while (std::fgets(line, sizeof line, f))
        if (std::sscanf(line, "VmHWM: %ld kB", &kib) == 1) break;
    std::fclose(f);
    return kib * 1024L;
}

std::size_t load(const std::string& path) { return fhr::io::read_mesh(path).n_faces(); }

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_io MESH [RUNS]\n");
        return 2;
    }
    const std::string path = argv[1];
    const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 7;
    try {
        const long before = peak_rss_bytes();
        const std::size_t faces = load(path);
        const long added = peak_rss_bytes() - before;
        std::vector<double> ms;
        for (int i = 0; i < runs; ++i) {
            const auto t0 = std::chrono::steady_clock::now();
            load(path);
            ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        }
        std::sort(ms.begin(), ms.end());
        std::printf("%-24s %9zu faces  read+validate median %8.2f ms  min %8.2f ms  peak +%6.1f MB (%.0f B/face)\n",
                    path.substr(path.find_last_of('/') + 1).c_str(), faces, ms[ms.size() / 2], ms.front(), added / 1e6,
                    static_cast<double>(added) / static_cast<double>(faces));
        return 0;
    } catch (const fhr::Error& e) {
        std::fprintf(stderr, "fhr: error: %s\n", e.what());
        return 2;  // a bad input file or option
    }
}
