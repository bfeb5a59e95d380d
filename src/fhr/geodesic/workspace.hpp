// FHR §3 (beyond the paper) — the caller's workspace for the geodesic searches.
//
// §3 computes one path Γ(x_j, x_k) per edge of D, each with searches (fast marching, exact window
// propagation) that touch only the few hundred vertices of the "ellipse" T_jk. Their per-vertex
// arrays must nevertheless be indexable by any vertex of T, and filling fresh arrays of #V entries
// for every search costs more than the search itself on large meshes (measured on the 44k-vertex
// refined_elephant: ~0.45 ms to allocate and fill an exact search's three arrays, against ~0.2 ms
// for the early-stopped search of a domain edge). So the arrays are reused from one search to the
// next, and handed back *clean*: every entry at its initial value. A search records the entries it
// changes and resets exactly those when it ends (normally or by an exception), so it costs what
// it touches, not O(#V).
//
// Decision: the reusable arrays live in a Workspace that the caller owns and passes in the search's
// options (`workspace`, like `executor`). Before, they lived in per-thread pools (static thread storage):
// hidden state, lost by every helper thread at each join of the executor, and kept by the main
// thread at the size of the largest mesh for the life of the process. Now their lifetime is the
// caller's: a partition owns a WorkspacePool for its call (one workspace per running task), and
// everything is freed when the call returns. A search given no workspace uses one of its own,
// local to the call: correct, only slower (its arrays are allocated and filled for that call).
//
// A workspace is not synchronized: one search (with the searches it runs inside it: the ellipse
// search runs two fast-marching runs and exact searches, all alive at once) at a time. It keeps at
// most max_kept scratch objects of each kind, and a transient buffer that grew past 2¹⁶ entries
// (a whole-mesh search may queue 10⁶ windows) gives its memory back instead of being kept.
//
// Pseudocode (src/fhr/geodesic/detail/scratch.hpp):
//   borrow<S>(workspace, n): a clean S of this kind from the workspace (or a new one), grown to
//                            n entries; without a workspace a new one
//   when the borrower ends:  reset the entries it touched; keep S in the workspace (at most
//                            max_kept of each kind), or free it
#pragma once

#include <cstddef>
#include <memory>
#include <mutex>
#include <vector>

namespace fhr::geodesic {

namespace detail {
struct ScratchBase;
struct WorkspaceAccess;
}  // namespace detail

/// The reusable scratch memory of the geodesic searches (fast_marching, FastMarching,
/// ExactGeodesic, ellipse_shortest_path): pass it as the options' `workspace`.
/// Not synchronized: it serves one search at a time (a search and the searches nested in it).
/// Reusing it across meshes of any sizes is allowed; results never depend on its history.
class Workspace {
public:
    /// Scratch objects of one kind kept for later searches (more are freed when handed back).
    static constexpr std::size_t max_kept = 4;

    Workspace();
    /// \pre no search that borrowed from it is still alive (an ExactGeodesic or FastMarching holds
    ///      its arrays until it is destroyed).
    ~Workspace();
    Workspace(const Workspace&) = delete;
    Workspace& operator=(const Workspace&) = delete;

private:
    friend struct detail::WorkspaceAccess;
    std::vector<std::unique_ptr<detail::ScratchBase>> kept_;  ///< clean, at most max_kept per kind
    std::size_t lent_ = 0;  ///< borrowed and not handed back: kept_ has room for all of them
};

/// Workspaces for searches that run in parallel: each task leases one for its duration and
/// gives it back, so that the threads reuse arrays across tasks. Thread-safe (a mutex, taken
/// twice per lease); holds at most as many workspaces as were ever leased at once, and frees
/// them when it is destroyed.
class WorkspacePool {
public:
    /// A workspace of the pool, given back when the lease is destroyed.
    class Lease {
    public:
        Lease(const Lease&) = delete;
        Lease& operator=(const Lease&) = delete;
        ~Lease();
        Workspace* get() const { return workspace_.get(); }

    private:
        friend class WorkspacePool;
        Lease(WorkspacePool& pool, std::unique_ptr<Workspace> workspace);
        WorkspacePool& pool_;
        std::unique_ptr<Workspace> workspace_;
    };

    WorkspacePool();
    /// \pre no lease is alive.
    ~WorkspacePool();
    WorkspacePool(const WorkspacePool&) = delete;
    WorkspacePool& operator=(const WorkspacePool&) = delete;

    /// An idle workspace of the pool, or a new one.
    Lease lease();

private:
    std::mutex mutex_;
    std::vector<std::unique_ptr<Workspace>> idle_;  ///< capacity >= made_: giving back cannot throw
    std::size_t made_ = 0;
};

}  // namespace fhr::geodesic
