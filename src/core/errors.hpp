// FHR core — the exception taxonomy shared by every stage.
//
// The paper (Floater, Hormann, Reimers 2001, §1) assumes a valid closed orientable manifold
// triangulation T. Everything that can go wrong is one of a few kinds, each mapped to one CLI
// exit code (spec/cli.md):
//   InvalidInput      exit 2  the input is not what the paper's method accepts (file, line, element)
//   NumericalFailure  exit 4  a numerical step could not reach its stated tolerance
//   PartitionFailure  exit 3  §3 conditions (1)/(2) cannot be met even after recovery
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace fhr {

/// Base of every error fhr throws on purpose. `what()` is the full one-line message
/// without the leading "fhr: error: ".
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
    virtual int exit_code() const = 0;
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

    int exit_code() const override { return 2; }
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
    int exit_code() const override { return 4; }
};

/// §3: the geodesic network cannot be made to satisfy conditions (1) and (2).
class PartitionFailure : public Error {
public:
    using Error::Error;
    int exit_code() const override { return 3; }
};

}  // namespace fhr
