// FHR io — reading a mesh file (spec/formats.md FMT-EXT-1, FMT-SIZE-0): the format from the
// extension, the whole file in one read, then the strict parser of that format.
#include <cerrno>
#include <cstring>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fhr/io/detail/text_scanner.hpp>
#include <fhr/io/read.hpp>

namespace fhr::io {

Format format_from_extension(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    const std::size_t dot = path.find_last_of('.');
    std::string ext =
        (dot == std::string::npos || (slash != std::string::npos && dot < slash)) ? "" : path.substr(dot + 1);
    for (char& c : ext) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    if (ext == "off" || ext == "coff") return Format::off;
    if (ext == "obj") return Format::obj;
    if (ext == "ply") return Format::ply;
    if (ext == "stl") return Format::stl;
    throw InvalidInput(path, 0,
                       "unknown format (extension " +
                           (ext.empty() ? std::string("missing") : detail::quoted("." + ext)) +
                           "; expected .off, .coff, .obj, .ply or .stl)");
}

std::string read_bytes(const std::string& path) {
    const auto refuse = [&](const char* what, int error) {
        throw InvalidInput(path, 0, std::string(what) + ": " + std::strerror(error));
    };
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) refuse("cannot open", errno);
    struct stat st {};
    if (::fstat(fd, &st) != 0 || S_ISDIR(st.st_mode)) {
        const int error = S_ISDIR(st.st_mode) ? EISDIR : errno;
        ::close(fd);
        refuse("cannot open", error);
    }
    std::string bytes;
    if (S_ISREG(st.st_mode)) bytes.reserve(static_cast<std::size_t>(st.st_size));
    char buffer[1 << 16];
    while (true) {
        const ssize_t got = ::read(fd, buffer, sizeof buffer);
        if (got == 0) break;
        if (got < 0) {
            if (errno == EINTR) continue;
            const int error = errno;
            ::close(fd);
            refuse("cannot read", error);
        }
        bytes.append(buffer, static_cast<std::size_t>(got));
    }
    ::close(fd);
    return bytes;
}

PolygonSoup read_soup(const std::string& path) {
    const Format format = format_from_extension(path);
    return parse(format, read_bytes(path), path);
}

TriMesh read_mesh(const std::string& path, const BuildOptions& options, BuildLog* log) {
    BuildLog ignored;
    return build_trimesh(read_soup(path), options, log ? *log : ignored);
}

PolygonSoup parse(Format format, std::string_view bytes, const std::string& name) {
    switch (format) {
        case Format::off: return parse_off(bytes, name);
        case Format::obj: return parse_obj(bytes, name);
        case Format::ply: return parse_ply(bytes, name);
        case Format::stl: return parse_stl(bytes, name);
    }
    throw InvalidInput(name, 0, "unknown format");
}

}  // namespace fhr::io
