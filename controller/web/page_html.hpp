#pragma once
// The operator page itself: one self-contained HTML document (styles and script inline, nothing
// fetched from anywhere else), fed by /events (server-sent events) and commanding through /cmd/<word>.

#include <string_view>

namespace cellctl::web {

[[nodiscard]] std::string_view operator_page_html() noexcept;

}  // namespace cellctl::web
