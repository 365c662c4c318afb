#include "cli/logging.hpp"

#include <spdlog/async.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

namespace cellctl::cli {

void init_logging(const std::string& level, bool trace) {
  spdlog::init_thread_pool(8192, 1);
  auto console = spdlog::create_async<spdlog::sinks::stderr_color_sink_mt>("cellctl");
  console->set_pattern("%H:%M:%S.%e %^%l%$ %v");
  spdlog::set_default_logger(console);
  spdlog::set_level(spdlog::level::from_str(level));
  if (trace) {
    auto t = spdlog::create_async<spdlog::sinks::stderr_color_sink_mt>("trace");
    t->set_pattern("trace %v");
    t->set_level(spdlog::level::info);
  }
}

}  // namespace cellctl::cli
