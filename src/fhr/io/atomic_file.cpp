// FHR io — atomic output files (spec/formats.md FMT-WRITE-1): the bytes go to `path.tmp-<pid>`,
// which is then renamed onto `path`, so a reader never sees a partial file and a failed write
// leaves nothing behind. The parts of a file are formatted on every thread of the executor and
// written where they belong (see atomic_file.hpp): part i waits only for the lengths of the parts
// before it, which are known as soon as those are formatted, not written.
#include <fhr/io/detail/atomic_file.hpp>

#include <algorithm>
#include <cerrno>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <utility>

#include <fcntl.h>
#include <unistd.h>

#include <fhr/core/errors.hpp>

namespace fhr::io {

namespace {

InvalidInput refusal(const std::string& path, int error) {
    return InvalidInput(path, 0, std::string("cannot write: ") + std::strerror(error));
}

}  // namespace

FileParts& FileParts::elements(std::size_t count, Put put) {
    puts_.push_back(std::move(put));
    for (std::size_t first = 0; first < count; first += block)
        parts_.push_back({puts_.size() - 1, first, std::min(count, first + block)});
    return *this;
}

FileParts& FileParts::text(std::string bytes) {
    texts_.push_back(std::move(bytes));
    parts_.push_back({SIZE_MAX, texts_.size() - 1, 0});
    return *this;
}

void FileParts::format(const Part& part, std::string& text) const {
    if (part.put == SIZE_MAX)
        text += texts_[part.first];
    else
        puts_[part.put](part.first, part.end, text);
}

std::string FileParts::joined() const {
    std::string all;
    for (const Part& part : parts_) format(part, all);
    return all;
}

void FileParts::write(const std::string& path, Executor* executor) const {
    const std::string temp = path + ".tmp-" + std::to_string(::getpid());
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) throw refusal(path, errno);
    // offset[i] is where part i goes, known for i <= known; a part whose formatting failed never
    // makes the next offset known, so no part after it is written.
    std::mutex lock;
    std::condition_variable published;
    std::vector<std::uint64_t> offset(parts_.size() + 1, 0);
    std::size_t known = 0;
    bool failed = false;
    try {
        executor_or_default(executor).for_each(parts_.size(), 2, [&](std::size_t i) {  // a lone part: no helper
            std::string bytes;
            try {
                format(parts_[i], bytes);
            } catch (...) {
                {
                    const std::lock_guard<std::mutex> hold(lock);
                    failed = true;
                }
                published.notify_all();
                throw;
            }
            std::uint64_t at = 0;
            {
                // Parts are handed out in order, so part i − 1 is being formatted or done: the wait is short.
                std::unique_lock<std::mutex> hold(lock);
                published.wait(hold, [&] { return known >= i || failed; });
                if (known < i) return;  // a part before this one failed
                at = offset[i];
                offset[i + 1] = at + bytes.size();
                known = i + 1;
            }
            published.notify_all();
            for (std::size_t done = 0; done < bytes.size();) {
                const ssize_t n = ::pwrite(fd, bytes.data() + done, bytes.size() - done, static_cast<off_t>(at + done));
                if (n < 0 && errno == EINTR) continue;
                if (n <= 0) throw refusal(path, n < 0 ? errno : EIO);
                done += static_cast<std::size_t>(n);
            }
        });
    } catch (...) {
        ::close(fd);
        std::remove(temp.c_str());
        throw;
    }
    if (::close(fd) != 0) {
        const int error = errno;
        std::remove(temp.c_str());
        throw refusal(path, error);
    }
    if (std::rename(temp.c_str(), path.c_str()) != 0) {
        const int error = errno;
        std::remove(temp.c_str());
        throw refusal(path, error);
    }
}

void write_file_atomically(const std::string& path, std::string_view bytes) {
    FileParts().text(std::string(bytes)).write(path);
}

}  // namespace fhr::io
