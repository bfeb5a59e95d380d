// Beyond the paper (§4) — a vertex's MIPS step (see mips.hpp).
#include <fhr/param/detail/mips.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fhr::param::detail {

MipsTerm mips_term(const Mat2& j, const Vec2& u, const Vec2& g, double area) {
    MipsTerm t;
    t.g = g;
    t.c = j - u * g.transpose();
    Mat2 adj;
    adj << t.c(1, 1), -t.c(0, 1), -t.c(1, 0), t.c(0, 0);
    t.dl = adj.transpose() * g;
    t.l0 = t.c.determinant();
    t.area = area;
    return t;
}

namespace {

// Symmetric `a` with its negative eigenvalues set to 0: cyclic Jacobi rotations diagonalise it.
Eigen::Matrix4d nonnegative_part(Eigen::Matrix4d a) {
    Eigen::Matrix4d v = Eigen::Matrix4d::Identity();
    for (int sweep = 0; sweep < 32; ++sweep) {
        double off = 0;
        for (int p = 0; p < 4; ++p)
            for (int q = p + 1; q < 4; ++q) off += a(p, q) * a(p, q);
        if (!(off > 1e-24 * a.squaredNorm())) break;
        for (int p = 0; p < 4; ++p)
            for (int q = p + 1; q < 4; ++q) {
                Eigen::JacobiRotation<double> r;
                if (!r.makeJacobi(a, p, q)) continue;
                a.applyOnTheLeft(p, q, r.adjoint());
                a.applyOnTheRight(p, q, r);
                v.applyOnTheRight(p, q, r);
            }
    }
    return v * a.diagonal().cwiseMax(0.0).asDiagonal() * v.transpose();
}

}  // namespace

MipsFace mips_face(const Mat2& j) {
    using Vec4 = Eigen::Vector4d;
    using Mat4 = Eigen::Matrix4d;
    const Vec4 x(j(0, 0), j(0, 1), j(1, 0), j(1, 1));
    const double q = x.squaredNorm(), l = j.determinant(), m = q / l;
    const Vec4 dl(x(3), -x(2), -x(1), x(0));  // ∇ det J
    Mat4 hl = Mat4::Zero();                   // ∇² det J
    hl(0, 3) = hl(3, 0) = 1;
    hl(1, 2) = hl(2, 1) = -1;
    const Vec4 dm = 2 * x / l - q * dl / (l * l);
    const Mat4 hm = 2 * Mat4::Identity() / l - 2 * (x * dl.transpose() + dl * x.transpose()) / (l * l) +
                    2 * q * dl * dl.transpose() / (l * l * l) - q * hl / (l * l);
    return {m * m, 2 * m * dm, nonnegative_part(2 * (dm * dm.transpose() + m * hm))};
}

template <int K>
double mips_energy(std::span<const MipsRing<K>> rings, const Eigen::Matrix<double, K, 1>& x) {
    double e = 0;
    for (const MipsRing<K>& ring : rings) {
        const Vec2 u = ring.u0 + ring.m * x;
        for (const MipsTerm& t : ring.terms) {
            const double l = t.l0 + t.dl.dot(u);
            if (!(l > 0)) return std::numeric_limits<double>::infinity();
            const double m = (t.c + u * t.g.transpose()).squaredNorm() / l;
            e += t.area * m * m;
        }
    }
    return e;
}

namespace {

// The largest m_f over the rings at x.
template <int K>
double largest(std::span<const MipsRing<K>> rings, const Eigen::Matrix<double, K, 1>& x) {
    double most = 0;
    for (const MipsRing<K>& ring : rings) {
        const Vec2 u = ring.u0 + ring.m * x;
        for (const MipsTerm& t : ring.terms)
            most = std::max(most, (t.c + u * t.g.transpose()).squaredNorm() / (t.l0 + t.dl.dot(u)));
    }
    return most;
}

}  // namespace

template <int K>
Eigen::Matrix<double, K, 1> mips_descend(std::span<const MipsRing<K>> rings, int steps, double cap) {
    using VecK = Eigen::Matrix<double, K, 1>;
    using MatK = Eigen::Matrix<double, K, K>;
    VecK x = VecK::Zero();
    double now = mips_energy(rings, x);
    if (!std::isfinite(now)) return x;
    const double ceiling = std::max(largest(rings, x), cap);
    auto fine = [&](const VecK& y, double e) { return e < now && largest(rings, y) <= ceiling; };
    for (int step = 0; step < steps; ++step) {
        VecK grad = VecK::Zero();
        MatK hess = MatK::Zero();
        for (const MipsRing<K>& ring : rings) {
            const Vec2 u = ring.u0 + ring.m * x;
            Vec2 g2 = Vec2::Zero();
            Mat2 h2 = Mat2::Zero();
            for (const MipsTerm& t : ring.terms) {
                const Mat2 j = t.c + u * t.g.transpose();
                const double q = j.squaredNorm(), l = t.l0 + t.dl.dot(u), m = q / l;
                const Vec2 dq = 2 * j * t.g;
                const Vec2 dm = dq / l - q * t.dl / (l * l);
                const Mat2 hm = 2 * t.g.squaredNorm() * Mat2::Identity() / l -
                                (dq * t.dl.transpose() + t.dl * dq.transpose()) / (l * l) +
                                2 * q * t.dl * t.dl.transpose() / (l * l * l);
                g2 += t.area * 2 * m * dm;  // (m²)′ = 2m m′, (m²)″ = 2m m″ + 2 m′m′ᵀ
                h2 += t.area * 2 * (m * hm + dm * dm.transpose());
            }
            grad += ring.m.transpose() * g2;
            hess += ring.m.transpose() * h2 * ring.m;
        }
        const VecK d = -hess.ldlt().solve(grad);
        if (!d.allFinite() || !(grad.dot(d) < 0)) break;
        // The least t > 0 at which a face's det J (affine in t) reaches 0.
        double bound = std::numeric_limits<double>::infinity();
        for (const MipsRing<K>& ring : rings) {
            const Vec2 u = ring.u0 + ring.m * x, du = ring.m * d;
            for (const MipsTerm& t : ring.terms) {
                const double slope = t.dl.dot(du);
                if (slope < 0) bound = std::min(bound, -(t.l0 + t.dl.dot(u)) / slope);
            }
        }
        double s = std::min(1.0, 0.9 * bound), e = mips_energy(rings, VecK(x + s * d));
        for (int halve = 0; halve < 30 && !fine(VecK(x + s * d), e); ++halve)
            e = mips_energy(rings, VecK(x + (s *= 0.5) * d));
        if (!fine(VecK(x + s * d), e)) break;
        x += s * d;
        const double gain = now - e;
        now = e;
        if (gain < 1e-12 * now) break;
    }
    return x;
}

template double mips_energy<1>(std::span<const MipsRing<1>>, const Eigen::Matrix<double, 1, 1>&);
template double mips_energy<2>(std::span<const MipsRing<2>>, const Eigen::Matrix<double, 2, 1>&);
template Eigen::Matrix<double, 1, 1> mips_descend<1>(std::span<const MipsRing<1>>, int, double);
template Eigen::Matrix<double, 2, 1> mips_descend<2>(std::span<const MipsRing<2>>, int, double);

}  // namespace fhr::param::detail
