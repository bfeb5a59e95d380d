// Beyond the paper (§4) — a vertex's MIPS step (see mips.hpp).
#include <fhr/param/detail/mips.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fhr::param::detail {

Vec2 singular_values(const Mat2& j) {
    const double q = j.squaredNorm(), d = std::abs(j.determinant());
    const double s1 = 0.5 * (std::sqrt(q + 2 * d) + std::sqrt(std::max(q - 2 * d, 0.0)));
    return {s1, s1 > 0 ? d / s1 : 0.0};
}

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

MipsFace mips_face(const Mat2& j, double power) {
    // m_f depends on J through q = ‖J‖² and l = det J only. In J's singular frames, J = U Σ Vᵀ with
    // U, V rotations (det J > 0) and Σ = diag(s1, s2), the Hessian of m^p splits into the twist
    // U [[0, 1], [−1, 0]] Vᵀ / √2 (eigenvalue p m^(p−1) (2l − q) / l² ≤ 0: dropped), the flip
    // U [[0, 1], [1, 0]] Vᵀ / √2 (eigenvalue p m^(p−1) (2l + q) / l²) and a 2 × 2 block on
    // U diag(·, ·) Vᵀ (∇m lies in it: (m^p)″ = p m^(p−1) m″ + p (p − 1) m^(p−2) m′m′ᵀ).
    using Vec4 = Eigen::Vector4d;
    const double q = j.squaredNorm(), l = j.determinant(), m = q / l;
    Mat2 cof;  // ∇ det J
    cof << j(1, 1), -j(1, 0), -j(0, 1), j(0, 0);
    const Mat2 dm = (2 * j - m * cof) / l;
    MipsFace out;
    const double mp2 = std::pow(m, power - 2);  // m^(p−2)
    out.energy = mp2 * m * m;
    out.gradient = power * mp2 * m * Vec4(dm(0, 0), dm(0, 1), dm(1, 0), dm(1, 1));
    const Eigen::JacobiSVD<Mat2> svd(j, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Mat2 u = svd.matrixU(), v = svd.matrixV();
    if (u.determinant() < 0) {  // both reflections (det J > 0): both made rotations
        u.col(1) *= -1;
        v.col(1) *= -1;
    }
    const double s1 = svd.singularValues()(0), s2 = svd.singularValues()(1);
    auto mode = [&](const Mat2& b) {
        const Mat2 w = u * b * v.transpose();
        return Vec4(w(0, 0), w(0, 1), w(1, 0), w(1, 1));
    };
    // The block on diag(1, 0), diag(0, 1): p m^(p−2) ((p − 1) ∇m ∇mᵀ + m ∇²m) there, at J = Σ (where
    // cof = diag(s2, s1)).
    const Vec2 g((2 * s1 - m * s2) / l, (2 * s2 - m * s1) / l);
    Mat2 hm;
    hm(0, 0) = 2 / l - 4 * s1 * s2 / (l * l) + 2 * q * s2 * s2 / (l * l * l);
    hm(1, 1) = 2 / l - 4 * s1 * s2 / (l * l) + 2 * q * s1 * s1 / (l * l * l);
    hm(0, 1) = hm(1, 0) = -2 * q / (l * l) + 2 * q * s1 * s2 / (l * l * l) - q / (l * l);
    Eigen::SelfAdjointEigenSolver<Mat2> block;
    block.computeDirect(power * mp2 * ((power - 1) * g * g.transpose() + m * hm));
    const Vec4 flip = mode((Mat2() << 0, 1, 1, 0).finished()) / std::sqrt(2.0);
    out.hessian = power * mp2 * m * (2 * l + q) / (l * l) * flip * flip.transpose();
    for (int k = 0; k < 2; ++k) {
        const double lambda = block.eigenvalues()(k);
        if (!(lambda > 0)) continue;
        const Vec4 w = mode(Mat2(block.eigenvectors().col(k).asDiagonal()));
        out.hessian += lambda * w * w.transpose();
    }
    return out;
}

template <int K>
double mips_energy(std::span<const MipsRing<K>> rings, const Eigen::Matrix<double, K, 1>& x, double power) {
    double e = 0;
    for (const MipsRing<K>& ring : rings) {
        const Vec2 u = ring.u0 + ring.m * x;
        for (const MipsTerm& t : ring.terms) {
            const double l = t.l0 + t.dl.dot(u);
            if (!(l > 0)) return std::numeric_limits<double>::infinity();
            const double m = (t.c + u * t.g.transpose()).squaredNorm() / l;
            e += t.area * (power == 2 ? m * m : std::pow(m, power));
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
Eigen::Matrix<double, K, 1> mips_descend(std::span<const MipsRing<K>> rings, int steps, double cap, double power) {
    using VecK = Eigen::Matrix<double, K, 1>;
    using MatK = Eigen::Matrix<double, K, K>;
    VecK x = VecK::Zero();
    double now = mips_energy(rings, x, power);
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
                // (m^p)′ = p m^(p−1) m′, (m^p)″ = p m^(p−2) (m m″ + (p − 1) m′m′ᵀ)
                const double w = t.area * power * (power == 2 ? 1 : std::pow(m, power - 2));
                g2 += w * m * dm;
                h2 += w * (m * hm + (power - 1) * dm * dm.transpose());
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
        double s = std::min(1.0, 0.9 * bound), e = mips_energy(rings, VecK(x + s * d), power);
        for (int halve = 0; halve < 30 && !fine(VecK(x + s * d), e); ++halve)
            e = mips_energy(rings, VecK(x + (s *= 0.5) * d), power);
        if (!fine(VecK(x + s * d), e)) break;
        x += s * d;
        const double gain = now - e;
        now = e;
        if (gain < 1e-12 * now) break;
    }
    return x;
}

template double mips_energy<1>(std::span<const MipsRing<1>>, const Eigen::Matrix<double, 1, 1>&, double);
template double mips_energy<2>(std::span<const MipsRing<2>>, const Eigen::Matrix<double, 2, 1>&, double);
template Eigen::Matrix<double, 1, 1> mips_descend<1>(std::span<const MipsRing<1>>, int, double, double);
template Eigen::Matrix<double, 2, 1> mips_descend<2>(std::span<const MipsRing<2>>, int, double, double);

}  // namespace fhr::param::detail
