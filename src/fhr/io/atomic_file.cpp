// FHR io — atomic output files (spec/formats.md FMT-WRITE-1): the bytes go to `path.tmp-<pid>`,
// which is then renamed onto `path`, so a reader never sees a partial file and a failed write
// leaves nothing behind.
#include <fhr/io/atomic_file.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include <unistd.h>

#include <fhr/core/errors.hpp>

namespace fhr::io {

void write_file_atomically(const std::string& path, std::string_view bytes) {
    const std::string temp = path + ".tmp-" + std::to_string(::getpid());
    const auto refuse = [&](int error) {
        std::remove(temp.c_str());
        throw InvalidInput(path, 0, std::string("cannot write: ") + std::strerror(error));
    };
    std::FILE* file = std::fopen(temp.c_str(), "wb");
    if (file == nullptr) refuse(errno);
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
    const int write_error = errno;
    if (std::fclose(file) != 0 || !written) refuse(written ? errno : write_error);
    if (std::rename(temp.c_str(), path.c_str()) != 0) refuse(errno);
}

}  // namespace fhr::io
