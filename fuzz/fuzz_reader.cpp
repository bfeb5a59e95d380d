// FHR io — libFuzzer entry point for one reader, chosen at compile time with
// -DFHR_FUZZ_FORMAT=off|obj|ply|stl (fuzz/meson.build builds fuzz_off, fuzz_obj, fuzz_ply, fuzz_stl).
#include "harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fhr::fuzz::run_one(fhr::io::Format::FHR_FUZZ_FORMAT, data, size);
    return 0;
}
