// FHR io — the fuzz harness body shared by the libFuzzer targets (fuzz_reader.cpp) and the
// always-built replayer (replay_main.cpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include <fhr/io/read.hpp>

namespace fhr::fuzz {

/// Parses `data` with the reader of `format`. InvalidInput is the expected way to refuse; any
/// other exception escapes (a finding). When parsing succeeds, the postconditions of
/// io::parse (finite points, indices in range, monotone offsets, polygons of ≥ 3 vertices, line
/// tables empty or complete) are checked and a violation traps.
void run_one(io::Format format, const std::uint8_t* data, std::size_t size);

}  // namespace fhr::fuzz
