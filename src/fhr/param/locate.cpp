// FHR §4 — point location in a patch's image and φ_i = ψ_i⁻¹ (see locate.hpp).
#include <fhr/param/locate.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include <fhr/core/errors.hpp>
#include <fhr/core/detail/predicates.hpp>
#include <fhr/param/detail/disk_topology.hpp>

namespace fhr::param {
namespace {

// The tolerance below 0 that locate() accepts for a component of β: callers compute β in
// floating point (e.g. 1 − a − b), which can dip a few ulps below 0 at a side; 1e-12 is far above
// that and far below any meaningful distance in the domain triangle.
constexpr double below_zero_tolerance = 1e-12;

double det(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

}  // namespace

PatchLocator::PatchLocator(const Disk& disk, const PatchMap& psi)
    : positions_(disk.positions), triangles_(disk.triangles), image_(disk.positions.size()) {
    for (std::size_t v = 0; v < image_.size(); ++v) image_[v] = {psi.beta[v][1], psi.beta[v][2]};

    // Sides, ordered from their canonical end (as map_patch measured them).
    const detail::DirectedEdges edges = detail::directed_edges(disk);
    const std::size_t n = disk.boundary.size();
    for (unsigned c = 0; c < 3; ++c) {
        const std::size_t first = disk.corners[c], last = c == 2 ? n : disk.corners[c + 1];
        std::vector<std::uint32_t> u;
        for (std::size_t p = first; p <= last; ++p) u.push_back(disk.boundary[p % n]);
        const bool forward = detail::measured_from_start(disk.positions[u.front()], disk.positions[u.back()]);
        Side& side = sides_[c];
        side.far_slot = forward ? (c + 1) % 3 : c;
        if (!forward) std::reverse(u.begin(), u.end());
        for (std::size_t p = 0; p < u.size(); ++p) side.tau.push_back(psi.beta[u[p]][side.far_slot]);
        for (std::size_t p = 0; p + 1 < u.size(); ++p) {
            // The boundary edge runs u_p -> u_{p+1} in the loop's orientation when forward.
            const std::uint32_t from = forward ? u[p] : u[p + 1], to = forward ? u[p + 1] : u[p];
            const std::uint32_t t = edges.at(detail::edge_key(from, to));
            const auto& f = triangles_[t];
            auto place = [&](std::uint32_t v) { return f[0] == v ? 0u : f[1] == v ? 1u : 2u; };
            side.segments.push_back({t, place(u[p]), place(u[p + 1])});
        }
    }

    // The grid: G² ≈ #T cells over [0,1]², each listing the triangles whose bounding box meets it.
    grid_ = std::max<std::size_t>(
        1, static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(triangles_.size())))));
    const double g = static_cast<double>(grid_);
    auto cell = [&](double x) { return std::min(grid_ - 1, static_cast<std::size_t>(std::max(0.0, x * g))); };
    std::vector<std::array<std::size_t, 4>> boxes(triangles_.size());  // i0, i1, j0, j1
    // Each cell of triangle t's box, in the same order for counting and for filling.
    auto for_each_cell = [&](std::size_t t, auto&& visit) {
        for (std::size_t i = boxes[t][0]; i <= boxes[t][1]; ++i)
            for (std::size_t j = boxes[t][2]; j <= boxes[t][3]; ++j) visit(i * grid_ + j);
    };
    cell_start_.assign(grid_ * grid_ + 1, 0);
    for (std::size_t t = 0; t < triangles_.size(); ++t) {
        const auto& f = triangles_[t];
        double lo[2] = {1, 1}, hi[2] = {0, 0};
        for (std::uint32_t v : f)
            for (int a = 0; a < 2; ++a) {
                lo[a] = std::min(lo[a], image_[v][a]);
                hi[a] = std::max(hi[a], image_[v][a]);
            }
        boxes[t] = {cell(lo[0]), cell(hi[0]), cell(lo[1]), cell(hi[1])};
        for_each_cell(t, [&](std::size_t c) { ++cell_start_[c + 1]; });
    }
    for (std::size_t k = 1; k < cell_start_.size(); ++k) cell_start_[k] += cell_start_[k - 1];
    cell_triangles_.resize(cell_start_.back());
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t t = 0; t < triangles_.size(); ++t)
        for_each_cell(t, [&](std::size_t c) { cell_triangles_[fill[c]++] = static_cast<std::uint32_t>(t); });
}

