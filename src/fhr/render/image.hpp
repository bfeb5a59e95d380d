// FHR §6 figures — the RGB8 raster image that the rasterizer (raster.hpp) produces and the PNG
// writer (png.hpp) encodes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fhr::render {

/// An 8-bit sRGB colour.
struct Rgb8 {
    std::uint8_t r = 0, g = 0, b = 0;
    friend bool operator==(const Rgb8&, const Rgb8&) = default;
};

/// width × height pixels, rows top to bottom, each pixel 3 bytes r, g, b.
struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;  ///< 3·width·height bytes

    Image() = default;
    /// \pre width ≥ 0, height ≥ 0 (checked by the writers, not here).
    Image(int w, int h, Rgb8 fill) : width(w), height(h), rgb(3 * std::size_t(w) * std::size_t(h)) {
        for (std::size_t i = 0; i < rgb.size(); i += 3) {
            rgb[i] = fill.r;
            rgb[i + 1] = fill.g;
            rgb[i + 2] = fill.b;
        }
    }
    Rgb8 at(int x, int y) const {
        const std::size_t i = 3 * (std::size_t(y) * std::size_t(width) + std::size_t(x));
        return {rgb[i], rgb[i + 1], rgb[i + 2]};
    }
    void set(int x, int y, Rgb8 c) {
        const std::size_t i = 3 * (std::size_t(y) * std::size_t(width) + std::size_t(x));
        rgb[i] = c.r;
        rgb[i + 1] = c.g;
        rgb[i + 2] = c.b;
    }
};

}  // namespace fhr::render
