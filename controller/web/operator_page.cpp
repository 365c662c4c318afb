#include "web/operator_page.hpp"

#include <fmt/format.h>
#include <httplib.h>

#include <algorithm>
#include <charconv>
#include <chrono>

#include "web/fault_remedy.hpp"
#include "web/page_html.hpp"

namespace cellctl::web {
namespace {

using namespace std::chrono_literals;

// Compares without stopping at the first difference, so the time taken tells nothing of the token.
bool same_token(std::string_view given, std::string_view token) {
  unsigned diff = given.size() == token.size() ? 0u : 1u;
  for (std::size_t i = 0; i < token.size(); ++i)
    diff |= static_cast<unsigned>(static_cast<unsigned char>(i < given.size() ? given[i] : 0) ^
                                  static_cast<unsigned char>(token[i]));
  return diff == 0 && !token.empty();
}

std::string given_token(const httplib::Request& req) {
  if (req.has_header("X-Cellctl-Token")) return req.get_header_value("X-Cellctl-Token");
  const auto auth = req.get_header_value("Authorization");
  if (auth.rfind("Bearer ", 0) == 0) return auth.substr(7);
  return {};
}

std::string sse(std::string_view event, const nlohmann::json& data) {
  return fmt::format("event: {}\ndata: {}\n\n", event, data.dump());
}

}  // namespace

std::optional<PageOptions> parse_listen_address(std::string_view text, std::string& why) {
  PageOptions o;
  auto port_text = text;
  if (const auto colon = text.rfind(':'); colon != std::string_view::npos) {
    o.address = std::string(text.substr(0, colon));
    port_text = text.substr(colon + 1);
    if (o.address.empty()) {
      why = "the address before ':' is empty (127.0.0.1:8080, or 8080 for loopback)";
      return std::nullopt;
    }
  }
  int port = 0;
  const auto r = std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (r.ec != std::errc() || r.ptr != port_text.data() + port_text.size() || port < 1 || port > 65535) {
    why = fmt::format("'{}' is no port (1 to 65535)", port_text);
    return std::nullopt;
  }
  o.port = port;
  return o;
}

OperatorPage::OperatorPage(PageOptions options, const config::CellCore& cell, plant_link::RunAccess run)
    : options_(std::move(options)),
      cell_(cell),
      run_(std::move(run)),
      mirror_(cell, run_.mode),
      desk_(cell, options_.recipes, run_, std::chrono::milliseconds(2000)),
      server_(std::make_unique<httplib::Server>()) {
  if (options_.token.empty()) throw std::invalid_argument("the operator page needs a token for commands");
  auto& s = *server_;
  s.Get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(std::string(operator_page_html()), "text/html; charset=utf-8");
  });
  s.Get("/events", [this](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-cache");
    auto last_admin = std::make_shared<std::uint64_t>(UINT64_MAX);
    auto first = std::make_shared<bool>(true);
    res.set_chunked_content_provider(
        "text/event-stream", [this, last_admin, first](std::size_t, httplib::DataSink& sink) {
          if (stop_.load()) return false;
          std::string out;
          if (*first) {
            out += sse("cell", {{"cell", cell_.name}});
            std::lock_guard lock(mutex_);
            out += sse("mode", mirror_.mode_tag());
            *first = false;
          } else {
            std::this_thread::sleep_for(200ms);  // the page's refresh period; a server thread, never the loop
          }
          out += sse("status", status_json());
          {
            std::lock_guard lock(mutex_);
            if (*last_admin != admin_version_) {
              *last_admin = admin_version_;
              out += sse("admin", admin_json());
              out += sse("mode", mirror_.mode_tag());
            }
          }
          return sink.write(out.data(), out.size());
        });
  });
  s.Post(R"(/cmd/([a-z-]+))", [this](const httplib::Request& req, httplib::Response& res) {
    const std::string word = req.matches[1];
    if (!same_token(given_token(req), options_.token)) {
      {
        std::lock_guard lock(mutex_);
        ++unauthorised_;
      }
      res.status = 401;
      res.set_content(
          plant_link::answer(word, nullptr, false, "a valid token is required for any command").dump(),
          "application/json");
      return;
    }
    const command::CommandSource source{command::CommandSource::Origin::web,
                                        fmt::format("{}:{}", req.remote_addr, req.remote_port), "token"};
    res.set_content(command(word, req.body, source).dump(), "application/json");
  });
  s.Get("/metrics", [this](const httplib::Request&, httplib::Response& res) {
    res.set_content(metrics_text(), "text/plain; version=0.0.4");
  });
  if (options_.port == 0) {
    port_ = s.bind_to_any_port(options_.address);
  } else {
    port_ = s.bind_to_port(options_.address, options_.port) ? options_.port : -1;
  }
  if (port_ <= 0)
    throw std::runtime_error(
        fmt::format("the operator page cannot listen on {}:{}", options_.address, options_.port));
  server_thread_ = std::thread([this] { server_->listen_after_bind(); });
  pump_thread_ = std::thread([this] { pump(); });
}

