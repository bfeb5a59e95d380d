// FHR §6 figures — an independent PNG reader for the render tests (spec/render.md REN-1, REN-2):
// chunk parsing with its own CRC-32 checks, an inflater for zlib streams with its own Adler-32
// (RFC 1950/1951: stored, fixed- and dynamic-Huffman blocks, canonical codes decoded bit by bit —
// not libpng's or zlib's code), and the five PNG filters undone. It throws std::runtime_error naming the first
// violation, so a test can REQUIRE_NOTHROW and read the message.
#pragma once

#include <array>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include <fhr/render/image.hpp>

namespace fhr::render::reader {

struct Chunk {
    std::string type;
    std::string data;
};

inline std::uint32_t be32(const std::string& s, std::size_t at) {
    return (std::uint32_t(std::uint8_t(s[at])) << 24) | (std::uint32_t(std::uint8_t(s[at + 1])) << 16) |
           (std::uint32_t(std::uint8_t(s[at + 2])) << 8) | std::uint32_t(std::uint8_t(s[at + 3]));
}

/// CRC-32 of ISO 3309 (reflected polynomial 0xEDB88320), bit by bit: checked against published
/// vectors in test_png.cpp.
inline std::uint32_t crc32(const std::string& bytes) {
    std::uint32_t c = 0xFFFFFFFFu;
    for (const char b : bytes) {
        c ^= std::uint8_t(b);
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
}

/// Adler-32 of RFC 1950 §8.2, reduced at every byte.
inline std::uint32_t adler32(const std::string& bytes) {
    std::uint32_t a = 1, b = 0;
    for (const char x : bytes) {
        a = (a + std::uint8_t(x)) % 65521;
        b = (b + a) % 65521;
    }
    return (b << 16) | a;
}

// The chunks after the signature; every length and CRC checked.
inline std::vector<Chunk> read_chunks(const std::string& png) {
    if (png.compare(0, 8, std::string("\x89PNG\r\n\x1a\n", 8)) != 0) throw std::runtime_error("bad signature");
    std::vector<Chunk> chunks;
    std::size_t at = 8;
    while (at < png.size()) {
        if (at + 12 > png.size()) throw std::runtime_error("truncated chunk header");
        const std::uint32_t length = be32(png, at);
        if (length > 0x7FFFFFFFu || at + 12 + length > png.size())
            throw std::runtime_error("chunk length out of range");
        const std::string typed = png.substr(at + 4, 4 + length);
        const std::uint32_t crc = be32(png, at + 8 + length);
        if (crc != crc32(typed)) throw std::runtime_error("bad CRC in chunk " + typed.substr(0, 4));
        chunks.push_back({typed.substr(0, 4), typed.substr(4)});
        at += 12 + length;
    }
    return chunks;
}

class BitReader {
public:
    explicit BitReader(const std::string& bytes, std::size_t start) : bytes_(bytes), byte_(start) {}
    unsigned bit() {
        if (byte_ >= bytes_.size()) throw std::runtime_error("inflate: out of input");
        const unsigned b = (std::uint8_t(bytes_[byte_]) >> bit_) & 1u;
        if (++bit_ == 8) {
            bit_ = 0;
            ++byte_;
        }
        return b;
    }
    unsigned bits(int n) {
        unsigned v = 0;
        for (int k = 0; k < n; ++k) v |= bit() << k;
        return v;
    }
    void align() {
        if (bit_ != 0) {
            bit_ = 0;
            ++byte_;
        }
    }
    std::size_t byte_position() const { return byte_; }
    void skip_bytes(std::size_t n) { byte_ += n; }

private:
    const std::string& bytes_;
    std::size_t byte_;
    int bit_ = 0;
};

// A canonical Huffman code given by code lengths (RFC 1951 §3.2.2), decoded one bit at a time.
class Huffman {
public:
    explicit Huffman(const std::vector<int>& lengths) : count_(16, 0) {
        for (const int l : lengths) ++count_[std::size_t(l)];
        count_[0] = 0;
        std::vector<int> offset(16, 0);
        for (int l = 1; l < 16; ++l) offset[std::size_t(l)] = offset[std::size_t(l - 1)] + count_[std::size_t(l - 1)];
        symbol_.resize(lengths.size());
        for (std::size_t s = 0; s < lengths.size(); ++s)
            if (lengths[s] != 0) symbol_[std::size_t(offset[std::size_t(lengths[s])]++)] = int(s);
    }
    int decode(BitReader& in) const {
        int code = 0, first = 0, index = 0;
        for (int l = 1; l < 16; ++l) {
            code |= int(in.bit());
            const int count = count_[std::size_t(l)];
            if (code - first < count) return symbol_[std::size_t(index + code - first)];
            index += count;
            first = (first + count) << 1;
            code <<= 1;
        }
        throw std::runtime_error("inflate: invalid Huffman code");
    }

private:
    std::vector<int> count_, symbol_;
};

inline void inflate_block(BitReader& in, const Huffman& literal, const Huffman& distance, std::string& out) {
    static const int length_base[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                        31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
    static const int length_extra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                         2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
    static const int distance_base[30] = {1,    2,    3,    4,    5,    7,    9,    13,    17,    25,
                                          33,   49,   65,   97,   129,  193,  257,  385,   513,   769,
                                          1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
    static const int distance_extra[30] = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                           6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
    for (;;) {
        const int symbol = literal.decode(in);
        if (symbol < 256) {
            out.push_back(char(symbol));
        } else if (symbol == 256) {
            return;
        } else {
            if (symbol > 285) throw std::runtime_error("inflate: bad length symbol");
            const int length = length_base[symbol - 257] + int(in.bits(length_extra[symbol - 257]));
            const int d = distance.decode(in);
            if (d > 29) throw std::runtime_error("inflate: bad distance symbol");
            const std::size_t dist = std::size_t(distance_base[d]) + in.bits(distance_extra[d]);
            if (dist > out.size() || dist > 32768) throw std::runtime_error("inflate: distance too far back");
            for (int k = 0; k < length; ++k) out.push_back(out[out.size() - dist]);
        }
    }
}

// The bytes of a zlib stream; header, block structure and Adler-32 checked, nothing may follow.
inline std::string inflate_zlib(const std::string& stream) {
    if (stream.size() < 6) throw std::runtime_error("zlib: too short");
    const unsigned cmf = std::uint8_t(stream[0]), flg = std::uint8_t(stream[1]);
    if ((cmf & 0x0F) != 8 || (cmf >> 4) > 7 || (cmf * 256 + flg) % 31 != 0 || (flg & 0x20))
        throw std::runtime_error("zlib: bad header");
    BitReader in(stream, 2);
    std::string out;
    for (bool last = false; !last;) {
        last = in.bit() == 1;
        const unsigned type = in.bits(2);
        if (type == 0) {
            in.align();
            const std::size_t at = in.byte_position();
            if (at + 4 > stream.size()) throw std::runtime_error("inflate: truncated stored block");
            const unsigned len = std::uint8_t(stream[at]) | (unsigned(std::uint8_t(stream[at + 1])) << 8);
            const unsigned nlen = std::uint8_t(stream[at + 2]) | (unsigned(std::uint8_t(stream[at + 3])) << 8);
            if ((len ^ 0xFFFFu) != nlen || at + 4 + len > stream.size())
                throw std::runtime_error("inflate: bad stored block");
            out.append(stream, at + 4, len);
            in.skip_bytes(4 + len);
        } else if (type == 1) {
            std::vector<int> lengths(288);
            for (int s = 0; s < 288; ++s) lengths[std::size_t(s)] = s < 144 ? 8 : s < 256 ? 9 : s < 280 ? 7 : 8;
            inflate_block(in, Huffman(lengths), Huffman(std::vector<int>(30, 5)), out);
        } else if (type == 2) {
            const unsigned hlit = in.bits(5) + 257, hdist = in.bits(5) + 1, hclen = in.bits(4) + 4;
            static const int order[19] = {16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15};
            std::vector<int> code_lengths(19, 0);
            for (unsigned k = 0; k < hclen; ++k) code_lengths[std::size_t(order[k])] = int(in.bits(3));
            const Huffman code_length_code(code_lengths);
            std::vector<int> lengths;
            while (lengths.size() < hlit + hdist) {
                const int s = code_length_code.decode(in);
                if (s < 16)
                    lengths.push_back(s);
                else if (s == 16) {
                    if (lengths.empty()) throw std::runtime_error("inflate: repeat with no previous length");
                    const int repeat = 3 + int(in.bits(2)), previous = lengths.back();
                    lengths.insert(lengths.end(), std::size_t(repeat), previous);
                } else {
                    const int repeat = s == 17 ? 3 + int(in.bits(3)) : 11 + int(in.bits(7));
                    lengths.insert(lengths.end(), std::size_t(repeat), 0);
                }
            }
            if (lengths.size() != hlit + hdist) throw std::runtime_error("inflate: code lengths overrun");
            inflate_block(in, Huffman({lengths.begin(), lengths.begin() + hlit}),
                          Huffman({lengths.begin() + hlit, lengths.end()}), out);
        } else {
            throw std::runtime_error("inflate: reserved block type");
        }
    }
    in.align();
    const std::size_t at = in.byte_position();
    if (at + 4 != stream.size()) throw std::runtime_error("zlib: Adler-32 missing or trailing bytes");
    if (be32(stream, at) != adler32(out)) throw std::runtime_error("zlib: Adler-32 mismatch");
    return out;
}

struct DecodedPng {
    Image image;
    std::vector<Chunk> chunks;
    std::string scanlines;  ///< the inflated IDAT stream: filter byte + row bytes, per row
};

// The whole file decoded: IHDR first with 8-bit RGB, no interlace; IDATs consecutive; IEND last
// and empty; each scanline's filter type 0..4 undone (PNG §9.2, Paeth §9.4).
inline DecodedPng decode_png(const std::string& png) {
    DecodedPng d;
    d.chunks = read_chunks(png);
    if (d.chunks.empty() || d.chunks.front().type != "IHDR" || d.chunks.front().data.size() != 13)
        throw std::runtime_error("IHDR missing or not first");
    if (d.chunks.back().type != "IEND" || !d.chunks.back().data.empty())
        throw std::runtime_error("IEND missing, not last or not empty");
    const std::string& h = d.chunks.front().data;
    const std::uint32_t width = be32(h, 0), height = be32(h, 4);
    if (width == 0 || height == 0 || width > 0x7FFFFFFFu || height > 0x7FFFFFFFu)
        throw std::runtime_error("IHDR: bad size");
    if (h.substr(8) != std::string("\x08\x02\x00\x00\x00", 5))
        throw std::runtime_error("IHDR: not 8-bit RGB, deflate, filter 0, no interlace");
    std::string stream;
    std::size_t first_idat = 0, last_idat = 0;
    for (std::size_t k = 0; k < d.chunks.size(); ++k)
        if (d.chunks[k].type == "IDAT") {
            if (stream.empty()) first_idat = k;
            last_idat = k;
            stream += d.chunks[k].data;
        }
    if (stream.empty()) throw std::runtime_error("no IDAT");
    for (std::size_t k = first_idat; k <= last_idat; ++k)
        if (d.chunks[k].type != "IDAT") throw std::runtime_error("IDAT chunks not consecutive");
    d.scanlines = inflate_zlib(stream);
    const std::size_t stride = 3 * std::size_t(width);
    if (d.scanlines.size() != (stride + 1) * height) throw std::runtime_error("scanlines have the wrong size");
    d.image = Image(int(width), int(height), Rgb8{});
    std::vector<int> previous(stride, 0), row(stride);
    for (std::size_t y = 0; y < height; ++y) {
        const std::size_t at = y * (stride + 1);
        const int type = std::uint8_t(d.scanlines[at]);
        if (type > 4) throw std::runtime_error("bad filter type");
        for (std::size_t i = 0; i < stride; ++i) {
            const int x = std::uint8_t(d.scanlines[at + 1 + i]);
            const int a = i >= 3 ? row[i - 3] : 0, b = previous[i], c = i >= 3 ? previous[i - 3] : 0;
            int predictor = 0;
            if (type == 1)
                predictor = a;
            else if (type == 2)
                predictor = b;
            else if (type == 3)
                predictor = (a + b) / 2;
            else if (type == 4) {
                const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
                predictor = (pa <= pb && pa <= pc) ? a : pb <= pc ? b : c;
            }
            row[i] = (x + predictor) & 0xFF;
            d.image.rgb[y * stride + i] = std::uint8_t(row[i]);
        }
        previous = row;
    }
    return d;
}

}  // namespace fhr::render::reader
