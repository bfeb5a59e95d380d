// FHR §3 — reusable per-vertex arrays for the searches of §3 (an implementation detail of
// fast_marching.cpp, exact.cpp and ellipse.cpp; not part of the paper).
//
// §3 computes one path Γ(x_j, x_k) per edge of D, each with searches (fast marching, exact
// window propagation) that touch only the few hundred vertices of the "ellipse" T_jk. Their
// per-vertex arrays must nevertheless be indexable by any vertex of T, and filling fresh arrays
// of #V entries for every search costs more than the search itself on large meshes (measured on
// the 44k-vertex refined_elephant: ~0.45 ms to allocate and fill an exact search's three arrays,
// against ~0.2 ms for the early-stopped search of a domain edge).
// So the arrays are borrowed from a per-thread pool and handed back *clean*: every entry at its
// initial value. The borrower records the entries it changes and resets exactly those.
//
// Pseudocode:
//   acquire<S>(n): take a clean S from this thread's pool (or make one); grow it to n entries
//   release(s):    s.reset() restores the touched entries; keep s in the pool (at most a few)
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace fhr::geodesic::detail {

/// Per-thread pool of clean scratch objects of type S. S provides `void fit(std::size_t n)`
/// (grow to n entries, new entries clean) and `void reset()` (make every entry clean again).
template <class S>
class ScratchPool {
public:
    /// A clean S with at least n entries; hand it back with release().
    static std::unique_ptr<S> acquire(std::size_t n) {
        std::vector<std::unique_ptr<S>>& pool = free_list();
        std::unique_ptr<S> s;
        if (pool.empty()) {
            s = std::make_unique<S>();
        } else {
            s = std::move(pool.back());
            pool.pop_back();
        }
        s->fit(n);
        return s;
    }

    /// Resets s and keeps it for the next acquire (a few per thread: nested searches).
    static void release(std::unique_ptr<S> s) {
        if (!s) return;
        s->reset();
        std::vector<std::unique_ptr<S>>& pool = free_list();
        if (pool.size() < max_kept) pool.push_back(std::move(s));
    }

private:
    static constexpr std::size_t max_kept = 4;
    static std::vector<std::unique_ptr<S>>& free_list() {
        thread_local std::vector<std::unique_ptr<S>> pool;
        return pool;
    }
};

/// Empties a transient buffer for reuse; one that grew past `keep` entries (a whole-mesh search
/// may queue 10⁶ windows) gives its memory back instead of parking it in the pool.
template <class V>
void clear_buffer(V& v, std::size_t keep = std::size_t{1} << 16) {
    if (v.capacity() > keep)
        V().swap(v);
    else
        v.clear();
}

/// unique_ptr deleter that hands the object back to its pool.
template <class S>
struct ReturnToPool {
    void operator()(S* s) const { ScratchPool<S>::release(std::unique_ptr<S>(s)); }
};

template <class S>
using Borrowed = std::unique_ptr<S, ReturnToPool<S>>;

template <class S>
Borrowed<S> borrow(std::size_t n) {
    return Borrowed<S>(ScratchPool<S>::acquire(n).release());
}

}  // namespace fhr::geodesic::detail
