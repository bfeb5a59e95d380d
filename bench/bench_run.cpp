// FHR bench — the whole method called from C++ (pipeline::run: §2 decimation, §3, §4, the oracle;
// no §5), the reference for the Python package's fhr.parameterize (bench/bench_python.py; the
// goal: within 10 %). The mesh is read and validated once, outside the timing.
// Usage: bench_run MESH FACES RUNS. Prints the median and minimum wall time of RUNS calls.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/io/read.hpp>
#include <fhr/pipeline/run.hpp>

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: bench_run MESH FACES RUNS\n");
        return 2;
    }
    try {
        const fhr::TriMesh T = fhr::io::read_mesh(argv[1]);
        fhr::pipeline::RunOptions options;
        options.faces = std::stoul(argv[2]);
        std::vector<double> ms;
        bool certified = true;
        for (int r = std::stoi(argv[3]); r > 0; --r) {
            const auto start = std::chrono::steady_clock::now();
            certified = fhr::pipeline::run(T, options).certified() && certified;
            ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        }
        std::sort(ms.begin(), ms.end());
        std::printf("pipeline::run median %.1f ms, min %.1f ms (%zu runs, %s)\n", ms[ms.size() / 2], ms.front(),
                    ms.size(), certified ? "certified" : "NOT certified");
        return certified ? 0 : 1;
    } catch (const fhr::Error& e) {
        std::fprintf(stderr, "bench_run: %s\n", e.what());
        return 2;
    }
}
