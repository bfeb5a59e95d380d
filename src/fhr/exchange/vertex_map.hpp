// FHR exchange — the oracle for per-vertex maps onto a base mesh (spec/vertex_map.md VMAP-*): for
// every vertex of a mesh T a point of a mesh D, a face and barycentric weights, as MAPS, MeshLab's
// iso-parameterization, successive self-parameterization and correspondence tools write them.
// Beyond the paper, whose map is given on a refinement T′ (spec/param.md): here only the vertices
// are given, and a stated rule (`adjacent`: straight in the unfolded faces around a vertex of D)
// maps T's edges and faces. The map is judged a homeomorphism when its 1-skeleton embeds in D
// with T's rotation at every vertex, ∂T on ∂D and the topologies equal (paper_notes/vertex_map.md),
// decided exactly on the numbers read.
//
// Independence: like verify.hpp, this uses only src/fhr/core and the oracle's own parts; it shares
// no code with the maps it judges.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fhr/core/polygon_soup.hpp>
#include <fhr/exchange/distortion.hpp>
#include <fhr/exchange/verify.hpp>

namespace fhr::exchange {

/// The file formats of spec/vertex_map.md "Reading".
enum class VertexMapFormat { plain, corr, vtpm, ijv };

/// "plain", "corr", "vtpm", "ijv".
const char* to_string(VertexMapFormat format);
/// The format named `name` (as to_string writes it), or nullopt.
std::optional<VertexMapFormat> vertex_map_format_named(std::string_view name);
/// The format of a file by its extension (.vmap, .corr, .vtpm, .ijv), or nullopt.
std::optional<VertexMapFormat> vertex_map_format_of(std::string_view path);

/// One vertex's record as written, before VMAP-2 resolves it against D.
struct VertexImageRecord {
    enum class Ref : std::uint8_t {
        none,      ///< the file gives no image (`-1`)
        face,      ///< `a` is a face of D; weights of its corners in its order (plain, corr)
        halfedge,  ///< the face left of the halfedge a → b of D; weights of (a, b, third) (vtpm)
        vertices,  ///< corners[k] vertices of D (−1 unused) with weights[k] (ijv)
    };
    Ref ref = Ref::none;
    std::int64_t a = -1, b = -1;
    std::array<std::int64_t, 3> corners{-1, -1, -1};
    std::array<double, 3> weights{};
    std::uint64_t line = 0;  ///< 1-based line of the record (the first line for ijv)
};

/// A per-vertex map as read: one record per vertex of T.
struct VertexMapFile {
    std::string source;  ///< the file name, for messages
    VertexMapFormat format = VertexMapFormat::plain;
    std::vector<VertexImageRecord> records;
};

/// Parses a map of a mesh T with `t_vertices` vertices onto a mesh D with `d_vertices` vertices
/// (VMAP-1). \throws InvalidInput naming the file, line and vertex.
VertexMapFile parse_vertex_map(std::string_view bytes, const std::string& name, VertexMapFormat format,
                               std::size_t t_vertices, std::size_t d_vertices);
/// Reads a file; the format by `format`, else by the extension. \throws InvalidInput (also when
/// neither names a format).
VertexMapFile read_vertex_map(const std::string& path, std::optional<VertexMapFormat> format, std::size_t t_vertices,
                              std::size_t d_vertices);

/// The rule that extends the map from vertices to edges and faces (spec/vertex_map.md).
enum class VertexMapRule { adjacent };

struct VertexMapReport {
    std::vector<CheckResult> checks;  ///< VMAP-2 … VMAP-9
    bool valid() const;
    const CheckResult* first_failure() const;

    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges_without_image;  ///< VMAP-5, (u < v), ascending
    std::uint64_t crossing_pairs = 0;                                          ///< VMAP-6's failures
    std::vector<std::uint32_t> folded;                                         ///< VMAP-7, ascending
    Distortion distortion;  ///< in D's metric (spec/vertex_map.md "Figures"); empty unless VMAP-5 holds
};

/// Judges `map` of T onto D under `rule` by VMAP-2..9. T and D are given as read (their numbering
/// is the files'); VMAP-3 builds them. Never throws InvalidInput: a broken map gives failed checks.
/// Cost: spec/vertex_map.md "Cost".
VertexMapReport verify_vertex_map(const VertexMapFile& map, const PolygonSoup& T, const PolygonSoup& D,
                                  VertexMapRule rule = VertexMapRule::adjacent);

}  // namespace fhr::exchange
