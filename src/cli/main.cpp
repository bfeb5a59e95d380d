// FHR cli — the `fhr` command. Subcommands follow the paper's pipeline (§2–§6); this file only
// dispatches and maps the error taxonomy (src/fhr/core/errors.hpp) to exit codes (spec/cli.md):
// 0 success, 2 invalid input or usage, 3 partition failure, 4 numerical failure, 70 internal error.
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/version.hpp>
#include "cli/common.hpp"

namespace {

constexpr const char* usage = R"(fhr — Floater, Hormann & Reimers (2001), Parameterization of Manifold Triangulations

usage:
  fhr info MESH [--json] [--triangulate]
      vertices, edges, faces, genus, components, boundary loops, bounding box, edge lengths,
      and whether MESH is a valid input (an orientable manifold, maybe with boundary loops and
      several components; spec/mesh.md)
  fhr generate --genus G --faces N [--holes H] [--components C] [--seed S] [--noise X] --out MESH
      a random orientable manifold mesh with exactly N faces: closed, connected, of genus G, or
      with H boundary loops (0-10000) in C components (1-10000), G and H spread over them
      (N even when H = 0)
  fhr generate [--family F] --genus G [--holes H] [--components C] [knobs] --min-faces
      prints the least face count N of that recipe (bench/run_families.py draws from it up)
  fhr convert MESH --out MESH2 [--triangulate]
      validate MESH and write it as .off, .obj or .ply
  fhr decimate MESH (--faces N | --vertices N) --out DOMAIN.off [--min-angle DEG]
               [--max-normal-deviation DEG] [--corner-angle DEG]
      §2: the parameter domain D by half-edge collapses; writes DOMAIN.off and, beside it,
      DOMAIN.correspondence (the vertex of MESH at each vertex of D). With boundary, D keeps
      the boundary's corners (turning by more than DEG, default 60) and --vertices is refused;
      several components share the faces in proportion to their areas
  fhr attach MESH --domain D.off --correspondence FILE [--out MESH2]
      §2: check a user-given domain D and its points x_j on MESH (a vertex index, or
      `f FACE b0 b1 b2` per line); points in faces or on edges are inserted (Fig. 4); with --out,
      write the refined mesh and MESH2.correspondence (every x_j now a vertex)
  fhr geodesic MESH SRC DST [--json] [--K K]
      §3: the exact shortest path between two vertices, searched in the ellipse sub-mesh
      (K = 1.06, grown until the result is certified): length, points, K, windows
  fhr run MESH (--faces N | --domain D.off --correspondence FILE) --out DIR
          [--weights shape-preserving|mean-value|uniform] [--solver sparse-lu|bicgstab] [--map relaxed|paper]
          [--paths keep|geodesic] [--levels J [--keep P,Q,...]] [--figures] [--html [--page-faces N]] [--up x|y|z]
          [--corner-angle DEG] [--threads N]
      §2–§4 end to end (--paths keep, the default: D is kept, edges whose geodesics conflict
      get restricted shortest paths; geodesic: the paper's geodesics only, D changed where they conflict;
      --map relaxed, the default: each patch map relaxed where that lowers its distortion; paper: the
      paper's §4 map exactly): writes DIR/domain.off, geodesics.obj, refined.ply, param.fhrp,
      textured.obj, report.json, timings.json; with --levels also §5's remesh_LJ.off and
      wavelet_keepP.off (the largest P % of the wavelet coefficients); with --figures DIR/figures/: the paper's
      Figures 6-9 as PNG, patches and the rate-distortion plot as SVG; with --html DIR/index.html: every
      stage in one interactive page that opens from file:// (spec/page.md), T′ drawn as is up to N faces
      (2,000,000), beyond that a display copy; exit 3 if §3 cannot partition, 4 if not certified
  fhr verify FILE [--mesh INPUT] [--json [--list]] [--kind param|atlas] [--paper] [--no-mirror] [--strict]
      the oracle: check a `fhr-param 1` file against PARAM-1..11 (spec/param.md), or a UV atlas (OBJ
      with vt, PLY with u v or texcoord) against ATLAS-1..8 (spec/atlas.md), the kind decided by
      content; with the distortion figures (spec/distortion.md); --paper judges chord length (PARAM-10);
      exit 1 if invalid
  fhr verify --vertex-map MAP --domain D --mesh T [--rule adjacent] [--format plain|corr|vtpm|ijv] [--json [--list]]
      the oracle on a per-vertex map of T onto D (.vmap, .corr, .vtpm, .ijv), its edges and faces
      mapped by the rule, against VMAP-1..9 (spec/vertex_map.md); exit 1 if invalid
  fhr oracle-fuzz --cmd 'PROGRAM {mesh} {out}' --count N [--family NAME|all] [--genus-max G]
                  [--holes-max H] [--components-max C] [--seed S] [--keep DIR] [--timeout SECONDS]
                  [--shard K/N'] [--table FILE] [--topology closed|disk|any] [--kind param|atlas|vertex-map]
                  [--faces-min F]
      fuzz another implementation: N random meshes (of every embedded family, or of NAME;
      genus 0-G, default 2; 0-H boundary loops, default 5; 1-C components, default 3; H = 0,
      C = 1 or --topology closed: closed and connected only; --topology disk: disks), each run
      through PROGRAM and its output checked by the oracle (a fhr-param 1 file, with --kind
      atlas a UV atlas, with --kind vertex-map a folder with map.vmap and D.off); failures kept in DIR with their reason and a smaller failing mesh of the
      same family. --shard K/N': only the meshes i with i mod N' = K-1; --table: the results as a
      table (tab-separated, no times)
  fhr oracle-fuzz --merge FILE... [--table FILE]
      the tables of a campaign's shards as the one table of the unsharded run; its failures and
      `N meshes, K failures`; exit 0 without failures, 1 with, 2 if the tables do not fit together
  fhr help | fhr --version

MESH files: .off/.coff, .obj, .ply (ascii or binary), .stl (ascii or binary).
exit codes: 0 ok, 2 invalid input or usage, 3 partition failure, 4 numerical failure, 70 bug.
)";

}  // namespace

namespace fhr::cli {
int run_verify(const std::vector<std::string>& args);       // src/cli/verify.cpp
int run_run(const std::vector<std::string>& args);          // src/cli/run.cpp
int run_oracle_fuzz(const std::vector<std::string>& args);  // src/cli/oracle_fuzz.cpp
}  // namespace fhr::cli

int main(int argc, char** argv) {
    const std::vector<std::string> args(argv + (argc > 1 ? 2 : argc), argv + argc);
    const std::string command = argc > 1 ? argv[1] : "";
    try {
        if (command == "info") return fhr::cli::run_info(args);
        if (command == "generate") return fhr::cli::run_generate(args);
        if (command == "convert") return fhr::cli::run_convert(args);
        if (command == "decimate") return fhr::cli::run_decimate(args);
        if (command == "attach") return fhr::cli::run_attach(args);
        if (command == "geodesic") return fhr::cli::run_geodesic(args);
        if (command == "verify") return fhr::cli::run_verify(args);
        if (command == "run") return fhr::cli::run_run(args);
        if (command == "oracle-fuzz") return fhr::cli::run_oracle_fuzz(args);
        if (command == "help" || command == "--help" || command == "-h") {
            std::fputs(usage, stdout);
            return 0;
        }
        if (command == "--version" || command == "version") {
            std::printf("fhr %.*s\n", static_cast<int>(fhr::version.size()), fhr::version.data());
            return 0;
        }
        fhr::cli::usage_error(command.empty() ? "no command given" : "unknown command '" + command + "'");
    } catch (const fhr::Error& e) {
        const int code = fhr::cli::exit_code_of(e);
        std::fprintf(stderr, code == 70 ? "fhr: internal error (a bug, please report it): %s\n" : "fhr: error: %s\n",
                     e.what());
        return code;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "fhr: error: out of memory\n");
        return 70;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fhr: internal error (a bug, please report it): %s\n", e.what());
        return 70;
    }
}
