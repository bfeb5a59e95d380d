// FHR §6 figures — the PNG writer (spec/render.md REN-1..3): its files read back by an independent
// reader (png_reader.hpp, whose CRC-32 and Adler-32 are checked against published vectors here),
// their zlib stream inflated by that reader and by Python's zlib module; structure and pixels,
// determinism, atomic writes and refusals.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/render/png.hpp>
#include "render/png_reader.hpp"
#include "support/test_support.hpp"

using namespace fhr;
using namespace fhr::render;
namespace fs = std::filesystem;

namespace {

// Inflates `stream` with zlib (Python's zlib module) and returns what it gave.
std::string inflate_with_zlib(const std::string& stream) {
    const std::string in = fhr::test::write_temp("zlib-in.bin", stream);
    const std::string out = fhr::test::temp_path("zlib-out.bin");
    const std::string command =
        "python3 -c \"import sys, zlib; open(sys.argv[2], 'wb').write(zlib.decompress(open(sys.argv[1], "
        "'rb').read()))\" '" +
        in + "' '" + out + "'";
    REQUIRE(std::system(command.c_str()) == 0);
    return fhr::test::read_file(out);
}

Image noise_image(int width, int height, std::uint64_t seed) {
    std::mt19937_64 random(seed);
    Image image(width, height, Rgb8{});
    for (std::uint8_t& b : image.rgb) b = std::uint8_t(random() >> 56);
    return image;
}

}  // namespace

TEST_CASE("REN-2: the reader's CRC-32 and Adler-32 give the published check values", "[unit][render]") {
    CHECK(reader::crc32("123456789") == 0xCBF43926u);  // the CRC catalogue's check value
    CHECK(reader::crc32("") == 0u);
    CHECK(reader::crc32("IEND") == 0xAE426082u);  // the CRC every PNG ends with
    CHECK(reader::adler32("Wikipedia") == 0x11E60398u);
    CHECK(reader::adler32("") == 1u);
}

TEST_CASE("REN-2: a PNG's zlib stream inflates to its scanlines, by the independent inflater and by zlib",
          "[oracle][render]") {
    for (const Image& image : {noise_image(97, 31, 3), Image(300, 200, Rgb8{10, 20, 30}), noise_image(1, 1, 4)}) {
        const reader::DecodedPng decoded = reader::decode_png(encode_png(image));
        std::string stream;
        for (const reader::Chunk& c : decoded.chunks)
            if (c.type == "IDAT") stream += c.data;
        INFO(image.width << " x " << image.height);
        CHECK(reader::inflate_zlib(stream) == decoded.scanlines);
        CHECK(inflate_with_zlib(stream) == decoded.scanlines);
        CHECK(decoded.image.rgb == image.rgb);
    }
}

TEST_CASE("REN-1: a PNG has the signature, IHDR, IDAT, IEND with valid CRCs and gives back its pixels",
          "[unit][render]") {
    Image image(5, 3, Rgb8{255, 255, 255});
    image.set(0, 0, {255, 0, 0});
    image.set(4, 2, {0, 0, 255});
    image.set(2, 1, {12, 34, 56});
    const std::string png = encode_png(image);
    CHECK(png.substr(0, 8) == std::string("\x89PNG\r\n\x1a\n", 8));
    reader::DecodedPng decoded;
    REQUIRE_NOTHROW(decoded = reader::decode_png(png));
    REQUIRE(decoded.chunks.size() == 3);
    CHECK(decoded.chunks[0].type == "IHDR");
    CHECK(reader::be32(decoded.chunks[0].data, 0) == 5);
    CHECK(reader::be32(decoded.chunks[0].data, 4) == 3);
    CHECK(decoded.chunks[0].data.substr(8) == std::string("\x08\x02\x00\x00\x00", 5));
    CHECK(decoded.chunks[1].type == "IDAT");
    CHECK(decoded.chunks[2].type == "IEND");
    CHECK(decoded.image.rgb == image.rgb);
    CHECK(decoded.scanlines.size() == 3 * (1 + 3 * 5));
    // The IDAT stream is also what zlib decompresses, byte for byte.
    CHECK(inflate_with_zlib(decoded.chunks[1].data) == decoded.scanlines);
}

