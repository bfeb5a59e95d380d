// FHR core — what a validator reports when an invariant is broken: which invariant (its id in
// spec/), which element and which one, and what is wrong — a structure, not a string a caller must
// parse (spec/library.md LIB-2).
#pragma once

#include <cstdint>
#include <string>

namespace fhr {

/// The kind of element a broken invariant names.
enum class Element : std::uint8_t {
    whole,  ///< the object as a whole (index -1)
    vertex,
    edge,
    face,
    boundary_position,  ///< a position in a boundary loop
    corners,            ///< the corners of a patch (index -1)
};

struct Violation {
    std::string invariant;  ///< e.g. "MAP-1"
    Element element = Element::whole;
    std::int64_t index = -1;  ///< the element's index, -1 when it names none
    std::string what;         ///< one line, naming the element
    std::string describe() const { return invariant + ": " + what; }
};

}  // namespace fhr
