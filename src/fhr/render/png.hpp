// FHR §6 figures — PNG files (spec/render.md REN-1..3), written by Debian's libpng: RGB, 8 bits
// per channel, no interlace, zlib level 9, libpng's adaptive choice of filter per row. For a given
// libpng and zlib the bytes are a function of the pixels (REN-3); ./run installs Debian's, whose
// versions spec/render.md names with the reference figures they give.
#pragma once

#include <string>

#include <fhr/render/image.hpp>

namespace fhr::render {

/// The PNG file of `image` (REN-1, REN-2, REN-3).
/// \pre image.rgb.size() == 3·width·height.
/// \throws InvalidInput when width or height is < 1 or the buffer size is not 3·width·height.
std::string encode_png(const Image& image);

/// encode_png(image) written atomically to `path` (io::write_file_atomically).
/// \throws InvalidInput as encode_png, or "cannot write: …".
void write_png(const std::string& path, const Image& image);

}  // namespace fhr::render
