// Beyond the paper (§4) — Newton's method on a whole map's MIPS energy (see mips_newton.hpp).
#include <fhr/param/detail/mips_newton.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/SparseCholesky>

namespace fhr::param::detail {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

Mat2 jacobian(const MipsProblem& p, const std::vector<Vec2>& uv, std::size_t f) {
    const auto& t = p.triangles[f];
    Eigen::Matrix<double, 2, 3> u;
    u << uv[t[0]], uv[t[1]], uv[t[2]];
    return u * p.gradients[f];
}

// The gradient of E in the variables and its projected Hessian.
void assemble(const MipsProblem& p, Eigen::VectorXd& gradient, Eigen::SparseMatrix<double>& hessian) {
    std::vector<Eigen::Triplet<double>> entries;
    gradient = Eigen::VectorXd::Zero(p.variables);
    for (std::size_t f = 0; f < p.triangles.size(); ++f) {
        const MipsFace face = mips_face(jacobian(p, p.uv, f), p.power);
        Eigen::Matrix<double, 4, 6> b = Eigen::Matrix<double, 4, 6>::Zero();  // ∂J / ∂(u_0, u_1, u_2)
        for (int k = 0; k < 3; ++k) {
            b(0, 2 * k) = b(2, 2 * k + 1) = p.gradients[f](k, 0);
            b(1, 2 * k) = b(3, 2 * k + 1) = p.gradients[f](k, 1);
        }
        const Eigen::Matrix<double, 6, 1> g = p.areas[f] * b.transpose() * face.gradient;
        const Eigen::Matrix<double, 6, 6> h = p.areas[f] * b.transpose() * face.hessian * b;
        const auto& t = p.triangles[f];
        for (int k = 0; k < 3; ++k)
            for (const Lift& x : p.lifts[t[k]]) {
                if (x.variable < 0) continue;
                gradient(x.variable) += x.direction.dot(g.segment<2>(2 * k));
                for (int l = 0; l < 3; ++l)
                    for (const Lift& y : p.lifts[t[l]])
                        if (y.variable >= 0)
                            entries.emplace_back(x.variable, y.variable,
                                                 x.direction.dot(h.block<2, 2>(2 * k, 2 * l) * y.direction));
            }
    }
    hessian.resize(p.variables, p.variables);
    hessian.setFromTriplets(entries.begin(), entries.end());
    double diagonal = 0;
    for (Eigen::Index k = 0; k < p.variables; ++k) diagonal += hessian.coeff(k, k);
    const double shift = 1e-9 * diagonal / static_cast<double>(p.variables);
    for (Eigen::Index k = 0; k < p.variables; ++k) hessian.coeffRef(k, k) += shift;
}

// One step; false when it found none that lowers E by more than `settled` of it.
// `solver` keeps its analysis of the Hessian's pattern (the same at every step) once it has one.
bool step(MipsProblem& p, double settled, double ceiling, Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>& solver,
          bool& analysed) {
    Eigen::VectorXd gradient;
    Eigen::SparseMatrix<double> hessian;
    assemble(p, gradient, hessian);
    if (!analysed) solver.analyzePattern(hessian);
    analysed = true;
    solver.factorize(hessian);
    if (solver.info() != Eigen::Success) return false;
    const Eigen::VectorXd d = -solver.solve(gradient);
    const double slope = gradient.dot(d);
    if (!d.allFinite() || !(slope < 0)) return false;
    std::vector<Vec2> du(p.uv.size(), Vec2::Zero());
    for (std::size_t v = 0; v < du.size(); ++v)
        for (const Lift& x : p.lifts[v])
            if (x.variable >= 0) du[v] += x.direction * d(x.variable);
    double bound = infinity;
    for (const auto& t : p.triangles) bound = std::min(bound, first_degenerate(p.uv, du, t));
    const auto [now, most] = mips_total(p);
    const std::vector<Vec2> start = p.uv;
    double t = std::min(1.0, 0.9 * bound);
    for (int halve = 0; halve < 30; ++halve, t *= 0.5) {
        for (std::size_t v = 0; v < du.size(); ++v) p.uv[v] = start[v] + t * du[v];
        const auto [e, m] = mips_total(p);
        if (e <= now + 1e-4 * t * slope && m <= std::max(most, ceiling)) return now - e > settled * now;
    }
    p.uv = start;
    return false;
}

}  // namespace

double first_degenerate(const std::vector<Vec2>& uv, const std::vector<Vec2>& du,
                        const std::array<std::uint32_t, 3>& t) {
    auto cross = [](const Vec2& x, const Vec2& y) { return x.x() * y.y() - x.y() * y.x(); };
    const Vec2 a = uv[t[1]] - uv[t[0]], b = uv[t[2]] - uv[t[0]];
    const Vec2 da = du[t[1]] - du[t[0]], db = du[t[2]] - du[t[0]];
    const double qa = cross(da, db), qb = cross(a, db) + cross(da, b), qc = cross(a, b);
    double best = infinity;
    auto take = [&](double r) {
        if (r > 0) best = std::min(best, r);
    };
    if (std::abs(qa) < 1e-300) {
        if (qb != 0) take(-qc / qb);
    } else if (const double disc = qb * qb - 4 * qa * qc; disc >= 0) {
        take((-qb - std::sqrt(disc)) / (2 * qa));
        take((-qb + std::sqrt(disc)) / (2 * qa));
    }
    return best;
}

std::array<Vec2, 3> lay_flat(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
    const Vec3 a = p1 - p0, b = p2 - p0;
    const double la = a.norm();
    return {Vec2(0, 0), Vec2(la, 0), Vec2(b.dot(a) / la, a.cross(b).norm() / la)};
}

std::pair<Eigen::Matrix<double, 3, 2>, double> hat_gradients(const Vec3& p0, const Vec3& p1, const Vec3& p2,
                                                             double scale) {
    const std::array<Vec2, 3> q = lay_flat(p0, p1, p2);
    Mat2 flat;
    flat << q[1], q[2];
    Eigen::Matrix<double, 3, 2> d;
    d << -1, -1, 1, 0, 0, 1;
    return {d * (scale * flat).inverse(), 0.5 * (p1 - p0).cross(p2 - p0).norm()};
}

void set_faces(MipsProblem& problem, const std::vector<Vec3>& positions,
               const std::vector<std::array<std::uint32_t, 3>>& triangles) {
    problem.triangles = triangles;
    problem.gradients.clear();
    problem.areas.clear();
    for (const auto& t : triangles) {
        const auto [g, a] = hat_gradients(positions[t[0]], positions[t[1]], positions[t[2]]);
        problem.gradients.push_back(g);
        problem.areas.push_back(a);
    }
}

std::array<double, 2> mips_total(const MipsProblem& p) {
    double e = 0, most = 0;
    for (std::size_t f = 0; f < p.triangles.size(); ++f) {
        const Mat2 j = jacobian(p, p.uv, f);
        const double l = j.determinant();
        if (!(l > 0)) return {infinity, infinity};
        const double m = j.squaredNorm() / l;
        e += p.areas[f] * (p.power == 2 ? m * m : std::pow(m, p.power));
        most = std::max(most, m);
    }
    return {e, most};
}

void mips_newton(MipsProblem& problem, int steps, double settled, double ceiling) {
    if (problem.variables == 0) return;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
    bool analysed = false;
    const double power = problem.power;
    for (double p = std::min(2.0, power);; p = std::min(2 * p, power)) {
        problem.power = p;
        for (int i = 0; i < steps && step(problem, settled, ceiling, solver, analysed); ++i) {}
        if (p == power) break;
    }
}

}  // namespace fhr::param::detail
