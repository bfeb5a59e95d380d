// FHR core — the polygon soup: what a reader hands to the mesh builder.
//
// Readers (src/fhr/io) check syntax only: numbers parse, coordinates are finite, indices are in range,
// counts fit the file. Everything topological (repeated vertices in a face, duplicate faces,
// non-manifold edges/vertices, orientation, boundary, components) is checked by build_trimesh()
// (src/fhr/core/build.hpp) against spec/mesh.md, so that every format gets the same rules.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products on Vec3

namespace fhr {

using Vec3 = Eigen::Vector3d;

/// INV-IN-1 / FMT-NUM: the largest accepted coordinate magnitude. Squared lengths of differences,
/// (2·1e150)² · 3 ≈ 1.2e301, stay below DBL_MAX ≈ 1.8e308, so no length, area or determinant of the
/// pipeline overflows.
inline constexpr double max_coordinate = 1e150;

/// Texture coordinates of a UV atlas (spec/atlas.md ATLAS-1). A reader fills them only when asked
/// (parse_obj / parse_ply with `texture`); a mesh read as the input T leaves them empty.
struct SoupTexture {
    static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::array<double, 2>> uv;       ///< the coordinate records (OBJ `vt`; PLY per vertex or per corner)
    std::vector<std::uint32_t> corner_uv;        ///< per entry of PolygonSoup::indices: its record in uv, or none
    std::vector<std::uint32_t> polygon_texture;  ///< per polygon: its texture (OBJ `usemtl` group, PLY `texnumber`)
    std::vector<std::string> texture_names;      ///< OBJ: the `usemtl` name of each texture number ("" before any)
    /// The largest rounding of a coordinate x, y, z as the file wrote it: half a unit in the last
    /// printed digit (text), half an ulp of the stored type (binary PLY).
    double rounding = 0;
};

/// Polygons in compressed-row form: polygon p has the 0-based point indices
/// `indices[offsets[p] .. offsets[p+1])`. offsets.size() == polygon count + 1.
struct PolygonSoup {
    std::string source;                     ///< file name for messages ("" if in memory)
    std::vector<Vec3> points;               ///< #P, all finite
    std::vector<std::uint32_t> offsets{0};  ///< #F+1
    std::vector<std::uint32_t> indices;     ///< each < points.size()
    /// 1-based source line of each point / polygon in a text file; empty for binary files
    /// (messages then name the element by index only).
    std::vector<std::uint64_t> point_line;
    std::vector<std::uint64_t> polygon_line;
    SoupTexture texture;  ///< empty unless the reader was asked for texture coordinates

    std::size_t polygon_count() const { return offsets.size() - 1; }
    std::uint32_t polygon_size(std::size_t p) const { return offsets[p + 1] - offsets[p]; }
    const std::uint32_t* polygon(std::size_t p) const { return indices.data() + offsets[p]; }
    void add_polygon(const std::uint32_t* first, std::uint32_t count) {
        indices.insert(indices.end(), first, first + count);
        offsets.push_back(static_cast<std::uint32_t>(indices.size()));
    }
};

}  // namespace fhr
