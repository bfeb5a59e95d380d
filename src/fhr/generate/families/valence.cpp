// FHR generate — the valence family (issue 17): PENDING, implemented on a helper's branch.
#include <fhr/generate/detail/family.hpp>

namespace fhr::generate::detail {

std::size_t valence_min_faces(const RandomMeshOptions&) { invalid("the valence family is not built yet"); }
TriMesh valence_mesh(const RandomMeshOptions&) { invalid("the valence family is not built yet"); }

}  // namespace fhr::generate::detail
