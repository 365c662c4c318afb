#include "web/operator_page.hpp"

#include <fmt/format.h>
#include <httplib.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <variant>

#include "schema/page_payloads.hpp"
#include "schema/plant_tags.hpp"
#include "web/answer_status.hpp"
#include "web/cell_board.hpp"
#include "web/client_watch.hpp"
#include "web/command_buttons.hpp"
#include "web/fault_remedy.hpp"
#include "web/hand_over.hpp"
#include "web/page_html.hpp"
#include "web/page_server.hpp"
#include "web/recipe_list.hpp"
#include "web/run_history.hpp"

namespace cellctl::web {
namespace {

using namespace std::chrono_literals;

std::string sse(std::string_view event, const std::string& payload) {
  return fmt::format("event: {}\ndata: {}\n\n", event, payload);
}

void refuse(httplib::Response& res, const Verdict& v) {
  res.status = v.status;
  if (v.retry_after_s > 0) res.set_header("Retry-After", std::to_string(v.retry_after_s));
  res.set_content(schema::page_reply_json(false, v.reason), "application/json");
}

// The request's body into `body`, at most kMaxBody of it (a chunked body has no length to judge
// before): false, with the answer set, when it is longer (the rest is never read) or breaks off.
bool read_body(const httplib::ContentReader& read, std::string& body, httplib::Response& res) {
  bool too_long = false;
  const bool whole = read([&](const char* data, std::size_t n) {
    too_long = body.size() + n > kMaxBody;
    if (!too_long) body.append(data, n);
    return !too_long;
  });
  if (too_long)
    refuse(res, {413, fmt::format("a body may have at most {} bytes", kMaxBody)});
  else if (!whole)
    refuse(res, {400, "the body broke off"});
  return whole && !too_long;
}

// The commands that bring the cell to rest: obeyed even when their client has gone, as it meant
// them when it sent them and nothing moves by them.
bool brings_to_rest(std::string_view word) {
  return word == "stop" || word == "abort" || word == "hold";
}

// A file of a run record as it was written (the plot): the plot's own script and style run in a
// sandbox (an origin of its own: it cannot reach the page's endpoints, cookie or not).
void send_record_file(const std::filesystem::path& file, const char* type, httplib::Response& res) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return refuse(res, {404, "no such file in the run record"});
  std::ostringstream text;
  text << in.rdbuf();
  res.headers.erase("Content-Security-Policy");
  res.set_header("Content-Security-Policy",
                 "sandbox allow-scripts; default-src 'none'; script-src 'unsafe-inline'; "
                 "style-src 'unsafe-inline'; img-src data:");
  res.set_content(text.str(), type);
}

}  // namespace

