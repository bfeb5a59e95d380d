// FHR core — the exception taxonomy shared by every stage.
//
// The paper (Floater, Hormann, Reimers 2001, §1) assumes a valid closed orientable manifold
// triangulation T. Everything that can go wrong is one of a few kinds; the library only throws
// them, and the `fhr` command maps each to its exit code (src/cli/main.cpp, spec/cli.md):
//   InvalidInput      the input is not what the paper's method accepts (file, line, element)
//   PartitionFailure  §3 conditions (1)/(2) cannot be met, and D cannot be kept either
//   NumericalFailure  a numerical step could not reach its stated tolerance
//   InternalError     a broken invariant of fhr's own making (a bug), e.g. a patch §3 built that
//                     §4 refuses
// and, outside that family, ContractViolation: the caller broke a documented precondition.
// Neither InternalError nor ContractViolation is ever caught inside the library: an expected
// failure of a strategy is a return value (core/detail/outcome.hpp), not an exception.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace fhr {

/// Base of every error fhr throws on purpose. `what()` is the full one-line message
/// without the leading "fhr: error: ". No exit codes here: those are the command's concern.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

/// Bad input: a file or a request that the method cannot accept.
/// The message has the form `FILE[:LINE]: what is wrong (which vertex/face/edge)`.
class InvalidInput : public Error {
public:
    /// \param file  the input's name as the user gave it (may be empty for in-memory data)
    /// \param line  1-based line in a text file, or 0 when there is no line (binary data, topology)
    /// \param what  the problem, naming the element (e.g. "face 17 repeats vertex 4")
    InvalidInput(const std::string& file, std::uint64_t line, const std::string& what)
        : Error(compose(file, line, what)), file_(file), line_(line), problem_(what) {}
    /// A request that is not about a file (arguments, arrays in memory): no file, no line.
    explicit InvalidInput(const std::string& what) : InvalidInput(std::string(), 0, what) {}

    const std::string& file() const { return file_; }
    std::uint64_t line() const { return line_; }
    const std::string& problem() const { return problem_; }

private:
    static std::string compose(const std::string& file, std::uint64_t line, const std::string& what) {
        std::string s = file;
        if (line != 0) s.append(":").append(std::to_string(line));
        if (!s.empty()) s.append(": ");
        s.append(what);
        return s;
    }
    std::string file_;
    std::uint64_t line_;
    std::string problem_;
};

/// A numerical step failed to reach its stated tolerance.
class NumericalFailure : public Error {
public:
    using Error::Error;
};

/// §3: the geodesic network cannot be made to satisfy conditions (1) and (2).
class PartitionFailure : public Error {
public:
    using Error::Error;
};

/// A broken invariant of fhr's own making: a bug, whatever the input.
class InternalError : public Error {
public:
    using Error::Error;
};

/// The caller broke a documented precondition (`\pre`), as FHR_DCHECK and the mesh builder's
/// own checks find it (spec/library.md LIB-2): a bug of the caller, before anything changed.
class ContractViolation : public std::logic_error {
public:
    using std::logic_error::logic_error;
};

}  // namespace fhr
