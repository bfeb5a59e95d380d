// FHR exchange — libFuzzer target for the per-vertex map readers (spec/vertex_map.md VMAP-1: plain,
// corr, vtpm, ijv; the first byte chooses) and the oracle behind them (VMAP-2..9), mapping a
// regular octahedron T onto itself as D: the reader must refuse any malformed bytes with
// InvalidInput, and whatever it accepts the oracle must judge without throwing or crashing, its
// lists consistent with its counts. Seeds: fuzz/corpus/vertex_map/ (a digit 0-3, then the file).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include <fhr/core/errors.hpp>
#include <fhr/exchange/vertex_map.hpp>

namespace {

fhr::PolygonSoup octahedron() {
    fhr::PolygonSoup s;
    s.points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const std::uint32_t faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                       {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (const auto& f : faces) s.add_polygon(f, 3);
    return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    static const fhr::PolygonSoup mesh = octahedron();
    const auto format = static_cast<fhr::exchange::VertexMapFormat>(data[0] % 4);
    const std::string_view bytes(reinterpret_cast<const char*>(data + 1), size - 1);
    try {
        const fhr::exchange::VertexMapFile map = fhr::exchange::parse_vertex_map(bytes, "fuzz", format, 6, 6);
        const fhr::exchange::VertexMapReport report = fhr::exchange::verify_vertex_map(map, mesh, mesh);
        // VMAP-2..9, one result each; VMAP-5's failures are the edges without an image.
        if (report.checks.size() != 8) __builtin_trap();
        if (report.checks[3].status == fhr::exchange::CheckStatus::fail &&
            report.checks[3].failures != report.edges_without_image.size())
            __builtin_trap();
        if (report.checks[5].status == fhr::exchange::CheckStatus::fail &&
            report.checks[5].failures != report.folded.size())
            __builtin_trap();
    } catch (const fhr::InvalidInput&) {
        // the expected refusal
    }
    return 0;
}
