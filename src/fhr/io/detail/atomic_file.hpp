// FHR io — atomic output files: no partial output is ever left behind (FMT-WRITE-1).
// Large files are made of parts formatted at once on the executor's threads (a
// 10⁶-triangle run writes about 800 MB; formatting each file whole into memory first cost as much
// memory as the run's meshes, and one thread per file left param.fhrp, the largest, alone on one
// core for two seconds after every other file was written).
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <fhr/core/executor.hpp>

namespace fhr::io {

/// A file's bytes as a sequence of parts: fixed texts and blocks of elements. write() writes them
/// atomically (FMT-WRITE-1): under the temporary name `path.tmp-<pid>`, renamed onto `path` when
/// every part is written; on any failure the temporary is removed and the failure rethrown —
/// InvalidInput(path, 0, "cannot write: <reason>") for the system's, else the exception of the
/// first part whose formatting failed. The parts are formatted at once on the executor's threads,
/// each into its own string, and each goes to its place in the file (pwrite) as soon as the parts
/// before it are formatted: the bytes are those of the parts one after another (joined()), on any
/// number of threads, and the memory held is a few parts per thread.
class FileParts {
public:
    /// Appends elements [first, end) to `text`; called from the executor's threads at once.
    using Put = std::function<void(std::size_t first, std::size_t end, std::string& text)>;
    /// Elements per part (a part of text is a few MB at most).
    static constexpr std::size_t block = 16384;

    /// `count` elements, formatted by put, a part per `block` of them.
    FileParts& elements(std::size_t count, Put put);
    /// A fixed text, as one part.
    FileParts& text(std::string bytes);

    /// Formats every part and writes the file atomically. \throws as above.
    void write(const std::string& path, Executor* executor = nullptr) const;
    /// Every part's bytes one after another, formatted on the calling thread.
    std::string joined() const;

private:
    struct Part {
        std::size_t put = 0;  // into puts_, or SIZE_MAX for texts_[first]
        std::size_t first = 0, end = 0;
    };
    void format(const Part& part, std::string& text) const;

    std::vector<Put> puts_;
    std::vector<std::string> texts_;
    std::vector<Part> parts_;
};

/// Writes `bytes` to `path` atomically (FileParts with one text).
void write_file_atomically(const std::string& path, std::string_view bytes);

}  // namespace fhr::io
