// FHR §4 — chord-length boundary and the convex-combination system of one patch (see
// patch_map.hpp for the pseudocode).
#include <fhr/param/patch_map.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>
#include <utility>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <fhr/core/errors.hpp>
#include <fhr/param/detail/disk_topology.hpp>

namespace fhr::param {
namespace {

constexpr std::uint32_t none = std::uint32_t(-1);

// Paper §4, chord length: the vertices u_1..u_r of side c get λ_p = L_p / L_r, measured from the
// side's canonical end (detail::measured_from_start) so that the neighbouring patch, which runs
// along the same curve the other way, computes the same numbers; β_{c+1} = λ_p from corner c.
void place_side(const Disk& disk, unsigned c, std::vector<std::array<double, 3>>& beta) {
    const std::size_t n = disk.boundary.size();
    const std::size_t first = disk.corners[c], last = c == 2 ? n : disk.corners[c + 1];
    std::vector<std::uint32_t> u;
    for (std::size_t p = first; p <= last; ++p) u.push_back(disk.boundary[p % n]);
    const bool forward = detail::measured_from_start(disk.positions[u.front()], disk.positions[u.back()]);
    if (!forward) std::reverse(u.begin(), u.end());
    // Now u runs from the canonical end E to the other end F; L_p accumulates from E.
    std::vector<double> L(u.size(), 0.0);
    for (std::size_t p = 1; p < u.size(); ++p)
        L[p] = L[p - 1] + (disk.positions[u[p]] - disk.positions[u[p - 1]]).norm();
    const double total = L.back();
    if (!(total > 0) || !std::isfinite(total))
        throw InvalidInput("patch: MAP-1: side " + std::to_string(c) + " has chord length " + std::to_string(total));
    const unsigned at_E = forward ? c : (c + 1) % 3, at_F = forward ? (c + 1) % 3 : c;
    for (std::size_t p = 0; p < u.size(); ++p) {
        // τ = L_p / L_r on the 2^-53 grid; 1 − τ is then exact. τ = 0 and 1 at the ends exactly.
        const double tau = p + 1 == u.size() ? 1.0 : detail::snap(L[p] / total);
        auto& b = beta[u[p]];
        b[(c + 2) % 3] = 0;
        b[at_F] = tau;
        b[at_E] = 1 - tau;
    }
}

// The neighbours of interior vertex v in cyclic order, from the triangles' successor pairs.
class Rings {
public:
    Rings(std::size_t n_vertices, std::span<const std::array<std::uint32_t, 3>> triangles) : start_(n_vertices + 1, 0) {
        for (const auto& f : triangles)
            for (int k = 0; k < 3; ++k) ++start_[f[k] + 1];
        for (std::size_t v = 1; v < start_.size(); ++v) start_[v] += start_[v - 1];
        pairs_.resize(start_.back());
        std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
        for (const auto& f : triangles)
            for (int k = 0; k < 3; ++k) pairs_[fill[f[k]]++] = {f[(k + 1) % 3], f[(k + 2) % 3]};
    }
    /// \pre v is interior: its pairs (b, c) of triangles (v, b, c) chain into one cycle.
    void ring(std::uint32_t v, std::vector<std::uint32_t>& out) const {
        out.clear();
        const std::uint32_t lo = start_[v], hi = start_[v + 1];
        std::uint32_t w = pairs_[lo].first;
        for (std::uint32_t k = lo; k < hi; ++k) {
            out.push_back(w);
            std::uint32_t next = none;
            for (std::uint32_t j = lo; j < hi; ++j)
                if (pairs_[j].first == w) next = pairs_[j].second;
            w = next;
        }
    }

private:
    std::vector<std::uint32_t> start_;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs_;
};

Eigen::MatrixXd solve(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& rhs, Solver solver) {
    if (solver == Solver::sparse_lu) {
        Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
        lu.compute(A);
        if (lu.info() != Eigen::Success)
            throw NumericalFailure("patch: SparseLU could not factor the system: " + lu.lastErrorMessage());
        Eigen::MatrixXd x = lu.solve(rhs);
        if (lu.info() != Eigen::Success || !x.allFinite()) throw NumericalFailure("patch: SparseLU solve failed");
        return x;
    }
    Eigen::BiCGSTAB<Eigen::SparseMatrix<double>, Eigen::IncompleteLUT<double>> it;
    it.setTolerance(bicgstab_tolerance);
    it.setMaxIterations(std::max<Eigen::Index>(2 * A.cols(), bicgstab_min_iterations));
    it.compute(A);
    if (it.info() != Eigen::Success) throw NumericalFailure("patch: BiCGSTAB preconditioner (incomplete LU) failed");
    Eigen::MatrixXd x(rhs.rows(), rhs.cols());
    for (Eigen::Index j = 0; j < rhs.cols(); ++j) {
        // Started from the preconditioner's solution: on a patch of a few unknowns the incomplete
        // LU is the exact one, so that start already meets the tolerance; started from 0,
        // BiCGSTAB's half step there reached a residual of exactly 0 and its next step divided 0
        // by 0 (NaN after 2 iterations: the pipeline fuzzer, density family, uniform weights).
        const Eigen::VectorXd start = it.preconditioner().solve(rhs.col(j));
        x.col(j) = it.solveWithGuess(rhs.col(j), start);
        if (it.info() != Eigen::Success || !x.col(j).allFinite()) {
            char what[160];  // %g: the tolerance is 1e-12-ish, which std::to_string prints as 0.000000
            std::snprintf(what, sizeof what,
                          "patch: BiCGSTAB did not reach relative residual %g (reached %g after %ld iterations)",
                          bicgstab_tolerance, it.error(), static_cast<long>(it.iterations()));
            throw NumericalFailure(what);
        }
    }
    return x;
}

}  // namespace

std::string_view name(Solver solver) { return solver == Solver::sparse_lu ? "sparse-lu" : "bicgstab"; }

Solver parse_solver(std::string_view text) {
    for (Solver s : {Solver::sparse_lu, Solver::bicgstab})
        if (text == name(s)) return s;
    throw InvalidInput("unknown solver '" + std::string(text) + "' (expected sparse-lu or bicgstab)");
}

void convex_combination(std::span<const Vec3> positions, std::span<const std::array<std::uint32_t, 3>> triangles,
                        std::span<const std::uint8_t> fixed, std::size_t midpoints,
                        std::vector<std::array<double, 2>>& images, const PatchMapOptions& options) {
    const std::size_t nv = positions.size();
    // The free vertices get unknowns 0..n-1 in vertex order.
    std::vector<std::uint32_t> unknown(nv, none);
    std::uint32_t n = 0;
    for (std::size_t v = 0; v < nv; ++v)
        if (!fixed[v]) unknown[v] = n++;
    if (n == 0) return;

    // FHR §4: ψ(v) − Σ_{w free} λ_vw ψ(w) = Σ_{w fixed} λ_vw ψ(w), in the plane of `images`.
    const Rings rings(nv, triangles);
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 2);
    std::vector<std::uint32_t> ring;
    std::vector<Vec3> ring_positions;
    for (std::uint32_t v = 0; v < nv; ++v) {
        const std::uint32_t i = unknown[v];
        if (i == none) continue;
        rings.ring(v, ring);
        ring_positions.clear();
        for (std::uint32_t w : ring) ring_positions.push_back(positions[w]);
        // A dividing edge's midpoint (MAP-4) is ours, not a vertex of T: any positive weights keep
        // Proposition 1, and uniform ones pull it off the side its edge joined. Weights from its
        // geometry could leave it far closer to that side than 2⁻⁵³ when the side's vertices are
        // a needle's (`./run families`, quality 45: its β rounded onto the side, three image
        // triangles degenerate).
        const std::vector<double> lambda_vw =
            v + midpoints >= nv ? std::vector<double>(ring.size(), 1.0 / static_cast<double>(ring.size()))
                                : one_ring_weights(options.weights, positions[v], ring_positions, v);
        entries.emplace_back(i, i, 1.0);
        for (std::size_t k = 0; k < ring.size(); ++k) {
            const std::uint32_t w = ring[k];
            if (unknown[w] != none) {
                entries.emplace_back(i, unknown[w], -lambda_vw[k]);
            } else {
                rhs(i, 0) += lambda_vw[k] * images[w][0];
                rhs(i, 1) += lambda_vw[k] * images[w][1];
            }
        }
    }
    Eigen::SparseMatrix<double> A(n, n);
    A.setFromTriplets(entries.begin(), entries.end());
    const Eigen::MatrixXd x = solve(A, rhs, options.solver);
    for (std::uint32_t v = 0; v < nv; ++v)
        if (unknown[v] != none) images[v] = {x(unknown[v], 0), x(unknown[v], 1)};
}

PatchMap map_patch(const Disk& disk, const PatchMapOptions& options) {
    validate(disk);
    const std::size_t nv = disk.positions.size();
    PatchMap result;
    result.beta.assign(nv, {0.0, 0.0, 0.0});
    for (unsigned c = 0; c < 3; ++c) place_side(disk, c, result.beta);
    // The interior in the reference plane (β1, β2).
    std::vector<std::uint8_t> fixed(nv, 0);
    for (std::uint32_t v : disk.boundary) fixed[v] = 1;
    std::vector<std::array<double, 2>> images(nv);
    for (std::size_t v = 0; v < nv; ++v) images[v] = {result.beta[v][1], result.beta[v][2]};
    convex_combination(disk.positions, disk.triangles, fixed, disk.midpoints, images, options);
    for (std::size_t v = 0; v < nv; ++v) {
        if (fixed[v]) continue;
        // On the 2^-53 grid, β0 = 1 − β1 − β2 is exact and the triple sums to exactly 1.
        const double b1 = detail::snap(images[v][0]), b2 = detail::snap(images[v][1]);
        result.beta[v] = {1 - b1 - b2, b1, b2};
    }
    return result;
}

}  // namespace fhr::param
