// Beyond the paper — a build without the page's script (meson option `page` off: web/'s npm
// packages absent): the page is not available (page.hpp).
#include <string_view>

namespace fhr::pipeline::detail {

std::string_view page_script() { return {}; }

}  // namespace fhr::pipeline::detail
