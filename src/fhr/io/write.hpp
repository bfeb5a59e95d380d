// FHR io — mesh writers. Every writer is atomic (temporary file, then rename; spec/formats.md
// FMT-WRITE-1) and exact: reading a written file back gives bit-identical coordinates
// (FMT-WRITE-2; text formats use the shortest round-trip decimal form). A file's parts are
// formatted and written on the threads of `executor` (default_executor() when null; io::FileParts):
// the same bytes on any number of threads.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <fhr/core/ids.hpp>
#include <fhr/core/executor.hpp>
#include <fhr/core/polygon_soup.hpp>

namespace fhr::io {

using Triangle = std::array<std::uint32_t, 3>;
using Vec2 = Eigen::Vector2d;

void write_off(const std::string& path, std::span<const Vec3> points, std::span<const Triangle> triangles,
               Executor* executor = nullptr);

/// OBJ; when `corner_uv` is non-empty it holds 3 texture coordinates per triangle (per corner,
/// in the triangle's order) written as `vt` lines and `f a/ta b/tb c/tc`.
void write_obj(const std::string& path, std::span<const Vec3> points, std::span<const Triangle> triangles,
               std::span<const Vec2> corner_uv = {}, Executor* executor = nullptr);
/// The same with corner c's texture coordinate (c = 3f + k, in the triangle's order) made by
/// corner_uv(c) as it is written, not held (fhr run's textured.obj: 4.9 million at 10⁶ faces);
/// corner_uv is called from the executor's threads at once, in no particular order.
void write_obj(const std::string& path, std::span<const Vec3> points, std::span<const Triangle> triangles,
               const std::function<Vec2(std::size_t)>& corner_uv, Executor* executor = nullptr);

/// OBJ polylines (`l` lines), one per entry of `polylines` (fhr run's geodesics.obj); with
/// `groups` (one name per polyline), each line is preceded by `g NAME` when its name changes.
void write_obj_polylines(const std::string& path, std::span<const Vec3> points,
                         std::span<const std::vector<std::uint32_t>> polylines,
                         std::span<const std::string> groups = {}, Executor* executor = nullptr);
/// Binary little-endian PLY with double vertex coordinates and uint32 face indices; when
/// `face_patch` is non-empty, one more face property `uint patch` (fhr run's refined.ply: the
/// domain face whose patch holds each face of T′).
void write_ply(const std::string& path, std::span<const Vec3> points, std::span<const Triangle> triangles,
               std::span<const DFaceId> face_patch = {}, Executor* executor = nullptr);

/// Writes a mesh in the format of the path's extension (.off, .obj or .ply; spec/formats.md).
/// \throws InvalidInput for STL (it has no shared vertices) or any other extension.
void write_mesh(const std::string& path, std::span<const Vec3> points, std::span<const Triangle> triangles,
                Executor* executor = nullptr);

}  // namespace fhr::io
