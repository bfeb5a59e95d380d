// Tests of the writers (spec/formats.md FMT-WRITE-*): exact round trip through our own readers
// for OFF, OBJ and PLY, the written layouts, and atomic replacement of the output file.
#include <algorithm>
#include <atomic>
#include <bit>
#include <cerrno>
#include <cfloat>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <sys/resource.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <fhr/core/executor.hpp>
#include <fhr/io/detail/atomic_file.hpp>
#include <fhr/io/detail/number_text.hpp>
#include <fhr/io/read.hpp>
#include <fhr/io/write.hpp>
#include "refusal.hpp"
#include "support/test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using fhr::Vec3;
using fhr::io::Triangle;
using fhr::test::refusal;

namespace {

/// Doubles of every kind a coordinate may be: special values (±0, 0.1, subnormals, the limits
/// ±1e150) and arbitrary bit patterns with the exponent folded into the accepted range
/// (exponent field < 1520, so |x| < 2^497 < 1e150; field 0 gives subnormals).
rc::Gen<double> coordinate() {
    return rc::gen::weightedOneOf<double>({
        {1, rc::gen::element(0.0, -0.0, 0.1, -0.1, 1.0 / 3.0, 1e-300, -1e-300, 1e150, -1e150, 5e-324,
                             2.2250738585072009e-308, DBL_MIN, 123456789.123456789)},
        {3, rc::gen::map(rc::gen::arbitrary<std::uint64_t>(),
                         [](std::uint64_t bits) {
                             const std::uint64_t exponent = ((bits >> 52) & 0x7ff) % 1520;
                             return std::bit_cast<double>((bits & ~(0x7ffULL << 52)) | (exponent << 52));
                         })},
    });
}

struct Mesh {
    std::vector<Vec3> points;
    std::vector<Triangle> triangles;
};

Mesh random_mesh() {
    Mesh m;
    const auto n = *rc::gen::inRange<std::uint32_t>(1, 30);
    for (std::uint32_t v = 0; v < n; ++v) m.points.emplace_back(*coordinate(), *coordinate(), *coordinate());
    const auto f = *rc::gen::inRange<std::size_t>(1, 30);
    for (std::size_t t = 0; t < f; ++t) {
        Triangle tri;
        for (std::uint32_t& i : tri) i = *rc::gen::inRange<std::uint32_t>(0, n);
        m.triangles.push_back(tri);
    }
    return m;
}

/// The soup read back holds exactly the mesh: bit-identical coordinates, the same triangles.
bool same_mesh(const fhr::PolygonSoup& soup, const Mesh& m) {
    if (soup.points.size() != m.points.size() || soup.polygon_count() != m.triangles.size()) return false;
    for (std::size_t v = 0; v < m.points.size(); ++v)
        for (int c = 0; c < 3; ++c)
            if (std::bit_cast<std::uint64_t>(soup.points[v][c]) != std::bit_cast<std::uint64_t>(m.points[v][c]))
                return false;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
        if (soup.polygon_size(t) != 3) return false;
        for (int c = 0; c < 3; ++c)
            if (soup.polygon(t)[c] != m.triangles[t][c]) return false;
    }
    return true;
}

/// The names in `dir`.
std::vector<std::string> listing(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

const std::vector<Vec3> unit_points = {{0.1, -0.0, 1e-300}, {1, 2, 3}, {5e-324, -1e150, 0.5}};
const std::vector<Triangle> unit_triangle = {{0, 1, 2}};

}  // namespace

TEST_CASE("FMT-WRITE-2: write then read is bit-identical for OFF, OBJ and PLY", "[property][io]") {
    const std::string off = fhr::test::temp_path("round-trip.off");
    const std::string obj = fhr::test::temp_path("round-trip.obj");
    const std::string ply = fhr::test::temp_path("round-trip.ply");
    rc::prop("OFF round trip", [&] {
        const Mesh m = random_mesh();
        fhr::io::write_off(off, m.points, m.triangles);
        RC_ASSERT(same_mesh(fhr::io::read_soup(off), m));
    });
    rc::prop("OBJ round trip", [&] {
        const Mesh m = random_mesh();
        std::vector<fhr::io::Vec2> uv;
        if (*rc::gen::arbitrary<bool>())
            for (std::size_t k = 0; k < 3 * m.triangles.size(); ++k) uv.emplace_back(*coordinate(), *coordinate());
        fhr::io::write_obj(obj, m.points, m.triangles, uv);
        RC_ASSERT(same_mesh(fhr::io::read_soup(obj), m));
    });
    rc::prop("PLY round trip", [&] {
        const Mesh m = random_mesh();
        fhr::io::write_ply(ply, m.points, m.triangles);
        RC_ASSERT(same_mesh(fhr::io::read_soup(ply), m));
    });
}

