// FHR exchange — the `fhr-param 1` file (spec/param.md): a parameterization
// φ: Ω_D → Ω_T of the paper (§1) written as the domain D, the refined surface T′ (§3) and, for
// every triangle of T′, its patch S_d (§3) and the barycentric coordinates of ψ at its corners in
// domain triangle d (ψ_i of §4, eq. (2)). Since ψ is linear on every triangle of T′, these numbers
// determine ψ and φ = ψ⁻¹ everywhere. Any implementation can write it; `fhr verify` checks it.
//
// The reader checks the grammar (PARAM-1) only: it keeps indices out of range, NaN and
// infinite numbers, so that the oracle (exchange/verify.hpp) can name the broken invariant
// (PARAM-2) instead of refusing to read the file.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <fhr/core/executor.hpp>
#include <fhr/core/polygon_soup.hpp>
#include <fhr/core/trimesh.hpp>

namespace fhr::exchange {

/// Barycentric coordinates (β_0, β_1, β_2) with respect to the corners (i, j, k) of a domain face.
using Beta = std::array<double, 3>;

/// One triangle (a, b, c) of T′ (counter-clockwise seen from outside), the domain face `patch`
/// whose patch S_patch contains it, and beta[n] = the barycentric coordinates of ψ(v[n]).
struct ParamFace {
    Triangle v{};
    std::uint32_t patch = 0;
    std::array<Beta, 3> beta{};
    bool operator==(const ParamFace&) const = default;
};

/// The whole file as values. Indices are 0-based and not checked against the counts (PARAM-2 is
/// the oracle's job, so that it can be reported as a broken invariant).
struct ParamFile {
    std::vector<Vec3> domain_vertices;     ///< #N: vertices of D
    std::vector<Triangle> domain_faces;    ///< #M: faces (i, j, k) of D, counter-clockwise from outside
    std::vector<Vec3> surface_vertices;    ///< #P: vertices of T′
    std::vector<ParamFace> surface_faces;  ///< #Q: faces of T′ with patch and β
    bool operator==(const ParamFile&) const = default;
};

/// Parses the bytes of a `fhr-param 1` file (the grammar of spec/param.md, PARAM-1): the header,
/// the four sections in order with counts that the remaining bytes can hold (checked before
/// anything is reserved), each record's tokens, and nothing after the last face. Numbers are
/// decimal in C syntax (`nan` and `inf` are read, and refused later by PARAM-2); an index is a
/// decimal integer in [0, 2^32). `name` is used in messages.
/// \throws InvalidInput(name, line, "...") naming the first syntax error, its line and element.
ParamFile parse_param(std::string_view bytes, const std::string& name);

/// Reads and parses a whole file. \throws InvalidInput (cannot open or read, or parse_param's).
ParamFile read_param(const std::string& path);

/// The file's bytes: one record per line, numbers in the shortest decimal form that reads back
/// to the same double (std::to_chars), single spaces, "\n" line ends, no comments. Deterministic:
/// equal values give equal bytes, and parse_param(format_param(p)) gives back every number bit
/// for bit (so it compares equal to p when p holds no NaN).
std::string format_param(const ParamFile& file);

/// Writes format_param(file) atomically (temporary name, then rename; FMT-WRITE-1), in parts
/// formatted and written on the threads of `executor` (default_executor() when null; io::FileParts):
/// the same bytes on any number of threads. \throws InvalidInput(path, 0, "cannot write: ...").
void write_param(const std::string& path, const ParamFile& file, Executor* executor = nullptr);

}  // namespace fhr::exchange
