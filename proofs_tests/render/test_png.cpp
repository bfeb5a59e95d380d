// FHR §6 figures — the PNG writer (spec/render.md REN-1..3): CRC-32 and Adler-32 against
// published vectors, our zlib stream inflated by an independent inflater (png_reader.hpp) and by
// zlib itself (Python's zlib module, the reference implementation), PNG structure and pixels
// read back, determinism, atomic writes and refusals.
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

std::span<const std::uint8_t> bytes_of(const std::string& s) {
    return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

std::string compress(const std::string& s) { return zlib_compress(bytes_of(s)); }

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

TEST_CASE("REN-2: CRC-32 and Adler-32 give the published check values", "[unit][render]") {
    CHECK(crc32(bytes_of("123456789")) == 0xCBF43926u);  // the CRC catalogue's check value
    CHECK(crc32(bytes_of("")) == 0u);
    CHECK(crc32(bytes_of("IEND")) == 0xAE426082u);  // the CRC every PNG ends with
    CHECK(adler32(bytes_of("Wikipedia")) == 0x11E60398u);
    CHECK(adler32(bytes_of("")) == 1u);
    // 5552 bytes of 0xFF is where zlib's deferred modulo must not overflow; ours reduces at every byte.
    const std::string ff(100000, '\xFF');
    std::uint32_t a = 1, b = 0;
    for (std::size_t i = 0; i < ff.size(); ++i) {
        a = (a + 255) % 65521;
        b = (b + a) % 65521;
    }
    CHECK(adler32(bytes_of(ff)) == ((b << 16) | a));
}

TEST_CASE("REN-2: zlib_compress round-trips through an independent inflater, on the edge cases of DEFLATE",
          "[unit][render]") {
    std::vector<std::string> inputs = {
        "", "a", "ab", "abc", "abcabcabcabc", std::string(258, 'x'), std::string(259, 'x'), std::string(100000, '\0')};
    // A match at exactly the largest distance, 32768, and one just beyond the window.
    std::mt19937_64 random(7);
    std::string far(32768, '\0');
    for (char& c : far) c = char(random() >> 56);
    inputs.push_back(far.substr(0, 300) + far.substr(300) + far.substr(0, 300));
    inputs.push_back(far.substr(0, 300) + far + far.substr(0, 300));
    for (const std::string& input : inputs) {
        const std::string stream = compress(input);
        INFO("input of " << input.size() << " bytes");
        CHECK(stream.substr(0, 2) == "\x78\x01");
        std::string back;
        REQUIRE_NOTHROW(back = reader::inflate_zlib(stream));
        CHECK(back == input);
    }
    // Long runs compress: a run of 100,000 equal bytes costs a few hundred bytes.
    CHECK(compress(std::string(100000, '\0')).size() < 1000);
}

TEST_CASE("REN-2: random byte strings round-trip through the independent inflater", "[property][render]") {
    rc::prop("inflate(zlib_compress(x)) == x", [](const std::vector<std::uint8_t>& raw, std::uint8_t alphabet) {
        // A small alphabet makes matches of every length and distance likely.
        std::string input;
        const unsigned k = 1u + alphabet % 6u;
        for (const std::uint8_t b : raw) input.push_back(char(b % k));
        for (int r = 0; r < 3; ++r) input += input.substr(0, input.size() / 2);
        RC_ASSERT(reader::inflate_zlib(compress(input)) == input);
    });
}

TEST_CASE("REN-2: zlib itself inflates our streams to the original bytes", "[oracle][render]") {
    std::mt19937_64 random(11);
    std::string text;
    for (int k = 0; k < 200000; ++k) text.push_back("fhr-render "[random() % 11]);
    const Image image = noise_image(97, 31, 3);
    const std::string pixels(image.rgb.begin(), image.rgb.end());
    for (const std::string& input : {std::string(), text, pixels, std::string(70000, '\0')}) {
        INFO("input of " << input.size() << " bytes");
        CHECK(inflate_with_zlib(compress(input)) == input);
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

TEST_CASE("REN-1: a stream over 1 MiB is split into consecutive IDAT chunks of at most 1 MiB", "[unit][render]") {
    const Image image = noise_image(700, 600, 5);  // 1.26 MB of incompressible pixels
    const reader::DecodedPng decoded = reader::decode_png(encode_png(image));
    std::size_t idats = 0;
    for (const reader::Chunk& c : decoded.chunks)
        if (c.type == "IDAT") {
            ++idats;
            CHECK(c.data.size() <= (std::size_t(1) << 20));
        }
    CHECK(idats == 2);
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