TEST_CASE("FMT-WRITE-2: tuples written through RecentNumbers are the bytes append_number writes, repeated or not",
          "[property][io]") {
    // A pool of tuples (every kind of double, 0 and −0 apart), drawn again and again: tuples seen
    // before, tuples whose slot of the table another took meanwhile (up to 9,000 in a pool for
    // 4,096 slots), and tuples that differ from an earlier one in one coordinate only.
    rc::prop("pairs and triples", [] {
        const auto pool_size = *rc::gen::inRange<std::size_t>(1, 9000);
        std::vector<std::array<double, 3>> pool(pool_size);
        for (auto& x : pool) x = {*coordinate(), *coordinate(), *coordinate()};
        if (pool_size > 1) pool[1] = {pool[0][0], pool[0][1], -pool[0][2]};
        fhr::io::RecentNumbers<3> triples;
        fhr::io::RecentNumbers<2> pairs;
        std::string recent3, plain3, recent2, plain2;
        const auto draws = *rc::gen::inRange<std::size_t>(1, 20000);
        for (std::size_t i = 0; i < draws; ++i) {
            const auto& x = pool[*rc::gen::inRange<std::size_t>(0, pool_size)];
            triples.append(recent3, x);
            pairs.append(recent2, {x[0], x[1]});
            for (std::size_t k = 0; k < 3; ++k) {
                if (k > 0) plain3 += ' ';
                fhr::io::append_number(plain3, x[k]);
            }
            fhr::io::append_number(plain2, x[0]);
            plain2 += ' ';
            fhr::io::append_number(plain2, x[1]);
            recent3 += '\n', plain3 += '\n', recent2 += '\n', plain2 += '\n';
        }
        RC_ASSERT(recent3 == plain3);
        RC_ASSERT(recent2 == plain2);
    });
}

TEST_CASE("FMT-WRITE-2: OFF text uses the shortest round-trip numbers", "[unit][io]") {
    const std::string path = fhr::test::temp_path("unit.off");
    fhr::io::write_off(path, unit_points, unit_triangle);
    CHECK(fhr::test::read_file(path) == "OFF\n3 1 0\n0.1 -0 1e-300\n1 2 3\n5e-324 -1e+150 0.5\n3 0 1 2\n");
}

TEST_CASE("FMT-WRITE-3: OBJ with per-corner texture coordinates", "[unit][io]") {
    const std::string path = fhr::test::temp_path("uv.obj");
    const std::vector<fhr::io::Vec2> uv = {{0, 0}, {1, 0.1}, {1.0 / 3.0, 1}};
    fhr::io::write_obj(path, unit_points, unit_triangle, uv);
    CHECK(fhr::test::read_file(path) ==
          "v 0.1 -0 1e-300\nv 1 2 3\nv 5e-324 -1e+150 0.5\nvt 0 0\nvt 1 0.1\nvt 0.3333333333333333 1\nf 1/1 2/2 3/3\n");
    fhr::io::write_obj(path, unit_points, unit_triangle);
    CHECK_THAT(fhr::test::read_file(path), Contains("\nf 1 2 3\n"));
    CHECK_THROWS_AS(fhr::io::write_obj(path, unit_points, unit_triangle, std::vector<fhr::io::Vec2>(2)),
                    std::invalid_argument);
    // Made as written: corner c's coordinate asked once, in order.
    std::vector<std::size_t> asked;
    fhr::io::write_obj(path, unit_points, unit_triangle, [&](std::size_t c) {
        asked.push_back(c);
        return uv[c];
    });
    CHECK(asked == std::vector<std::size_t>{0, 1, 2});
    CHECK(fhr::test::read_file(path) ==
          "v 0.1 -0 1e-300\nv 1 2 3\nv 5e-324 -1e+150 0.5\nvt 0 0\nvt 1 0.1\nvt 0.3333333333333333 1\nf 1/1 2/2 3/3\n");
}

