// FHR io — strict mesh readers. The paper (§1) takes a manifold triangulation T as given; these
// readers make sure that what reaches the algorithms is exactly what the file says, or refuse it
// with a one-line InvalidInput naming file, line and element (spec/formats.md, spec/mesh.md).
#pragma once

#include <string>
#include <string_view>

#include <fhr/core/build.hpp>
#include <fhr/core/polygon_soup.hpp>
#include <fhr/core/trimesh.hpp>

namespace fhr::io {

enum class Format { off, obj, ply, stl };

/// The format of `path`, from its extension (case-insensitive: .off .coff .obj .ply .stl).
/// \throws InvalidInput "unknown format" for any other extension.
Format format_from_extension(const std::string& path);

/// The whole file's bytes. \throws InvalidInput(path, 0, "cannot open: <reason>") or "cannot read: ...".
std::string read_bytes(const std::string& path);

/// Reads a whole file and parses it with the reader for its extension.
/// \throws InvalidInput (unreadable file, empty file, any syntax error of spec/formats.md).
PolygonSoup read_soup(const std::string& path);

/// A mesh file read and validated: read_soup, then build_trimesh (every rule of spec/mesh.md).
/// What the builder changed (warnings, dropped vertices) goes to `log` when it is given.
/// \throws InvalidInput naming the file, the line (text formats) and the element.
TriMesh read_mesh(const std::string& path, const BuildOptions& options = {}, BuildLog* log = nullptr);

/// Parsers over bytes already in memory; `name` is used in messages. These are what the fuzz
/// harnesses call. \post every point is finite, every index < points.size(), every polygon has
/// at least one index; polygons may still be degenerate (build_trimesh decides).
/// With `texture`, OBJ and PLY also fill soup.texture (spec/atlas.md ATLAS-1): every record read is
/// finite and every corner's record index is in range or SoupTexture::none (a corner without one).
PolygonSoup parse_off(std::string_view bytes, const std::string& name);
PolygonSoup parse_obj(std::string_view bytes, const std::string& name, bool texture = false);
PolygonSoup parse_ply(std::string_view bytes, const std::string& name, bool texture = false);
PolygonSoup parse_stl(std::string_view bytes, const std::string& name);
PolygonSoup parse(Format format, std::string_view bytes, const std::string& name);

}  // namespace fhr::io