PatchLocator::Location PatchLocator::on_side(unsigned c, double tau) const {
    const Side& side = sides_[c];
    // The segment p with τ_p ≤ τ < τ_{p+1} (the last one for τ = 1): a vertex's own τ selects the
    // segment that starts there, where s = 0 and φ is the vertex's position exactly.
    const std::size_t segments = side.segments.size();
    const auto above = std::upper_bound(side.tau.begin(), side.tau.end(), tau);
    const std::size_t p = std::min<std::size_t>(
        segments - 1, static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, above - side.tau.begin() - 1)));
    const double s = std::clamp((tau - side.tau[p]) / (side.tau[p + 1] - side.tau[p]), 0.0, 1.0);
    Location hit{side.segments[p].triangle, {0.0, 0.0, 0.0}};
    hit.weights[side.segments[p].near_place] = 1 - s;
    hit.weights[side.segments[p].far_place] = s;
    return hit;
}

PatchLocator::Location PatchLocator::in_interior(double x, double y) const {
    const double g = static_cast<double>(grid_);
    const std::size_t i = std::min(grid_ - 1, static_cast<std::size_t>(std::max(0.0, x * g)));
    const std::size_t j = std::min(grid_ - 1, static_cast<std::size_t>(std::max(0.0, y * g)));
    const Eigen::Vector2d q(x, y);
    // Barycentric coordinates from the three sub-triangles' areas, normalized by their sum: at a
    // vertex two of them are exactly 0 and the vertex's weight is exactly 1.
    auto weights = [&](std::uint32_t t) {
        const auto& f = triangles_[t];
        double d[3];
        for (int k = 0; k < 3; ++k) {
            const auto& b = image_[f[(k + 1) % 3]];
            const auto& c = image_[f[(k + 2) % 3]];
            d[k] = det(b[0] - x, b[1] - y, c[0] - x, c[1] - y);
        }
        return std::array<double, 3>{d[0], d[1], d[2]};
    };
    auto normalized = [](std::uint32_t t, std::array<double, 3> d) {
        for (double& v : d) v = std::max(0.0, v);
        const double sum = std::accumulate(d.begin(), d.end(), 0.0);
        return Location{t, {d[0] / sum, d[1] / sum, d[2] / sum}};
    };
    for (std::uint32_t k = cell_start_[i * grid_ + j]; k < cell_start_[i * grid_ + j + 1]; ++k) {
        const std::uint32_t t = cell_triangles_[k];
        const auto& f = triangles_[t];
        auto point = [&](std::uint32_t v) { return Eigen::Vector2d(image_[v][0], image_[v][1]); };
        const Eigen::Vector2d a = point(f[0]), b = point(f[1]), c = point(f[2]);
        // Exact containment in the closed triangle (the images are positively oriented).
        if (orient2d(a, b, q) >= 0 && orient2d(b, c, q) >= 0 && orient2d(c, a, q) >= 0)
            return normalized(t, weights(t));
    }
    // Not in any closed image triangle: β lies outside the reference triangle by rounding
    // (within below_zero_tolerance). Take the triangle whose coordinates are least negative.
    std::uint32_t best = 0;
    double best_score = -std::numeric_limits<double>::infinity();
    for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
        const auto d = weights(t);
        const double sum = std::accumulate(d.begin(), d.end(), 0.0);
        const double score = *std::min_element(d.begin(), d.end()) / sum;
        if (sum > 0 && score > best_score) {
            best_score = score;
            best = t;
        }
    }
    return normalized(best, weights(best));
}

PatchLocator::Location PatchLocator::locate(const std::array<double, 3>& beta) const {
    std::array<double, 3> b = beta;
    for (double& x : b) {
        if (!std::isfinite(x) || x < -below_zero_tolerance) {
            std::ostringstream s;
            s.precision(17);
            s << "φ: barycentric coordinates (" << beta[0] << ", " << beta[1] << ", " << beta[2]
              << ") are outside the domain triangle";
            throw InvalidInput(s.str());
        }
        x = std::max(0.0, x);
    }
    for (unsigned c = 0; c < 3; ++c)
        if (b[(c + 2) % 3] == 0) return on_side(c, b[sides_[c].far_slot]);
    return in_interior(b[1], b[2]);
}

Vec3 PatchLocator::phi(const std::array<double, 3>& beta) const {
    const Location hit = locate(beta);
    const auto& f = triangles_[hit.triangle];
    // FHR §4 eq. (2): φ_i is linear on each image triangle.
    return hit.weights[0] * positions_[f[0]] + hit.weights[1] * positions_[f[1]] + hit.weights[2] * positions_[f[2]];
}

}  // namespace fhr::param
