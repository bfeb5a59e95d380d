// FHR §6 figures — a self-contained PNG encoder (no libpng, no zlib): spec/render.md REN-1..3.
//
// PNG (ISO/IEC 15948, W3C PNG 2nd ed.) = 8-byte signature, then chunks `length | type | data |
// CRC-32(type + data)`: IHDR (width, height, bit depth 8, colour type 2 = RGB, compression 0,
// filter 0, interlace 0), IDAT chunks (at most 1 MiB each) whose concatenation is the zlib
// stream (RFC 1950) of the filtered scanlines, IEND. Each scanline is one filter-type byte then 3·width bytes; the filter of each row is the
// one of the five (None, Sub, Up, Average, Paeth) with the least sum of |signed bytes| (the
// heuristic the PNG specification recommends, §12.8). The zlib stream holds one DEFLATE block
// (RFC 1951) with the fixed Huffman codes and greedy LZ77 matches found through hash chains.
// Everything is integer arithmetic in a fixed order, so the bytes are a function of the pixels.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include <fhr/render/image.hpp>

namespace fhr::render {

/// CRC-32 of ISO 3309 / ITU-T V.42 (reflected polynomial 0xEDB88320), as PNG chunks use it.
/// crc32("123456789") = 0xCBF43926.
std::uint32_t crc32(std::span<const std::uint8_t> bytes);

/// Adler-32 of RFC 1950 §8.2. adler32("Wikipedia") = 0x11E60398.
std::uint32_t adler32(std::span<const std::uint8_t> bytes);

/// The zlib stream (RFC 1950: header 0x78 0x01, one fixed-Huffman DEFLATE block, Adler-32)
/// of `bytes`; any inflater (zlib's among them) gives back exactly `bytes` (REN-2).
std::string zlib_compress(std::span<const std::uint8_t> bytes);

/// The PNG file of `image` (REN-1, REN-2, REN-3).
/// \pre image.rgb.size() == 3·width·height.
/// \throws InvalidInput when width or height is < 1 or the buffer size is not 3·width·height.
std::string encode_png(const Image& image);

/// encode_png(image) written atomically to `path` (io::write_file_atomically).
/// \throws InvalidInput as encode_png, or "cannot write: …".
void write_png(const std::string& path, const Image& image);

}  // namespace fhr::render
