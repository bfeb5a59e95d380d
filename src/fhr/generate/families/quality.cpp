// FHR generate — the quality family (issue 17): PENDING, implemented on a helper's branch.
#include <fhr/generate/detail/family.hpp>

namespace fhr::generate::detail {

std::size_t quality_min_faces(const RandomMeshOptions&) { invalid("the quality family is not built yet"); }
TriMesh quality_mesh(const RandomMeshOptions&) { invalid("the quality family is not built yet"); }

}  // namespace fhr::generate::detail