OperatorPage::OperatorPage(PageOptions options, const config::CellCore& cell, plant_link::RunAccess run)
    : options_(std::move(options)),
      cell_(cell),
      run_(std::move(run)),
      guard_(options_),
      mirror_(cell, run_.mode),
      desk_(cell, options_.recipes, starts_for_present_clients(run_), std::chrono::milliseconds(2000)) {
  for (const auto& a : cell.axes) axis_names_.push_back(a.name);
  // The command line refuses a token shorter than kMinTokenBytes (page_token.hpp).
  if (options_.token.empty()) throw std::invalid_argument("the operator page needs a token");
  if (const auto problem = listen_problem(options_); !problem.empty()) throw std::runtime_error(problem);
  server_ = make_page_server(options_);
  route();
  auto& s = *server_;
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

void OperatorPage::route() {
  auto& s = *server_;
  // Before the body is read: the pre-routing handler, and the answer to "Expect: 100-continue" (so a
  // client that waits for it is refused before it sends its body at all).
  const auto admitted = [this](const httplib::Request& req, httplib::Response& res) {
    const auto verdict = guard_.admit(req);
    if (verdict.status == 0) return true;
    if (verdict.status == 401 && req.path.rfind("/cmd/", 0) == 0) ++commands_unauthorised_;
    refuse(res, verdict);
    return false;
  };
  s.set_pre_routing_handler([admitted](const httplib::Request& req, httplib::Response& res) {
    return admitted(req, res) ? httplib::Server::HandlerResponse::Unhandled
                              : httplib::Server::HandlerResponse::Handled;
  });
  s.set_expect_100_continue_handler([admitted](const httplib::Request& req, httplib::Response& res) {
    return admitted(req, res) ? 100 : res.status;
  });
  s.Get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(std::string(operator_page_html()), "text/html; charset=utf-8");
  });
  s.Get("/page.css", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(std::string(operator_page_style()), "text/css; charset=utf-8");
  });
  s.Get("/page.js", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(std::string(operator_page_script()), "text/javascript; charset=utf-8");
  });
  s.Post("/login", [this](const httplib::Request& req, httplib::Response& res,
                          const httplib::ContentReader& read) {
    std::string ignored;
    if (!read_body(read, ignored, res)) return;
    const auto result = guard_.login(req);
    if (const auto* refused = std::get_if<Verdict>(&result)) return refuse(res, *refused);
    const auto& session = std::get<SessionStore::Opened>(result);
    res.set_header("Set-Cookie", guard_.session_cookie(session.id));
    res.set_content(schema::page_reply_json(true, fmt::format("logged in (session #{})", session.number)),
                    "application/json");
  });
  s.Post("/logout",
         [this](const httplib::Request& req, httplib::Response& res, const httplib::ContentReader& read) {
           std::string ignored;
           if (!read_body(read, ignored, res)) return;
           guard_.logout(req);
           res.set_header("Set-Cookie", guard_.session_cookie(""));
           res.set_content(schema::page_reply_json(true, "logged out"), "application/json");
         });
  s.Get("/events", [this](const httplib::Request& req, httplib::Response& res) {
    const auto caller = guard_.caller(req);
    if (!caller) return refuse(res, {401, "the session has ended: log in again"});
    if (streams_.fetch_add(1) >= options_.max_streams) {
      streams_.fetch_sub(1);
      ++streams_refused_;
      return refuse(res, {503, fmt::format("all {} live views are taken", options_.max_streams), 5});
    }
    auto last_admin = std::make_shared<std::uint64_t>(UINT64_MAX);
    auto first = std::make_shared<bool>(true);
    const auto session = caller->session;  // the stream ends with its session
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, last_admin, first, session](std::size_t, httplib::DataSink& sink) {
          if (stop_.load() || (session && !guard_.session_open(*session))) return false;
          std::string out;
          if (*first) {
            out += sse("cell", schema::cell_payload(cell_.name));
            std::lock_guard lock(mutex_);
            out += sse("mode", schema::mode_payload(mirror_.mode_tag()));
            *first = false;
          } else {
            std::this_thread::sleep_for(200ms);  // the page's refresh period; a server thread, never the loop
          }
          out += sse("status", status_payload());
          out += sse("board", board_payload());
          {
            std::lock_guard lock(mutex_);
            if (*last_admin != admin_version_) {
              *last_admin = admin_version_;
              out += sse("admin", admin_payload());
              out += sse("mode", schema::mode_payload(mirror_.mode_tag()));
            }
          }
          return sink.write(out.data(), out.size());
        },
        [this](bool) { streams_.fetch_sub(1); });
  });
  s.Post(R"(/cmd/([a-z-]{1,32}))", [this](const httplib::Request& req, httplib::Response& res,
                                          const httplib::ContentReader& read) {
    // Called once the headers are read, before the body: the command's age counts from here.
    const auto received = std::chrono::steady_clock::now();
    const std::string word = req.matches[1];
    std::string body;
    if (!read_body(read, body, res)) return;
    const auto caller = guard_.caller(req);
    if (!caller) return refuse(res, {401, "the session has ended: log in again"});
    const command::CommandSource source{command::CommandSource::Origin::web,
                                        fmt::format("{}:{}", req.remote_addr, req.remote_port), caller->who};
    const auto reply = [&res](const schema::CommandAnswer& a) {
      res.status = answer_status(a);
      res.set_content(schema::answer_payload(a), "application/json");
    };
    if (brings_to_rest(word)) return reply(command(word, body, source, received));
    // Asked before the command desk and again at the hand-over (hand_over.hpp).
    const ClientWatch client(req);
    const auto abandon = [&] {
      ++commands_abandoned_;
      // Journaled by the arbiter as never obeyed, so the record shows who sent it.
      run_.arbiter->ignore(fmt::format("{} from {} not obeyed: its client had gone", word, source.words()));
    };
    if (client.gone()) {
      abandon();
      return reply(plant_link::answer(word, {}, false, std::string(kClientGone)));
    }
    const ClientAtHandOver at_hand_over([&client] { return client.gone(); });
    const auto answer = command(word, body, source, received);
    if (at_hand_over.abandoned()) abandon();
    reply(answer);
  });
  // The recipes a start may name, and the runs made: read when asked, on this server thread.
  s.Get("/recipes", [this](const httplib::Request&, httplib::Response& res) {
    // Planned from where the page last saw the axes stand (a start is taken only at rest, in Idle).
    std::array<std::optional<double>, cell::kMaxAxes> start{};
    auto at_rest = run_.at_rest ? run_.at_rest() : std::optional<status::StatusView>{};
    {
      std::lock_guard lock(mutex_);
      const auto& view = last_view_ ? last_view_ : at_rest;
      for (std::size_t i = 0; view && i < view->axes && i < start.size(); ++i)
        if (view->position_known[i]) start[i] = view->position_mm[i];
    }
    res.set_content(schema::recipe_list_json(recipe_list(options_.recipes, cell_, options_.plan, start)),
                    "application/json");
  });
  s.Get("/runs", [this](const httplib::Request&, httplib::Response& res) {
    res.set_content(schema::run_history_json(run_history(options_.runs)), "application/json");
  });
  // The run's name is bounded by the pattern (and checked again as a plain name): never a path.
  s.Get(R"(/runs/([A-Za-z0-9][A-Za-z0-9_.-]{0,127})/(plot\.html|plot\.svg|report))",
        [this](const httplib::Request& req, httplib::Response& res) {
          const std::string run = req.matches[1], file = req.matches[2];
          if (options_.runs.empty() || !plain_run_name(run)) return refuse(res, {404, "no such run record"});
          if (file == "report") {
            const auto report = run_report(options_.runs, run);
            if (!report) return refuse(res, {404, "no such run record"});
            return res.set_content(*report, "text/plain; charset=utf-8");
          }
          send_record_file(options_.runs / run / file,
                           file == "plot.svg" ? "image/svg+xml" : "text/html; charset=utf-8", res);
        });
  s.Get("/metrics", [this](const httplib::Request&, httplib::Response& res) {
    res.set_content(metrics_text(), "text/plain; version=0.0.4");
  });
}

