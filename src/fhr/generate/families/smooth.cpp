// FHR generate — the smooth family (issue 17): PENDING, implemented on a helper's branch.
#include <fhr/generate/detail/family.hpp>

namespace fhr::generate::detail {

std::size_t smooth_min_faces(const RandomMeshOptions&) { invalid("the smooth family is not built yet"); }
TriMesh smooth_mesh(const RandomMeshOptions&) { invalid("the smooth family is not built yet"); }

}  // namespace fhr::generate::detail
