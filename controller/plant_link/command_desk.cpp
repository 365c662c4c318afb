#include "plant_link/command_desk.hpp"

#include <fmt/format.h>

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
std::optional<double> number_field(const schema::Field<double>& f, const char* key, double lo, double hi,
                                   std::string& why) {
  if (!f.given) return std::nullopt;
  if (!f.value || *f.value < lo || *f.value > hi) {
    why = fmt::format("'{}' must be a number from {:g} to {:g}", key, lo, hi);
    return std::nullopt;
  }
  return f.value;
}

std::variant<StartRequest, std::string> routine_start(std::string_view word,
                                                      const schema::CommandPayload& body) {
  std::string why;
  if (word == "home") {
    StartHoming h;
    if (body.axes.given) {
      if (!body.axes.value) return std::string("'axes' must be a list of axis names: {\"axes\":[\"x\"]}");
      h.axes = *body.axes.value;
    }
    return h;
  }
  StartTeachIn t;
  if (!body.axis.value)
    return std::string("teach-in needs the axis and the distance: {\"axis\":\"x\",\"distance_mm\":100}");
  t.axis = *body.axis.value;
  const auto distance = number_field(body.distance_mm, "distance_mm", 0.1, 10000.0, why);
  if (!distance && why.empty())
    return std::string("teach-in needs the distance: {\"axis\":\"x\",\"distance_mm\":100}");
  t.from_mm = number_field(body.from_mm, "from_mm", -1e6, 1e6, why);
  t.speed_mm_s = number_field(body.speed_mm_s, "speed_mm_s", 0.01, 1000.0, why);
  if (!why.empty()) return why;
  t.distance_mm = *distance;
  return t;
}

}  // namespace

CommandAnswer answer(std::string_view command, AnswerId id, bool ok, std::string text) {
  CommandAnswer a;
  a.command = std::string(command);
  a.id = std::move(id);
  a.ok = ok;
  a.text = std::move(text);
  return a;
}

CommandDesk::CommandDesk(const config::CellCore& cell, std::filesystem::path recipes, RunAccess access,
                         std::chrono::milliseconds answer_timeout)
    : cell_(cell), recipes_(std::move(recipes)), access_(std::move(access)), timeout_(answer_timeout) {}

std::optional<CommandAnswer> CommandDesk::submit(const Incoming& in, std::string_view state) {
  const auto word = command::capped(in.word, 24);  // echoed in every answer: never whole
  command::Order order{in.source, in.received, std::nullopt};
  // Every answer says whose command it answers, the refusals of a payload too.
  auto with_source = [&](CommandAnswer a) {
    a.source = order.source.words();
    return a;
  };
  auto parsed = schema::read_command_payload(in.payload);
  if (auto* why = std::get_if<std::string>(&parsed))
    return with_source(answer(word, in.id ? AnswerId(*in.id) : AnswerId(), false,
                              *why + " (expected {\"id\":…} or nothing)"));
  const auto& body = std::get<schema::CommandPayload>(parsed);
  const AnswerId id = in.id ? AnswerId(*in.id) : body.id;
  if (body.by.value) order.source.who = command::capped(*body.by.value);
  if (body.issued_at.given) {
    order.issued_at = body.issued_at.value ? command::parse_utc(*body.issued_at.value) : std::nullopt;
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

std::variant<StartRequest, CommandAnswer> CommandDesk::recipe_start(
    const AnswerId& id, const schema::CommandPayload& body) const {
  if (!body.recipe.value)
    return answer("start", id, false, "start needs the recipe's name: {\"recipe\":\"demo\"}");
  const auto& name = *body.recipe.value;
  if (!plain_name(name))
    return answer("start", id, false,
                  fmt::format("'{}' is no recipe name (letters, digits, '-', '_', '.'; no path)", name));
  auto path = recipes_ / name;
  if (path.extension() != ".yaml") path += ".yaml";
  std::vector<std::string> errors;
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
  a.exit = kExitConfig;  // as `cellctl check` and `cellctl run` would end
  a.errors = std::move(errors);
  return a;
}

CommandAnswer CommandDesk::start(std::string_view word, const AnswerId& id,
                                 const schema::CommandPayload& body, const command::Order& order,
                                 std::string_view state) const {
  // Asked first, so that a start the state refuses costs nothing more (a flood of them included).
  if (auto why = access_.arbiter->start_refusal(order); !why.empty())
    return answer(word, id, false, std::move(why));
  StartRequest request;
  if (word == "start") {
    auto r = recipe_start(id, body);
    if (auto* refusal = std::get_if<CommandAnswer>(&r)) return std::move(*refusal);
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
    a.valid = recipe != nullptr;
    return a;
  }
  const auto taken = access_.arbiter->start(order, [&] { return access_.start(request, order.source); });
  auto a = answer(word, id, taken.how != Taken::How::refused, taken.text);
  a.valid = std::holds_alternative<StartRecipe>(request);
  return a;
}

std::vector<CommandAnswer> CommandDesk::on_event(const RunEvent& e) {
  std::vector<CommandAnswer> out;
  const std::lock_guard lock(mutex_);
  using Kind = RunEvent::Kind;
  using supervisor::Command;
  if (e.kind == Kind::run_ended) {
    // The run ended with these still untaken: answered now, never by the next job's events.
    for (const auto& p : pending_) {
      auto a = answer(supervisor::to_string(p.command), p.id, false,
                      "the run ended before it took the command; see the state tag");
      a.t = e.t;
      a.source = p.source;
      out.push_back(std::move(a));
    }
    pending_.clear();
    return out;
  }
  for (auto it = pending_.begin(); it != pending_.end();) {
    const auto name = supervisor::to_string(it->command);
    std::optional<CommandAnswer> a;
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
      a->t = e.t;
      a->source = it->source;
      out.push_back(std::move(*a));
      it = pending_.erase(it);
    } else {
      ++it;
    }
  }
  return out;
}

std::vector<CommandAnswer> CommandDesk::expire(SteadyTime now) {
  std::vector<CommandAnswer> out;
  const std::lock_guard lock(mutex_);
  while (!pending_.empty() && pending_.front().deadline <= now) {
    const auto& p = pending_.front();
    auto a =
        answer(supervisor::to_string(p.command), p.id, false,
               fmt::format("the run gave no answer within {} ms: the outcome is unknown; see the state tag",
                           timeout_.count()));
    a.source = p.source;
    out.push_back(std::move(a));
    pending_.pop_front();
  }
  return out;
}

}  // namespace cellctl::plant_link