TEST_CASE("FMT-WRITE-3: binary PLY layout (little endian doubles, uchar/uint face lists)", "[unit][io]") {
    const std::string path = fhr::test::temp_path("unit.ply");
    fhr::io::write_ply(path, unit_points, unit_triangle);
    const std::string bytes = fhr::test::read_file(path);
    const std::string header =
        "ply\nformat binary_little_endian 1.0\ncomment written by fhr\nelement vertex 3\nproperty double x\n"
        "property double y\nproperty double z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n";
    REQUIRE(bytes.size() == header.size() + 3 * 24 + 13);
    CHECK(bytes.substr(0, header.size()) == header);
    CHECK(bytes.substr(header.size(), 8) == std::string("\x9a\x99\x99\x99\x99\x99\xb9\x3f", 8));  // 0.1
    CHECK(bytes.substr(header.size() + 72) == std::string("\x03\0\0\0\0\x01\0\0\0\x02\0\0\0", 13));
}

TEST_CASE("FMT-WRITE-*: writers refuse triangles that index past the points", "[unit][io]") {
    const std::vector<Triangle> bad = {{0, 1, 3}};
    const std::string path = fhr::test::temp_path("bad.off");
    CHECK_THROWS_AS(fhr::io::write_off(path, unit_points, bad), std::invalid_argument);
    CHECK_THROWS_AS(fhr::io::write_obj(path, unit_points, bad), std::invalid_argument);
    CHECK_THROWS_AS(fhr::io::write_ply(path, unit_points, bad), std::invalid_argument);
    CHECK_FALSE(fs::exists(path));
}

TEST_CASE("FMT-WRITE-1: a successful write replaces the file and leaves no temporary", "[unit][io]") {
    const fs::path dir = fhr::test::temp_path("atomic-ok");
    fs::create_directories(dir);
    const std::string path = (dir / "mesh.off").string();
    fhr::io::write_file_atomically(path, "old");
    fhr::io::write_off(path, unit_points, unit_triangle);
    CHECK(listing(dir) == std::vector<std::string>{"mesh.off"});
    CHECK(fhr::io::read_soup(path).points.size() == 3);
}

TEST_CASE("FMT-WRITE-1: a failed write throws InvalidInput and leaves nothing behind", "[unit][io]") {
    const fs::path dir = fhr::test::temp_path("atomic-fail");
    fs::create_directories(dir);

    const std::string missing_dir = (dir / "no-such-dir" / "mesh.off").string();
    const fhr::InvalidInput missing = refusal([&] { fhr::io::write_off(missing_dir, unit_points, unit_triangle); });
    CHECK(missing.file() == missing_dir);
    CHECK(missing.line() == 0);
    CHECK(missing.problem() == "cannot write: No such file or directory");

    const std::string under_file = fhr::test::write_temp("atomic-plain-file", "x") + "/mesh.ply";
    CHECK(refusal([&] { fhr::io::write_ply(under_file, unit_points, unit_triangle); }).problem() ==
          "cannot write: Not a directory");

    // the temporary is written, then the rename onto a directory fails: the temporary goes
    fs::create_directories(dir / "occupied.obj");
    const fhr::InvalidInput occupied =
        refusal([&] { fhr::io::write_obj((dir / "occupied.obj").string(), unit_points, unit_triangle); });
    CHECK_THAT(occupied.problem(), Contains("cannot write: Is a directory"));

    std::vector<std::string> expected = {"occupied.obj"};
    if (::geteuid() != 0) {  // permissions do not stop root
        const fs::path read_only = dir / "read-only";
        fs::create_directories(read_only);
        fs::permissions(read_only, fs::perms::owner_read | fs::perms::owner_exec);
        CHECK_THAT(
            refusal([&] { fhr::io::write_off((read_only / "m.off").string(), unit_points, unit_triangle); }).problem(),
            Contains("cannot write: Permission denied"));
        CHECK(listing(read_only).empty());
        fs::permissions(read_only, fs::perms::owner_all);
        expected.push_back("read-only");
    }
    CHECK(listing(dir) == expected);
    CHECK(listing(dir / "occupied.obj").empty());
}

