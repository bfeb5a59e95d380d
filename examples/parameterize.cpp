// examples/parameterize.cpp — the paper's method from a program (spec/library.md LIB-3): read a
// closed mesh T, decimate it to a domain D of the given size (§2), map T onto D (§3, §4, every
// patch certified and the result judged by the independent oracle), and print, for each vertex v
// of T, the face of D and the barycentric coordinates of ψ(v) in that face's corner order.
//
// Build against an installed fhr:  c++ -std=c++20 parameterize.cpp $(pkg-config --cflags --libs fhr)
// Usage: parameterize MESH FACES > params.txt   (lines "v d β0 β1 β2"; a vertex of T on a patch
// boundary lies in several domain faces: the one printed is that of the first face of T′ around it)
// Exit: 0 certified, 1 not certified, 2 bad input, 3 the partition failed, 4 a numerical failure,
// 70 an internal error.
#include <cstdint>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fhr/fhr.hpp>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: parameterize MESH FACES\n");
        return 2;
    }
    try {
        const fhr::TriMesh T = fhr::io::read_mesh(argv[1]);
        fhr::pipeline::RunOptions options;
        options.faces = std::stoul(argv[2]);
        options.method.relax = false;  // the paper's §4 map, as the reference outputs hold it (fhr run --map paper)
        const fhr::pipeline::RunResult result = fhr::pipeline::run(T, options);
        if (!result.certified()) {
            const fhr::exchange::CheckResult* failed = result.oracle.first_failure();
            std::fprintf(stderr, "parameterize: not certified%s%s\n", failed ? ": " : "",
                         failed ? failed->first_failure.c_str() : "");
            return 1;
        }
        // T′ keeps T's vertices under their own numbers, before the points the paths added.
        const fhr::pipeline::Parameterization& p = result.parameterization;
        std::vector<std::optional<std::pair<std::uint32_t, fhr::exchange::Beta>>> at(T.n_vertices());
        for (fhr::RefinedFaceId f : p.face_patch.ids())  // the faces of the final T′, in the file's order
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t v = p.refined_faces[f.idx()][k];
                if (v < at.size() && !at[v]) at[v] = {p.face_patch[f].idx(), p.face_beta[f][k]};
            }
        for (std::size_t v = 0; v < at.size(); ++v)
            std::printf("%zu %u %.17g %.17g %.17g\n", v, at[v]->first, at[v]->second[0], at[v]->second[1],
                        at[v]->second[2]);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "parameterize: %s\n", e.what());
        // The library's error kinds (spec/library.md LIB-2), mapped as the `fhr` command maps them.
        if (dynamic_cast<const fhr::InvalidInput*>(&e)) return 2;
        if (dynamic_cast<const fhr::PartitionFailure*>(&e)) return 3;
        if (dynamic_cast<const fhr::NumericalFailure*>(&e)) return 4;
        return 70;
    }
}
