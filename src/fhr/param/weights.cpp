// FHR §4 — convex-combination weights λ_vw (see weights.hpp for the formulas and sources, and
// paper_notes/parameterization.md for the decisions at degenerate and sharp rings).
#include <fhr/param/weights.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>

#include <fhr/core/errors.hpp>

namespace fhr::param {
namespace {

constexpr double pi = std::numbers::pi;

// The 3-D angle between u and v in [0, π], atan2 form (accurate for angles near 0 and π).
double angle(const Vec3& u, const Vec3& v) { return std::atan2(u.cross(v).norm(), u.dot(v)); }

// tan(θ/2) for θ = ∠(u, v) without forming θ: |u×v| / (|u||v| + u·v), or, when u·v < 0 would make
// that denominator cancel, (|u||v| − u·v) / |u×v| (the two are equal: their product of
// numerators equals the product of denominators, |u|²|v|² − (u·v)² = |u×v|²).
double tan_half_angle(const Vec3& u, const Vec3& v) {
    const double s = u.cross(v).norm(), uv = u.norm() * v.norm(), c = u.dot(v);
    return c >= 0 ? s / (uv + c) : (uv - c) / s;
}

// Floater 1997 §4 (see weights.hpp). Angles are taken as differences of the polar angles φ
// rather than from the planar points, so each sign below is decided by an angle comparison.
std::vector<double> shape_preserving(const Vec3& p, std::span<const Vec3> ring) {
    const std::size_t d = ring.size();
    std::vector<double> r(d), theta(d);
    double total = 0;
    for (std::size_t k = 0; k < d; ++k) {
        const Vec3 u = ring[k] - p, v = ring[(k + 1) % d] - p;
        r[k] = u.norm();
        theta[k] = angle(u, v);
        total += theta[k];
    }
    // φ_0 = 0 ≤ φ_1 ≤ … ≤ φ_{d−1} < φ_d = 2π (the last one closes the ring exactly).
    std::vector<double> phi(d + 1);
    phi[0] = 0;
    for (std::size_t k = 1; k < d; ++k) phi[k] = phi[k - 1] + 2 * pi * theta[k - 1] / total;
    phi[d] = 2 * pi;

    std::vector<double> mu(d, 0.0);
    for (std::size_t k = 0; k < d; ++k) {
        // The ray from q_k through the origin has direction angle φ_k + π. Choose l with
        // φ_l ≤ φ_k + π < φ_{l+1} (mod 2π): half-open, so that when the ray passes exactly
        // through a vertex q_l (the origin on the segment [q_k, q_l]; e.g. every even regular
        // ring) the choice is unique; both candidate triangles give the same coordinates there,
        // with a zero at the unshared vertex.
        const double target = phi[k] < pi ? phi[k] + pi : phi[k] - pi;
        const std::size_t l =
            static_cast<std::size_t>(std::upper_bound(phi.begin(), phi.begin() + d, target) - phi.begin()) - 1;
        const std::size_t l1 = (l + 1) % d;
        if (l == k || l1 == k) return {};  // a scaled angle ≥ π: the origin is not inside; no weights
        // Barycentric coordinates of the origin in (q_k, q_l, q_{l+1}) from the signed areas
        // det(q_i, q_j) = r_i r_j sin(φ_j − φ_i):
        //   A_k = det(q_l, q_{l+1}), A_l = det(q_{l+1}, q_k), A_{l+1} = det(q_k, q_l).
        // With δ1 = φ_l − φ_k and δ2 = φ_{l+1} − φ_k (mod 2π), the choice of l gives
        // 0 < δ1 ≤ π < δ2 < 2π and δ2 − δ1 = φ_{l+1} − φ_l ∈ (0, π), so A_k > 0, A_l > 0 and
        // A_{l+1} ≥ 0 in exact arithmetic; the clamp only removes round-off of a sine at π.
        const double delta1 = l > k ? phi[l] - phi[k] : phi[l] + 2 * pi - phi[k];
        const double delta2 = l + 1 > k ? phi[l + 1] - phi[k] : phi[l + 1] + 2 * pi - phi[k];
        const double a_k = r[l] * r[l1] * std::sin(phi[l + 1] - phi[l]);
        const double a_l = std::max(0.0, -r[l1] * r[k] * std::sin(delta2));
        const double a_l1 = std::max(0.0, r[k] * r[l] * std::sin(delta1));
        const double area = a_k + a_l + a_l1;
        mu[k] += a_k / area;
        mu[l] += a_l / area;
        mu[l1] += a_l1 / area;
    }
    // Every μ_k ≥ A_k / area > 0 from its own term, so the average stays positive.
    return mu;
}

// Floater 2003, eq. (3.1), with the 3-D angles at p.
std::vector<double> mean_value(const Vec3& p, std::span<const Vec3> ring) {
    const std::size_t d = ring.size();
    std::vector<double> t(d), w(d);
    for (std::size_t k = 0; k < d; ++k) t[k] = tan_half_angle(ring[k] - p, ring[(k + 1) % d] - p);
    for (std::size_t k = 0; k < d; ++k) w[k] = (t[(k + d - 1) % d] + t[k]) / (ring[k] - p).norm();
    return w;
}

}  // namespace

std::string_view name(Weights kind) {
    switch (kind) {
        case Weights::shape_preserving: return "shape-preserving";
        case Weights::mean_value: return "mean-value";
        case Weights::uniform: return "uniform";
    }
    return "?";
}

Weights parse_weights(std::string_view text) {
    for (Weights w : {Weights::shape_preserving, Weights::mean_value, Weights::uniform})
        if (text == name(w)) return w;
    throw InvalidInput("unknown weights '" + std::string(text) +
                       "' (expected shape-preserving, mean-value or uniform)");
}

std::vector<double> one_ring_weights(Weights kind, const Vec3& p, std::span<const Vec3> ring, std::uint32_t vertex) {
    const std::size_t d = ring.size();
    if (d < 3)
        throw InvalidInput("patch: vertex " + std::to_string(vertex) + " is interior with " + std::to_string(d) +
                           " neighbours (an interior vertex of a triangulated disk has at least 3)");
    std::vector<double> w;
    switch (kind) {
        case Weights::shape_preserving: w = shape_preserving(p, ring); break;
        case Weights::mean_value: w = mean_value(p, ring); break;
        case Weights::uniform: w.assign(d, 1.0); break;
    }
    // MAP-2: strictly positive, finite, sum one. Theorem (Floater 1997, 2003): for a
    // non-degenerate ring both constructions give positive weights; a failure here means a
    // degenerate ring (a neighbour at p, or a straight angle at p in a flat ring).
    double sum = 0;
    for (double x : w) sum += x;
    bool ok = w.size() == d && std::isfinite(sum) && sum > 0;
    for (double& x : w) {
        x /= sum;
        ok = ok && std::isfinite(x) && x > 0;
    }
    double check = 0;
    for (double x : w) check += x;
    ok = ok && std::abs(check - 1) <= 2 * static_cast<double>(d) * std::numeric_limits<double>::epsilon();
    if (!ok) {
        std::ostringstream s;
        s.precision(17);
        s << "MAP-2: " << name(kind) << " weights of interior vertex " << vertex << " (valence " << d
          << ") are not all finite and positive with sum 1";
        if (w.size() == d) {
            s << ":";
            for (double x : w) s << ' ' << x;
        } else {
            s << ": its 1-ring leaves no polar-map triangle around it (a straight angle at the vertex)";
        }
        throw NumericalFailure(s.str());
    }
    return w;
}

}  // namespace fhr::param