TEST_CASE(
    "FMT-WRITE-1, FMT-WRITE-2: files of many chunks are written whole, and one failing after its first chunks leaves "
    "nothing",
    "[unit][io]") {
    // io::FileParts makes a part of every 16,384 elements: 200,000 points and triangles make
    // several MiB and dozens of parts in every format.
    const fs::path dir = fhr::test::temp_path("atomic-chunks");
    fs::create_directories(dir);
    std::vector<Vec3> points;
    std::vector<Triangle> triangles;
    for (std::uint32_t i = 0; i < 200000; ++i) {
        points.emplace_back(i / 7.0, -(i / 3.0), 1.0 / (i + 1));
        triangles.push_back({i, (i + 1) % 200000, (i + 2) % 200000});
    }
    for (const char* name : {"big.off", "big.obj", "big.ply"}) {
        const std::string path = (dir / name).string();
        fhr::io::write_mesh(path, points, triangles);
        CHECK(fs::file_size(path) > (std::size_t{3} << 20));
        const fhr::PolygonSoup soup = fhr::io::read_soup(path);
        CHECK(soup.points == points);
        CHECK(soup.polygon_count() == triangles.size());
        CHECK(std::equal(soup.polygon(199999), soup.polygon(199999) + 3, triangles.back().begin()));
    }
    // The last polyline indexes past the points: refused after several MiB went to the temporary.
    const std::vector<std::vector<std::uint32_t>> lines = {std::vector<std::uint32_t>(300000, 1), {0, 200000}};
    CHECK_THROWS_AS(fhr::io::write_obj_polylines((dir / "lines.obj").string(), points, lines, {}),
                    std::invalid_argument);
    CHECK(listing(dir) == std::vector<std::string>{"big.obj", "big.off", "big.ply"});
}

TEST_CASE("FMT-WRITE-4: a file of many parts has the same bytes on one thread and on three, as joined", "[unit][io]") {
    // Parts of unequal sizes, texts between element blocks, and a part formatted slowly so that
    // later parts are formatted first and wait for its length.
    const fs::path dir = fhr::test::temp_path("parts-threads");
    fs::create_directories(dir);
    auto parts = [](std::atomic<int>& slow_calls) {
        fhr::io::FileParts p;
        p.text("head\n");
        p.elements(3 * fhr::io::FileParts::block + 5,
                   [&slow_calls](std::size_t first, std::size_t end, std::string& out) {
                       if (first == fhr::io::FileParts::block) {  // the second part
                           ++slow_calls;
                           std::this_thread::sleep_for(std::chrono::milliseconds(50));
                       }
                       for (std::size_t i = first; i < end; ++i) {
                           fhr::io::append_number(out, i * i);
                           out += i % 7 == 0 ? "\n" : " ";
                       }
                   });
        p.text("");
        p.text("middle\n");
        p.elements(2, [](std::size_t first, std::size_t end, std::string& out) {
            out += std::to_string(first) + "-" + std::to_string(end);
        });
        return p;
    };
    std::atomic<int> calls{0};
    const fhr::io::FileParts p = parts(calls);
    const std::string joined = p.joined();
    CHECK(joined.substr(0, 5) == "head\n");
    CHECK(joined.substr(joined.size() - 10) == "middle\n0-2");
    fhr::ThreadPool one(1), three(3);
    p.write((dir / "one.txt").string(), &one);
    p.write((dir / "three.txt").string(), &three);
    p.write((dir / "default.txt").string());
    CHECK(calls == 4);
    CHECK(fhr::test::read_file((dir / "one.txt").string()) == joined);
    CHECK(fhr::test::read_file((dir / "three.txt").string()) == joined);
    CHECK(fhr::test::read_file((dir / "default.txt").string()) == joined);
    CHECK(listing(dir) == std::vector<std::string>{"default.txt", "one.txt", "three.txt"});
}

