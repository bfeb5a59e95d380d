// Beyond the paper (§4) — the curves' vertices slid along their domain edges (see slide.hpp).
#include <fhr/pipeline/detail/slide.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>

#include <fhr/core/detail/predicates.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/param/detail/disk_topology.hpp>
#include <fhr/param/detail/mips.hpp>
#include <fhr/param/detail/mips_newton.hpp>

namespace fhr::pipeline {
namespace {

using param::detail::Mat2;
using param::detail::MipsRing;
using param::detail::Vec2;
using Grad = Eigen::Matrix<double, 3, 2>;

// The triangle's corners laid flat: corner 0 at the origin, corner 1 along x.
std::array<Vec2, 3> flat_triangle(const TriMesh& D, FaceId d) {
    const auto v = D.face_vertices(d);
    return param::detail::lay_flat(D.position(v[0]), D.position(v[1]), D.position(v[2]));
}

double anisotropy(double m) { return 0.5 * (m + std::sqrt(std::max(m * m - 4, 0.0))); }  // σ₁/σ₂ from m

// One patch laid flat: its images, and per face its hat gradients and area.
struct Flat {
    std::array<Vec2, 3> corner;
    std::vector<Vec2> uv;
    std::vector<Grad> g;
    std::vector<double> area;
    std::vector<std::vector<std::pair<std::uint32_t, int>>> ring;  // per vertex: (face, its place there)
    std::vector<std::uint8_t> on_boundary;

    // image_weighted: each face's area weighed by its share of the patch's image area over its share
    // of the patch's surface area, within [0.1, 10] (slide.hpp's SlideOptions::image_weighted).
    Flat(const param::Disk& disk, const param::PatchMap& psi, const std::array<Vec2, 3>& corners, bool image_weighted)
        : corner(corners),
          uv(disk.positions.size()),
          ring(disk.positions.size()),
          on_boundary(disk.positions.size(), 0) {
        for (std::size_t v = 0; v < uv.size(); ++v) uv[v] = psi.beta[v][1] * corner[1] + psi.beta[v][2] * corner[2];
        for (std::size_t f = 0; f < disk.triangles.size(); ++f) {
            const auto& t = disk.triangles[f];
            const auto [grad, a] =
                param::detail::hat_gradients(disk.positions[t[0]], disk.positions[t[1]], disk.positions[t[2]]);
            g.push_back(grad);
            area.push_back(a);
            for (int k = 0; k < 3; ++k) ring[disk.triangles[f][k]].emplace_back(static_cast<std::uint32_t>(f), k);
        }
        for (std::uint32_t v : disk.boundary) on_boundary[v] = 1;
        if (image_weighted) weigh_by_image(disk);
    }

    void weigh_by_image(const param::Disk& disk) {
        std::vector<double> image(area.size());
        double image_total = 0, total = 0;
        for (std::size_t f = 0; f < area.size(); ++f) {
            const auto& t = disk.triangles[f];
            const Vec2 a = uv[t[1]] - uv[t[0]], b = uv[t[2]] - uv[t[0]];
            image[f] = 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
            image_total += image[f];
            total += area[f];
        }
        for (std::size_t f = 0; f < area.size(); ++f)
            area[f] *= std::clamp((image[f] / image_total) / (area[f] / total), 0.1, 10.0);
    }

    Mat2 jacobian(const param::Disk& disk, std::size_t f) const {
        const auto& t = disk.triangles[f];
        Eigen::Matrix<double, 2, 3> u;
        u << uv[t[0]], uv[t[1]], uv[t[2]];
        return u * g[f];
    }

    // Σ_f A_f m_f and the largest σ₁/σ₂.
    std::pair<double, double> energy(const param::Disk& disk) const {
        double e = 0, worst = 0;
        for (std::size_t f = 0; f < g.size(); ++f) {
            const Mat2 j = jacobian(disk, f);
            const double m = j.squaredNorm() / j.determinant();
            e += area[f] * m;
            worst = std::max(worst, m > 0 ? anisotropy(m) : INFINITY);
        }
        return {e, worst};
    }

