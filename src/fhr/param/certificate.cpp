// FHR §4 Proposition 1 — the injectivity certificate of one patch (see certificate.hpp).
#include <fhr/param/certificate.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include <fhr/core/detail/predicates.hpp>

namespace fhr::param {
namespace {

using Point = Eigen::Vector2d;

Point plane_point(const std::array<double, 3>& beta) { return {beta[1], beta[2]}; }

// Neumaier's compensated sum (Neumaier 1974): the error is a few rounding errors of the total,
// independent of the number of terms.
class CompensatedSum {
public:
    void add(double x) {
        const double t = sum_ + x;
        compensation_ += std::abs(sum_) >= std::abs(x) ? (sum_ - t) + x : (x - t) + sum_;
        sum_ = t;
    }
    double value() const { return sum_ + compensation_; }

private:
    double sum_ = 0, compensation_ = 0;
};

// The smallest angle of a sequence of triangles, in degrees (atan2 form: atan2(|u×w|, u·w) at
// each corner). A corner's atan2 is computed only where it could lower the minimum. It cannot
// when u·w < 0 (above 90°: never a triangle's smallest), nor when |u×w|² > t·(u·w)·(u·w), once
// the minimum is acute, with t = tan²(minimum) enlarged by a relative 2·10⁻⁶ and raised to 10⁻²⁹⁰
// if below (a larger t only skips fewer corners): t·(u·w) is then a normal double within an ulp,
// unless u·w < 10⁻¹⁷, where the whole bound rounds to 0 and a positive |u×w|² is far above it;
// the bound is within two ulps when normal, and when subnormal is rounded once to the grid that
// |u×w|² lies on, so exceeding it exceeds the exact bound. The margin covers these ulps and those
// of tan and atan2: the minimum is exactly the one of all corners. (Images rounded to one point
// give u·w = 0 and |u×w| = 0: computed, atan2(0, 0) = 0.)
class SmallestAngle {
public:
    void add(const Vec3& a, const Vec3& b, const Vec3& c) {
        const Vec3 p[3] = {a, b, c};
        for (int k = 0; k < 3; ++k) {
            const Vec3 u = p[(k + 1) % 3] - p[k], w = p[(k + 2) % 3] - p[k];
            const double cross2 = u.cross(w).squaredNorm(), dot = u.dot(w);
            if (dot < 0 || cross2 > tan2_ * dot * dot) continue;  // ∞ · 0 is NaN: not skipped
            const double angle = std::atan2(std::sqrt(cross2), dot) * 180 / std::numbers::pi;
            if (angle < degrees_) {
                degrees_ = angle;
                if (angle < 89) {
                    const double tan = std::tan(angle * std::numbers::pi / 180) * (1 + 1e-6);
                    tan2_ = std::max(tan * tan, 1e-290);
                }
            }
        }
    }
    double degrees() const { return degrees_; }

private:
    double degrees_ = 180, tan2_ = std::numeric_limits<double>::infinity();
};

std::string vertex_text(const std::array<double, 3>& b) {
    std::ostringstream s;
    s.precision(17);
    s << '(' << b[0] << ", " << b[1] << ", " << b[2] << ')';
    return s.str();
}

}  // namespace

Certificate certify(const Disk& disk, const PatchMap& psi, const std::array<Vec3, 3>& domain_triangle) {
    Certificate cert;
    auto fail = [&](const char* invariant, Element element, std::int64_t index, const std::string& what) {
        if (!cert.first_failure) cert.first_failure = Violation{invariant, element, index, what};
    };
    if (const auto broken = disk_violation(disk)) {
        cert.first_failure = broken;
        return cert;
    }
    const std::size_t nv = disk.positions.size();
    if (psi.beta.size() != nv) {
        fail("MAP-8", Element::whole, -1,
             std::to_string(psi.beta.size()) + " images for " + std::to_string(nv) + " vertices");
        return cert;
    }
    // MAP-6: finite barycentric triples. On the 2^-53 grid they sum to 1 exactly; any producer
    // that rounds once per addition stays within 2ε.
    for (std::size_t v = 0; v < nv; ++v) {
        const auto& b = psi.beta[v];
        const double sum = b[0] + b[1] + b[2];
        if (!std::isfinite(sum) || std::abs(sum - 1) > 2 * std::numeric_limits<double>::epsilon())
            fail("MAP-6", Element::vertex, static_cast<std::int64_t>(v),
                 "vertex " + std::to_string(v) + " has β " + vertex_text(b) + ", not summing to 1");
    }
    if (cert.first_failure) return cert;

    // Orientation: Theorem (degree argument, certificate.hpp) needs every sign exactly.
    cert.triangles = disk.triangles.size();
    SmallestAngle smallest;
    CompensatedSum area;
    for (std::size_t t = 0; t < disk.triangles.size(); ++t) {
        const auto& f = disk.triangles[t];
        const Point a = plane_point(psi.beta[f[0]]), b = plane_point(psi.beta[f[1]]), c = plane_point(psi.beta[f[2]]);
        area.add(0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x())));
        if (orient2d(a, b, c) <= 0) {
            if (cert.flipped_triangles++ == 0)
                fail("MAP-8", Element::face, static_cast<std::int64_t>(t),
                     "orientation: image of triangle " + std::to_string(t) + " (" + std::to_string(f[0]) + ", " +
                         std::to_string(f[1]) + ", " + std::to_string(f[2]) + ") is folded or degenerate");
            continue;
        }
        auto in_domain = [&](std::uint32_t v) {
            const auto& beta = psi.beta[v];
            return Vec3(beta[0] * domain_triangle[0] + beta[1] * domain_triangle[1] + beta[2] * domain_triangle[2]);
        };
        smallest.add(in_domain(f[0]), in_domain(f[1]), in_domain(f[2]));
    }
    cert.min_image_angle_degrees = cert.flipped_triangles > 0 ? 0 : smallest.degrees();

    // Boundary: side c runs from e_c to e_{c+1}; its parameter (β1 on side 0, β2 on side 1, −β2
    // on side 2) must increase strictly, every vertex lying exactly on the side's line.
    const Point corner[3] = {{0, 0}, {1, 0}, {0, 1}};
    const std::size_t n = disk.boundary.size();
    for (unsigned c = 0; c < 3; ++c) {
        const std::size_t first = disk.corners[c], last = c == 2 ? n : disk.corners[c + 1];
        double previous = -std::numeric_limits<double>::infinity();
        for (std::size_t p = first; p <= last; ++p) {
            const std::uint32_t u = disk.boundary[p % n];
            const auto& beta = psi.beta[u];
            const Point x = plane_point(beta);
            const double parameter = c == 0 ? x.x() : c == 1 ? x.y() : -x.y();
            std::string problem;
            if ((p == first && x != corner[c]) || (p == last && x != corner[(c + 1) % 3]))
                problem = "corner not on its triangle corner";
            else if (beta[(c + 2) % 3] != 0 || orient2d(corner[c], corner[(c + 1) % 3], x) != 0)
                problem = "not on side " + std::to_string(c);
            else if (!(parameter > previous))
                problem = "not strictly after the previous vertex along side " + std::to_string(c);
            previous = parameter;
            if (!problem.empty()) {
                ++cert.boundary_violations;
                fail("MAP-8", Element::boundary_position, static_cast<std::int64_t>(p % n),
                     "boundary: vertex " + std::to_string(u) + " at boundary position " + std::to_string(p % n) +
                         " with β " + vertex_text(beta) + ": " + problem);
            }
        }
    }

    // Area: the images tile the reference triangle of area 1/2.
    cert.image_area = area.value();
    if (!(std::abs(cert.image_area - 0.5) <= area_tolerance * 0.5)) {
        std::ostringstream s;
        s.precision(17);
        s << "area: the images cover area " << cert.image_area << ", not 1/2";
        fail("MAP-8", Element::whole, -1, s.str());
    }
    cert.passed = !cert.first_failure;
    return cert;
}

Certificate certify(const Disk& disk, const PatchMap& psi) {
    const std::array<Vec3, 3> equilateral{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, std::sqrt(3.0) / 2, 0)};
    return certify(disk, psi, equilateral);
}

}  // namespace fhr::param
