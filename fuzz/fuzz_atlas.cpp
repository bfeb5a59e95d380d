// FHR exchange — libFuzzer target for the atlas readers (OBJ with vt, PLY with u v or texcoord;
// spec/atlas.md ATLAS-1) and the atlas oracle behind them (ATLAS-2..7): the reader must refuse any
// malformed bytes with InvalidInput, and whatever it accepts the oracle must judge without throwing
// or crashing, its sets consistent with its counts. Seeds: fuzz/corpus/atlas/.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include <fhr/core/errors.hpp>
#include <fhr/exchange/atlas.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        const fhr::exchange::Atlas atlas = fhr::exchange::parse_atlas(bytes, "fuzz");
        const fhr::exchange::AtlasReport report = fhr::exchange::verify_atlas(atlas, nullptr);
        // ATLAS-1..7, one result each; ATLAS-6's failures are the overlapping pairs found.
        if (report.checks.size() != 7) __builtin_trap();
        if (report.checks[5].status == fhr::exchange::CheckStatus::fail &&
            report.checks[5].failures != report.overlapping.size())
            __builtin_trap();
    } catch (const fhr::InvalidInput&) {
        // the expected refusal
    }
    return 0;
}
