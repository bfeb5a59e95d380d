// FHR tests — the `fhr-param 1` reader and writer (spec/param.md PARAM-1): exact
// round trips, deterministic bytes, and a strict reader that refuses every malformed file with a
// one-line InvalidInput naming the line, without crashing or allocating beyond the file size.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <bit>
#include <cmath>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/exchange/fhr_param.hpp>
#include <fhr/exchange/verify.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/testing/rapidcheck.hpp>
#include "support/test_support.hpp"
#include "synthetic.hpp"

using fhr::InvalidInput;
using fhr::exchange::format_param;
using fhr::exchange::ParamFile;
using fhr::exchange::parse_param;

namespace {

/// A small valid file: the 2-to-4 subdivision of a random genus-0 mesh with 12 faces.
ParamFile small_file() {
    fhr::generate::RandomMeshOptions o;
    o.genus = 0;
    o.faces = 12;
    o.seed = 3;
    o.noise = 0.1;
    return fhr::test::subdivided_param(fhr::generate::random_closed_mesh(o), 2);
}

/// The message of the InvalidInput that parsing `bytes` throws ("" if it parses).
std::string refusal(const std::string& bytes) {
    try {
        parse_param(bytes, "t.fhrp");
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

bool bitwise_equal(const ParamFile& a, const ParamFile& b) { return format_param(a) == format_param(b) && a == b; }

}  // namespace

TEST_CASE("PARAM-1: write -> read -> write is byte-identical and gives back every double bit for bit",
          "[exchange][property]") {
    rc::prop("random domains, k-to-k^2 subdivisions, noisy coordinates", [] {
        const auto& domain = *fhr::testing::gen_closed_mesh(0, 3, 300);
        const int k = *rc::gen::inRange(1, 4);
        ParamFile file = fhr::test::subdivided_param(domain, k);
        // Awkward doubles too: subnormals, negative zero, the largest finite magnitudes.
        file.surface_vertices[0].x() = -0.0;
        file.surface_vertices[0].y() = 4.9406564584124654e-324;
        file.domain_vertices[0].z() = -1.7976931348623157e308;
        file.surface_faces[0].beta[0][0] = 0.1 + 0.2;
        const std::string bytes = format_param(file);
        const ParamFile back = parse_param(bytes, "mem");
        RC_ASSERT(back == file);
        RC_ASSERT(std::bit_cast<std::uint64_t>(back.surface_vertices[0].x()) == std::bit_cast<std::uint64_t>(-0.0));
        RC_ASSERT(format_param(back) == bytes);
    });
}

TEST_CASE("PARAM-1: file equality, which the round trips rely on, sees a change in any one field", "[exchange]") {
    const ParamFile file = small_file();
    CHECK(file == small_file());
    std::vector<ParamFile> changed(7, file);
    changed[0].domain_vertices[1].y() += 1e-9;
    changed[1].domain_faces[2][1] = changed[1].domain_faces[2][0];
    changed[2].surface_vertices.pop_back();
    changed[3].surface_faces[4].v[2] += 1;
    changed[4].surface_faces[4].patch += 1;
    changed[5].surface_faces[4].beta[1][2] += 0.25;
    changed[6].surface_faces.pop_back();
    for (std::size_t i = 0; i < changed.size(); ++i) {
        INFO("change " << i);
        CHECK_FALSE(changed[i] == file);
    }
}

TEST_CASE("PARAM-1: write_param is atomic and its file reads back", "[exchange]") {
    const ParamFile file = small_file();
    const std::string path = fhr::test::temp_path("small.fhrp");
    fhr::exchange::write_param(path, file);
    CHECK(fhr::test::read_file(path) == format_param(file));
    CHECK(bitwise_equal(fhr::exchange::read_param(path), file));
    // An unwritable destination leaves nothing behind and says why.
    CHECK_THROWS_WITH(fhr::exchange::write_param(fhr::test::temp_path("no-such-dir/x.fhrp"), file),
                      Catch::Contains("cannot write"));
}

TEST_CASE("PARAM-1: tokens may be separated by any whitespace, and comments are ignored", "[exchange]") {
    const std::string text =
        "# a parameterization\nfhr-param 1 domain_vertices 4 0 0 0  1 0 0\t0 1 0 0 0 1\r\n"
        "domain_faces 4 0 2 1 0 1 3 0 3 2 1 2 3 # the tetrahedron\n"
        "surface_vertices 4\n0 0 0\v1 0 0\f0 1 0\n0 0 1\n"
        "surface_faces 4\n"
        "0 2 1 0  1 0 0  0 1 0  0 0 1\n0 1 3 1  1 0 0  0 1 0  0 0 1\n"
        "0 3 2 2  1 0 0  0 1 0  0 0 1\n1 2 3 3  1 0 0  0 1 0  0 0 1 # the end";  // no final newline
    const ParamFile file = parse_param(text, "tet.fhrp");
    REQUIRE(file.domain_faces.size() == 4);
    CHECK(file.surface_faces[3].v == fhr::Triangle{1, 2, 3});
    CHECK(file.surface_faces[3].patch == 3);
    CHECK(file.surface_faces[1].beta[2] == fhr::exchange::Beta{0, 0, 1});
    CHECK(fhr::exchange::verify(file, nullptr).valid());  // T′ = D: the identity
}

TEST_CASE("PARAM-1: malformed files are refused with one line naming the file, the line and the problem",
          "[exchange]") {
    const std::string body = format_param(small_file());
    const std::string after_header = body.substr(body.find('\n') + 1);
    struct Bad {
        const char* name;
        std::string bytes;
        const char* expect;
    };
    const std::vector<Bad> cases{
        {"empty", "", "empty file"},
        {"only comments", "# nothing\n\n", "empty file"},
        {"wrong magic", "fhr-params 1\n" + after_header, "t.fhrp:1: header: PARAM-1: not a fhr-param file"},
        {"wrong version", "fhr-param 2\n" + after_header, "unsupported version '2'"},
        {"header only", "fhr-param 1\n", "expected 'domain_vertices'"},
        {"sections out of order", "fhr-param 1\ndomain_faces 0\n",
         "expected the section 'domain_vertices', found 'domain_faces'"},
        {"huge count", "fhr-param 1\ndomain_vertices 4000000000\n0 0 0\n", "truncated"},
        {"count beyond 32 bits", "fhr-param 1\ndomain_vertices 99999999999\n", "not in [0, 2^32)"},
        {"negative count", "fhr-param 1\ndomain_vertices -4\n", "not in [0, 2^32)"},
        {"count beyond 64 bits", "fhr-param 1\ndomain_vertices 99999999999999999999\n",
         "a count '99999999999999999999' is not in [0, 2^32)"},
        {"word for a number", "fhr-param 1\ndomain_vertices 1\n0 zero 0\n",
         "t.fhrp:3: domain vertex 0: expected a number, found 'zero'"},
        {"number out of range", "fhr-param 1\ndomain_vertices 1\n0 1e999 0\n", "out of double range"},
        {"negative index", "fhr-param 1\ndomain_vertices 3\n0 0 0\n1 0 0\n0 1 0\ndomain_faces 1\n0 -1 2\n",
         "t.fhrp:7: domain face 0: a vertex index '-1' is not in [0, 2^32)"},
        {"trailing data", body + "7\n", "unexpected '7' after the last surface face"},
        {"binary garbage", "fhr-param 1\ndomain_vertices 1\n\x01\x02\xff 0 0\n", "'\\x01\\x02\\xff'"},
    };
    for (const Bad& c : cases) {
        DYNAMIC_SECTION(c.name) {
            const std::string message = refusal(c.bytes);
            CHECK_THAT(message, Catch::Contains(c.expect));
            CHECK(message.find('\n') == std::string::npos);
        }
    }
}

TEST_CASE("PARAM-1: every truncation of a valid file is refused, naming where the file ends", "[exchange]") {
    const std::string bytes = format_param(small_file());
    std::size_t refused = 0;
    for (std::size_t n = 0; n < bytes.size(); ++n) {
        const std::string message = refusal(bytes.substr(0, n));
        // Cutting the final newline or inside the last number's trailing digits may still parse
        // (to a different last β); every other prefix is refused.
        if (!message.empty())
            ++refused;
        else
            CHECK(n + 20 > bytes.size());
    }
    CHECK(refused + 20 >= bytes.size());
}

TEST_CASE("PARAM-1: arbitrary bytes never crash the reader, and whatever it accepts the oracle judges without throwing",
          "[exchange][property]") {
    rc::prop("random mutations of a valid file", [] {
        std::string bytes = format_param(small_file());
        const int edits = *rc::gen::inRange(1, 8);
        for (int e = 0; e < edits; ++e) {
            const std::size_t at = *rc::gen::inRange<std::size_t>(0, bytes.size());
            bytes[at] = *rc::gen::element('0', '1', '9', '-', ' ', '\n', '#', 'e', '.', 'x', '\0');
        }
        try {
            const ParamFile file = parse_param(bytes, "mutated");
            const auto report = fhr::exchange::verify(file, nullptr);
            RC_ASSERT(report.checks.size() == 9u);  // PARAM-2..10, whatever their results
        } catch (const InvalidInput& e) {
            RC_ASSERT(std::string(e.what()).find('\n') == std::string::npos);
        }
    });
}
