// FHR tests — a random decimated domain D of a random mesh T (paper §2), for the RapidCheck
// properties of §3 and §4: between min_closed_faces(genus) + 8 and #F(T)/3 faces.
#pragma once

#include <rapidcheck.h>

#include <algorithm>

#include <fhr/core/errors.hpp>
#include <fhr/domain/decimate.hpp>

namespace fhr::test {

/// Inside rc::prop only: decimates T to a random even face count; the case is discarded when that
/// size is beyond T or cannot be reached under the decimation's validity rules.
inline domain::Domain random_domain(const TriMesh& T, long genus) {
    const std::size_t lo = domain::min_closed_faces(genus) + 2 * 4;
    const std::size_t hi = std::max(lo, T.n_faces() / 3);
    const std::size_t target = 2 * *rc::gen::inRange(lo / 2, hi / 2 + 1);
    RC_PRE(target <= T.n_faces());
    domain::Domain D;
    try {
        D = domain::decimate(T, {.target_faces = target});
    } catch (const InvalidInput&) {
        RC_DISCARD("the decimation cannot reach this size under its rules");
    }
    return D;
}

/// The same for a surface with boundary or several components (DOM-18): any face count from 1 to
/// #F(T)/3 (even when every component is closed); §2 may give more (raised to the components'
/// least sizes, or stopped by the boundary's loops and corners); discarded when a closed component
/// cannot reach its share (DOM-9).
inline domain::Domain random_open_domain(const TriMesh& T) {
    std::size_t target = *rc::gen::inRange<std::size_t>(1, std::max<std::size_t>(2, T.n_faces() / 3 + 1));
    if (T.is_closed()) target += target % 2;
    try {
        return domain::decimate(T, {.target_faces = target});
    } catch (const InvalidInput&) {
        RC_DISCARD("a closed component cannot reach its share under the decimation's rules");
    }
}

}  // namespace fhr::test
