// FHR io — atomic output files: no partial output is ever left behind (DEVELOPERS.md standards).
// Large files are written as they are formatted, a chunk at a time (issue 18: a 10⁶-triangle run
// writes about 800 MB of text; formatting each file whole into memory first cost as much memory
// as the run's meshes and the time of growing the strings).
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace fhr::io {

/// A file written under the temporary name `path.tmp-<pid>` and renamed onto `path` by commit().
/// Appended bytes gather in `text` and go to the temporary file whenever a chunk (1 MiB) is full
/// (step()); a file never committed (an exception, a formatting error) is removed by the
/// destructor. Failures throw InvalidInput(path, 0, "cannot write: <reason>").
class AtomicFile {
public:
    explicit AtomicFile(std::string path);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::string text;  ///< bytes appended and not yet written
    /// Writes `text` out when it holds a full chunk (call it after each element).
    void step() {
        if (text.size() >= chunk) write_out();
    }
    /// Writes `text`, then `bytes` as they are (a block already formatted).
    void write(std::string_view bytes);
    /// Writes the rest, closes and renames the file onto its path.
    void commit();

private:
    static constexpr std::size_t chunk = std::size_t{1} << 20;
    void write_out();
    [[noreturn]] void refuse(int error);

    std::string path_, temp_;
    std::FILE* file_ = nullptr;
};

/// Writes `bytes` to `path` atomically (an AtomicFile committed at once).
void write_file_atomically(const std::string& path, std::string_view bytes);

}  // namespace fhr::io
