// FHR exchange — the distortion of a piecewise-linear map, defined once (spec/distortion.md
// DIST-*): for each face the affine map from its image (UV, or a domain triangle laid flat in its
// own shape) onto its surface triangle, its singular values after Sander et al.'s (2001)
// normalisation, and the figures every kind of map is reported with — L2 and L∞ stretch, the
// symmetric Dirichlet energy, the anisotropy σ₁/σ₂ and the area distortion with their
// area-weighted percentiles. Beyond the paper, which measures nothing of its map's quality.
//
// Part of the oracle: it shares no code with the parameterization it measures.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <fhr/core/polygon_soup.hpp>

namespace fhr::exchange {

/// DIST-1: one face's affine map from its image triangle q onto its surface triangle p.
struct FaceStretch {
    double sigma1 = 0, sigma2 = 0;            ///< singular values, σ₁ ≥ σ₂, before normalisation
    double image_area = 0, surface_area = 0;  ///< unsigned areas A_Q, A_P
    bool degenerate = true;                   ///< DIST-2: left out of every figure
};

/// DIST-1 for image corners q (3D: a 2D image has z = 0) and surface corners p, corner k onto corner k.
FaceStretch face_stretch(const Vec3& q0, const Vec3& q1, const Vec3& q2, const Vec3& p0, const Vec3& p1,
                         const Vec3& p2);

/// DIST-4..8; every value is empty (JSON null) when every face is degenerate.
struct Distortion {
    std::uint64_t faces = 0;       ///< faces measured, degenerate ones included
    std::uint64_t degenerate = 0;  ///< DIST-2
    std::optional<double> l2_stretch, linf_stretch, symmetric_dirichlet;
    std::optional<double> anisotropy_p50, anisotropy_p99, anisotropy_p999, anisotropy_max;
    std::uint64_t anisotropy_above_10 = 0;
    std::optional<double> area_distortion_p99, area_distortion_max;
};

/// DIST-3..9 over the faces' stretches (any order). Cost: O(n log n) (the percentiles sort).
Distortion summarize(const std::vector<FaceStretch>& faces);

/// The same over `faces` stretches given one by one: face(i) is called twice for each i (the
/// normalisation needs the totals first), so that no stretch is stored — at 10⁶ faces of T′ that
/// is 40 bytes a face less at the oracle's peak; the percentiles hold (value, weight) pairs.
Distortion summarize(std::size_t faces, const std::function<FaceStretch(std::size_t)>& face);

/// DIST-9: the p-th weighted percentile of `values` with weights `weights` (both as long; p in
/// [0, 1]; the total weight positive): the smallest value whose faces at or below it weigh at
/// least p of the total. \pre values.size() == weights.size() > 0.
double weighted_percentile(const std::vector<double>& values, const std::vector<double>& weights, double p);

}  // namespace fhr::exchange