    // The ring of v as seen from this patch into `r` (its terms' storage reused), the variable
    // moving v's image by m.
    template <int K>
    void ring_of(const param::Disk& disk, std::uint32_t v, const Eigen::Matrix<double, 2, K>& m, MipsRing<K>& r) const {
        r.u0 = uv[v];
        r.m = m;
        r.terms.clear();
        for (const auto& [f, k] : ring[v])
            r.terms.push_back(param::detail::mips_term(jacobian(disk, f), uv[v], g[f].row(k).transpose(), area[f]));
    }
};

// Σ_f A_f m_f, Σ_f A_f and the largest σ₁/σ₂ of a patch's map, without laying it out.
struct Activity {
    double energy = 0, area = 0, worst = 0;
};

Activity activity(const param::Disk& disk, const param::PatchMap& psi, const std::array<Vec2, 3>& corner) {
    Activity out;
    for (const auto& t : disk.triangles) {
        const auto [grad, a] =
            param::detail::hat_gradients(disk.positions[t[0]], disk.positions[t[1]], disk.positions[t[2]]);
        Eigen::Matrix<double, 2, 3> u;
        for (int k = 0; k < 3; ++k) u.col(k) = psi.beta[t[k]][1] * corner[1] + psi.beta[t[k]][2] * corner[2];
        const Mat2 j = u * grad;
        const double m = j.squaredNorm() / j.determinant();
        out.energy += a * m;
        out.area += a;
        out.worst = std::max(out.worst, m > 0 ? anisotropy(m) : INFINITY);
    }
    return out;
}

// A vertex of a curve in one of its patches: side c of the disk, and whether the side runs against
// D's halfedge (e, 0).
struct Occurrence {
    std::size_t patch;  // index into the moving patches
    std::uint32_t local;
    int side;
    bool reversed;
};

struct Sliding {
    double s = 0;  // along D's halfedge (e, 0)
    std::vector<Occurrence> at;
};

// The boundary positions of side c, corner to corner inclusive.
std::vector<std::uint32_t> side_vertices(const param::Disk& disk, int c) {
    std::vector<std::uint32_t> out;
    const std::size_t first = disk.corners[c], last = c == 2 ? disk.boundary.size() : disk.corners[c + 1];
    for (std::size_t p = first; p < last; ++p) out.push_back(disk.boundary[p]);
    out.push_back(disk.boundary[c == 2 ? 0 : disk.corners[c + 1]]);
    return out;
}

class Slider {
public:
    Slider(const TriMesh& D, const partition::Patches& patches, const IdVector<DFaceId, param::Disk>& disks,
           const IdVector<DFaceId, param::PatchMap>& maps, Executor& executor, const SlideOptions& options)
        : D_(D), patches_(patches), disks_(disks), maps_(maps), executor_(executor), options_(options) {}

