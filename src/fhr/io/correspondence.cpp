// FHR io — strict reader of correspondence files (see correspondence.hpp, FMT-CORR-*).
#include <fhr/io/correspondence.hpp>

#include <cmath>

#include <fhr/io/detail/text_scanner.hpp>

namespace fhr::io {

std::vector<CorrespondenceEntry> parse_correspondence(std::string_view bytes, const std::string& name,
                                                      std::size_t n_vertices, std::size_t n_faces) {
    detail::check_input_size(bytes, name);
    detail::TextScanner s(bytes, name);
    std::vector<CorrespondenceEntry> entries;
    // FMT-CORR-3: barycentric coordinates sum to 1 up to the rounding of a decimal file.
    constexpr double sum_tolerance = 1e-12;
    while (s.next_line()) {
        const detail::Where where{"entry", entries.size()};
        CorrespondenceEntry e{SurfacePoint(), s.line()};
        const std::string_view first = s.token();
        if (first == "f") {
            const FaceId f(s.index(where, n_faces));
            std::array<double, 3> b{};
            for (double& x : b) {
                x = s.real(where);
                if (!(x >= 0 && x <= 1))
                    s.fail(where, "barycentric coordinate " + std::to_string(x) + " is not in [0, 1]");
            }
            if (std::abs(b[0] + b[1] + b[2] - 1) > sum_tolerance)
                s.fail(where, "barycentric coordinates sum to " + std::to_string(b[0] + b[1] + b[2]) + ", not 1");
            e.point = SurfacePoint::in_face(f, b);
        } else {
            std::int64_t v = 0;
            const detail::NumberStatus status = detail::parse_int64(first, v);
            if (status == detail::NumberStatus::not_a_number)
                s.fail(where, "expected a vertex index or 'f FACE b0 b1 b2', found " + detail::quoted(first));
            if (status == detail::NumberStatus::out_of_range)
                s.fail(where, "vertex index " + detail::quoted(first) + " is out of range");
            e.point = SurfacePoint::at_vertex(VertexId(detail::checked_index(v, n_vertices, name, s.line(), where)));
        }
        s.expect_end_of_line(where);
        entries.push_back(e);
    }
    return entries;
}

}  // namespace fhr::io
