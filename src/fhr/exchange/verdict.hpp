// FHR exchange — the oracle's verdict as one JSON object (spec/cli.md CLI-VERIFY-4): what
// `fhr verify --json` prints and what the Python package's fhr.verify returns, written once for
// both. Each kind of map has its own keys after the shared ones; the distortion figures
// (spec/distortion.md) are in every verdict.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fhr/exchange/atlas.hpp>
#include <fhr/exchange/fhr_param.hpp>
#include <fhr/exchange/verify.hpp>
#include <fhr/exchange/vertex_map.hpp>

namespace fhr::io {
class JsonWriter;
}

namespace fhr::exchange {

/// DIST-4..8 (spec/distortion.md) as the members of the object `distortion` of a verdict or a
/// report, written into the object the caller opened: the one place their layout is written.
void write_distortion_fields(io::JsonWriter& j, const Distortion& d);

enum class MapKind { param, atlas };

/// The kind of map a file holds (spec/cli.md `fhr verify`), by its content: a `fhr-param 1` file when
/// its first token is `fhr-param`, an atlas when it starts with the `ply` magic; otherwise by the
/// name: `.fhrp` a `fhr-param 1` file (its reader then says what is wrong), anything else an OBJ atlas.
MapKind kind_of_content(std::string_view bytes, std::string_view name);

/// A `fhr-param 1` file's verdict: `checks` are PARAM-1 (grammar_check) and the report's.
/// `path` and `mesh` are the names written under `file` and `mesh` (mesh null when absent).
std::string verdict_json(const std::string& path, const std::optional<std::string>& mesh, const ParamFile& file,
                         const std::vector<CheckResult>& checks, const Distortion& distortion);

/// An atlas's verdict; with `lists`, also the folded faces, overlapping pairs and contacts.
std::string verdict_json(const std::string& path, const std::optional<std::string>& mesh, const Atlas& atlas,
                         const AtlasReport& report, bool lists);

/// A per-vertex map's verdict (spec/vertex_map.md): `kind` vertex_map, `rule`, `format`, the
/// domain's file, the figures; with `lists`, the folded faces and the edges without an image.
std::string verdict_json(const std::string& path, const std::string& domain, const std::string& mesh,
                         const VertexMapFile& map, const PolygonSoup& D, const PolygonSoup& T,
                         const VertexMapReport& report, bool lists);

}  // namespace fhr::exchange
