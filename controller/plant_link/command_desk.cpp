#include "plant_link/command_desk.hpp"

#include <fmt/format.h>

#include "command/bounded_json.hpp"
#include "exit_codes/exit_codes.hpp"
#include "recipe/program.hpp"
#include "recipe/recipe_loader.hpp"

namespace cellctl::plant_link {
namespace {

bool contains(std::string_view s, std::string_view part) {
  return s.find(part) != std::string_view::npos;
}

// A recipe is named, not pathed: letters, digits, '-', '_', '.', no leading dot.
bool plain_name(const std::string& n) {
  if (n.empty() || n.size() > 100 || n.front() == '.') return false;
  for (const char c : n)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') return false;
  return true;
}

// A number field of a start's payload within [lo, hi]; absent: nullopt; otherwise `why` says what is wrong.
std::optional<double> number_field(const nlohmann::json& body, const char* key, double lo, double hi,
                                   std::string& why) {
  const auto it = body.find(key);
  if (it == body.end()) return std::nullopt;
  if (!it->is_number() || it->get<double>() < lo || it->get<double>() > hi) {
    why = fmt::format("'{}' must be a number from {:g} to {:g}", key, lo, hi);
    return std::nullopt;
  }
  return it->get<double>();
}

std::variant<StartRequest, std::string> routine_start(std::string_view word, const nlohmann::json& body) {
  std::string why;
  if (word == "home") {
    StartHoming h;
    if (const auto it = body.find("axes"); it != body.end()) {
      if (!it->is_array()) return std::string("'axes' must be a list of axis names: {\"axes\":[\"x\"]}");
      for (const auto& a : *it) {
        if (!a.is_string()) return std::string("'axes' must be a list of axis names: {\"axes\":[\"x\"]}");
        h.axes.push_back(a.get<std::string>());
      }
    }
    return h;
  }
  StartTeachIn t;
  const auto axis = body.find("axis");
  if (axis == body.end() || !axis->is_string())
    return std::string("teach-in needs the axis and the distance: {\"axis\":\"x\",\"distance_mm\":100}");
  t.axis = axis->get<std::string>();
  const auto distance = number_field(body, "distance_mm", 0.1, 10000.0, why);
  if (!distance && why.empty())
    return std::string("teach-in needs the distance: {\"axis\":\"x\",\"distance_mm\":100}");
  t.from_mm = number_field(body, "from_mm", -1e6, 1e6, why);
  t.speed_mm_s = number_field(body, "speed_mm_s", 0.01, 1000.0, why);
  if (!why.empty()) return why;
  t.distance_mm = *distance;
  return t;
}

}  // namespace

nlohmann::json answer(std::string_view command, const nlohmann::json& id, bool ok, std::string text) {
  nlohmann::json j{{"command", command}, {"ok", ok}};
  if (!id.is_null()) j["id"] = id;
  j[ok ? "outcome" : "reason"] = std::move(text);
  return j;
}

CommandDesk::CommandDesk(const config::CellCore& cell, std::filesystem::path recipes, RunAccess access,
                         std::chrono::milliseconds answer_timeout)
    : cell_(cell), recipes_(std::move(recipes)), access_(std::move(access)), timeout_(answer_timeout) {}

std::optional<nlohmann::json> CommandDesk::submit(const Incoming& in, std::string_view state) {
  const auto word = command::capped(in.word, 24);  // echoed in every answer: never whole
  command::Order order{in.source, in.received, std::nullopt};
  // Every answer says whose command it answers, the refusals of a payload too.
  auto with_source = [&](nlohmann::json a) {
    a["source"] = order.source.words();
    return a;
  };
  auto parsed = command::parse_bounded_object(in.payload);
  if (auto* why = std::get_if<std::string>(&parsed))
    return with_source(answer(word, in.id ? nlohmann::json(*in.id) : nlohmann::json(), false,
                              *why + " (expected {\"id\":…} or nothing)"));
  auto& body = std::get<nlohmann::json>(parsed);
  const nlohmann::json id = in.id                 ? nlohmann::json(*in.id)
                            : body.contains("id") ? body["id"]
                                                  : nlohmann::json();
  if (const auto by = body.find("by"); by != body.end() && by->is_string())
    order.source.who = command::capped(by->get_ref<const std::string&>());
  if (const auto at = body.find("issued_at"); at != body.end()) {
    order.issued_at = at->is_string() ? command::parse_utc(at->get_ref<const std::string&>()) : std::nullopt;
    if (!order.issued_at)
      return with_source(
          answer(word, id, false, "'issued_at' must be a UTC time: \"2026-11-27T19:50:00.125Z\""));
  }
  if (word == "start" || word == "home" || word == "teach-in")
    return with_source(start(word, id, body, order, state));
  using supervisor::Command;
  std::optional<Command> cmd;
  for (const auto c :
       {Command::hold, Command::unhold, Command::stop, Command::abort, Command::reset, Command::clear})
    if (supervisor::to_string(c) == word) cmd = c;
  if (!cmd)
    return with_source(answer(
        word, id, false,
        fmt::format("'{}' is not a command: hold, unhold, stop, abort, reset, clear, start, home or teach-in",
                    word)));
  const auto taken = access_.arbiter->command(*cmd, order);
  if (taken.how != Taken::How::by_run)
    return with_source(answer(word, id, taken.how == Taken::How::done, taken.text));
  const std::lock_guard lock(mutex_);
  pending_.push_back({*cmd, id, order.source.words(), std::chrono::steady_clock::now() + timeout_});
  return std::nullopt;
}

std::variant<StartRequest, nlohmann::json> CommandDesk::recipe_start(const nlohmann::json& id,
                                                                     const nlohmann::json& body) const {
  const auto it = body.find("recipe");
  if (it == body.end() || !it->is_string())
    return answer("start", id, false, "start needs the recipe's name: {\"recipe\":\"demo\"}");
  const auto name = it->get<std::string>();
  if (!plain_name(name))
    return answer("start", id, false,
                  fmt::format("'{}' is no recipe name (letters, digits, '-', '_', '.'; no path)", name));
  auto path = recipes_ / name;
  if (path.extension() != ".yaml") path += ".yaml";
  nlohmann::json errors = nlohmann::json::array();
  std::size_t steps = 0;
  try {
    steps = recipe::unroll(recipe::load_recipe(path, cell_)).instructions.size();
  } catch (const recipe::RecipeErrors& e) {
    for (const auto& err : e.errors()) errors.push_back(err.what());
  } catch (const config::ConfigError& e) {
    errors.push_back(e.what());
  }
  if (errors.empty()) return StartRecipe{name, path, steps};
  auto a = answer("start", id, false,
                  fmt::format("recipe '{}' is not valid for cell '{}': {} problem{} (exit {}); nothing moved",
                              name, cell_.name, errors.size(), errors.size() == 1 ? "" : "s", kExitConfig));
  a["exit"] = kExitConfig;  // as `cellctl check` and `cellctl run` would end
  a["errors"] = errors;
  return a;
}

nlohmann::json CommandDesk::start(std::string_view word, const nlohmann::json& id, const nlohmann::json& body,
                                  const command::Order& order, std::string_view state) const {
  // Asked first, so that a start the state refuses costs nothing more (a flood of them included).
  if (auto why = access_.arbiter->start_refusal(order); !why.empty())
    return answer(word, id, false, std::move(why));
  StartRequest request;
  if (word == "start") {
    auto r = recipe_start(id, body);
    if (auto* refusal = std::get_if<nlohmann::json>(&r)) return std::move(*refusal);
    request = std::get<StartRequest>(std::move(r));
  } else {
    auto r = routine_start(word, body);
    if (auto* why = std::get_if<std::string>(&r)) return answer(word, id, false, std::move(*why));
    request = std::get<StartRequest>(std::move(r));
  }
  if (!access_.start) {
    // cellctl run drives the one recipe it was started with; anything else needs another process.
    const auto* recipe = std::get_if<StartRecipe>(&request);
    auto a =
        answer(word, id, false,
               recipe ? fmt::format("recipe '{}' is valid ({} steps), but this cellctl drives one run and it "
                                    "is in state {}: start it with `cellctl run {}`, or run `cellctl serve`",
                                    recipe->name, recipe->steps, state, recipe->file.string())
                      : fmt::format("this cellctl drives one run (state {}): {} needs `cellctl serve` or "
                                    "`cellctl {}`",
                                    state, word, word));
    if (recipe) a["valid"] = true;
    return a;
  }
  const auto taken = access_.arbiter->start(order, [&] { return access_.start(request, order.source); });
  auto a = answer(word, id, taken.how != Taken::How::refused, taken.text);
  if (std::holds_alternative<StartRecipe>(request)) a["valid"] = true;
  return a;
}

std::vector<nlohmann::json> CommandDesk::on_event(const RunEvent& e) {
  std::vector<nlohmann::json> out;
  const std::lock_guard lock(mutex_);
  using Kind = RunEvent::Kind;
  using supervisor::Command;
  if (e.kind == Kind::run_ended) {
    // The run ended with these still untaken: answered now, never by the next job's events.
    for (const auto& p : pending_) {
      auto a = answer(supervisor::to_string(p.command), p.id, false,
                      "the run ended before it took the command; see the state tag");
      a["t"] = e.t;
      a["source"] = p.source;
      out.push_back(std::move(a));
    }
    pending_.clear();
    return out;
  }
  for (auto it = pending_.begin(); it != pending_.end();) {
    const auto name = supervisor::to_string(it->command);
    std::optional<nlohmann::json> a;
    const auto text = e.text.view();
    if (e.kind == Kind::note && contains(text, fmt::format("{} is not possible", name))) {
      a = answer(name, it->id, false, std::string(text));
    } else if (it->command == Command::unhold) {
      // An unhold is judged after it is journaled: Unholding follows, or a latched fault refuses it.
      if (e.kind == Kind::state && e.name.view() == "Unholding")
        a = answer(name, it->id, true, "unholding: the interrupted step resumes");
      else if (e.kind == Kind::note && contains(text, "unhold refused"))
        a = answer(name, it->id, false, std::string(text));
    } else if (it->command == Command::reset || it->command == Command::clear) {
      if (e.kind == Kind::note && contains(text, fmt::format("{} refused", name)))
        a = answer(name, it->id, false, std::string(text));
      else if ((e.kind == Kind::note && contains(text, "faults reset")) ||
               (e.kind == Kind::command && e.name.view() == name))
        a = answer(name, it->id, true, it->command == Command::reset ? "faults reset" : "cleared");
    } else if (e.kind == Kind::command && e.name.view() == name) {
      a = answer(name, it->id, true, fmt::format("accepted at t = {:.3f} s", e.t));
    }
    if (a) {
      (*a)["t"] = e.t;
      (*a)["source"] = it->source;
      out.push_back(std::move(*a));
      it = pending_.erase(it);
    } else {
      ++it;
    }
  }
  return out;
}

std::vector<nlohmann::json> CommandDesk::expire(SteadyTime now) {
  std::vector<nlohmann::json> out;
  const std::lock_guard lock(mutex_);
  while (!pending_.empty() && pending_.front().deadline <= now) {
    const auto& p = pending_.front();
    auto a =
        answer(supervisor::to_string(p.command), p.id, false,
               fmt::format("the run gave no answer within {} ms: the outcome is unknown; see the state tag",
                           timeout_.count()));
    a["source"] = p.source;
    out.push_back(std::move(a));
    pending_.pop_front();
  }
  return out;
}

}  // namespace cellctl::plant_link