OperatorPage::~OperatorPage() {
  stop_.store(true);
  server_->stop();
  if (server_thread_.joinable()) server_thread_.join();
  if (pump_thread_.joinable()) pump_thread_.join();
}

void OperatorPage::on_journal_line(const nlohmann::json& line) noexcept {
  events_.push(line);
}

void OperatorPage::pump() {
  while (!stop_.load()) {
    bool any = false;
    {
      std::lock_guard lock(mutex_);
      while (const auto e = events_.pop()) {
        any = true;
        const auto changed = mirror_.apply(*e);
        if (changed.admin || changed.state) ++admin_version_;
        for (auto& a : desk_.on_event(*e)) answers_.push_back(std::move(a));
      }
      for (auto& a : desk_.expire(std::chrono::steady_clock::now())) answers_.push_back(std::move(a));
    }
    answered_.notify_all();
    if (!any) std::this_thread::sleep_for(5ms);
  }
}

nlohmann::json OperatorPage::command(const std::string& word, const std::string& body,
                                     const command::CommandSource& source) {
  const auto received = std::chrono::steady_clock::now();
  // The desk bounds the body before it parses it; the page's own id is the one its answer is found by.
  std::uint64_t id = 0;
  std::string state;
  {
    const std::lock_guard lock(mutex_);
    ++commands_;
    id = next_id_++;
    state = std::string(mirror_.state());
  }
  auto immediate = desk_.submit({word, body, source, received, id}, state);
  std::unique_lock lock(mutex_);
  if (!immediate) {
    // The desk times out unanswered commands itself; the wait's own bound is a little longer.
    const nlohmann::json mine = id;
    const auto found = [&] {
      return std::find_if(answers_.begin(), answers_.end(),
                          [&](const nlohmann::json& a) { return a.contains("id") && a.at("id") == mine; });
    };
    answered_.wait_for(lock, 3s, [&] { return found() != answers_.end(); });
    if (const auto it = found(); it != answers_.end()) {
      immediate = std::move(*it);
      answers_.erase(it);
    } else {
      immediate = plant_link::answer(word, id, false, "no answer from the run");
    }
  }
  if (!immediate->value("ok", false)) ++refused_;
  return *immediate;
}

nlohmann::json OperatorPage::status_json() {
  plant_link::LiveStatus live;
  if (const auto r = run_.status())
    live = {true, r->view.t, r->view.step, r->view.steps, r->label, r->view.jitter_max_us};
  std::lock_guard lock(mutex_);
  return mirror_.status_tag(live);
}

nlohmann::json OperatorPage::admin_json() {
  auto a = mirror_.admin_tag();
  for (auto& f : a["active_faults"]) f["remedy"] = std::string(fault_remedy(f["rule"].get<std::string>()));
  return a;
}

