// FHR generate — the degenerate family (issue 17): PENDING, implemented on a helper's branch.
#include <fhr/generate/detail/family.hpp>

namespace fhr::generate::detail {

std::size_t degenerate_min_faces(const RandomMeshOptions&) { invalid("the degenerate family is not built yet"); }
TriMesh degenerate_mesh(const RandomMeshOptions&) { invalid("the degenerate family is not built yet"); }

}  // namespace fhr::generate::detail
