// Beyond the paper — the run as one interactive page for teaching (spec/page.md PAGE-*): T and D
// (§2), the network of curves and the patches (§3), the checkerboard carried by φ, each patch in its
// domain triangle and the distortion per face (§4), D^j, f^j and the compressed surfaces (§5), the
// timings beside the paper's table and the oracle's verdict. One self-contained HTML file: the
// page's script (web/src, bundled at build time) and the run's data are embedded, so that it opens
// from file:// with no network and no server.
//
// What the page holds (PAGE-3): every array as little-endian typed data in base64 inside one JSON
// document, positions quantised to 16 bits over their own bounding box (2⁻¹⁶ of it: below a
// pixel at any zoom the page offers), the β of the checkerboard to 16 bits, ids and distortion
// figures exact (u32, f32). Everything but the timings is the same bytes on every run (PAGE-2).
#pragma once

#include <string>
#include <vector>

#include <fhr/core/trimesh.hpp>
#include <fhr/app/outputs.hpp>
#include <fhr/pipeline/pipeline.hpp>
#include <fhr/wavelet/analyse.hpp>

namespace fhr::app {

/// Whether this build holds the page's script (meson option `page`, which needs web/'s npm
/// packages: `./run` installs them). Without it write_page throws.
bool page_available();

/// T′ drawn as is up to this many faces by default; beyond, a display copy with at most that many (PAGE-9).
inline constexpr std::size_t page_display_faces = 2'000'000;

/// What the page shows beside the meshes.
struct PageContent {
    std::string title;         ///< the mesh's name
    std::string report_json;   ///< report.json's text (RunTexts::report)
    std::string timings_json;  ///< timings.json's text (RunTexts::timings): the only part that varies
    int up_axis = 1;           ///< 0, 1, 2: x, y or z up (fhr run --up)
    const wavelet::WaveletResult* wavelets = nullptr;  ///< §5, or null
    std::vector<RateStep> rate;                        ///< with §5: rate_steps
    std::size_t display_faces = page_display_faces;    ///< T′ drawn as is up to this many faces (≥ 1000)
};

/// Writes the page to `path` (`fhr run --html`: DIR/index.html), atomically.
/// \throws InvalidInput when !page_available() (naming how to build it), display_faces < 1000, or
///         the file cannot be written.
void write_page(const std::string& path, const TriMesh& T, const Parameterization& p, const PageContent& content);

}  // namespace fhr::app
