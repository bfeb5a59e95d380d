// FHR generate — the density family (issue 17): PENDING, implemented on a helper's branch.
#include <fhr/generate/detail/family.hpp>

namespace fhr::generate::detail {

std::size_t density_min_faces(const RandomMeshOptions&) { invalid("the density family is not built yet"); }
TriMesh density_mesh(const RandomMeshOptions&) { invalid("the density family is not built yet"); }

}  // namespace fhr::generate::detail
