// Beyond the paper (§4) — the patch map relaxed (see relax.hpp for the pseudocode).
#include <fhr/param/relax.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include <fhr/param/detail/disk_topology.hpp>
#include <fhr/param/detail/mips.hpp>
#include <fhr/param/detail/mips_newton.hpp>

namespace fhr::param {
namespace {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;
using Grad = Eigen::Matrix<double, 3, 2>;  // J = [u0 u1 u2] · G: the gradients of the three hat functions

struct Face {
    Grad g;
    double area = 0;  // on the surface, scaled to the patch's share of its triangle's area
};

class Relaxer {
public:
    Relaxer(const Disk& disk, const PatchMap& start, const std::array<Vec3, 3>& corners)
        : disk_(disk), start_(start), n_(disk.positions.size()) {
        // T_i laid flat: corner 0 at the origin, corner 1 along x.
        const std::array<Vec2, 3> q = detail::lay_flat(corners[0], corners[1], corners[2]);
        basis_ << q[1], q[2];
        uv_.resize(n_);
        for (std::size_t v = 0; v < n_; ++v) uv_[v] = start.beta[v][1] * q[1] + start.beta[v][2] * q[2];
        // Each face laid flat in its own plane, the patch scaled to its triangle's area.
        double surface = 0;
        faces_.resize(disk.triangles.size());
        auto hat = [&](std::size_t f, double scale) {
            const auto& t = disk.triangles[f];
            return detail::hat_gradients(disk.positions[t[0]], disk.positions[t[1]], disk.positions[t[2]], scale);
        };
        for (std::size_t f = 0; f < faces_.size(); ++f) surface += faces_[f].area = hat(f, 1).second;
        const double scale = std::sqrt(0.5 * q[1].x() * q[2].y() / surface);
        for (std::size_t f = 0; f < faces_.size(); ++f) {
            faces_[f].g = hat(f, scale).first;
            faces_[f].area *= scale * scale;
        }
        fixed_.assign(n_, 0);
        for (std::uint32_t v : disk.boundary) fixed_[v] = 1;
        index_.assign(n_, -1);
        for (std::size_t v = 0; v < n_; ++v)
            if (!fixed_[v]) index_[v] = unknowns_++;
    }

    double energy(const std::vector<Vec2>& uv) const {
        double e = 0;
        for (std::size_t f = 0; f < faces_.size(); ++f) {
            const Mat2 j = jacobian(uv, f);
            const double det = j.determinant();
            if (!(det > 0)) return std::numeric_limits<double>::infinity();
            e += faces_[f].area * (j.squaredNorm() + j.squaredNorm() / (det * det));
        }
        return e;
    }

    double area() const {
        double a = 0;
        for (const Face& f : faces_) a += f.area;
        return a;
    }

    PatchMap result() const {
        PatchMap out;
        out.beta.resize(n_);
        const Mat2 to_beta = basis_.inverse();
        for (std::size_t v = 0; v < n_; ++v) {
            if (fixed_[v]) {  // the boundary keeps the paper's β bit for bit (MAP-5)
                out.beta[v] = start_.beta[v];
                continue;
            }
            const Vec2 b = to_beta * uv_[v];
            const double b1 = detail::snap(b.x()), b2 = detail::snap(b.y());
            out.beta[v] = {1 - b1 - b2, b1, b2};
        }
        return out;
    }

    const std::vector<Vec2>& uv() const { return uv_; }
    double worst() const { return measures(uv_).worst; }

private:
    Mat2 jacobian(const std::vector<Vec2>& uv, std::size_t f) const {
        const auto& t = disk_.triangles[f];
        Eigen::Matrix<double, 2, 3> u;
        u << uv[t[0]], uv[t[1]], uv[t[2]];
        return u * faces_[f].g;
    }