    std::vector<std::pair<DFaceId, param::PatchMap>> run() {
        if (!choose()) return {};
        flats_.reserve(moving_.size());
        for (DFaceId d : moving_)
            flats_.emplace_back(disks_[d], maps_[d], flat_triangle(D_, FaceId(d)), options_.image_weighted);
        find_sliding();
        for (const Flat& flat : flats_) start_uv_.push_back(flat.uv);
        for (const Sliding& v : sliding_) start_s_.push_back(v.s);
        std::vector<std::pair<double, double>> before(moving_.size());
        executor_.for_each(moving_.size(), 1, [&](std::size_t i) { before[i] = flats_[i].energy(disks_[moving_[i]]); });
        double total = 0, worst = options_.worst;
        for (const auto& b : before) {
            total += b.first;
            worst = std::max(worst, b.second);
        }
        cap_ = worst + 1 / worst;
        if (options_.missed) newton();
        const int sweeps = options_.missed ? options_.sweeps_missed : options_.sweeps;
        const double settle = options_.missed ? options_.settled_missed : options_.settled;
        for (int sweep = 0; sweep < sweeps; ++sweep) {
            executor_.for_each(moving_.size(), 1, [&](std::size_t i) { interior_sweep(i); });
            for (Sliding& v : sliding_) slide_vertex(v);
            double now = 0;
            for (std::size_t i = 0; i < moving_.size(); ++i) now += flats_[i].energy(disks_[moving_[i]]).first;
            const bool settled = !(now < (1 - settle) * total);
            total = std::min(total, now);
            if (settled) break;
        }
        std::vector<std::pair<DFaceId, param::PatchMap>> out = maps_after();
        put_back_folded(out);
        double start = 0, end = 0;
        for (std::size_t i = 0; i < moving_.size(); ++i) {
            start += before[i].first;
            end += flats_[i].energy(disks_[moving_[i]]).first;
        }
        if (!(end < start)) return {};
        return out;
    }

private:
    // Newton steps on Σ_f A_f m_f^p over all the moving patches' images and sliding parameters at
    // once (param/detail/mips_newton.hpp), the sweeps' ceiling kept; then s from the images.
    void newton() {
        param::detail::MipsProblem problem;
        problem.power = options_.power;
        std::vector<std::size_t> offset;
        for (std::size_t i = 0; i < flats_.size(); ++i) {
            const Flat& flat = flats_[i];
            offset.push_back(problem.uv.size());
            for (std::size_t v = 0; v < flat.uv.size(); ++v) {
                problem.uv.push_back(flat.uv[v]);
                problem.lifts.emplace_back();
                if (flat.on_boundary[v]) continue;
                problem.lifts.back() = {param::detail::Lift{problem.variables, Vec2(1, 0)},
                                        param::detail::Lift{problem.variables + 1, Vec2(0, 1)}};
                problem.variables += 2;
            }
            for (auto t : disks_[moving_[i]].triangles) {
                for (std::uint32_t& v : t) v += static_cast<std::uint32_t>(offset[i]);
                problem.triangles.push_back(t);
            }
            problem.gradients.insert(problem.gradients.end(), flat.g.begin(), flat.g.end());
            problem.areas.insert(problem.areas.end(), flat.area.begin(), flat.area.end());
        }
        for (const Sliding& v : sliding_) {
            for (const Occurrence& o : v.at)
                problem.lifts[offset[o.patch] + o.local][0] = {problem.variables, along(o)};
            ++problem.variables;
        }
        param::detail::mips_newton(problem, options_.newton_steps, options_.settled_missed, cap_);
        for (std::size_t i = 0; i < flats_.size(); ++i)
            std::copy_n(problem.uv.begin() + static_cast<std::ptrdiff_t>(offset[i]), flats_[i].uv.size(),
                        flats_[i].uv.begin());
        for (Sliding& v : sliding_) {
            const Occurrence& o = v.at.front();
            const Flat& flat = flats_[o.patch];
            const Vec2 side = flat.corner[(o.side + 1) % 3] - flat.corner[o.side];
            const double t = (flat.uv[o.local] - flat.corner[o.side]).dot(side) / side.squaredNorm();
            v.s = o.reversed ? 1 - t : t;
        }
    }

    // How s moves a sliding vertex's image in one of its patches.
    Vec2 along(const Occurrence& o) const {
        const Flat& flat = flats_[o.patch];
        return (o.reversed ? -1.0 : 1.0) * (flat.corner[(o.side + 1) % 3] - flat.corner[o.side]);
    }

    // The active patches and their neighbours; false when none is active.
    bool choose() {
        std::vector<std::uint8_t> active(D_.n_faces(), 0);
        executor_.for_each(D_.n_faces(), 16, [&](std::size_t i) {
            const DFaceId d(static_cast<DFaceId::Index>(i));
            const Activity a = activity(disks_[d], maps_[d], flat_triangle(D_, FaceId(d)));
            active[i] = a.energy > 2 * (1 + options_.threshold) * a.area || a.worst > options_.worst;
        });
        if (std::none_of(active.begin(), active.end(), [](std::uint8_t a) { return a != 0; })) return false;
        active_ = active;
        std::vector<std::uint8_t> moving = active;
        for (FaceId f : D_.faces())
            if (active[f.idx()])
                for (HalfedgeId h : {D_.halfedge(f), D_.next(D_.halfedge(f)), D_.prev(D_.halfedge(f))})
                    if (const FaceId g = D_.face(TriMesh::twin(h)); g.valid()) moving[g.idx()] = 1;
        index_.assign(D_.n_faces(), -1);
        for (FaceId f : D_.faces())
            if (moving[f.idx()]) {
                index_[f.idx()] = static_cast<std::int64_t>(moving_.size());
                moving_.push_back(DFaceId(f));
            }
        return true;
    }

