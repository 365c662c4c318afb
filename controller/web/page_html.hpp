#pragma once
// The operator page itself: an HTML document, its style sheet and its script, served as three
// resources (/, /page.css, /page.js) so that the page's Content-Security-Policy can forbid inline
// code; nothing is fetched from anywhere else. Fed by /events (server-sent events), commanding
// through /cmd/<word>, known by a session cookie after logging in with the token (POST /login). The
// document and its style are in page_html.cpp, the script in page_script.cpp.

#include <string_view>

namespace cellctl::web {

[[nodiscard]] std::string_view operator_page_html() noexcept;
[[nodiscard]] std::string_view operator_page_style() noexcept;
[[nodiscard]] std::string_view operator_page_script() noexcept;

}  // namespace cellctl::web
