// FHR generate — the immersed family (issue 17): PENDING, implemented on a helper's branch.
#include <fhr/generate/detail/family.hpp>

namespace fhr::generate::detail {

std::size_t immersed_min_faces(const RandomMeshOptions&) { invalid("the immersed family is not built yet"); }
TriMesh immersed_mesh(const RandomMeshOptions&) { invalid("the immersed family is not built yet"); }

}  // namespace fhr::generate::detail
