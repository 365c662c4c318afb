// The operator page's /metrics (Prometheus text format): the loop, every device's link, the run's
// counters and the page's own. A part of OperatorPage in a file of its own.
#include <fmt/format.h>

#include <tuple>

#include "web/operator_page.hpp"

namespace cellctl::web {

std::string OperatorPage::metrics_text() {
  std::string out;
  const auto add = [&](std::string_view name, std::string_view type, std::string_view help) {
    out += fmt::format("# HELP {} {}\n# TYPE {} {}\n", name, help, name, type);
  };
  if (const auto r = run_.status()) {
    const auto& v = r->view;
    add("cellctl_loop_jitter_seconds", "histogram", "Control loop wake-up minus deadline.");
    for (std::size_t b = 0; b < status::kJitterBucketsUs.size(); ++b)
      out += fmt::format("cellctl_loop_jitter_seconds_bucket{{le=\"{:g}\"}} {}\n",
                         status::kJitterBucketsUs[b] * 1e-6, v.jitter_le[b]);
    out += fmt::format("cellctl_loop_jitter_seconds_bucket{{le=\"+Inf\"}} {}\n", v.jitter_le.back());
    out += fmt::format("cellctl_loop_jitter_seconds_sum {:.9f}\ncellctl_loop_jitter_seconds_count {}\n",
                       v.jitter_sum_s, v.jitter_le.back());
    add("cellctl_loop_overrun_cycles_total", "counter", "Cycles that ran past their next deadline.");
    out += fmt::format("cellctl_loop_overrun_cycles_total {}\n", v.overruns);
    // Every device the cell has, by the name its slot carries (an empty slot: no device).
    add("cellctl_device_link_fault", "gauge", "1 when the device's session gave up on its link.");
    for (std::size_t d = 0; d < v.devices.size(); ++d)
      if (!v.devices[d].empty())
        out += fmt::format("cellctl_device_link_fault{{device=\"{}\"}} {}\n", v.devices[d],
                           v.link_fault[d] ? 1 : 0);
    add("cellctl_device_silent_seconds", "gauge", "Time since the device's last good reply.");
    for (std::size_t d = 0; d < v.devices.size(); ++d)
      if (!v.devices[d].empty())
        out += fmt::format("cellctl_device_silent_seconds{{device=\"{}\"}} {:.6f}\n", v.devices[d],
                           v.link_silent_s[d]);
    add("cellctl_device_exchanges_total", "counter", "Good replies from the device.");
    for (std::size_t d = 0; d < v.devices.size(); ++d)
      if (!v.devices[d].empty())
        out += fmt::format("cellctl_device_exchanges_total{{device=\"{}\"}} {}\n", v.devices[d],
                           v.link_counts[d].good_replies);
    add("cellctl_device_errors_total", "counter",
        "Failed exchanges: no answer in time, a bad frame, or a reply in which the device refused.");
    for (std::size_t d = 0; d < v.devices.size(); ++d) {
      if (v.devices[d].empty()) continue;
      const auto& c = v.link_counts[d];
      for (const auto& [kind, n] : {std::pair{"timeout", c.timeouts}, std::pair{"bad_frame", c.bad_frames},
                                    std::pair{"refused", c.refusals}})
        out += fmt::format("cellctl_device_errors_total{{device=\"{}\",kind=\"{}\"}} {}\n", v.devices[d],
                           kind, n);
    }
    add("cellctl_run_seconds", "gauge", "Time since the run started (the run's clock).");
    out += fmt::format("cellctl_run_seconds {:.6f}\n", v.t);
  }
  std::lock_guard lock(mutex_);
  const auto& a = mirror_.admin_tag();
  for (const auto& [key, help, n] :
       {std::tuple{"runs", "Runs started.", a.runs},
        std::tuple{"steps_done", "Recipe steps completed.", a.steps_done},
        std::tuple{"steps_failed", "Recipe steps failed.", a.steps_failed},
        std::tuple{"faults", "Safety monitor faults latched.", a.faults},
        std::tuple{"processed", "Recipe runs completed (PackML Admin.ProdProcessedCount).", a.processed},
        std::tuple{"defective", "Recipe runs ended Stopped or Aborted (PackML Admin.ProdDefectiveCount).",
                   a.defective}}) {
    const auto name = fmt::format("cellctl_{}_total", key);
    add(name, "counter", help);
    out += fmt::format("{} {}\n", name, n);
  }
  add("cellctl_state", "gauge", "PackML StateCurrent of the cell.");
  out +=
      fmt::format("cellctl_state{{state=\"{}\"}} {}\n", mirror_.state(), mirror_.state_tag().state_current);
  for (const auto& [name, help, n] :
       {std::tuple{"cellctl_web_commands_total", "Commands received by the page.", commands_},
        std::tuple{"cellctl_web_commands_refused_total", "Commands the page received and refused.", refused_},
        std::tuple{"cellctl_web_commands_unauthorised_total", "Commands without a valid token or session.",
                   commands_unauthorised_.load()},
        std::tuple{"cellctl_web_commands_abandoned_total",
                   "Commands not obeyed because their client had gone.", commands_abandoned_.load()}}) {
    add(name, "counter", help);  // each its own HELP and TYPE: a series without them is untyped
    out += fmt::format("{} {}\n", name, n);
  }
  const auto g = guard_.counters();
  add("cellctl_web_requests_refused_total", "counter",
      "Requests the page refused before reading their body: wrong Host or Origin (forbidden), no valid "
      "token or session (unauthorised), a wrong token (wrong_token, also counted as unauthorised), held "
      "back after wrong tokens (throttled), a body too large (too_large).");
  for (const auto& [why, n] : {std::pair{"forbidden", g.forbidden}, std::pair{"unauthorised", g.unauthorised},
                               std::pair{"wrong_token", g.wrong_tokens}, std::pair{"throttled", g.throttled},
                               std::pair{"too_large", g.too_large}})
    out += fmt::format("cellctl_web_requests_refused_total{{why=\"{}\"}} {}\n", why, n);
  add("cellctl_web_streams", "gauge", "Live-event readers connected now.");
  out += fmt::format("cellctl_web_streams {}\n", streams_.load());
  add("cellctl_web_streams_refused_total", "counter", "Live-event readers refused: every stream was taken.");
  out += fmt::format("cellctl_web_streams_refused_total {}\n", streams_refused_.load());
  add("cellctl_web_dropped_events_total", "counter", "Run events the page's queue had no room for.");
  out += fmt::format("cellctl_web_dropped_events_total {}\n", events_.dropped());
  return out;
}

}  // namespace cellctl::web
