// FHR io — fuzz harness body: run one reader on arbitrary bytes and check what it returns
// against the postconditions of src/fhr/io/read.hpp (spec/formats.md).
#include "harness.hpp"

#include <cmath>
#include <string>
#include <string_view>

#include <fhr/core/errors.hpp>

namespace fhr::fuzz {

namespace {

void require(bool condition) {
    if (!condition) __builtin_trap();
}

void check_postconditions(const PolygonSoup& soup) {
    for (const Vec3& p : soup.points) require(p.allFinite() && p.cwiseAbs().maxCoeff() <= 1e150);
    require(!soup.offsets.empty() && soup.offsets.front() == 0 && soup.offsets.back() == soup.indices.size());
    require(soup.polygon_count() > 0);
    for (std::size_t f = 0; f < soup.polygon_count(); ++f)
        require(soup.polygon_size(f) >= 3 && soup.offsets[f] < soup.offsets[f + 1]);
    for (std::uint32_t i : soup.indices) require(i < soup.points.size());
    require(soup.point_line.empty() || soup.point_line.size() == soup.points.size());
    require(soup.polygon_line.empty() || soup.polygon_line.size() == soup.polygon_count());
}

}  // namespace

void run_one(io::Format format, const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        check_postconditions(io::parse(format, bytes, "fuzz"));
    } catch (const InvalidInput&) {
        // the expected refusal
    }
}

}  // namespace fhr::fuzz
