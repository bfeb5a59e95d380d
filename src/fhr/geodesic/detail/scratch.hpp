// FHR §3 (beyond the paper) — borrowing clean scratch objects from the caller's
// Workspace (an implementation detail of fast_marching.cpp, exact.cpp and ellipse.cpp). Why the
// searches reuse their arrays, and why the caller owns them: geodesic/workspace.hpp.
//
// Every kind S of scratch derives from ScratchBase and provides `void fit(std::size_t n)` (grow
// to n entries, new entries clean) and `void reset() noexcept` (make every entry clean again,
// by resetting exactly the entries its borrower recorded as touched). A borrower records an
// entry *before* changing it, so an exception at any point leaves a scratch that reset() cleans.
//
// Pseudocode:
//   acquire<S>(ws, n): a kept S of ws (else a new one), fit(n); ws reserves room to keep it back
//   release(ws, s):    s.reset(); keep s in ws when fewer than max_kept of its kind are kept,
//                      else free it (never allocates: the room was reserved when it was lent)
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

#include <fhr/geodesic/workspace.hpp>

namespace fhr::geodesic::detail {

/// The base of every kind of scratch a Workspace keeps; the kind is the dynamic type.
struct ScratchBase {
    virtual ~ScratchBase() = default;
};

/// The Workspace's side of borrowing (its only friend). Without a workspace (nullptr) every
/// acquire makes a new S and every release frees it.
struct WorkspaceAccess {
    /// A clean S with at least n entries; hand it back with release(), to the same workspace.
    template <class S>
    static std::unique_ptr<S> acquire(Workspace* ws, std::size_t n) {
        std::unique_ptr<S> s;
        if (ws) {
            std::vector<std::unique_ptr<ScratchBase>>& kept = ws->kept_;
            const auto it = std::find_if(kept.begin(), kept.end(),
                                         [](const auto& k) { return dynamic_cast<S*>(k.get()) != nullptr; });
            if (it != kept.end()) {
                s.reset(static_cast<S*>(it->release()));
                kept.erase(it);
            }
        }
        if (!s) s = std::make_unique<S>();
        s->fit(n);
        if (ws) {
            ws->kept_.reserve(ws->kept_.size() + ws->lent_ + 1);
            ++ws->lent_;
        }
        return s;
    }

    /// Resets s and keeps it in ws for the next acquire (at most Workspace::max_kept per kind).
    template <class S>
    static void release(Workspace* ws, std::unique_ptr<S> s) noexcept {
        if (!s) return;
        s->reset();
        if (!ws) return;
        --ws->lent_;
        std::vector<std::unique_ptr<ScratchBase>>& kept = ws->kept_;
        const auto same =
            std::count_if(kept.begin(), kept.end(), [](const auto& k) { return dynamic_cast<S*>(k.get()) != nullptr; });
        if (static_cast<std::size_t>(same) < Workspace::max_kept) kept.push_back(std::move(s));
    }
};

/// Empties a transient buffer for reuse; one that grew past `keep` entries (a whole-mesh search
/// may queue 10⁶ windows) gives its memory back instead of being kept in the workspace.
template <class V>
void clear_buffer(V& v, std::size_t keep = std::size_t{1} << 16) noexcept {
    if (v.capacity() > keep)
        V().swap(v);
    else
        v.clear();
}

/// unique_ptr deleter that hands the object back to the workspace it was borrowed from.
template <class S>
struct GiveBack {
    Workspace* workspace = nullptr;
    void operator()(S* s) const noexcept { WorkspaceAccess::release(workspace, std::unique_ptr<S>(s)); }
};

template <class S>
using Borrowed = std::unique_ptr<S, GiveBack<S>>;

/// A clean S with at least n entries, from `workspace` (nullptr: a new one), handed back to it
/// when the Borrowed is destroyed.
template <class S>
Borrowed<S> borrow(Workspace* workspace, std::size_t n) {
    return Borrowed<S>(WorkspaceAccess::acquire<S>(workspace, n).release(), GiveBack<S>{workspace});
}

}  // namespace fhr::geodesic::detail
