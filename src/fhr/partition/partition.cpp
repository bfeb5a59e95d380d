// FHR §3 — the partition with recovery (see partition.hpp for the pseudocode).
#include <fhr/core/executor.hpp>
#include <fhr/partition/partition.hpp>

#include <algorithm>
#include <map>
#include <optional>
#include <stdexcept>
#include <utility>

#include <fhr/core/detail/cones.hpp>
#include <fhr/domain/decimate.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/partition/detail/keep.hpp>

namespace fhr::partition {
namespace {

// Γ(a, b) for every edge of D̂ (D closed by the cones of T̂, core/detail/cones.hpp), reusing the paths of
// edges whose ends are unchanged: the exact geodesic on T for an edge of D inside the surface, the
// arc of T's boundary for a boundary edge of D, the edge itself for a cone edge. The searches run
// in parallel, each on a workspace leased from the cache's pool: the threads reuse
// their arrays from path to path and round to round, and the partition call frees them.
class PathCache {
public:
    PathCache(const TriMesh& T, const TriMesh& T_hat, const geodesic::EllipseOptions& options, Executor& executor)
        : T_(T), T_hat_(T_hat), options_(options), executor_(executor) {}

    std::vector<geodesic::EllipsePath> all(const domain::Domain& D_hat) {
        const auto ends = domain::edge_endpoints(D_hat);
        // The paths not known yet, computed in parallel (core/executor.hpp).
        std::vector<Key> missing;
        for (EdgeId e : D_hat.mesh.edges()) {
            const auto& [a, b] = ends[e.idx()];
            const Key key = key_of(a, b);
            if (!fixed(D_hat, e) && !cache_.count(key) &&
                std::find(missing.begin(), missing.end(), key) == missing.end())
                missing.push_back(key);
        }
        // One fast-marching field per end, shared by its paths, then the paths.
        std::vector<VertexId::Index> foci;
        for (const Key& k : missing) foci.insert(foci.end(), {k.first, k.second});
        std::sort(foci.begin(), foci.end());
        foci.erase(std::unique(foci.begin(), foci.end()), foci.end());
        auto focus_index = [&](VertexId::Index v) {
            return static_cast<std::size_t>(std::lower_bound(foci.begin(), foci.end(), v) - foci.begin());
        };
        std::vector<std::vector<VertexId>> partners(foci.size());
        for (const Key& k : missing) {
            partners[focus_index(k.first)].push_back(VertexId(k.second));
            partners[focus_index(k.second)].push_back(VertexId(k.first));
        }
        std::vector<geodesic::FocusField> fields(foci.size());
        executor_.for_each(foci.size(), 8, [&](std::size_t i) {
            const geodesic::WorkspacePool::Lease workspace = workspaces_.lease();
            fields[i] =
                geodesic::focus_field(T_, VertexId(foci[i]), partners[i], options_.K, field_reach, workspace.get());
        });
        std::vector<geodesic::EllipsePath> found(missing.size());
        executor_.for_each(missing.size(), 8, [&](std::size_t i) {
            const geodesic::WorkspacePool::Lease workspace = workspaces_.lease();
            geodesic::EllipseOptions options = options_;
            options.workspace = workspace.get();
            options.field_a = &fields[focus_index(missing[i].first)];
            options.field_b = &fields[focus_index(missing[i].second)];
            found[i] =
                geodesic::ellipse_shortest_path(T_, VertexId(missing[i].first), VertexId(missing[i].second), options);
        });
        for (std::size_t i = 0; i < missing.size(); ++i) cache_.emplace(missing[i], std::move(found[i]));
        std::vector<geodesic::EllipsePath> paths;
        paths.reserve(ends.size());
        for (EdgeId e : D_hat.mesh.edges()) {
            const auto& [a, b] = ends[e.idx()];
            if (fixed(D_hat, e)) {
                paths.push_back(fixed_path(D_hat, e));
                continue;
            }
            geodesic::EllipsePath p = cache_.at(key_of(a, b));
            // The ellipse search ends without a path only when the exact search exhausted a's
            // component without reaching b (ellipse.hpp): a loss to rounding, not a property of D.
            if (p.path.points.empty())
                throw PartitionFailure("no shortest path found for domain edge " + std::to_string(e.idx()) +
                                       " between vertices " + std::to_string(a.idx()) + " and " +
                                       std::to_string(b.idx()) +
                                       " of T: the exact geodesic search exhausted the component of " +
                                       std::to_string(a.idx()) + " without reaching " + std::to_string(b.idx()) +
                                       " (a loss to rounding, possible on needle triangles)");
            if (a.idx() > b.idx()) std::reverse(p.path.points.begin(), p.path.points.end());
            paths.push_back(std::move(p));
        }
        return paths;
    }