    // What a step must not make worse (spec/distortion.md): Σ_f A_img(f) · σ₁/σ₂ (the weights of
    // its percentiles), the largest σ₁/σ₂, and the patch's part of the L2 stretch, Σ_f A_img(f) ·
    // (σ₁⁻² + σ₂⁻²) (the image onto the surface has the inverse singular values; the patch's image
    // and surface areas are the same before and after, so this is its share of L2² exactly).
    struct Measures {
        double anisotropy = 0, worst = 0, l2 = 0;
    };
    Measures measures(const std::vector<Vec2>& uv) const {
        Measures m;
        for (std::size_t f = 0; f < faces_.size(); ++f) {
            const Mat2 j = jacobian(uv, f);
            const Vec2 sigma = detail::singular_values(j);
            const double s1 = sigma[0], s2 = sigma[1];
            m.anisotropy += faces_[f].area * j.determinant() * s1 / s2;
            m.worst = std::max(m.worst, s1 / s2);
            m.l2 += faces_[f].area * j.determinant() * (1 / (s1 * s1) + 1 / (s2 * s2));
        }
        return m;
    }

    // argmin Σ_f A_f ((a − d)² + (b + c)²), J_f = [[a, b], [c, d]]: the conformal (least squares
    // conformal) images of the interior, the boundary fixed. One sparse SPD solve.
    std::vector<Vec2> conformal_minimum() const {
        const auto m = static_cast<Eigen::Index>(2 * unknowns_);
        std::vector<Eigen::Triplet<double>> entries;
        Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m);
        for (std::size_t f = 0; f < faces_.size(); ++f) {
            const Grad& g = faces_[f].g;
            const auto& t = disk_.triangles[f];
            // Two residuals, each Σ_k (α_k x_k + β_k y_k).
            const std::array<std::array<Vec2, 3>, 2> forms{
                std::array<Vec2, 3>{Vec2(g(0, 0), -g(0, 1)), Vec2(g(1, 0), -g(1, 1)), Vec2(g(2, 0), -g(2, 1))},
                std::array<Vec2, 3>{Vec2(g(0, 1), g(0, 0)), Vec2(g(1, 1), g(1, 0)), Vec2(g(2, 1), g(2, 0))}};
            for (const auto& form : forms)
                for (int i = 0; i < 3; ++i) {
                    if (fixed_[t[i]]) continue;
                    const Eigen::Index row = 2 * index_[t[i]];
                    for (int k = 0; k < 3; ++k) {
                        const Mat2 block = faces_[f].area * form[i] * form[k].transpose();
                        if (fixed_[t[k]]) {
                            rhs.segment<2>(row) -= block * uv_[t[k]];
                            continue;
                        }
                        const Eigen::Index col = 2 * index_[t[k]];
                        for (int a = 0; a < 2; ++a)
                            for (int b = 0; b < 2; ++b) entries.emplace_back(row + a, col + b, block(a, b));
                    }
                }
        }
        Eigen::SparseMatrix<double> k(m, m);
        k.setFromTriplets(entries.begin(), entries.end());
        const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(k);
        std::vector<Vec2> out = uv_;
        if (solver.info() != Eigen::Success) return out;
        const Eigen::VectorXd x = solver.solve(rhs);
        for (std::size_t v = 0; v < n_; ++v)
            if (!fixed_[v]) out[v] = x.segment<2>(2 * index_[v]);
        return out;
    }

public:
    // Towards the conformal images, as far as no image triangle degenerates (90 % of the way to the
    // first that would), kept only when the area-weighted anisotropy falls and neither the worst
    // anisotropy nor the patch's L2 stretch grows.
    bool conformal_step() {
        const std::vector<Vec2> target = conformal_minimum();
        std::vector<Vec2> direction(n_);
        for (std::size_t v = 0; v < n_; ++v) direction[v] = target[v] - uv_[v];
        const double t = std::min(1.0, 0.9 * max_step(direction));
        std::vector<Vec2> trial(n_);
        for (std::size_t v = 0; v < n_; ++v) trial[v] = uv_[v] + t * direction[v];
        const Measures before = measures(uv_), after = measures(trial);
        if (!(after.anisotropy < before.anisotropy && after.worst <= before.worst && after.l2 <= before.l2))
            return false;
        uv_.swap(trial);
        return true;
    }

