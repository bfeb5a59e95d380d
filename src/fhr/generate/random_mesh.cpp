// FHR generate — random orientable manifold meshes (random_mesh.hpp): the families as entries of
// one table (name, least face count, maker, knobs), each family in its own file (the block, the
// base of them all, in block.cpp; the others in families/), and the recipe's text as
// `fhr generate` reads it. Adding a family is an enum value, its knobs' fields, its file and one
// entry here.
#include <fhr/generate/random_mesh.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/generate/detail/family.hpp>

namespace fhr::generate {
namespace {

using detail::invalid;

/// A knob of a family: its name as `fhr generate` spells it and its field of FamilyKnobs (a real
/// or an integer one).
struct Knob {
    const char* name = nullptr;
    double FamilyKnobs::*real = nullptr;
    int FamilyKnobs::*integer = nullptr;
};

struct FamilyEntry {
    Family family;
    const char* name;
    std::size_t (*min_faces)(const RandomMeshOptions&);
    TriMesh (*make)(const RandomMeshOptions&);
    std::array<Knob, 2> knobs;  // the first `knob_count`
    int knob_count;
};

// In the enum's order.
constexpr FamilyEntry families[] = {
    {Family::block, "block", detail::block_min_faces, detail::block_mesh, {}, 0},
    {Family::smooth,
     "smooth",
     detail::smooth_min_faces,
     detail::smooth_mesh,
     {{{"roundness", &FamilyKnobs::roundness}, {"amplitude", &FamilyKnobs::amplitude}}},
     2},
    {Family::quality,
     "quality",
     detail::quality_min_faces,
     detail::quality_mesh,
     {{{"bad-fraction", &FamilyKnobs::bad_fraction}, {"smallest-angle", &FamilyKnobs::smallest_angle_deg}}},
     2},
    {Family::valence,
     "valence",
     detail::valence_min_faces,
     [](const RandomMeshOptions& o) { return detail::valence_mesh(o); },
     {{{"high-valence", nullptr, &FamilyKnobs::high_valence}, {"low-fraction", &FamilyKnobs::low_fraction}}},
     2},
    {Family::density,
     "density",
     detail::density_min_faces,
     detail::density_mesh,
     {{{"edge-ratio", &FamilyKnobs::edge_ratio}, {"anisotropy", &FamilyKnobs::anisotropy}}},
     2},
    {Family::degenerate,
     "degenerate",
     detail::degenerate_min_faces,
     detail::degenerate_mesh,
     {{{"grid-cells", nullptr, &FamilyKnobs::grid_cells}}},
     1},
    {Family::immersed,
     "immersed",
     detail::immersed_min_faces,
     detail::immersed_mesh,
     {{{"depth", &FamilyKnobs::depth}}},
     1},
};

const FamilyEntry& entry(Family family) {
    const auto k = static_cast<std::size_t>(family);
    if (k >= std::size(families)) invalid("unknown family " + std::to_string(k));
    return families[k];
}

/// The shortest decimal that reads back as x (std::to_chars): a knob printed so exactly reproduces.
std::string shortest(double x) {
    char buffer[32];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;
    return std::string(buffer, end);
}

/// Every family's knobs, in the table's order, each with its family.
std::vector<KnobName> all_knobs() {
    std::vector<KnobName> knobs;
    for (const FamilyEntry& f : families)
        for (int k = 0; k < f.knob_count; ++k) knobs.push_back({f.knobs[static_cast<std::size_t>(k)].name, f.family});
    return knobs;
}

}  // namespace

std::size_t min_faces(const RandomMeshOptions& options) { return entry(options.family).min_faces(options); }

TriMesh random_mesh(const RandomMeshOptions& options) {
    const FamilyEntry& family = entry(options.family);
    detail::check_recipe(options, family.min_faces);
    return family.make(options);
}

TriMesh random_closed_mesh(const RandomMeshOptions& options) {
    if (options.holes != 0)
        invalid("random_closed_mesh makes closed surfaces: the number of holes must be 0 (got " +
                std::to_string(options.holes) + "); random_mesh makes surfaces with holes");
    return random_mesh(options);
}

const char* family_name(Family family) { return entry(family).name; }

Family parse_family(const std::string& name) {
    std::string names;
    for (const FamilyEntry& f : families) {
        if (name == f.name) return f.family;
        names += std::string(names.empty() ? "" : ", ") + f.name;
    }
    invalid("unknown family '" + name + "' (one of " + names + ")");
}

std::span<const KnobName> knob_names() {
    static const std::vector<KnobName> knobs = all_knobs();
    return knobs;
}

void set_knob(FamilyKnobs& knobs, Family family, const std::string& name, double value) {
    std::string dashed = name;
    std::replace(dashed.begin(), dashed.end(), '_', '-');
    for (const FamilyEntry& f : families)
        for (int k = 0; k < f.knob_count; ++k) {
            const Knob& knob = f.knobs[static_cast<std::size_t>(k)];
            if (dashed != knob.name) continue;
            if (f.family != family)
                invalid("--" + dashed + " is a knob of the " + f.name + " family, not of " + family_name(family));
            if (knob.real) {
                knobs.*knob.real = value;
                return;
            }
            if (!(value == std::floor(value) && std::abs(value) < 2e9))
                invalid("--" + dashed + " must be an integer (got " + shortest(value) + ")");
            knobs.*knob.integer = static_cast<int>(value);
            return;
        }
    invalid("unknown knob '" + name + "'");
}

std::string generate_command(const RandomMeshOptions& o, const std::string& out) {
    char noise[32];
    std::snprintf(noise, sizeof noise, "%g", o.noise);
    std::string s = "fhr generate";
    if (o.family != Family::block) s += std::string(" --family ") + family_name(o.family);
    s += " --genus " + std::to_string(o.genus);
    if (o.holes != 0) s += " --holes " + std::to_string(o.holes);
    if (o.components != 1) s += " --components " + std::to_string(o.components);
    s += " --faces " + std::to_string(o.faces) + " --seed " + std::to_string(o.seed);
    if (o.noise != 0) s += std::string(" --noise ") + noise;
    // The family's own knobs, where they differ from the defaults.
    const FamilyKnobs defaults{};
    const FamilyEntry& f = entry(o.family);
    for (int k = 0; k < f.knob_count; ++k) {
        const Knob& knob = f.knobs[static_cast<std::size_t>(k)];
        if (knob.real && o.knobs.*knob.real != defaults.*knob.real)
            s += std::string(" --") + knob.name + " " + shortest(o.knobs.*knob.real);
        if (knob.integer && o.knobs.*knob.integer != defaults.*knob.integer)
            s += std::string(" --") + knob.name + " " + std::to_string(o.knobs.*knob.integer);
    }
    return s + " --out " + out;
}

}  // namespace fhr::generate
