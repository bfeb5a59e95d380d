// examples/verify.cpp — fhr as an oracle for another implementation (spec/param.md, spec/library.md
// LIB-3): read a parameterization that some program wrote as a `fhr-param 1` file, check it against
// the invariants PARAM-2..11 with the surface T it claims to parameterize, and print the verdict.
//
// Build against an installed fhr:  c++ -std=c++20 verify.cpp $(pkg-config --cflags --libs fhr)
// Usage: verify PARAM.fhrp MESH
// Prints "valid", or "INVALID <check id>: <its first failure>"; exit 0 valid, 1 invalid, 2 unreadable.
#include <cstdio>

#include <fhr/fhr.hpp>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: verify PARAM.fhrp MESH\n");
        return 2;
    }
    try {
        const fhr::exchange::ParamFile file = fhr::exchange::read_param(argv[1]);
        const fhr::TriMesh T = fhr::io::read_mesh(argv[2]);
        const fhr::exchange::VerifyReport report = fhr::exchange::verify(file, &T);
        if (const fhr::exchange::CheckResult* failed = report.first_failure()) {
            std::printf("INVALID %s: %s\n", failed->id.c_str(), failed->first_failure.c_str());
            return 1;
        }
        std::printf("valid\n");
        return 0;
    } catch (const fhr::InvalidInput& e) {  // the file or the mesh cannot be read
        std::fprintf(stderr, "verify: %s\n", e.what());
        return 2;
    }
}