    bool apex(VertexId x) const { return x.idx() >= T_.n_vertices(); }
    bool fixed(const domain::Domain& D_hat, EdgeId e) const {
        return domain::on_cone(D_hat.mesh, D_hat.t_vertex, e, T_.n_vertices());
    }

private:
    using Key = std::pair<VertexId::Index, VertexId::Index>;
    // How far past K times its farthest partner a field goes: d_a(x_k, x_j) may exceed d_a(x_j,
    // x_k), which sets the ellipse (a path whose field falls short runs its own fast marching).
    static constexpr double field_reach = 1.05;
    static Key key_of(VertexId a, VertexId b) { return {std::min(a.idx(), b.idx()), std::max(a.idx(), b.idx())}; }

    // The curve of D̂'s halfedge (e, 0), from x_a to x_b: a cone edge, or the boundary arc.
    geodesic::EllipsePath fixed_path(const domain::Domain& D_hat, EdgeId e) const {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        const VertexId a = D_hat.t_vertex[D_hat.mesh.from(h)], b = D_hat.t_vertex[D_hat.mesh.to(h)];
        std::vector<VertexId> nodes;
        if (apex(a) || apex(b)) {
            nodes = {a, b};
        } else {
            // D's face on the left of a -> b is a face of T when the cone face is on the right.
            bool cone_on_left = false;
            for (VertexId v : D_hat.mesh.face_vertices(D_hat.mesh.face(h)))
                cone_on_left = cone_on_left || apex(D_hat.t_vertex[v]);
            nodes = cone_on_left ? boundary_arc(T_hat_, T_.n_vertices(), b, a)
                                 : boundary_arc(T_hat_, T_.n_vertices(), a, b);
            if (cone_on_left) std::reverse(nodes.begin(), nodes.end());
        }
        geodesic::EllipsePath out;
        out.certificate = geodesic::EllipsePath::Certificate::boundary_arc;
        for (std::size_t i = 0; i < nodes.size(); ++i) {
            out.path.points.push_back(SurfacePoint::at_vertex(nodes[i]));
            if (i) out.path.length += (T_hat_.position(nodes[i]) - T_hat_.position(nodes[i - 1])).norm();
        }
        return out;
    }

