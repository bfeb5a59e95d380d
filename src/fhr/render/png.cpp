// FHR §6 figures — the PNG encoder (see png.hpp): filtered scanlines, zlib/DEFLATE with fixed
// Huffman codes (RFC 1950, RFC 1951 §3.2.6), chunks with CRC-32.
#include <fhr/render/png.hpp>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <limits>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/io/atomic_file.hpp>

namespace fhr::render {
namespace {

constexpr std::array<std::uint32_t, 256> make_crc_table() {
    std::array<std::uint32_t, 256> table{};
    for (std::uint32_t n = 0; n < 256; ++n) {
        std::uint32_t c = n;
        for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[n] = c;
    }
    return table;
}
constexpr std::array<std::uint32_t, 256> crc_table = make_crc_table();

// LSB-first bit packing (RFC 1951 §3.1.1); Huffman codes go most significant bit first.
class BitWriter {
public:
    explicit BitWriter(std::string& out) : out_(out) {}
    void bits(std::uint32_t value, int count) {
        buffer_ |= std::uint64_t(value) << filled_;
        filled_ += count;
        while (filled_ >= 8) {
            out_.push_back(char(buffer_ & 0xFF));
            buffer_ >>= 8;
            filled_ -= 8;
        }
    }
    void code(std::uint32_t code, int length) {
        std::uint32_t reversed = 0;
        for (int k = 0; k < length; ++k) reversed |= ((code >> k) & 1u) << (length - 1 - k);
        bits(reversed, length);
    }
    void flush() {
        if (filled_ > 0) out_.push_back(char(buffer_ & 0xFF));
        buffer_ = 0;
        filled_ = 0;
    }

private:
    std::string& out_;
    std::uint64_t buffer_ = 0;
    int filled_ = 0;
};

// RFC 1951 §3.2.6: the fixed literal/length code.
void fixed_literal(BitWriter& w, unsigned symbol) {
    if (symbol < 144)
        w.code(0x30 + symbol, 8);
    else if (symbol < 256)
        w.code(0x190 + (symbol - 144), 9);
    else if (symbol < 280)
        w.code(symbol - 256, 7);
    else
        w.code(0xC0 + (symbol - 280), 8);
}

// RFC 1951 §3.2.5: length codes 257..285 and distance codes 0..29 with their extra bits.
constexpr std::array<int, 29> length_base = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                             31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr std::array<int, 29> length_extra = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                              2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
constexpr std::array<int, 30> distance_base = {1,    2,    3,    4,    5,    7,    9,    13,    17,    25,
                                               33,   49,   65,   97,   129,  193,  257,  385,   513,   769,
                                               1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
constexpr std::array<int, 30> distance_extra = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                                6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

void emit_match(BitWriter& w, int length, int distance) {
    int l = 28;
    while (length_base[l] > length) --l;
    fixed_literal(w, 257 + unsigned(l));
    w.bits(std::uint32_t(length - length_base[l]), length_extra[l]);
    int d = 29;
    while (distance_base[d] > distance) --d;
    w.code(std::uint32_t(d), 5);
    w.bits(std::uint32_t(distance - distance_base[d]), distance_extra[d]);
}

// Greedy LZ77 over a 32 KiB window with hash chains of 3-byte prefixes (the scheme of RFC 1951
// §4), the chain walk capped at 128 candidates; then one final fixed-Huffman block.
void deflate_fixed(std::span<const std::uint8_t> in, BitWriter& w) {
    constexpr int window = 32768, min_match = 3, max_match = 258, max_chain = 128;
    constexpr std::uint32_t hash_mask = (1u << 15) - 1;
    const std::size_t n = in.size();
    std::vector<std::int64_t> head(hash_mask + 1, -1), prev(window, -1);
    const auto hash = [&](std::size_t p) {
        return ((std::uint32_t(in[p]) << 10) ^ (std::uint32_t(in[p + 1]) << 5) ^ std::uint32_t(in[p + 2])) & hash_mask;
    };
    const auto insert = [&](std::size_t p) {
        if (p + min_match > n) return;
        const std::uint32_t h = hash(p);
        prev[p & (window - 1)] = head[h];
        head[h] = std::int64_t(p);
    };
    w.bits(1, 1);  // BFINAL
    w.bits(1, 2);  // BTYPE = 01, fixed Huffman codes
    std::size_t pos = 0;
    while (pos < n) {
        int best_length = 0, best_distance = 0;
        if (pos + min_match <= n) {
            const int limit = int(std::min<std::size_t>(max_match, n - pos));
            std::int64_t candidate = head[hash(pos)];
            for (int chain = 0; candidate >= 0 && std::int64_t(pos) - candidate <= window && chain < max_chain;
                 ++chain) {
                const std::size_t c = std::size_t(candidate);
                int length = 0;
                while (length < limit && in[c + std::size_t(length)] == in[pos + std::size_t(length)]) ++length;
                if (length > best_length) {
                    best_length = length;
                    best_distance = int(pos - c);
                    if (length == limit) break;
                }
                candidate = prev[c & (window - 1)];
            }
        }
        if (best_length >= min_match) {
            emit_match(w, best_length, best_distance);
            for (int k = 0; k < best_length; ++k) insert(pos + std::size_t(k));
            pos += std::size_t(best_length);
        } else {
            fixed_literal(w, in[pos]);
            insert(pos);
            ++pos;
        }
    }
    fixed_literal(w, 256);  // end of block
    w.flush();
}

void put_u32(std::string& out, std::uint32_t v) {
    out.push_back(char(v >> 24));
    out.push_back(char((v >> 16) & 0xFF));
    out.push_back(char((v >> 8) & 0xFF));
    out.push_back(char(v & 0xFF));
}

std::span<const std::uint8_t> as_bytes(const std::string& s) {
    return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

void put_chunk(std::string& out, const char (&type)[5], const std::string& data) {
    put_u32(out, std::uint32_t(data.size()));
    std::string typed(type, 4);
    typed += data;
    out += typed;
    put_u32(out, crc32(as_bytes(typed)));
}

std::uint8_t paeth(int a, int b, int c) {
    const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    if (pa <= pb && pa <= pc) return std::uint8_t(a);
    return std::uint8_t(pb <= pc ? b : c);
}

// PNG §9: each row filtered with the type of least Σ|signed byte| (§12.8), ties to the lower type.
std::vector<std::uint8_t> filtered_scanlines(const Image& image) {
    const std::size_t stride = 3 * std::size_t(image.width);
    std::vector<std::uint8_t> out;
    out.reserve((stride + 1) * std::size_t(image.height));
    std::vector<std::uint8_t> zero(stride, 0), candidate(stride);
    std::vector<std::uint8_t> best(stride);
    for (int y = 0; y < image.height; ++y) {
        const std::uint8_t* row = image.rgb.data() + stride * std::size_t(y);
        const std::uint8_t* up = y > 0 ? row - stride : zero.data();
        long best_cost = std::numeric_limits<long>::max();
        std::uint8_t best_type = 0;
        for (std::uint8_t type = 0; type < 5; ++type) {
            long cost = 0;
            for (std::size_t i = 0; i < stride; ++i) {
                const int a = i >= 3 ? row[i - 3] : 0, b = up[i], c = i >= 3 ? up[i - 3] : 0;
                int predictor = 0;
                switch (type) {
                    case 1: predictor = a; break;
                    case 2: predictor = b; break;
                    case 3: predictor = (a + b) / 2; break;
                    case 4: predictor = paeth(a, b, c); break;
                    default: break;
                }
                candidate[i] = std::uint8_t(row[i] - predictor);
                cost += std::abs(int(std::int8_t(candidate[i])));
            }
            if (cost < best_cost) {
                best_cost = cost;
                best_type = type;
                best.swap(candidate);
            }
        }
        out.push_back(best_type);
        out.insert(out.end(), best.begin(), best.end());
    }
    return out;
}

}  // namespace

std::uint32_t crc32(std::span<const std::uint8_t> bytes) {
    std::uint32_t c = 0xFFFFFFFFu;
    for (const std::uint8_t b : bytes) c = crc_table[(c ^ b) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

std::uint32_t adler32(std::span<const std::uint8_t> bytes) {
    constexpr std::uint32_t mod = 65521;
    std::uint32_t a = 1, b = 0;
    for (const std::uint8_t x : bytes) {
        a = (a + x) % mod;
        b = (b + a) % mod;
    }
    return (b << 16) | a;
}

std::string zlib_compress(std::span<const std::uint8_t> bytes) {
    std::string out;
    out.push_back(char(0x78));  // CM = 8 (deflate), CINFO = 7 (32 KiB window)
    out.push_back(char(0x01));  // FLEVEL 0, no dictionary, (0x78·256 + 0x01) % 31 == 0
    BitWriter writer(out);
    deflate_fixed(bytes, writer);
    put_u32(out, adler32(bytes));
    return out;
}

std::string encode_png(const Image& image) {
    if (image.width < 1 || image.height < 1)  // PNG §11.2.2: 1 ≤ width, height ≤ 2^31 − 1 (an int)
        throw InvalidInput("png: image size " + std::to_string(image.width) + "×" + std::to_string(image.height) +
                           " is not at least 1×1");
    if (image.rgb.size() != 3 * std::size_t(image.width) * std::size_t(image.height))
        throw InvalidInput("png: pixel buffer has " + std::to_string(image.rgb.size()) + " bytes, expected 3·" +
                           std::to_string(image.width) + "·" + std::to_string(image.height));
    std::string out = "\x89PNG\r\n\x1a\n";
    std::string header;
    put_u32(header, std::uint32_t(image.width));
    put_u32(header, std::uint32_t(image.height));
    header += std::string("\x08\x02\x00\x00\x00", 5);  // bit depth 8, RGB, deflate, filter 0, no interlace
    put_chunk(out, "IHDR", header);
    const std::vector<std::uint8_t> scanlines = filtered_scanlines(image);
    // The zlib stream split into IDAT chunks of at most 1 MiB (PNG §11.2.4: their concatenation
    // is the stream; a chunk's length must stay below 2^31).
    constexpr std::size_t idat_size = std::size_t(1) << 20;
    const std::string stream = zlib_compress(scanlines);
    for (std::size_t first = 0; first < stream.size(); first += idat_size)
        put_chunk(out, "IDAT", stream.substr(first, idat_size));
    put_chunk(out, "IEND", "");
    return out;
}

void write_png(const std::string& path, const Image& image) { io::write_file_atomically(path, encode_png(image)); }

}  // namespace fhr::render
