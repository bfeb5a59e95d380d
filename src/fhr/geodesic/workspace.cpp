// FHR §3 (beyond the paper) — the caller's workspace and the pool of workspaces for
// parallel searches (see workspace.hpp; borrowing from a workspace: detail/scratch.hpp).
#include <fhr/geodesic/workspace.hpp>

#include <utility>

#include <fhr/geodesic/detail/scratch.hpp>

namespace fhr::geodesic {

Workspace::Workspace() = default;
Workspace::~Workspace() = default;

WorkspacePool::WorkspacePool() = default;
WorkspacePool::~WorkspacePool() = default;

WorkspacePool::Lease WorkspacePool::lease() {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (idle_.empty()) {
        std::unique_ptr<Workspace> workspace = std::make_unique<Workspace>();
        idle_.reserve(made_ + 1);  // room for every workspace to come back
        ++made_;
        return Lease(*this, std::move(workspace));
    }
    std::unique_ptr<Workspace> workspace = std::move(idle_.back());
    idle_.pop_back();
    return Lease(*this, std::move(workspace));
}

WorkspacePool::Lease::Lease(WorkspacePool& pool, std::unique_ptr<Workspace> workspace)
    : pool_(pool), workspace_(std::move(workspace)) {}

WorkspacePool::Lease::~Lease() {
    const std::lock_guard<std::mutex> lock(pool_.mutex_);
    pool_.idle_.push_back(std::move(workspace_));  // no allocation: lease() reserved the room
}

}  // namespace fhr::geodesic