    const TriMesh& T_;
    const TriMesh& T_hat_;
    geodesic::EllipseOptions options_;
    Executor& executor_;
    geodesic::WorkspacePool workspaces_;
    std::map<Key, geodesic::EllipsePath> cache_;
};

// The vertices of T that D should keep to resolve the conflicts: those at the conflicts' places
// (paper_notes/partition.md); when all of them are D's already, the middle node of each
// conflicting curve. Only vertices not yet in D and not yet kept are returned.
std::vector<VertexId> new_keep(const TriMesh& T, const domain::Domain& D, const Embedding& embedding,
                               std::vector<std::uint8_t>& kept) {
    std::vector<std::uint8_t> in_d(T.n_vertices(), 0);
    for (VertexId x : D.t_vertex) in_d[x.idx()] = 1;
    std::vector<VertexId> keep;
    auto add = [&](VertexId v) {  // never an apex of T̂ (it is in D̂ anyway)
        if (v.valid() && v.idx() < T.n_vertices() && !in_d[v.idx()] && !kept[v.idx()]) {
            kept[v.idx()] = 1;
            keep.push_back(v);
        }
    };
    for (const Conflict& c : embedding.conflicts)
        for (TVertexId v : c.near) add(VertexId(v));
    if (!keep.empty()) return keep;
    // All at the conflicts is kept already: the middle node of each conflicting curve; failing
    // that both ends of the edges of T its nodes lie on; failing that the neighbours in T of the
    // conflicts' places.
    const Network& net = embedding.network;
    auto nearest = [&](VertexId v) {
        const Origin& o = net.origin[v];
        return o.vertex.valid() ? VertexId(o.vertex) : T.from(TriMesh::halfedge(EdgeId(o.edge), o.t < 0.5 ? 0 : 1));
    };
    for (const Conflict& c : embedding.conflicts)
        for (DEdgeId e : {c.d_edge_a, c.d_edge_b}) {
            const auto& path = net.path[e];
            add(nearest(path[path.size() / 2]));
        }
    if (!keep.empty()) return keep;
    for (const Conflict& c : embedding.conflicts)
        for (DEdgeId e : {c.d_edge_a, c.d_edge_b})
            for (VertexId v : net.path[e]) {
                const Origin& o = net.origin[v];
                if (o.vertex.valid()) continue;
                add(T.from(TriMesh::halfedge(EdgeId(o.edge), 0)));
                add(T.to(TriMesh::halfedge(EdgeId(o.edge), 0)));
            }
    if (!keep.empty()) return keep;
    // Last, the neighbours in T of the conflicts' places.
    for (const Conflict& c : embedding.conflicts)
        for (TVertexId v : c.near)
            if (v.valid()) T.for_each_outgoing(VertexId(v), [&](HalfedgeId h) { add(T.to(h)); });
    return keep;
}

// A curve Γ(x_j, x_k) that runs over a corner x_m of one of the two faces at [v_j, v_k] says that
// this face is flat in the geodesic sense; the edge's flip [v_m, v_n] replaces it by Γ(x_m, x_n)
// and keeps Γ(x_j, x_m), Γ(x_m, x_k). An edge made by a flip is never flipped again (`made`, as
// pairs of vertices of T, each with the pair it replaced), so flips cannot cycle. Returns the
// number of edges flipped.
using VertexPair = std::pair<VertexId::Index, VertexId::Index>;
using Flips = std::map<VertexPair, VertexPair>;  // edge made -> edge replaced, as vertices of T
VertexPair pair_of(const domain::Domain& D, VertexId a, VertexId b) {
    const VertexId::Index x = D.t_vertex[a].idx(), y = D.t_vertex[b].idx();
    return {std::min(x, y), std::max(x, y)};
}

// After D is decimated again or stepped back, the flips made before where they apply again: the
// replaced edge is in D with the made edge's ends opposite it (the same two faces). The paths of
// such an edge ran over a corner before and would again. Returns the number of edges flipped.
std::size_t reapply_flips(domain::Domain& D, const Flips& made) {
    std::map<VertexId::Index, VertexId> vertex;  // vertex of T -> vertex of D
    for (VertexId j : D.t_vertex.ids()) vertex.emplace(D.t_vertex[j].idx(), j);
    std::size_t flips = 0;
    for (const auto& [to, from] : made) {
        const auto a = vertex.find(from.first), b = vertex.find(from.second);
        if (a == vertex.end() || b == vertex.end()) continue;
        const HalfedgeId h = D.mesh.find_halfedge(a->second, b->second);
        if (!h.valid() || !D.mesh.is_flip_ok(TriMesh::edge(h))) continue;
        if (pair_of(D, D.mesh.to(D.mesh.next(h)), D.mesh.to(D.mesh.next(TriMesh::twin(h)))) != to) continue;
        D.mesh.flip(TriMesh::edge(h));
        ++flips;
    }
    return flips;
}

std::size_t flip_over_corners(domain::Domain& D, const std::vector<Conflict>& conflicts, Flips& made) {
    std::vector<std::uint8_t> touched(D.mesh.n_edges(), 0);
    std::size_t flips = 0;
    for (const Conflict& c : conflicts) {
        // D̂'s own edges beyond D's are cone edges: never flipped (nor are D's boundary edges).
        if (c.kind != Conflict::Kind::through_corner || c.d_edge_a.idx() >= D.mesh.n_edges() ||
            touched[c.d_edge_a.idx()])
            continue;
        const EdgeId e(c.d_edge_a);
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        const VertexId m(c.d_vertex);
        if (D.mesh.to(D.mesh.next(h)) != m && D.mesh.to(D.mesh.next(TriMesh::twin(h))) != m) continue;
        const VertexPair replaced = pair_of(D, D.mesh.from(h), D.mesh.to(h));
        if (!D.mesh.is_flip_ok(e) || made.count(replaced)) continue;
        // The four edges of the two faces change their faces: none of them may flip this round.
        for (HalfedgeId g : {h, TriMesh::twin(h)})
            for (HalfedgeId k = D.mesh.next(g); k != g; k = D.mesh.next(k)) touched[TriMesh::edge(k).idx()] = 1;
        touched[e.idx()] = 1;
        D.mesh.flip(e);
        made.emplace(pair_of(D, D.mesh.from(h), D.mesh.to(h)), replaced);
        ++flips;
    }
    return flips;
}

// A decimation of T to exactly the vertices of a domain given by the user (its history is where
// keeping D starts), or nullopt with the reason when §2 cannot reach them.
std::optional<domain::Domain> decimation_to_vertices(const TriMesh& T, const domain::Domain& D, std::string& why) {
    domain::DecimateOptions o;
    o.target_faces = D.mesh.n_faces();
    o.keep = D.t_vertex.values();
    o.best_effort = true;
    o.corner_angle_deg = 180;  // the given domain's boundary vertices, and no corners of their own
    try {
        domain::Domain H = domain::decimate(T, o);
        std::vector<VertexId> a = H.t_vertex.values(), b = D.t_vertex.values();
        std::sort(a.begin(), a.end());
        std::sort(b.begin(), b.end());
        if (a == b) return H;
        why = "§2 stops at " + std::to_string(H.mesh.n_vertices()) + " vertices, not the domain's " +
              std::to_string(b.size());
    } catch (const InvalidInput& e) {
        why = std::string("§2 cannot decimate T to the domain's vertices: ") + e.what();
    }
    return std::nullopt;
}

// §3 with its recovery, one method per step: the geodesics of D embedded; where they conflict,
// keeping D (keep.hpp) first; else, for a decimated D, one of three named strategies a round —
// flip the domain edges that run over a corner, decimate again keeping the vertices at the
// conflicts (local), or step back along the decimation (global) — until (1) and (2) hold.
class Partitioner {
public:
    Partitioner(const TriMesh& T, domain::Domain D, const PartitionOptions& options)
        : T_(T),
          options_(options),
          D0_(D),
          D_(std::move(D)),
          decimated_(!D0_.history.empty()),
          vertices0_(D0_.mesh.n_vertices()),
          kept_(T.n_vertices(), 0),
          executor_(executor_or_default(options.executor)),
          cones_(T.is_closed() ? std::nullopt : std::optional<Coned>(add_cones(T))),
          T_hat_(cones_ ? cones_->mesh : T),
          cache_(T, T_hat_, options.ellipse, executor_) {}