TEST_CASE("REN-1: random images of random sizes decode to their exact pixels", "[property][render]") {
    rc::prop("decode_png(encode_png(image)) == image", [] {
        const int width = *rc::gen::inRange(1, 40), height = *rc::gen::inRange(1, 40);
        const int levels = *rc::gen::inRange(1, 257);  // few levels: flat areas; 256: noise
        Image image(width, height, Rgb8{});
        for (std::uint8_t& b : image.rgb) b = std::uint8_t(*rc::gen::inRange(0, levels));
        const reader::DecodedPng decoded = reader::decode_png(encode_png(image));
        RC_ASSERT(decoded.image.width == width);
        RC_ASSERT(decoded.image.height == height);
        RC_ASSERT(decoded.image.rgb == image.rgb);
    });
}

TEST_CASE("REN-1: a large image's stream is split into consecutive IDAT chunks of at most 1 MiB", "[unit][render]") {
    const Image image = noise_image(700, 600, 5);  // 1.26 MB of incompressible pixels
    const reader::DecodedPng decoded = reader::decode_png(encode_png(image));
    std::size_t idats = 0, first = 0, last = 0;
    for (std::size_t i = 0; i < decoded.chunks.size(); ++i)
        if (decoded.chunks[i].type == "IDAT") {
            if (idats++ == 0) first = i;
            last = i;
            CHECK(decoded.chunks[i].data.size() <= (std::size_t(1) << 20));
        }
    CHECK(idats >= 2);
    CHECK(last - first + 1 == idats);  // consecutive
    CHECK(decoded.image.rgb == image.rgb);
}

TEST_CASE("REN-1: rows choose different filter types (Sub and Up among them), each undone exactly", "[unit][render]") {
    // Bands of rows built to favour different filters: small values, ramps, repeated rows, planes, noise.
    Image image(64, 40, Rgb8{});
    for (int y = 0; y < 40; ++y)
        for (int x = 0; x < 64; ++x) {
            const int band = y / 8;
            std::uint8_t v = 0;
            if (band == 0)
                v = std::uint8_t((x % 2) * 3);  // tiny values: None
            else if (band == 1)
                v = std::uint8_t(100 + 2 * x);  // horizontal ramp: Sub
            else if (band == 2)
                v = std::uint8_t((x * 37) % 256);  // repeated rows: Up
            else if (band == 3)
                v = std::uint8_t(2 * x + 2 * y);  // plane: Average or Paeth
            else
                v = std::uint8_t((x * 91 + y * 53) % 256);  // noise
            image.set(x, y, {v, std::uint8_t(v / 2), std::uint8_t(255 - v)});
        }
    const reader::DecodedPng decoded = reader::decode_png(encode_png(image));
    std::vector<int> used(5, 0);
    for (int y = 0; y < 40; ++y) ++used[std::size_t(std::uint8_t(decoded.scanlines[std::size_t(y) * (1 + 3 * 64)]))];
    INFO("rows per filter type: " << used[0] << " " << used[1] << " " << used[2] << " " << used[3] << " " << used[4]);
    CHECK(used[1] > 0);
    CHECK(used[2] > 0);
    CHECK(decoded.image.rgb == image.rgb);
}

TEST_CASE("REN-3: encoding is deterministic and write_png writes exactly encode_png atomically", "[unit][render]") {
    const Image image = noise_image(33, 17, 9);
    const std::string png = encode_png(image);
    CHECK(encode_png(image) == png);
    const fs::path dir = fhr::test::temp_path("png-dir");
    fs::create_directories(dir);
    const std::string path = (dir / "image.png").string();
    write_png(path, image);
    CHECK(fhr::test::read_file(path) == png);
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
    CHECK(files == 1);  // no temporary left behind
    CHECK_THROWS_AS(write_png((dir / "missing" / "image.png").string(), image), InvalidInput);
}

TEST_CASE("REN-1: an empty image or a pixel buffer of the wrong size is refused", "[unit][render]") {
    CHECK_THROWS_AS(encode_png(Image(0, 4, Rgb8{})), InvalidInput);
    CHECK_THROWS_AS(encode_png(Image(4, 0, Rgb8{})), InvalidInput);
    Image wrong(4, 4, Rgb8{});
    wrong.rgb.pop_back();
    CHECK_THROWS_AS(encode_png(wrong), InvalidInput);
}