void OperatorPage::pump() {
  while (!stop_.load()) {
    // The run's view as often as the pump turns, so that a job too short for the page's refresh still
    // leaves its last view to be shown between jobs (outside mutex_: status() locks the scheduler).
    if (auto live = run_.status()) {
      std::lock_guard lock(mutex_);
      last_view_ = std::move(live->view);
    }
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

schema::CommandAnswer OperatorPage::command(const std::string& word, const std::string& body,
                                            const command::CommandSource& source,
                                            command::SteadyTime received) {
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
    const schema::AnswerId mine = id;
    const auto found = [&] {
      return std::find_if(answers_.begin(), answers_.end(),
                          [&](const schema::CommandAnswer& a) { return a.id == mine; });
    };
    answered_.wait_for(lock, 3s, [&] { return found() != answers_.end(); });
    if (const auto it = found(); it != answers_.end()) {
      immediate = std::move(*it);
      answers_.erase(it);
    } else {
      immediate = plant_link::answer(word, id, false, "no answer from the run");
    }
  }
  if (!immediate->ok) ++refused_;
  return *immediate;
}

std::string OperatorPage::status_payload() {
  plant_link::LiveStatus live;
  if (const auto r = run_.status())
    live = {true, r->view.t, r->view.step, r->view.steps, r->label, r->view.jitter_max_us};
  std::lock_guard lock(mutex_);
  return schema::status_payload(mirror_.status_tag(live));
}

std::string OperatorPage::board_payload() {
  auto live = run_.status();
  // Before the first job, the cell as serve read it (outside mutex_: it locks the scheduler).
  auto at_rest = !live && run_.at_rest ? run_.at_rest() : std::optional<status::StatusView>{};
  std::lock_guard lock(mutex_);
  // Between jobs (cellctl serve) the last job's view, marked as not live.
  if (live) last_view_ = live->view;
  const bool read_at_start = !last_view_ && at_rest;
  auto board = board_view(axis_names_, read_at_start ? at_rest : last_view_, live.has_value());
  board.read_at_start = read_at_start;
  board.state = mirror_.state();
  board.state_current = mirror_.state_tag().state_current;  // PackML's number for it
  board.buttons = command_buttons(mirror_.state(), static_cast<bool>(run_.start));
  board.history = !options_.runs.empty();
  return schema::board_json(board);
}

std::string OperatorPage::admin_payload() {
  auto a = mirror_.admin_tag();
  for (auto& f : a.active_faults) f.remedy = std::string(fault_remedy(f.rule));
  return schema::admin_payload(a);
}

}  // namespace cellctl::web