    Partition run() {
        for (;;) {
            const domain::Domain D_hat = domain::close_domain(D_, T_);
            out_.paths = EdgeData<geodesic::EllipsePath>(cache_.all(D_hat));
            std::vector<geodesic::GeodesicPath> paths;
            paths.reserve(out_.paths.size());
            for (const auto& p : out_.paths) paths.push_back(p.path);
            Embedding embedding = embed(T_hat_, D_hat, paths, {}, &executor_);
            std::string keep_failure;  // why D could not be kept, for the message of a given domain
            std::optional<KeptNetwork> attempt;
            if (!embedding.conflicts.empty() && options_.keep_domain && out_.retries == 0)
                attempt = keeping(D_hat, embedding, keep_failure);
            std::vector<std::uint8_t> unsnapped;
            std::optional<Patches> patches;  // the kept network's, cut already with its embedding
            if (!embedding.conflicts.empty() && attempt) take_kept(D_hat, *attempt, embedding, unsnapped, patches);
            if (embedding.conflicts.empty()) return finish(D_hat, embedding, unsnapped, patches);
            if (!decimated_) refuse_given(embedding, keep_failure);
            recover(embedding);
        }
    }

private:
    const TriMesh& T_;
    const PartitionOptions& options_;
    const domain::Domain D0_;
    domain::Domain D_;
    bool decimated_;
    std::size_t vertices0_;
    std::vector<VertexId> keep_;      // vertices of T the decimation must keep (local recovery)
    std::vector<std::uint8_t> kept_;  // per vertex of T: in keep_ (or tried)
    Flips flipped_;                   // edges made by flips
    // The last decimation, from which the recovery decimates again or steps back: D itself when
    // its history describes it, else (D changed after its decimation) T decimated afresh to D's
    // size when first needed.
    std::optional<domain::Domain> base_;
    Executor& executor_;
    // With boundary, §3 works on T̂ and D̂, closed by cones (core/detail/cones.hpp); D's own vertices,
    // edges and faces are the first of D̂'s, so conflicts, paths and flips name them alike.
    std::optional<Coned> cones_;
    const TriMesh& T_hat_;
    PathCache cache_;
    Partition out_;

    void progress(const std::string& line) const {
        if (options_.progress) options_.progress(line);
    }

    domain::Domain& last_decimation() {
        if (!base_) {
            if (domain::history_describes(D0_, T_)) {
                base_ = D0_;
            } else {
                domain::DecimateOptions o;
                o.target_faces = D0_.mesh.n_faces();
                o.best_effort = true;
                base_ = domain::decimate(T_, o);
            }
        }
        return *base_;
    }