TEST_CASE("FMT-WRITE-1, FMT-WRITE-4: when parts fail, the first failing part's exception is thrown and nothing is left",
          "[unit][io]") {
    const fs::path dir = fhr::test::temp_path("parts-fail");
    fs::create_directories(dir);
    fhr::io::FileParts p;
    p.elements(8 * fhr::io::FileParts::block, [](std::size_t first, std::size_t, std::string& out) {
        const std::size_t part = first / fhr::io::FileParts::block;
        // Part 5 fails at once, part 3 only after the parts around it are done: still part 3's.
        if (part == 3) {
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
            throw std::runtime_error("part 3");
        }
        if (part == 5) throw std::runtime_error("part 5");
        out += std::string(1000, 'x');
    });
    fhr::ThreadPool three(3);
    for (fhr::Executor* executor : {static_cast<fhr::Executor*>(&three), static_cast<fhr::Executor*>(nullptr)}) {
        try {
            p.write((dir / "failed.txt").string(), executor);
            FAIL("no exception");
        } catch (const std::runtime_error& e) {
            CHECK(std::string(e.what()) == "part 3");
        }
        CHECK(listing(dir).empty());
    }
}

TEST_CASE(
    "FMT-WRITE-1, FMT-WRITE-4: a part the system refuses to write (a file size limit) throws InvalidInput and leaves "
    "nothing",
    "[unit][io]") {
    // RLIMIT_FSIZE makes writes past 64 KiB fail with EFBIG (SIGXFSZ ignored), after a first part
    // went to the temporary in full and the one across the limit in part.
    const fs::path dir = fhr::test::temp_path("parts-limit");
    fs::create_directories(dir);
    fhr::io::FileParts p;
    p.elements(4 * fhr::io::FileParts::block,
               [](std::size_t first, std::size_t end, std::string& out) { out.append(4 * (end - first), 'x'); });
    rlimit before{};
    REQUIRE(::getrlimit(RLIMIT_FSIZE, &before) == 0);
    const auto previous = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limited = before;
    limited.rlim_cur = 64 * 1024;
    REQUIRE(::setrlimit(RLIMIT_FSIZE, &limited) == 0);
    const std::string path = (dir / "big.txt").string();
    std::string problem;
    try {
        p.write(path);
    } catch (const fhr::InvalidInput& e) {
        problem = e.problem();
        CHECK(e.file() == path);
    }
    ::setrlimit(RLIMIT_FSIZE, &before);
    std::signal(SIGXFSZ, previous);
    CHECK(problem == "cannot write: File too large");
    CHECK(listing(dir).empty());
    p.write(path);  // the limit lifted: the whole file
    CHECK(fs::file_size(path) == 4 * 4 * fhr::io::FileParts::block);
}

TEST_CASE(
    "FMT-WRITE-1: a one-byte file, a file whose descriptor is 0 (standard input closed), and a stale errno: each "
    "written",
    "[unit][io]") {
    // open() returns the lowest free descriptor: with standard input closed, the temporary is fd 0,
    // which is a valid descriptor, not a failure; a write of one byte is a whole write; errno left
    // at EINTR by an earlier call says nothing about a write that succeeded.
    const fs::path dir = fhr::test::temp_path("parts-small");
    fs::create_directories(dir);
    const std::string one = (dir / "one.txt").string();
    errno = EINTR;
    fhr::io::write_file_atomically(one, "x");
    CHECK(fhr::test::read_file(one) == "x");
    const int saved = ::dup(0);
    REQUIRE(saved >= 0);
    ::close(0);
    const std::string zero = (dir / "zero.txt").string();
    std::string problem;
    try {
        fhr::io::write_file_atomically(zero, "written through descriptor 0\n");
    } catch (const fhr::InvalidInput& e) {
        problem = e.problem();
    }
    ::dup2(saved, 0);
    ::close(saved);
    CHECK(problem.empty());
    CHECK(fhr::test::read_file(zero) == "written through descriptor 0\n");
    CHECK(listing(dir) == std::vector<std::string>{"one.txt", "zero.txt"});
}