    // The vertices of the curves beside an active patch, but their ends.
    void find_sliding() {
        for (const Flat& flat : flats_) sliding_at_.emplace_back(flat.uv.size(), -1);
        for (EdgeId e : D_.edges()) {
            std::vector<Occurrence> at;
            std::vector<std::vector<std::uint32_t>> sides;
            bool beside_active = false;
            for (int s = 0; s < 2; ++s) {
                const HalfedgeId h = TriMesh::halfedge(e, s);
                const FaceId f = D_.face(h);
                if (!f.valid()) continue;
                beside_active = beside_active || active_[f.idx()];
                int c = 0;
                for (HalfedgeId g = D_.halfedge(f); g != h; g = D_.next(g)) ++c;
                const param::Disk& disk = disks_[DFaceId(f)];
                std::vector<std::uint32_t> side = side_vertices(disk, c);
                if (s == 1) std::reverse(side.begin(), side.end());  // along (e, 0)
                at.push_back({static_cast<std::size_t>(index_[f.idx()]), 0, c, s == 1});
                sides.push_back(std::move(side));
            }
            if (!beside_active) continue;
            const std::size_t n = sides[0].size();
            for (std::size_t k = 1; k < sides.size(); ++k)
                if (sides[k].size() != n) throw InternalError("sliding: the two sides of a curve differ in length");
            for (std::size_t i = 1; i + 1 < n; ++i) {
                Sliding v;
                for (std::size_t k = 0; k < at.size(); ++k) {
                    Occurrence o = at[k];
                    o.local = sides[k][i];
                    v.at.push_back(o);
                }
                if (v.at.size() == 2 && vertex_of(v.at[0]) != vertex_of(v.at[1]))
                    throw InternalError("sliding: the two sides of a curve hold other vertices of T′");
                const Occurrence& o = v.at.front();
                const double t = maps_[moving_[o.patch]].beta[o.local][(o.side + 1) % 3];
                v.s = o.reversed ? 1 - t : t;
                for (const Occurrence& at : v.at)
                    sliding_at_[at.patch][at.local] = static_cast<std::int64_t>(sliding_.size());
                sliding_.push_back(std::move(v));
            }
        }
    }

    // A step never takes a face above the ring's worst, nor above the m_f of the moving patches'
    // worst face before (or of σ₁/σ₂ = options.worst): the map's worst face never gets worse.
    double cap() const { return cap_; }

    VertexId vertex_of(const Occurrence& o) const {
        return patches_.patch[FaceId(moving_[o.patch])].vertices.at(o.local);
    }

    void interior_sweep(std::size_t i) {
        Flat& flat = flats_[i];
        const param::Disk& disk = disks_[moving_[i]];
        MipsRing<2> ring;
        for (std::uint32_t v = 0; v < flat.uv.size(); ++v) {
            if (flat.on_boundary[v]) continue;
            flat.ring_of<2>(disk, v, Mat2::Identity(), ring);
            flat.uv[v] +=
                param::detail::mips_descend<2>(std::span<const MipsRing<2>>(&ring, 1), 1, cap(), options_.power);
        }
    }

    // Side c's image at parameter t from corner c.
    static Vec2 on_side(const Flat& flat, int c, double t) {
        return (1 - t) * flat.corner[c] + t * flat.corner[(c + 1) % 3];
    }

    void slide_vertex(Sliding& v) {
        std::vector<MipsRing<1>>& rings = rings_;
        rings.resize(v.at.size());
        for (std::size_t k = 0; k < v.at.size(); ++k) {
            const Occurrence& o = v.at[k];
            flats_[o.patch].ring_of<1>(disks_[moving_[o.patch]], o.local, along(o), rings[k]);
        }
        v.s += param::detail::mips_descend<1>(std::span<const MipsRing<1>>(rings), 1, cap(), options_.power)(0);
        for (const Occurrence& o : v.at)
            flats_[o.patch].uv[o.local] = on_side(flats_[o.patch], o.side, o.reversed ? 1 - v.s : v.s);
    }

    // The images on the 2^-53 grid can turn a face that the optimisation left thin over (a sliver
    // of T′ whose image it made as thin): every moved vertex of such a face goes back to where it
    // started, with its β (a sliding vertex in all its patches), and its faces are looked at
    // again. Each vertex goes back at most once, and a face of vertices that all started where
    // they are is as the certified start had it.
    void put_back_folded(std::vector<std::pair<DFaceId, param::PatchMap>>& maps) {
        std::vector<std::pair<std::size_t, std::uint32_t>> work;  // (moving patch, face)
        for (std::size_t i = 0; i < moving_.size(); ++i)
            for (std::uint32_t f = 0; f < disks_[moving_[i]].triangles.size(); ++f) work.emplace_back(i, f);
        while (!work.empty()) {
            const auto [i, f] = work.back();
            work.pop_back();
            const auto& t = disks_[moving_[i]].triangles[f];
            const param::PatchMap& psi = maps[i].second;
            std::array<Vec2, 3> q;
            for (int k = 0; k < 3; ++k) q[k] = Vec2(psi.beta[t[k]][1], psi.beta[t[k]][2]);
            if (orient2d(q[0], q[1], q[2]) > 0) continue;
            for (std::uint32_t v : t) put_back(i, v, maps, work);
        }
    }

