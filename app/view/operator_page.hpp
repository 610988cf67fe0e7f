// The operator page: one self-contained HTML document (styles and script inline, nothing fetched
// from the internet) served at / by the operator view.
#pragma once

#include <string_view>

namespace rovctl::app {

std::string_view operator_page_html();

}  // namespace rovctl::app
