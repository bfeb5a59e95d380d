// FHR tests — the invariants PART-1..8 and PART-13 of spec/partition.md, checked on any result of §3's
// partition: shared by the unit, property and real-mesh tests.
#pragma once

#include <string>
#include <vector>

#include <fhr/core/trimesh.hpp>
#include <fhr/geodesic/exact.hpp>
#include <fhr/partition/partition.hpp>

namespace fhr::test {

/// The exact shortest geodesic Γ(x_j, x_k) of every edge of D (the ellipse search), along D's
/// halfedge (e, 0): the paths embed() takes.
std::vector<geodesic::GeodesicPath> exact_paths(const TriMesh& T, const domain::Domain& D);

/// The first broken invariant of spec/partition.md for partition P of T ("" when all hold).
std::string partition_violation(const TriMesh& T, const partition::Partition& P);

/// PART-9 for a partition P of T that started from the decimated domain D0 ("" when it holds).
std::string recovery_violation(const TriMesh& T, const domain::Domain& D0, const partition::Partition& P);

/// PART-10 for a partition P of T that kept the domain D0 ("" when it holds): D0 delivered as
/// given; every curve an exact geodesic (its length Γ's, recomputed here) or a restricted path
/// no shorter than Γ, within its separation bound of the restricted shortest length, with a reason.
std::string keep_violation(const TriMesh& T, const domain::Domain& D0, const partition::Partition& P);

}  // namespace fhr::test
