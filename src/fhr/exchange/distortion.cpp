// FHR exchange — DIST-1..9 of spec/distortion.md. The singular values come from the two Gram
// matrices, so an image given in 3D (a domain triangle in its own plane) and one given in UV are
// measured by the same few lines, with no frame to choose.
#include <fhr/exchange/distortion.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <numeric>
#include <utility>

#include <fhr/core/detail/predicates.hpp>

namespace fhr::exchange {

namespace {

/// The Gram matrix [a·a, a·b; a·b, b·b] of a triangle's two edge vectors, as (E, F, G).
struct Gram {
    double e, f, g;
};

Gram gram(const Vec3& a, const Vec3& b) { return {a.dot(a), a.dot(b), b.dot(b)}; }

}  // namespace

FaceStretch face_stretch(const Vec3& q0, const Vec3& q1, const Vec3& q2, const Vec3& p0, const Vec3& p1,
                         const Vec3& p2) {
    // DIST-1: M = G_Q⁻¹ G_P, its eigenvalues σ₁², σ₂².
    const Gram gq = gram(q1 - q0, q2 - q0), gp = gram(p1 - p0, p2 - p0);
    // Each area from the cross product: it keeps its accuracy where det G = |a|²|b|² − (a·b)² cancels.
    FaceStretch s;
    s.image_area = 0.5 * (q1 - q0).cross(q2 - q0).norm();
    s.surface_area = 0.5 * (p1 - p0).cross(p2 - p0).norm();
    // DIST-2: exactly degenerate triangles (a rounded area can be 1e-16 for three collinear points).
    if (collinear(q0, q1, q2) || collinear(p0, p1, p2) || !(s.image_area > 0) || !(s.surface_area > 0)) return s;
    // Each triangle in a frame of its own plane: edge a along x, edge b at (a·b/|a|, 2A/|a|). The
    // map's matrix J = P Q⁻¹ is then upper triangular, and σ₁ = √(E² + H²) + √(F² + G²) with
    // E, F = (j₁₁ ± j₂₂)/2, G = −H = j₁₂/2: a sum of two non-negative terms, accurate where σ₁ ≈ σ₂
    // (where √(tr² − 4 det) of M = JᵀJ would lose half the digits to cancellation).
    const double qa = std::sqrt(gq.e), qbx = gq.f / qa, qby = 2 * s.image_area / qa;
    const double pa = std::sqrt(gp.e), pbx = gp.f / pa, pby = 2 * s.surface_area / pa;
    const double j11 = pa / qa, j12 = (pbx - j11 * qbx) / qby, j22 = pby / qby;
    const double root_d = s.surface_area / s.image_area;  // σ₁σ₂ = √det M
    s.sigma1 = std::hypot((j11 + j22) / 2, j12 / 2) + std::hypot((j11 - j22) / 2, j12 / 2);
    s.sigma2 = root_d / s.sigma1;
    s.degenerate = !(std::isfinite(s.sigma1) && std::isfinite(s.sigma2) && s.sigma2 > 0);
    return s;
}

namespace {

/// DIST-9 for several p (ascending) with one sort of (value, weight) pairs.
std::vector<double> weighted_percentiles(std::vector<std::pair<double, double>> sorted,
                                         std::initializer_list<double> ps) {
    std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    double total = 0;
    for (const auto& [value, weight] : sorted) total += weight;
    std::vector<double> out;
    double below = 0;
    std::size_t i = 0;
    for (const double p : ps) {
        while (i < sorted.size() && below + sorted[i].second < p * total) below += sorted[i++].second;
        out.push_back(sorted[std::min(i, sorted.size() - 1)].first);  // rounding of the sum: p = 1 may run past the end
    }
    return out;
}

}  // namespace

double weighted_percentile(const std::vector<double>& values, const std::vector<double>& weights, double p) {
    std::vector<std::pair<double, double>> pairs(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) pairs[i] = {values[i], weights[i]};
    return weighted_percentiles(std::move(pairs), {p}).front();
}

Distortion summarize(const std::vector<FaceStretch>& faces) {
    return summarize(faces.size(), [&](std::size_t i) { return faces[i]; });
}

Distortion summarize(std::size_t faces, const std::function<FaceStretch(std::size_t)>& face) {
    Distortion d;
    d.faces = faces;
    double image = 0, surface = 0;
    for (std::size_t i = 0; i < faces; ++i) {
        const FaceStretch f = face(i);
        if (f.degenerate) {
            ++d.degenerate;
            continue;
        }
        image += f.image_area;
        surface += f.surface_area;
    }
    if (d.degenerate == d.faces) return d;
    // DIST-3: images scaled by k = √(ΣA_P / ΣA_Q): σ′ = σ / k, weight A = k²·A_Q.
    const double k2 = surface / image, k = std::sqrt(k2);
    double weight = 0, l2 = 0, dirichlet = 0, linf = 0, aniso_max = 0, area_max = 0;
    std::vector<std::pair<double, double>> anisotropy, area;  // (value, weight) of each face
    anisotropy.reserve(faces - d.degenerate);
    area.reserve(faces - d.degenerate);
    for (std::size_t i = 0; i < faces; ++i) {
        const FaceStretch f = face(i);
        if (f.degenerate) continue;
        const double a = k2 * f.image_area, s1 = f.sigma1 / k, s2 = f.sigma2 / k;
        weight += a;
        l2 += a * (s1 * s1 + s2 * s2) / 2;
        dirichlet += a * (s1 * s1 + s2 * s2 + 1 / (s1 * s1) + 1 / (s2 * s2));
        linf = std::max(linf, s1);
        const double ratio = f.sigma1 / f.sigma2, scale = s1 * s2, distortion = std::max(scale, 1 / scale);
        aniso_max = std::max(aniso_max, ratio);
        area_max = std::max(area_max, distortion);
        if (ratio > 10) ++d.anisotropy_above_10;
        anisotropy.emplace_back(ratio, a);
        area.emplace_back(distortion, a);
    }
    d.l2_stretch = std::sqrt(l2 / weight);
    d.linf_stretch = linf;
    d.symmetric_dirichlet = dirichlet / weight;
    const std::vector<double> p = weighted_percentiles(std::move(anisotropy), {0.5, 0.99, 0.999});
    d.anisotropy_p50 = p[0];
    d.anisotropy_p99 = p[1];
    d.anisotropy_p999 = p[2];
    d.anisotropy_max = aniso_max;
    d.area_distortion_p99 = weighted_percentiles(std::move(area), {0.99}).front();
    d.area_distortion_max = area_max;
    return d;
}

}  // namespace fhr::exchange
