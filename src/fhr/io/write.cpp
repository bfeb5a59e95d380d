// FHR io — mesh writers (spec/formats.md FMT-WRITE-*): OFF, OBJ (optionally with per-corner
// texture coordinates: the parameterization of the paper's §4 as a texture) and binary
// little-endian PLY. Text numbers are the shortest decimal form that reads back to the same
// double (std::to_chars), so write → read is bit-identical (FMT-WRITE-2). Every file is written
// atomically (FMT-WRITE-1), in parts formatted at once on the executor's threads (io::FileParts).
#include <fhr/io/write.hpp>

#include <bit>
#include <stdexcept>
#include <string>

#include <fhr/core/errors.hpp>
#include <fhr/io/detail/atomic_file.hpp>
#include <fhr/io/detail/number_text.hpp>
#include <fhr/io/read.hpp>

namespace fhr::io {

namespace {

/// \pre every index of `triangles` is < point_count (a caller bug otherwise).
void check_indices(std::size_t point_count, std::span<const Triangle> triangles) {
    for (const Triangle& t : triangles)
        for (std::uint32_t v : t)
            if (v >= point_count) throw std::invalid_argument("fhr::io writer: triangle index out of range");
}

void append_little_endian(std::string& out, std::uint64_t bits, int size) {
    for (int b = 0; b < size; ++b) out += static_cast<char>((bits >> (8 * b)) & 0xff);
}

}  // namespace

void write_off(const std::string& path, std::span<const Vec3> points, std::span<const Triangle> triangles,
               Executor* executor) {
    check_indices(points.size(), triangles);
    std::string header = "OFF\n";
    append_number(header, points.size());
    header += ' ';
    append_number(header, triangles.size());
    header += " 0\n";
    FileParts file;
    file.text(std::move(header));
    file.elements(points.size(), [&](std::size_t first, std::size_t end, std::string& out) {
        for (std::size_t i = first; i < end; ++i) append_point(out, points[i]);
    });
    file.elements(triangles.size(), [&](std::size_t first, std::size_t end, std::string& out) {
        for (std::size_t f = first; f < end; ++f) {
            out += '3';
            for (std::uint32_t v : triangles[f]) {
                out += ' ';
                append_number(out, std::uint64_t{v});
            }
            out += '\n';
        }
    });
    file.write(path, executor);
}

void write_obj(const std::string& path, std::span<const Vec3> points, std::span<const Triangle> triangles,
               std::span<const Vec2> corner_uv, Executor* executor) {
    if (!corner_uv.empty() && corner_uv.size() != 3 * triangles.size())
        throw std::invalid_argument("fhr::io::write_obj: corner_uv must hold 3 entries per triangle");
    write_obj(
        path, points, triangles,
        corner_uv.empty() ? std::function<Vec2(std::size_t)>() : [&](std::size_t c) { return corner_uv[c]; }, executor);
}

void write_obj(const std::string& path, std::span<const Vec3> points, std::span<const Triangle> triangles,
               const std::function<Vec2(std::size_t)>& corner_uv, Executor* executor) {
    check_indices(points.size(), triangles);
    FileParts file;
    file.elements(points.size(), [&](std::size_t first, std::size_t end, std::string& out) {
        for (std::size_t i = first; i < end; ++i) {
            out += "v ";
            append_point(out, points[i]);
        }
    });
    file.elements(corner_uv ? 3 * triangles.size() : 0, [&](std::size_t first, std::size_t end, std::string& out) {
        RecentNumbers<2> uvs;  // a vertex's place in a chart is written with each face around it
        for (std::size_t c = first; c < end; ++c) {
            const Vec2 uv = corner_uv(c);
            out += "vt ";
            uvs.append(out, {uv.x(), uv.y()});
            out += '\n';
        }
    });
    file.elements(triangles.size(), [&](std::size_t first, std::size_t end, std::string& out) {
        for (std::size_t f = first; f < end; ++f) {
            out += 'f';
            for (std::size_t c = 0; c < 3; ++c) {
                out += ' ';
                append_number(out, std::uint64_t{triangles[f][c]} + 1);
                if (corner_uv) {
                    out += '/';
                    append_number(out, 3 * f + c + 1);
                }
            }
            out += '\n';
        }
    });
    file.write(path, executor);
}

void write_obj_polylines(const std::string& path, std::span<const Vec3> points,
                         std::span<const std::vector<std::uint32_t>> polylines, std::span<const std::string> groups,
                         Executor* executor) {
    if (!groups.empty() && groups.size() != polylines.size())
        throw std::invalid_argument("fhr::io::write_obj_polylines: one group per polyline");
    FileParts file;
    file.elements(points.size(), [&](std::size_t first, std::size_t end, std::string& out) {
        for (std::size_t i = first; i < end; ++i) {
            out += "v ";
            append_point(out, points[i]);
        }
    });
    file.elements(polylines.size(), [&](std::size_t first, std::size_t end, std::string& out) {
        for (std::size_t i = first; i < end; ++i) {
            if (!groups.empty() && (i == 0 || groups[i] != groups[i - 1])) out += "g " + groups[i] + '\n';
            out += 'l';
            for (std::uint32_t v : polylines[i]) {
                if (v >= points.size()) throw std::invalid_argument("fhr::io::write_obj_polylines: index out of range");
                out += ' ';
                append_number(out, std::uint64_t{v} + 1);
            }
            out += '\n';
        }
    });
    file.write(path, executor);
}

void write_ply(const std::string& path, std::span<const Vec3> points, std::span<const Triangle> triangles,
               std::span<const DFaceId> face_patch, Executor* executor) {
    check_indices(points.size(), triangles);
    if (!face_patch.empty() && face_patch.size() != triangles.size())
        throw ContractViolation("write_ply: one patch id per face is needed");
    std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by fhr\nelement vertex ";
    append_number(header, points.size());
    header += "\nproperty double x\nproperty double y\nproperty double z\nelement face ";
    append_number(header, triangles.size());
    header += "\nproperty list uchar uint vertex_indices\n";
    if (!face_patch.empty()) header += "property uint patch\n";
    header += "end_header\n";
    FileParts file;
    file.text(std::move(header));
    file.elements(points.size(), [&](std::size_t first, std::size_t end, std::string& out) {
        for (std::size_t i = first; i < end; ++i)
            for (int c = 0; c < 3; ++c) append_little_endian(out, std::bit_cast<std::uint64_t>(points[i][c]), 8);
    });
    file.elements(triangles.size(), [&](std::size_t first, std::size_t end, std::string& out) {
        for (std::size_t f = first; f < end; ++f) {
            out += '\3';
            for (std::uint32_t v : triangles[f]) append_little_endian(out, v, 4);
            if (!face_patch.empty()) append_little_endian(out, face_patch[f].idx(), 4);
        }
    });
    file.write(path, executor);
}

void write_mesh(const std::string& path, std::span<const Vec3> points, std::span<const Triangle> triangles,
                Executor* executor) {
    switch (format_from_extension(path)) {
        case Format::off: write_off(path, points, triangles, executor); return;
        case Format::obj: write_obj(path, points, triangles, std::span<const Vec2>(), executor); return;
        case Format::ply: write_ply(path, points, triangles, {}, executor); return;
        case Format::stl: break;
    }
    throw InvalidInput(path, 0, "cannot write STL (it has no shared vertices): use .off, .obj or .ply");
}

}  // namespace fhr::io