    // Sweeps of one vertex at a time, each interior vertex's image moved to lower Σ_f A_f m_f^p
    // over its faces (param/detail/mips.hpp), never taking a face above the ring's worst or σ₁/σ₂ = 2,
    // until a sweep lowers Σ_f A_f m_f by less than a millionth of it; kept only when Σ_f A_f m_f fell.
    bool mips_descent(int sweeps, double power) {
        ring_.resize(n_);
        for (std::size_t f = 0; f < faces_.size(); ++f)
            for (int k = 0; k < 3; ++k) ring_[disk_.triangles[f][k]].push_back({static_cast<std::uint32_t>(f), k});
        const std::vector<Vec2> start = uv_;
        const double start_energy = mips();
        double before = start_energy;
        for (int i = 0; i < sweeps; ++i) {
            for (std::size_t v = 0; v < n_; ++v)
                if (!fixed_[v]) mips_vertex(v, power);
            const double after = mips();
            if (!(after < (1 - 1e-4) * before)) break;
            before = after;
        }
        if (mips() < start_energy) return true;
        uv_ = start;  // Σ A m_f^p fell but Σ A m_f did not: the L2 stretch would rise
        return false;
    }

private:
    struct Corner {
        std::uint32_t face;
        int k;  // the vertex's place in the face
    };

    double mips() const {
        double e = 0;
        for (std::size_t f = 0; f < faces_.size(); ++f) {
            const Mat2 j = jacobian(uv_, f);
            e += faces_[f].area * j.squaredNorm() / j.determinant();
        }
        return e;
    }

    void mips_vertex(std::size_t v, double power) {
        constexpr double cap = 2.5;  // m_f at σ₁/σ₂ = 2
        detail::MipsRing<2>& ring = ring_scratch_;
        ring.u0 = uv_[v];
        ring.m = Mat2::Identity();
        ring.terms.clear();
        for (const Corner& c : ring_[v])
            ring.terms.push_back(detail::mips_term(jacobian(uv_, c.face), uv_[v], faces_[c.face].g.row(c.k).transpose(),
                                                   faces_[c.face].area));
        uv_[v] += detail::mips_descend<2>(std::span<const detail::MipsRing<2>>(&ring, 1), 1, cap, power);
    }

    // The least t > 0 at which some face of uv + t·d has zero area (its signed area is a
    // quadratic in t), or infinity.
    double max_step(const std::vector<Vec2>& d) const {
        double best = std::numeric_limits<double>::infinity();
        for (const auto& t : disk_.triangles) best = std::min(best, detail::first_degenerate(uv_, d, t));
        return best;
    }

    const Disk& disk_;
    const PatchMap& start_;
    std::size_t n_;
    Mat2 basis_;  // columns: corners 1 and 2 of T_i laid flat (corner 0 at the origin)
    std::vector<Vec2> uv_;
    std::vector<Face> faces_;
    std::vector<std::uint8_t> fixed_;
    std::vector<Eigen::Index> index_;
    std::size_t unknowns_ = 0;
    std::vector<std::vector<Corner>> ring_;  // per vertex: its faces
    detail::MipsRing<2> ring_scratch_;
};

}  // namespace

std::optional<PatchMap> relax(const Disk& disk, const PatchMap& start, const std::array<Vec3, 3>& domain_triangle,
                              const RelaxOptions& options) {
    Relaxer r(disk, start, domain_triangle);
    const double e = r.energy(r.uv());
    // Near the isometry's energy already with no sliver, or an image triangle too thin for a finite energy.
    if (!std::isfinite(e) || (e <= 4 * (1 + options.threshold) * r.area() && r.worst() <= options.worst))
        return std::nullopt;
    bool moved = false;
    for (int i = 0; i < options.iterations && r.conformal_step(); ++i) moved = true;
    if (r.mips_descent(options.sweeps, options.power)) moved = true;
    if (!moved) return std::nullopt;
    return r.result();
}

}  // namespace fhr::param
