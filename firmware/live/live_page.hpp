#pragma once
// The live view's one page (live_page.html), compiled into irlocd so that it works offline.

#include <string_view>

namespace irloc::firmware {

extern const std::string_view kLivePageHtml;

}  // namespace irloc::firmware
