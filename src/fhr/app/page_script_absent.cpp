// Beyond the paper — a build without the page's script (meson option `page` off: web/'s npm
// packages absent): the page is not available (page.hpp).
#include <string_view>

namespace fhr::app::detail {

std::string_view page_script() { return {}; }

}  // namespace fhr::app::detail
