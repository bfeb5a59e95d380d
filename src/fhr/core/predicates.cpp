// FHR core — exact orientation predicates (see predicates.hpp for the method and its source).
#include <fhr/core/detail/predicates.hpp>

#include <cmath>
#include <limits>

#include <gmpxx.h>

namespace fhr {
namespace {

constexpr double eps = std::numeric_limits<double>::epsilon() / 2;  // unit round-off 2^-53
// Shewchuk 1997, §4.3: |det − fl(det)| <= bound · permanent for the naive expansion.
constexpr double ccw_bound = (3.0 + 16.0 * eps) * eps;
constexpr double o3d_bound = (7.0 + 56.0 * eps) * eps;

int sign_of(const mpq_class& q) { return sgn(q); }

// The relative bounds hold only without overflow and underflow: products below 2^-1022 lose
// relative accuracy, so a tiny or non-finite permanent always goes to the exact path.
constexpr double smallest_trusted_permanent = 1e-200;

bool decided_by_filter(double det, double permanent, double bound) {
    return std::isfinite(permanent) && permanent >= smallest_trusted_permanent && std::abs(det) > bound * permanent;
}

// Error-free transformations, exact in round-to-nearest when nothing overflows or underflows:
// a + b = s + e (Knuth's TwoSum) and a · b = p + e (Dekker's TwoProduct, Veltkamp's splitting).
void two_sum(double a, double b, double& s, double& e) {
    s = a + b;
    const double bv = s - a, av = s - bv;
    e = (a - av) + (b - bv);
}

void two_product(double a, double b, double& p, double& e) {
    constexpr double splitter = 134217729.0;  // 2^27 + 1
    p = a * b;
    const double ca = splitter * a, ah = ca - (ca - a), al = a - ah;
    const double cb = splitter * b, bh = cb - (cb - b), bl = b - bh;
    e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
}

/// Coordinates for which the expansion below is exact: 0, or a magnitude in [2^-450, 2^450]
/// (every product and its rounding error then lies far inside the normal range).
bool expansion_safe(double x) {
    const double m = std::abs(x);
    return m == 0 || (m >= 0x1.0p-450 && m <= 0x1.0p450);
}

/// The exact sign of orient2d without rationals (Shewchuk 1997, §2): the determinant is the sum
/// ax·by − ax·cy − cx·by − ay·bx + ay·cx + bx·cy (cx·cy cancels); each product is split exactly
/// into two doubles and the twelve are summed exactly by Grow-Expansion into a nonoverlapping
/// expansion, whose sign is that of its largest non-zero component. \pre expansion_safe for
/// every coordinate.
int orient2d_expansion(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    const double factors[6][3] = {{a.x(), b.y(), 1},  {a.x(), c.y(), -1}, {c.x(), b.y(), -1},
                                  {a.y(), b.x(), -1}, {a.y(), c.x(), 1},  {b.x(), c.y(), 1}};
    double expansion[12];
    int n = 0;
    const auto grow = [&](double q) {
        for (int i = 0; i < n; ++i) two_sum(q, expansion[i], q, expansion[i]);
        expansion[n++] = q;
    };
    for (const auto& f : factors) {
        double p, e;
        two_product(f[0], f[1], p, e);
        grow(f[2] * p);
        grow(f[2] * e);
    }
    for (int i = n - 1; i >= 0; --i)
        if (expansion[i] != 0) return expansion[i] > 0 ? 1 : -1;
    return 0;
}

int orient2d_exact(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    if (expansion_safe(a.x()) && expansion_safe(a.y()) && expansion_safe(b.x()) && expansion_safe(b.y()) &&
        expansion_safe(c.x()) && expansion_safe(c.y()))
        return orient2d_expansion(a, b, c);
    const mpq_class ax(a.x()), ay(a.y());
    const mpq_class det =
        (mpq_class(b.x()) - ax) * (mpq_class(c.y()) - ay) - (mpq_class(b.y()) - ay) * (mpq_class(c.x()) - ax);
    return sign_of(det);
}

// The filtered sign of orient2d: ±1 when the floating-point value is certain, 0 when undecided.
int orient2d_filtered(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    const double detleft = (a.x() - c.x()) * (b.y() - c.y());
    const double detright = (a.y() - c.y()) * (b.x() - c.x());
    const double det = detleft - detright;
    const double permanent = std::abs(detleft) + std::abs(detright);
    return decided_by_filter(det, permanent, ccw_bound) ? (det > 0 ? 1 : -1) : 0;
}

}  // namespace

int orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    const int s = orient2d_filtered(a, b, c);
    return s != 0 ? s : orient2d_exact(a, b, c);
}

int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
    const Eigen::Vector3d ad = a - d, bd = b - d, cd = c - d;
    const double bdxcdy = bd.x() * cd.y(), cdxbdy = cd.x() * bd.y();
    const double cdxady = cd.x() * ad.y(), adxcdy = ad.x() * cd.y();
    const double adxbdy = ad.x() * bd.y(), bdxady = bd.x() * ad.y();
    const double det = ad.z() * (bdxcdy - cdxbdy) + bd.z() * (cdxady - adxcdy) + cd.z() * (adxbdy - bdxady);
    const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(ad.z()) +
                             (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bd.z()) +
                             (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cd.z());
    if (decided_by_filter(det, permanent, o3d_bound)) return det > 0 ? 1 : -1;
    auto q = [](const Eigen::Vector3d& p, int i) { return mpq_class(p[i]); };
    mpq_class m[3][3];
    const Eigen::Vector3d* rows[3] = {&a, &b, &c};
    for (int r = 0; r < 3; ++r)
        for (int i = 0; i < 3; ++i) m[r][i] = q(*rows[r], i) - q(d, i);
    const mpq_class exact = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                            m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                            m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    return sign_of(exact);
}

bool collinear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    // The cross product vanishes iff its three components do, i.e. iff the projections of the
    // triangle onto the three coordinate planes are all degenerate.
    auto drop = [](const Eigen::Vector3d& p, int axis) {
        return Eigen::Vector2d(p[(axis + 1) % 3], p[(axis + 2) % 3]);
    };
    // First the cheap filtered signs: one certain non-zero component settles it. (Axis-aligned
    // faces have an exactly zero component, which the filter can never decide.)
    for (int axis = 0; axis < 3; ++axis)
        if (orient2d_filtered(drop(a, axis), drop(b, axis), drop(c, axis)) != 0) return false;
    for (int axis = 0; axis < 3; ++axis)
        if (orient2d_exact(drop(a, axis), drop(b, axis), drop(c, axis)) != 0) return false;
    return true;
}

}  // namespace fhr
