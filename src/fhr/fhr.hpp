// <fhr/fhr.hpp> — the whole public API of the fhr library in one include (spec/library.md): the
// paper's pipeline end to end (pipeline::run), each stage on its own (§2 domain, §3 geodesics and
// partition, §4 patch maps and their certificate, §5 wavelets), the mesh readers and writers, the
// `fhr-param 1` exchange file with its independent oracle, the random mesh generator and the
// figures. Internals (the detail/ folders) are not part of it. <fhr/testing/rapidcheck.hpp>, which
// needs RapidCheck, is included separately.
#pragma once

#include <fhr/core/build.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/executor.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/core/ids.hpp>
#include <fhr/core/polygon_soup.hpp>
#include <fhr/core/predicates.hpp>
#include <fhr/core/surface_point.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/core/violation.hpp>
#include <fhr/domain/decimate.hpp>
#include <fhr/domain/user_domain.hpp>
#include <fhr/exchange/atlas.hpp>
#include <fhr/exchange/distortion.hpp>
#include <fhr/exchange/fhr_param.hpp>
#include <fhr/exchange/verdict.hpp>
#include <fhr/exchange/verify.hpp>
#include <fhr/generate/embedding.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/geodesic/ellipse.hpp>
#include <fhr/geodesic/exact.hpp>
#include <fhr/geodesic/fast_marching.hpp>
#include <fhr/geodesic/workspace.hpp>
#include <fhr/io/atomic_file.hpp>
#include <fhr/io/correspondence.hpp>
#include <fhr/io/read.hpp>
#include <fhr/io/write.hpp>
#include <fhr/param/certificate.hpp>
#include <fhr/param/disk.hpp>
#include <fhr/param/dividing_edges.hpp>
#include <fhr/param/locate.hpp>
#include <fhr/param/patch_map.hpp>
#include <fhr/param/weights.hpp>
#include <fhr/partition/embed.hpp>
#include <fhr/partition/keep.hpp>
#include <fhr/partition/partition.hpp>
#include <fhr/partition/patches.hpp>
#include <fhr/pipeline/outputs.hpp>
#include <fhr/pipeline/page.hpp>
#include <fhr/pipeline/pipeline.hpp>
#include <fhr/pipeline/run.hpp>
#include <fhr/render/figures.hpp>
#include <fhr/render/image.hpp>
#include <fhr/render/png.hpp>
#include <fhr/render/raster.hpp>
#include <fhr/render/svg.hpp>
#include <fhr/version.hpp>
#include <fhr/wavelet/analyse.hpp>
#include <fhr/wavelet/compress.hpp>
#include <fhr/wavelet/filter_bank.hpp>
#include <fhr/wavelet/hausdorff.hpp>
#include <fhr/wavelet/prewavelet.hpp>
#include <fhr/wavelet/refine.hpp>
