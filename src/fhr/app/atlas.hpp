// Beyond the paper — textured.obj's atlas: the patches laid out in [0, 1]² for texturing, one chart
// per patch S_i, in the true shape of its domain triangle T_i (so each face keeps in UV the
// anisotropy σ₁/σ₂ it has in param.fhrp), each chart scaled to its patch's surface area (equal
// texel density), rotated but never mirrored, packed with a gutter between charts.
//
// Pseudocode:
//   for each patch i: T_i laid flat (its longest side along u, the apex above it), scaled by
//       s_i = sqrt(area of S_i on the surface / area of T_i), so that every chart has the same
//       texel density sqrt(UV area / surface area);
//       F_i <- T_i grown about its incentre until each side has moved out by r (F_i contains T_i's
//       r-neighbourhood: charts whose F_i do not overlap are at least 2r apart)
//   pack the F_i in shelves, tallest first: within a shelf they alternate upright (base on the
//       shelf's floor) and turned by 180° (base on its ceiling, nested between the upright ones),
//       each slid left until it touches a chart already placed (at the heights where they meet)
//   try several shelf widths, keep the layout whose bounding square is smallest; scale it into
//       [0, 1]²; r is chosen so that the gutter 2r is at least `gutter_texels` texels of a
//       `texture_size`² texture (repacked with a larger r until it is)
// Decisions and their measurements: paper_notes/atlas.md, "fhr's own atlas".
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <fhr/exchange/fhr_param.hpp>
#include <fhr/io/write.hpp>

namespace fhr::app {

struct AtlasOptions {
    double texture_size = 2048;  ///< texels along each side of the texture the gutter is measured in
    double gutter_texels = 2;    ///< the least distance between two charts, in texels
};

/// The layout of textured.obj: for each patch, where its domain triangle's corners go in [0, 1]².
class ChartAtlas {
public:
    /// \pre file holds a parameterization whose patches each have a face (fhr run's param.fhrp).
    explicit ChartAtlas(const exchange::ParamFile& file, const AtlasOptions& options = {});
    /// The texture coordinate of corner c (3f + k) of face f of T′: its β in its patch's chart.
    io::Vec2 operator()(std::size_t c) const;
    /// Corner k of patch d's chart (corner k of domain face d), counter-clockwise like the face.
    const std::array<io::Vec2, 3>& chart(std::size_t d) const { return chart_[d]; }
    /// The least distance between two charts that the layout guarantees, in [0, 1]² units.
    double gutter() const { return gutter_; }

private:
    const exchange::ParamFile& file_;
    std::vector<std::array<io::Vec2, 3>> chart_;
    double gutter_ = 0;
};

}  // namespace fhr::app
