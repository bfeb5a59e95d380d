// FHR io — the correspondence file (spec/formats.md FMT-CORR-*): for each vertex v_j of a domain
// D, its point x_j on Ω_T (paper §2) — a vertex of T, or a point in a face of T given by
// barycentric coordinates (which covers points on edges, paper §3 Fig. 4).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <fhr/core/surface_point.hpp>

namespace fhr::io {

/// One entry of the file: a vertex of T or a point in a face of T, with its line.
using CorrespondenceEntry = NamedSurfacePoint;

/// Parses a correspondence file against a mesh with `n_vertices` vertices and `n_faces` faces.
/// Lines: `V` (a vertex index of T) or `f F b0 b1 b2` (face F of T, barycentric coordinates with
/// respect to its corners in the order `fhr info` / the file's face line lists them); `#` comments.
/// \throws InvalidInput naming file, line and entry: non-numeric tokens, indices out of range,
///         barycentric coordinates that are not finite, negative, or do not sum to 1 within 1e−12.
std::vector<CorrespondenceEntry> parse_correspondence(std::string_view bytes, const std::string& name,
                                                      std::size_t n_vertices, std::size_t n_faces);

}  // namespace fhr::io
