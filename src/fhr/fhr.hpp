// <fhr/fhr.hpp> — the public API of the fhr library in one include (spec/library.md LIB-5): the
// paper's pipeline end to end (pipeline::run), one call per stage (§2 domain::decimate, §3
// geodesic::ellipse_shortest_path and partition::partition, §4 param::map_patch and param::relax,
// §5 wavelet::analyse), the mesh (core), its readers and writers (io), the `fhr-param 1` exchange
// file with its independent oracle (exchange::verify, UV atlases, per-vertex maps, distortion) and
// the random mesh generator.
// Exactly the installed headers: everything else is in detail/ folders or the command's and the
// Python module's application layer (src/fhr/app, src/fhr/render), neither installed.
// <fhr/testing/rapidcheck.hpp>, which needs RapidCheck, is included separately.
#pragma once

#include <fhr/core/build.hpp>
#include <fhr/core/disk.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/executor.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/core/ids.hpp>
#include <fhr/core/polygon_soup.hpp>
#include <fhr/core/surface_point.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/core/violation.hpp>
#include <fhr/domain/decimate.hpp>
#include <fhr/domain/domain.hpp>
#include <fhr/domain/user_domain.hpp>
#include <fhr/exchange/atlas.hpp>
#include <fhr/exchange/distortion.hpp>
#include <fhr/exchange/fhr_param.hpp>
#include <fhr/exchange/verdict.hpp>
#include <fhr/exchange/verify.hpp>
#include <fhr/exchange/vertex_map.hpp>
#include <fhr/generate/embedding.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/geodesic/ellipse.hpp>
#include <fhr/geodesic/exact.hpp>
#include <fhr/geodesic/workspace.hpp>
#include <fhr/io/correspondence.hpp>
#include <fhr/io/read.hpp>
#include <fhr/io/write.hpp>
#include <fhr/param/certificate.hpp>
#include <fhr/param/disk.hpp>
#include <fhr/param/locate.hpp>
#include <fhr/param/patch_map.hpp>
#include <fhr/param/relax.hpp>
#include <fhr/param/weights.hpp>
#include <fhr/partition/embed.hpp>
#include <fhr/partition/partition.hpp>
#include <fhr/partition/patches.hpp>
#include <fhr/pipeline/pipeline.hpp>
#include <fhr/pipeline/run.hpp>
#include <fhr/version.hpp>
#include <fhr/wavelet/analyse.hpp>
#include <fhr/wavelet/hausdorff.hpp>
#include <fhr/wavelet/refine.hpp>
