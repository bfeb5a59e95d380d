// FHR io — atomic output files (spec/formats.md FMT-WRITE-1): the bytes go to `path.tmp-<pid>`,
// which is then renamed onto `path`, so a reader never sees a partial file and a failed write
// leaves nothing behind.
#include <fhr/io/atomic_file.hpp>

#include <cerrno>
#include <cstring>
#include <utility>

#include <unistd.h>

#include <fhr/core/errors.hpp>

namespace fhr::io {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)), temp_(path_ + ".tmp-" + std::to_string(::getpid())) {
    file_ = std::fopen(temp_.c_str(), "wb");
    if (file_ == nullptr) refuse(errno);
    text.reserve(chunk + chunk / 4);  // a chunk and the element that completed it
}

AtomicFile::~AtomicFile() {
    if (file_ != nullptr) {  // never committed
        std::fclose(file_);
        std::remove(temp_.c_str());
    }
}

void AtomicFile::write(std::string_view bytes) {
    write_out();
    if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) refuse(errno);
}

void AtomicFile::write_out() {
    if (std::fwrite(text.data(), 1, text.size(), file_) != text.size()) refuse(errno);
    text.clear();
}

void AtomicFile::commit() {
    write_out();
    if (std::fclose(std::exchange(file_, nullptr)) != 0) refuse(errno);
    if (std::rename(temp_.c_str(), path_.c_str()) != 0) refuse(errno);
}

void AtomicFile::refuse(int error) {
    if (file_ != nullptr) std::fclose(std::exchange(file_, nullptr));
    std::remove(temp_.c_str());
    throw InvalidInput(path_, 0, std::string("cannot write: ") + std::strerror(error));
}

void write_file_atomically(const std::string& path, std::string_view bytes) {
    AtomicFile file(path);
    file.write(bytes);
    file.commit();
}

}  // namespace fhr::io
