#include "schema/page_payloads.hpp"

#include <nlohmann/json.hpp>

namespace cellctl::schema {
namespace {

nlohmann::json maybe(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json();
}

nlohmann::json axis_json(const BoardAxis& a) {
  nlohmann::json j{{"name", a.name}};
  if (!a.read) return j;
  j["target_mm"] = maybe(a.read->target_mm);
  j["scu_mm"] = maybe(a.read->scu_mm);
  j["encoder_mm"] = maybe(a.read->encoder_mm);
  j["homed"] = {{"record", a.read->homed_record}, {"scu", a.read->homed_scu}};
  return j;
}

nlohmann::json device_json(const BoardDevice& d) {
  nlohmann::json j{{"name", d.name},
                   {"link", d.link},
                   {"round_trip_ms", d.round_trip_ms},
                   {"last_good_s", d.last_good_s},
                   {"replies", d.replies},
                   {"timeouts", d.timeouts},
                   {"bad_frames", d.bad_frames},
                   {"refusals", d.refusals}};
  if (d.safe) j["safe"] = *d.safe;
  return j;
}

}  // namespace

std::string board_json(const Board& board) {
  nlohmann::json axes = nlohmann::json::array();
  for (const auto& a : board.axes) axes.push_back(axis_json(a));
  nlohmann::json devices = nlohmann::json::array();
  for (const auto& d : board.devices) devices.push_back(device_json(d));
  nlohmann::json out{{"live", board.live}, {"axes", std::move(axes)}, {"devices", std::move(devices)}};
  if (board.t) out["t"] = *board.t;
  if (board.spindle)
    out["spindle"] = {{"set_hz", board.spindle->set_hz}, {"actual_hz", board.spindle->actual_hz}};
  if (board.read_at_start) out["read_at_start"] = true;
  out["state"] = board.state;
  out["state_current"] = board.state_current;
  nlohmann::json buttons = nlohmann::json::object();
  for (const auto& b : board.buttons)
    buttons[b.command] = b.refusal.empty() ? nlohmann::json{{"enabled", true}}
                                           : nlohmann::json{{"enabled", false}, {"reason", b.refusal}};
  out["buttons"] = std::move(buttons);
  out["history"] = board.history;
  return out.dump();
}

std::string recipe_list_json(const RecipeList& list) {
  nlohmann::json recipes = nlohmann::json::array();
  for (const auto& r : list.recipes) {
    nlohmann::json j{{"name", r.name}};
    if (r.steps) j["steps"] = *r.steps;
    if (r.planned_s) j["planned_s"] = *r.planned_s;
    if (r.not_counted > 0) j["not_counted"] = r.not_counted;
    if (r.problem) j["problem"] = *r.problem;
    recipes.push_back(std::move(j));
  }
  return nlohmann::json{{"recipes", std::move(recipes)}, {"more", list.more}}.dump();
}

std::string page_reply_json(bool ok, std::string_view text) {
  return nlohmann::json{{"ok", ok}, {ok ? "outcome" : "reason", text}}.dump();
}

}  // namespace cellctl::schema