    // Keeping D (partition/detail/keep.hpp): restricted shortest paths where the geodesics conflict,
    // directly on D, else from D's own decimation, or for a domain given by the user from a
    // decimation of T to its vertices (H, made or proved only when first needed). Redoing many
    // collapses can crowd curves around one point until there is no room to separate them: then
    // again from the nearest valid level; failing that, a decimated D is changed as the paper-only
    // mode does and a given one is refused (`keep_failure` says why).
    std::optional<KeptNetwork> keeping(const domain::Domain& D_hat, const Embedding& embedding,
                                       std::string& keep_failure) {
        std::optional<domain::Domain> H;
        std::string no_base;  // why there is no H, once found
        auto base = [&]() -> const domain::Domain& {
            if (!H && no_base.empty()) {
                if (decimated_ && domain::history_describes(D_, T_))
                    H = D_hat;
                else if (decimated_)
                    no_base = "D's history does not describe it";
                else if (const std::optional<domain::Domain> h = decimation_to_vertices(T_, D_, no_base))
                    H = domain::close_domain(*h, T_);
            }
            if (!H) throw PartitionFailure(no_base);
            return *H;
        };
        for (const Start start : {Start::fast, Start::gradual}) {
            if (!no_base.empty()) break;
            try {
                return keep_domain(
                    T_hat_, T_.n_vertices(), D_hat, base, out_.paths.values(), embedding.conflicts,
                    [&](const domain::Domain& d) { return cache_.all(d); }, options_.progress, executor_, start);
            } catch (const PartitionFailure& e) {
                keep_failure = e.what();
                progress("keeping the domain failed (" + keep_failure +
                         (start == Start::fast && no_base.empty() ? "); again from the nearest valid level"
                          : decimated_                            ? "); changing D instead"
                                                                  : "); the given domain is refused"));
            }
        }
        return std::nullopt;
    }

    // The kept network in place of the geodesics: its curves, and their embedding (the direct
    // start's when its curves stayed as they were, else made now).
    void take_kept(const domain::Domain& D_hat, KeptNetwork& kept, Embedding& embedding,
                   std::vector<std::uint8_t>& unsnapped, std::optional<Patches>& patches) {
        for (EdgeId e : kept.paths.ids()) out_.paths[e].path = kept.paths[e];
        out_.curves = kept.info;
        out_.keep_start_faces = kept.start_faces;
        out_.resolved = embedding.conflicts;
        unsnapped = kept.unsnapped.values();
        if (kept.embedded) {
            embedding = std::move(kept.embedded->embedding);
            patches = std::move(kept.embedded->patches);
        } else {
            embedding = embed(T_hat_, D_hat, kept.paths.values(), unsnapped, &executor_);
        }
        if (!embedding.conflicts.empty())
            throw InternalError("keeping the domain: the final network breaks (1)/(2): " +
                                embedding.conflicts.front().describe());
    }

    // The partition of a network that satisfies (1) and (2); with boundary, the cones taken off.
    Partition finish(const domain::Domain& D_hat, Embedding& embedding, std::vector<std::uint8_t>& unsnapped,
                     std::optional<Patches>& patches) {
        if (out_.curves.empty())
            for (EdgeId e : out_.paths.ids())
                out_.curves.push_back(CurveInfo{cache_.fixed(D_hat, e) ? CurveKind::boundary : CurveKind::geodesic,
                                                out_.paths[e].path.length,
                                                0,
                                                0,
                                                {}});
        if (cones_) {
            // The cones off: D's edges are D̂'s first ones; T′ is embedded on T itself, where the
            // network must again satisfy (1) and (2) (the cones only closed the loops).
            const std::size_t ne = D_.mesh.n_edges();
            out_.paths.resize(ne);
            out_.curves.resize(ne);
            if (!unsnapped.empty()) unsnapped.resize(ne);
            std::vector<geodesic::GeodesicPath> open;
            for (const auto& p : out_.paths) open.push_back(p.path);
            embedding = embed(T_, D_, open, unsnapped, &executor_);
            if (!embedding.conflicts.empty())
                throw InternalError("partition: the network breaks (1)/(2) without the cones: " +
                                    embedding.conflicts.front().describe());
            patches.reset();  // D̂'s on T̂
        }
        out_.patches = patches ? std::move(*patches) : extract_patches(D_, embedding.network, &executor_);
        out_.network = std::move(embedding.network);
        out_.vertices_added = D_.mesh.n_vertices() - vertices0_;
        out_.kept = std::move(keep_);
        out_.domain = std::move(D_);
        return std::move(out_);
    }

