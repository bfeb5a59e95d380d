// FHR exchange — the oracle for UV atlases (spec/atlas.md ATLAS-*): a triangle mesh whose every
// face corner carries texture coordinates, as MeshLab, CGAL's Surface_mesh_parameterization, UV
// unwrappers and fhr's own textured.obj write it. Beyond the paper, whose map goes to a domain D
// rather than the plane: an atlas is judged by what makes it usable — every chart one-to-one, no
// two pieces of texture on top of each other, no crack — with exact predicates, and measured by
// the distortion figures of spec/distortion.md.
//
// Independence: like verify.hpp, this uses only src/fhr/core, src/fhr/io's readers and the oracle's
// own parts; it shares no code with the maps it judges.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fhr/core/polygon_soup.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/exchange/distortion.hpp>
#include <fhr/exchange/verify.hpp>

namespace fhr::exchange {

using UV = std::array<double, 2>;

/// An atlas as read (ATLAS-1): triangles over the file's points, each corner with a UV record.
struct Atlas {
    std::string source;                       ///< the file name, for messages
    std::vector<Vec3> points;                 ///< as in the file, before welding
    std::vector<Triangle> faces;              ///< into points
    std::vector<UV> uv;                       ///< texture coordinate records
    std::vector<Triangle> face_uv;            ///< per face, per corner: its record in uv
    std::vector<std::uint32_t> face_texture;  ///< per face: its texture (0 when the file has one)
    std::vector<std::string> texture_names;   ///< by texture number (OBJ `usemtl`; may be empty)
    double rounding = 0;                      ///< ATLAS-8's ρ: the coordinates' largest rounding as written
};

/// ATLAS-1 on a polygon soup read with texture coordinates (io::parse_obj / parse_ply with
/// `texture`): every face a triangle, every corner with a record.
/// \throws InvalidInput naming the file, line and face.
Atlas atlas_from_soup(PolygonSoup soup);

/// Reads an atlas: a PLY file when it starts with the `ply` magic, OBJ otherwise.
/// \throws InvalidInput (unreadable, or breaking ATLAS-1).
Atlas read_atlas(const std::string& path);
Atlas parse_atlas(std::string_view bytes, const std::string& name);

struct AtlasOptions {
    bool no_mirror = false;  ///< a mirrored chart fails ATLAS-4
    bool strict = false;     ///< a contact fails ATLAS-7
};

/// The verdict on an atlas, and its figures (spec/atlas.md "Figures").
struct AtlasReport {
    std::vector<CheckResult> checks;  ///< ATLAS-1 .. ATLAS-7, and ATLAS-8 with an input mesh
    bool valid() const;
    const CheckResult* first_failure() const;

    std::uint64_t vertices = 0;  ///< welded surface vertices
    std::uint64_t charts = 0, mirrored_charts = 0, textures = 0;
    std::vector<std::uint32_t> folded;                                 ///< ATLAS-4, ascending
    std::vector<std::pair<std::uint32_t, std::uint32_t>> overlapping;  ///< ATLAS-6, (f < g), ascending
    std::vector<std::pair<std::uint32_t, std::uint32_t>> contacts;     ///< ATLAS-7, (f < g), ascending
    std::optional<double> seam_length, packing_unit_square, packing_bounding_square;
    Distortion distortion;
};

/// Judges `atlas` by ATLAS-2..7 and, with `input_mesh`, ATLAS-8; a check that another relies on
/// failing skips it. Never throws for any atlas: a broken one gives failed checks.
/// \pre input_mesh, when given, is a valid mesh (build_trimesh). Cost: spec/atlas.md "Cost".
AtlasReport verify_atlas(const Atlas& atlas, const TriMesh* input_mesh, const AtlasOptions& options = {},
                         Executor* executor = nullptr);

}  // namespace fhr::exchange
