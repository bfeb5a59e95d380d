// FHR §6 figures — PNG files by Debian's libpng (see png.hpp).
#include <fhr/render/png.hpp>

#include <png.h>

#include <csetjmp>
#include <cstddef>
#include <string>

#include <fhr/core/errors.hpp>
#include <fhr/io/detail/atomic_file.hpp>

namespace fhr::render {

namespace {

void append(png_structp png, png_bytep data, png_size_t length) {
    static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), length);
}

void no_flush(png_structp) {}

// libpng reports an error by a long jump back to encode_png's setjmp (its C frames cannot pass a
// C++ exception), the message kept for the InternalError thrown there; nothing is printed.
[[noreturn]] void on_error(png_structp png, png_const_charp message) {
    *static_cast<std::string*>(png_get_error_ptr(png)) = message;
    png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}  // about metadata, which encode_png sets itself

// libpng's write structures, destroyed however encode_png leaves.
struct Writer {
    std::string error;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, on_error, on_warning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    ~Writer() { png_destroy_write_struct(&png, &info); }
};

}  // namespace

std::string encode_png(const Image& image) {
    if (image.width < 1 || image.height < 1)  // PNG §11.2.2: 1 ≤ width, height ≤ 2^31 − 1 (an int)
        throw InvalidInput("png: image size " + std::to_string(image.width) + "×" + std::to_string(image.height) +
                           " is not at least 1×1");
    if (image.rgb.size() != 3 * std::size_t(image.width) * std::size_t(image.height))
        throw InvalidInput("png: pixel buffer has " + std::to_string(image.rgb.size()) + " bytes, expected 3·" +
                           std::to_string(image.width) + "·" + std::to_string(image.height));
    Writer w;
    if (!w.png || !w.info) throw InternalError("png: libpng could not allocate its write structures");
    std::string out;
    if (setjmp(png_jmpbuf(w.png))) throw InternalError("png: libpng: " + w.error);
    png_set_write_fn(w.png, &out, append, no_flush);
    png_set_IHDR(w.png, w.info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_filter(w.png, PNG_FILTER_TYPE_BASE, PNG_ALL_FILTERS);
    png_set_compression_level(w.png, 9);
    png_write_info(w.png, w.info);
    const std::size_t stride = 3 * std::size_t(image.width);
    for (int y = 0; y < image.height; ++y)
        png_write_row(w.png, const_cast<png_bytep>(image.rgb.data() + stride * std::size_t(y)));
    png_write_end(w.png, nullptr);
    return out;
}

void write_png(const std::string& path, const Image& image) { io::write_file_atomically(path, encode_png(image)); }

}  // namespace fhr::render