    // A domain given by the user is never changed: its conflicts, each pair of domain edges once
    // (a crossing is found in every face where it happens) and each problem of one edge at one
    // domain vertex once, and why it could not be kept.
    [[noreturn]] static void refuse_given(const Embedding& embedding, const std::string& keep_failure) {
        std::vector<const Conflict*> pairs;
        for (const Conflict& c : embedding.conflicts)
            if (std::none_of(pairs.begin(), pairs.end(), [&](const Conflict* p) {
                    return p->d_edge_a == c.d_edge_a && p->d_edge_b == c.d_edge_b &&
                           (c.d_edge_a != c.d_edge_b || (p->kind == c.kind && p->d_vertex == c.d_vertex));
                }))
                pairs.push_back(&c);
        std::string what = "conditions (1)/(2) of §3 fail for the given domain:";
        for (std::size_t i = 0; i < std::min<std::size_t>(pairs.size(), 4); ++i)
            what += (i ? "; " : " ") + pairs[i]->describe();
        if (pairs.size() > 4) what += "; and " + std::to_string(pairs.size() - 4) + " more";
        if (!keep_failure.empty()) what += "; and the domain cannot be kept: " + keep_failure;
        throw PartitionFailure(what);
    }

    // One round of the recovery of a decimated D: the first strategy that applies.
    void recover(const Embedding& embedding) {
        const std::string conflicts =
            std::to_string(embedding.conflicts.size()) + " conflicts (" + embedding.conflicts.front().describe() + ")";
        out_.resolved.insert(out_.resolved.end(), embedding.conflicts.begin(), embedding.conflicts.end());
        ++out_.retries;
        if (const std::size_t flips = flip_over_corners(D_, embedding.conflicts, flipped_)) {
            progress("partition: " + conflicts + "; flipped " + std::to_string(flips) +
                     " domain edges that ran over a corner");
            return;
        }
        if (decimate_again(embedding, conflicts)) return;
        step_back(conflicts);
    }

    // Local: decimate T again to two more faces per new vertex to keep, keeping the vertices at the
    // conflicts — when they are few: at most an eighth of D's faces (a quarter more faces).
    bool decimate_again(const Embedding& embedding, const std::string& conflicts) {
        const std::vector<VertexId> more = new_keep(T_, D_, embedding, kept_);
        if (more.empty() || 8 * more.size() > D_.mesh.n_faces()) {
            for (VertexId v : more) kept_[v.idx()] = 0;  // not kept after all: candidates again later
            return false;
        }
        keep_.insert(keep_.end(), more.begin(), more.end());
        domain::DecimateOptions o;
        o.target_faces = std::min(T_.n_faces(), D_.mesh.n_faces() + 2 * more.size());
        o.keep = keep_;
        o.best_effort = true;
        base_ = domain::decimate_again(T_, last_decimation(), o);
        D_ = *base_;
        const std::size_t again = reapply_flips(D_, flipped_);
        progress("partition: " + conflicts + "; decimating again keeping " + std::to_string(keep_.size()) +
                 " vertices: " + std::to_string(D_.mesh.n_faces()) + " faces, " + std::to_string(again) +
                 " earlier flips made again");
        return true;
    }

    // Global: step back along the last decimation, undoing its last collapses until D has a
    // quarter more faces; at the end of the history D = T, whose paths are T's own edges, so (1)
    // and (2) hold and the loop ends.
    void step_back(const std::string& conflicts) {
        domain::Domain& last = last_decimation();
        if (last.history.empty()) throw InternalError("partition: conflicts on D = T, whose paths are T's edges");
        const std::size_t undo = std::min(last.history.size(), std::max<std::size_t>(1, D_.mesh.n_faces() / 8));
        base_ = domain::undo_collapses(last, T_, undo);
        D_ = *base_;
        const std::size_t again = reapply_flips(D_, flipped_);
        progress("partition: " + conflicts + "; stepping back " + std::to_string(undo) +
                 " collapses of the decimation: " + std::to_string(D_.mesh.n_faces()) + " faces, " +
                 std::to_string(again) + " earlier flips made again");
    }
};

}  // namespace

Partition partition(const TriMesh& T, domain::Domain D, const PartitionOptions& options) {
    return Partitioner(T, std::move(D), options).run();
}

}  // namespace fhr::partition
