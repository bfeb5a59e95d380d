// FHR exchange — libFuzzer target for the `fhr-param 1` reader (spec/param.md PARAM-1) and the
// oracle behind it (`fhr verify`, PARAM-2..10): the reader must refuse any malformed bytes with
// InvalidInput, and whatever it accepts the oracle must judge without throwing or crashing —
// the oracle's inputs are other programs' outputs, so anything can arrive. Seeds: fuzz/corpus/param/.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include <fhr/core/errors.hpp>
#include <fhr/exchange/fhr_param.hpp>
#include <fhr/exchange/verify.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        const fhr::exchange::ParamFile file = fhr::exchange::parse_param(bytes, "fuzz");
        // PARAM-2..10, one result each, whatever they are.
        if (fhr::exchange::verify(file, nullptr).checks.size() != 9) __builtin_trap();
    } catch (const fhr::InvalidInput&) {
        // the expected refusal
    }
    return 0;
}
