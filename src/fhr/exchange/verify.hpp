// FHR exchange — the oracle: does a `fhr-param 1` file describe a valid parameterization in the
// sense of the paper? It checks the invariants PARAM-2..11 of spec/param.md (PARAM-1, the
// grammar, is parse_param's): the surfaces are manifolds of one topology, component by component
// (§1, §2; closed as in the paper, or — beyond the paper — with boundary and several
// components: spec/param.md "Boundary and components"), every patch S_i is a disk (§3), ψ is
// continuous across patch boundaries and maps ∂T′ onto ∂D (§4), one-to-one on each patch
// (§4, Proposition 1: exact orientation of every image triangle, and the patch boundary mapped
// monotonically onto the triangle's boundary), chord length along every curve (§4), and with the
// input mesh T, Ω_T′ = Ω_T (§3).
//
// Independence: this module uses only src/fhr/core (mesh building, exact predicates) and the file
// value; it shares no code with the parameterization it judges (src/fhr/param, src/fhr/partition).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include <fhr/core/executor.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/exchange/distortion.hpp>
#include <fhr/exchange/fhr_param.hpp>

namespace fhr::exchange {

enum class CheckStatus {
    pass,     ///< every element satisfies the invariant
    fail,     ///< `failures` elements break it; the first is described
    skipped,  ///< not checked because a check it relies on failed (named in `first_failure`)
    info,     ///< reported, not judged: `failures` elements break it, the first is described, and
              ///< the map is valid nonetheless (PARAM-10 without `paper`; ATLAS-7 without `strict`)
};

/// Whether a check's result makes the map invalid: fail and skipped do, pass and info do not.
inline bool judged_against(CheckStatus status) { return status == CheckStatus::fail || status == CheckStatus::skipped; }

struct CheckResult;
/// The first of `checks` judged against the map (judged_against), or nullptr: the verdict's first failure.
const CheckResult* first_judged_failure(const std::vector<CheckResult>& checks);

/// "pass", "fail", "skipped" or "info".
const char* to_string(CheckStatus status);

/// The result of one invariant.
struct CheckResult {
    std::string id;     ///< "PARAM-7"
    std::string title;  ///< what it checks, a few words
    CheckStatus status = CheckStatus::skipped;
    std::uint64_t checked = 0;   ///< elements examined (faces, vertices, patches, …; see spec/param.md)
    std::uint64_t failures = 0;  ///< elements that break the invariant
    std::string first_failure;   ///< one line naming the first broken element ("" when it passed)
    /// Where the first failure is, as indices into the file (surface face, surface vertex, patch =
    /// domain face); −1 when not applicable. PARAM-11's "vertex of T missing" names T's vertex.
    std::int64_t face = -1, vertex = -1, patch = -1;
    /// An atlas check's first failure (spec/atlas.md): its chart (−1 when none) and UV point.
    std::int64_t chart = -1;
    std::optional<std::array<double, 2>> uv;
};

struct VerifyReport {
    /// PARAM-2 … PARAM-10, and PARAM-11 when an input mesh was given, in this order.
    std::vector<CheckResult> checks;
    /// True iff every check passed.
    bool valid() const;
    /// The first check that did not pass, or nullptr.
    const CheckResult* first_failure() const;
    /// DIST-* of spec/distortion.md: each face of T′ from its image in its domain triangle (the β
    /// of its corners on that triangle's 3D corners) onto its 3D triangle. Measured whenever
    /// PARAM-2 holds (the indices are in range), whatever the verdict; empty otherwise.
    Distortion distortion;
};

/// Tolerances of spec/param.md (each derived there and at its use in verify.cpp).
inline constexpr double beta_sum_tolerance = 1e-12;    ///< PARAM-5
inline constexpr double continuity_tolerance = 1e-12;  ///< PARAM-7
inline constexpr double area_tolerance = 1e-12;        ///< PARAM-8 (relative)
inline constexpr double chord_tolerance = 1e-9;        ///< PARAM-10
inline constexpr double geometry_tolerance = 1e-9;     ///< PARAM-11 (relative to T's bounding box)

/// PARAM-1 for a file that parse_param accepted: passed, with the number of records read. (A file
/// that breaks the grammar is refused by the reader with InvalidInput and never gets here.)
CheckResult grammar_check(const ParamFile& file);

/// Checks `file` against PARAM-2..10 of spec/param.md, and PARAM-11 against `input_mesh` when it
/// is not null. Every check runs unless one it relies on failed; each counts its failures and
/// names the first one.
/// \pre input_mesh, when given, is a valid mesh (built by build_trimesh; it may have boundary and
///      several components).
/// \post never throws InvalidInput for any file: a broken file gives failed checks. Runs in time
///       O(size of the file · log), plus O(|T| log |T|) with an input mesh.
/// PARAM-11's distances of T′'s vertices to T are computed in parallel on `executor`
/// (default_executor() when null); the report is the same on any number of threads.
///
/// `paper`: judge PARAM-10 (chord length, the paper's own boundary map, §4). Without it PARAM-10 is
/// reported (`info` when it does not hold) and a homeomorphism with another boundary map is valid.
VerifyReport verify(const ParamFile& file, const TriMesh* input_mesh, Executor* executor = nullptr, bool paper = false);

namespace detail {
struct InputSide;
}

/// PARAM-11's side of an input mesh T alone — its tolerance, its area, and the grids over its
/// faces and boundary edges — prepared once. It then serves every file verified against T, and
/// can be made before a file exists (fhr run prepares it beside §2's decimation, which runs on one
/// thread). Read-only once made: concurrent verify calls may share it.
class PreparedInput {
public:
    /// \pre T is a valid mesh (as for verify), kept alive and unchanged while this object is used.
    explicit PreparedInput(const TriMesh& T);
    ~PreparedInput();
    PreparedInput(PreparedInput&&) noexcept;
    PreparedInput& operator=(PreparedInput&&) noexcept;
    const TriMesh& mesh() const { return *mesh_; }

private:
    friend VerifyReport verify(const ParamFile&, const PreparedInput&, Executor*, bool);
    const TriMesh* mesh_;
    std::unique_ptr<detail::InputSide> side_;
};

/// verify(file, &input.mesh(), executor), the same report, with T's side already prepared.
VerifyReport verify(const ParamFile& file, const PreparedInput& input, Executor* executor = nullptr,
                    bool paper = false);

}  // namespace fhr::exchange
