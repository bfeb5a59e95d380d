// FHR io — fuzz_replay: runs every committed crasher (fuzz/crashers/<reader>/) and seed
// (fuzz/corpus/<reader>/) through the fuzz harness, so that each fixed finding stays fixed in the
// ordinary build (meson test 'fuzz-replay'). Usage: fuzz_replay <fuzz source dir>.
#include <algorithm>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "harness.hpp"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: fuzz_replay <fuzz source dir>\n";
        return 2;
    }
    const std::pair<const char*, fhr::io::Format> readers[] = {{"off", fhr::io::Format::off},
                                                               {"obj", fhr::io::Format::obj},
                                                               {"ply", fhr::io::Format::ply},
                                                               {"stl", fhr::io::Format::stl}};
    int runs = 0, failures = 0;
    for (const auto& [reader, format] : readers) {
        for (const char* kind : {"crashers", "corpus"}) {
            const fs::path dir = fs::path(argv[1]) / kind / reader;
            if (!fs::is_directory(dir)) continue;
            std::vector<fs::path> files;
            for (const auto& entry : fs::directory_iterator(dir))
                if (entry.is_regular_file()) files.push_back(entry.path());
            std::sort(files.begin(), files.end());
            for (const fs::path& file : files) {
                // printed first, so that a trap (a broken postcondition) still names its input
                std::cerr << "replay " << file.string() << '\n';
                std::ifstream in(file, std::ios::binary);
                const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
                ++runs;
                try {
                    fhr::fuzz::run_one(format, reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
                } catch (const std::exception& e) {
                    std::cerr << "FAILED " << file.string() << ": unexpected exception: " << e.what() << '\n';
                    ++failures;
                }
            }
        }
    }
    std::cout << runs << " inputs replayed, " << failures << " failed\n";
    if (runs == 0) std::cerr << "no inputs under " << argv[1] << "/{crashers,corpus}/<reader>/\n";
    return failures == 0 && runs > 0 ? 0 : 1;
}