    void put_back(std::size_t i, std::uint32_t v, std::vector<std::pair<DFaceId, param::PatchMap>>& maps,
                  std::vector<std::pair<std::size_t, std::uint32_t>>& work) {
        auto restore = [&](std::size_t patch, std::uint32_t local) {
            maps[patch].second.beta[local] = maps_[moving_[patch]].beta[local];
            for (const auto& [face, k] : flats_[patch].ring[local]) work.emplace_back(patch, face);
        };
        Flat& flat = flats_[i];
        if (!flat.on_boundary[v]) {
            if (flat.uv[v] == start_uv_[i][v]) return;
            flat.uv[v] = start_uv_[i][v];
            restore(i, v);
            return;
        }
        const std::int64_t k = sliding_at_[i][v];
        if (k < 0) return;  // a corner, or a vertex of a curve that does not slide: never moved
        Sliding& s = sliding_[static_cast<std::size_t>(k)];
        if (s.s == start_s_[static_cast<std::size_t>(k)]) return;
        s.s = start_s_[static_cast<std::size_t>(k)];
        for (const Occurrence& o : s.at) {
            flats_[o.patch].uv[o.local] = on_side(flats_[o.patch], o.side, o.reversed ? 1 - s.s : s.s);
            restore(o.patch, o.local);
        }
    }

    std::vector<std::pair<DFaceId, param::PatchMap>> maps_after() const {
        std::vector<std::pair<DFaceId, param::PatchMap>> out;
        for (std::size_t i = 0; i < moving_.size(); ++i) {
            const Flat& flat = flats_[i];
            Mat2 basis;
            basis << flat.corner[1], flat.corner[2];
            const Mat2 to_beta = basis.inverse();
            out.emplace_back(moving_[i], maps_[moving_[i]]);
            param::PatchMap& psi = out.back().second;
            for (std::size_t v = 0; v < flat.uv.size(); ++v) {
                if (flat.on_boundary[v] || flat.uv[v] == start_uv_[i][v]) continue;  // unmoved: its β bit for bit
                const Vec2 b = to_beta * flat.uv[v];
                const double b1 = param::detail::snap(b.x()), b2 = param::detail::snap(b.y());
                psi.beta[v] = {1 - b1 - b2, b1, b2};
            }
        }
        for (std::size_t k = 0; k < sliding_.size(); ++k) {
            const Sliding& v = sliding_[k];
            if (v.s == start_s_[k]) continue;
            const double s = param::detail::snap(v.s);  // 1 − s is then a double exactly
            for (const Occurrence& o : v.at) {
                std::array<double, 3> beta{0, 0, 0};
                beta[o.side] = o.reversed ? s : 1 - s;
                beta[(o.side + 1) % 3] = o.reversed ? 1 - s : s;
                out[o.patch].second.beta[o.local] = beta;
            }
        }
        return out;
    }

    const TriMesh& D_;
    const partition::Patches& patches_;
    const IdVector<DFaceId, param::Disk>& disks_;
    const IdVector<DFaceId, param::PatchMap>& maps_;
    Executor& executor_;
    const SlideOptions& options_;
    std::vector<std::uint8_t> active_;
    std::vector<DFaceId> moving_;
    std::vector<std::int64_t> index_;  // per D face: its place in moving_, or −1
    std::vector<Flat> flats_;
    std::vector<Sliding> sliding_;
    std::vector<MipsRing<1>> rings_;                     // slide_vertex's, their storage reused
    std::vector<std::vector<std::int64_t>> sliding_at_;  // per moving patch and vertex: its sliding_ index, or −1
    std::vector<std::vector<Vec2>> start_uv_;            // per moving patch: the images before the sweeps
    std::vector<double> start_s_;                        // per sliding vertex: its parameter before the sweeps
    double cap_ = 0;
};

}  // namespace

std::vector<std::pair<DFaceId, param::PatchMap>> slide(const TriMesh& D, const partition::Patches& patches,
                                                       const IdVector<DFaceId, param::Disk>& disks,
                                                       const IdVector<DFaceId, param::PatchMap>& maps,
                                                       Executor& executor, const SlideOptions& options) {
    return Slider(D, patches, disks, maps, executor, options).run();
}

}  // namespace fhr::pipeline