std::string OperatorPage::metrics_text() {
  std::string out;
  const auto add = [&](std::string_view name, std::string_view type, std::string_view help) {
    out += fmt::format("# HELP {} {}\n# TYPE {} {}\n", name, help, name, type);
  };
  if (const auto r = run_.status()) {
    const auto& v = r->view;
    add("cellctl_loop_jitter_seconds", "histogram", "Control loop wake-up minus deadline.");
    for (std::size_t b = 0; b < runtime::kJitterBucketsUs.size(); ++b)
      out += fmt::format("cellctl_loop_jitter_seconds_bucket{{le=\"{:g}\"}} {}\n",
                         runtime::kJitterBucketsUs[b] * 1e-6, v.jitter_le[b]);
    out += fmt::format("cellctl_loop_jitter_seconds_bucket{{le=\"+Inf\"}} {}\n", v.jitter_le.back());
    out += fmt::format("cellctl_loop_jitter_seconds_sum {:.9f}\ncellctl_loop_jitter_seconds_count {}\n",
                       v.jitter_sum_s, v.jitter_le.back());
    add("cellctl_loop_overrun_cycles_total", "counter", "Cycles that ran past their next deadline.");
    out += fmt::format("cellctl_loop_overrun_cycles_total {}\n", v.overruns);
    static constexpr const char* kDevices[] = {"scu", "spindle", "encoder"};
    add("cellctl_device_link_fault", "gauge", "1 when the device's session gave up on its link.");
    for (std::size_t d = 0; d < v.link_fault.size(); ++d)
      out += fmt::format("cellctl_device_link_fault{{device=\"{}\"}} {}\n", kDevices[d],
                         v.link_fault[d] ? 1 : 0);
    add("cellctl_device_silent_seconds", "gauge", "Time since the device's last good reply.");
    for (std::size_t d = 0; d < v.link_silent_s.size(); ++d)
      out += fmt::format("cellctl_device_silent_seconds{{device=\"{}\"}} {:.6f}\n", kDevices[d],
                         v.link_silent_s[d]);
    add("cellctl_device_exchanges_total", "counter", "Good replies from the device.");
    for (std::size_t d = 0; d < v.link_counts.size(); ++d)
      out += fmt::format("cellctl_device_exchanges_total{{device=\"{}\"}} {}\n", kDevices[d],
                         v.link_counts[d].good_replies);
    add("cellctl_device_errors_total", "counter",
        "Failed exchanges: no answer in time, a bad frame, or a reply in which the device refused.");
    for (std::size_t d = 0; d < v.link_counts.size(); ++d) {
      const auto& c = v.link_counts[d];
      for (const auto& [kind, n] : {std::pair{"timeout", c.timeouts}, std::pair{"bad_frame", c.bad_frames},
                                    std::pair{"refused", c.refusals}})
        out += fmt::format("cellctl_device_errors_total{{device=\"{}\",kind=\"{}\"}} {}\n", kDevices[d], kind,
                           n);
    }
    add("cellctl_run_seconds", "gauge", "Time since the run started (the run's clock).");
    out += fmt::format("cellctl_run_seconds {:.6f}\n", v.t);
  }
  std::lock_guard lock(mutex_);
  const auto a = mirror_.admin_tag();
  for (const auto& [key, help] :
       {std::pair{"runs", "Runs started."}, std::pair{"steps_done", "Recipe steps completed."},
        std::pair{"steps_failed", "Recipe steps failed."},
        std::pair{"faults", "Safety monitor faults latched."},
        std::pair{"ProdProcessedCount", "Runs completed (PackML Admin.ProdProcessedCount)."}}) {
    const auto name =
        fmt::format("cellctl_{}_total", key == std::string_view("ProdProcessedCount") ? "processed" : key);
    add(name, "counter", help);
    out += fmt::format("{} {}\n", name, a[key].get<std::uint64_t>());
  }
  add("cellctl_state", "gauge", "PackML StateCurrent of the cell.");
  out += fmt::format("cellctl_state{{state=\"{}\"}} {}\n", mirror_.state(),
                     mirror_.state_tag()["StateCurrent"].get<int>());
  add("cellctl_web_commands_total", "counter",
      "Commands received by the page, refused ones, and ones without a valid token.");
  out += fmt::format(
      "cellctl_web_commands_total {}\ncellctl_web_commands_refused_total {}\n"
      "cellctl_web_commands_unauthorised_total {}\n",
      commands_, refused_, unauthorised_);
  add("cellctl_web_dropped_events_total", "counter", "Run events the page's queue had no room for.");
  out += fmt::format("cellctl_web_dropped_events_total {}\n", events_.dropped());
  return out;
}

}  // namespace cellctl::web
