#include "recipe/recipe_loader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace cellctl::recipe {
namespace {

using config::CellCore;
using config::ConfigError;
using config::YamlNode;

std::string join_messages(const std::vector<ConfigError>& errors) {
  std::string out;
  for (const auto& e : errors) {
    if (!out.empty()) out += '\n';
    out += e.what();
  }
  return out;
}

// Parses one recipe, collecting errors step by step so that one run of `cellctl check` shows them all.
class Parser {
 public:
  explicit Parser(const CellCore& cell) : cell_(cell) {}

  Recipe parse(const YamlNode& root) {
    Recipe r;
    r.source = root.file();
    attempt([&] { root.only_keys({"recipe", "limits", "steps"}); });
    attempt([&] { parse_header(root.at("recipe"), r); });
    bool limits_ok = false;
    attempt([&] {
      r.limits = parse_limits(root.at("limits"));
      limits_ok = true;
    });
    if (limits_ok) {
      limits_ = &r.limits;
      try {
        attempt([&] {
          const auto steps = root.at("steps");
          if (steps.items().empty()) steps.fail("a recipe needs at least one step");
          r.steps = parse_steps(steps, 0);
        });
      } catch (const TooLong& e) {
        errors_.push_back(e.error);
      }
    }
    if (!errors_.empty()) throw RecipeErrors(std::move(errors_));
    return r;
  }

 private:
  // Ends the whole parse (attempt() does not catch it): past the limit, every further step would
  // only cost time, and a list given by an alias can repeat the same steps many times over.
  struct TooLong {
    ConfigError error;
  };

  template <class Fn>
  void attempt(Fn&& fn) {
    try {
      fn();
    } catch (const ConfigError& e) {
      errors_.push_back(e);
    }
  }

  void parse_header(const YamlNode& h, Recipe& r) {
    h.only_keys({"name", "version", "cell", "description"});
    r.name = h.string_at("name");
    if (r.name.empty()) h.at("name").fail("must not be empty");
    r.version = h.string_at("version");
    r.cell = h.string_at("cell");
    if (r.cell != cell_.name)
      h.at("cell").fail(fmt::format("the recipe is for cell '{}', but this cell is '{}' ({})", r.cell,
                                    cell_.name, cell_.source.string()));
  }

  int axis_index(const YamlNode& key_node, const std::string& axis_name) const {
    for (std::size_t i = 0; i < cell_.axes.size(); ++i)
      if (cell_.axes[i].name == axis_name) return static_cast<int>(i);
    std::string names;
    for (const auto& a : cell_.axes) names += (names.empty() ? "" : ", ") + a.name;
    key_node.fail(fmt::format("the cell has no axis '{}' (its axes: {})", axis_name, names));
  }

  Limits parse_limits(const YamlNode& n) {
    n.only_keys({"axes", "spindle", "timeouts"});
    Limits l;
    l.axes.resize(cell_.axes.size());
    const auto axes = n.at("axes");
    for (const auto& name : axes.keys()) {
      const auto a = axes.at(name);
      attempt([&] {
        const int idx = axis_index(a, name);
        const auto& cell_axis = cell_.axes[static_cast<std::size_t>(idx)];
        a.only_keys({"min_mm", "max_mm", "max_speed_mm_s", "tolerance_mm"});
        AxisLimits al;
        al.min_mm = a.double_in("min_mm", cell_axis.min_mm, cell_axis.max_mm);
        al.max_mm = a.double_in("max_mm", cell_axis.min_mm, cell_axis.max_mm);
        if (al.max_mm <= al.min_mm)
          a.at("max_mm").fail(fmt::format("must be above min_mm ({:g})", al.min_mm));
        al.max_speed_mm_s = a.double_in("max_speed_mm_s", cell_axis.min_speed_mm_s, cell_axis.max_speed_mm_s);
        // Tighter than one SCU edge cannot be reached; wider than 5 mm is no process tolerance.
        al.tolerance_mm = a.double_in("tolerance_mm", 1.0 / cell_axis.edges_per_mm, 5.0);
        l.axes[static_cast<std::size_t>(idx)] = al;
      });
    }
    if (auto s = n.maybe("spindle")) {
      s->only_keys({"min_hz", "max_hz"});
      l.spindle_min_hz = s->double_in("min_hz", cell_.limits.spindle_min_hz, cell_.limits.spindle_max_hz);
      l.spindle_max_hz = s->double_in("max_hz", cell_.limits.spindle_min_hz, cell_.limits.spindle_max_hz);
      if (l.spindle_max_hz < l.spindle_min_hz) s->at("max_hz").fail("must not be below min_hz");
      has_spindle_limits_ = true;
    }
    if (auto t = n.maybe("timeouts")) {
      t->only_keys({"move_s", "spindle_s"});
      l.move_timeout_s = t->double_in_or("move_s", 0.1, 3600.0, l.move_timeout_s);
      l.spindle_timeout_s = t->double_in_or("spindle_s", 0.1, 3600.0, l.spindle_timeout_s);
    }
    return l;
  }

  std::vector<Step> parse_steps(const YamlNode& list, int depth) {
    std::vector<Step> steps;
    for (const auto& item : list.items()) {
      if (++checked_ > kMaxInstructions)
        throw TooLong{make_error(
            item, fmt::format("more than {} steps to check, aliases counted (the limit)", kMaxInstructions))};
      attempt([&] { steps.push_back(parse_step(item, depth)); });
    }
    return steps;
  }

  static ConfigError make_error(const YamlNode& n, const std::string& rule) {
    return ConfigError(n.file(), std::max(n.line(), 1), std::max(n.column(), 1), n.field(), rule);
  }

  static constexpr std::array<std::string_view, 7> kActions = {"move",   "spindle", "dwell", "wait",
                                                               "repeat", "require", "home"};

  Step parse_step(const YamlNode& item, int depth) {
    if (!item.is_map())
      item.fail("a step is a mapping with one of: move, spindle, dwell, wait, repeat, require, home");
    item.only_keys({"name", "move", "spindle", "dwell", "wait", "repeat", "require", "home"});
    std::string action;
    for (auto a : kActions) {
      if (!item.has(a)) continue;
      if (!action.empty())
        item.fail(fmt::format("a step does one thing: both '{}' and '{}' given", action, a));
      action = a;
    }
    if (action.empty()) item.fail("a step needs one of: move, spindle, dwell, wait, repeat, require, home");
    Step s;
    s.name = item.string_or("name", action);
    s.line = item.line();
    const auto body = item.at(action);
    if (action == "move") s.action = parse_move(body);
    if (action == "spindle") s.action = parse_spindle(body);
    if (action == "dwell") s.action = Dwell{body.as_double_in(0.001, 3600.0)};
    if (action == "wait") s.action = parse_wait(body);
    if (action == "require") s.action = parse_require(body);
    if (action == "home") s.action = Home{homed_axes(body)};
    if (action == "repeat") {
      s.action = parse_repeat(body, depth);
      return s;
    }
    // One instruction for every time the enclosing repeats run it; multiplier_ ≤ the limit, so the
    // sum cannot overflow before it is compared.
    unrolled_ += multiplier_;
    if (unrolled_ > kMaxInstructions)
      throw TooLong{make_error(
          item, fmt::format("the recipe unrolls to more than {} steps here (the limit)", kMaxInstructions))};
    return s;
  }

  Move parse_move(const YamlNode& n) {
    n.only_keys({"to", "speed_mm_s", "path"});
    Move m;
    // `line`: the planner's phase synchronisation (a straight line in joint space); `time` (the
    // default): its time synchronisation (each axis its own profile, all ending together).
    if (const auto path = n.maybe("path"))
      m.path = path->as_choice({"time", "line"}) == "line" ? Path::line : Path::time;
    const auto to = n.at("to");
    const auto names = to.keys();
    if (names.empty()) to.fail("name at least one axis and its target");
    const auto speed = n.at("speed_mm_s");
    m.speed_mm_s = speed.as_double();
    // An axis whose actuator moves at any speed has no minimum (0): that is no licence to stand still,
    // or to run backwards.
    if (!(m.speed_mm_s > 0.0))
      speed.fail(fmt::format("{:g} mm/s: a move needs a speed above 0 mm/s", m.speed_mm_s));
    for (const auto& name : names) {
      const auto t = to.at(name);
      const int idx = axis_index(t, name);
      const auto& lim = limits_->axes[static_cast<std::size_t>(idx)];
      if (!lim) t.fail(fmt::format("axis '{}' has no limits in this recipe (limits.axes.{})", name, name));
      m.targets.push_back({idx, t.as_double_in(lim->min_mm, lim->max_mm)});
      const auto& cell_axis = cell_.axes[static_cast<std::size_t>(idx)];
      if (m.speed_mm_s > lim->max_speed_mm_s)
        speed.fail(fmt::format("{:g} mm/s is above axis '{}''s recipe limit {:g} mm/s", m.speed_mm_s, name,
                               lim->max_speed_mm_s));
      if (m.speed_mm_s < cell_axis.min_speed_mm_s)
        speed.fail(
            fmt::format("{:g} mm/s is below axis '{}''s minimum {:g} mm/s: the actuator would not move",
                        m.speed_mm_s, name, cell_axis.min_speed_mm_s));
    }
    return m;
  }

  Spindle parse_spindle(const YamlNode& n) {
    if (n.is_scalar()) {
      if (n.as_choice({"stop"}) == "stop") return Spindle{false, 0.0, SpindleDirection::cw};
    }
    n.only_keys({"start_hz", "direction"});
    if (!has_spindle_limits_)
      n.fail("the recipe starts the spindle but has no limits.spindle (min_hz, max_hz)");
    Spindle s;
    s.start = true;
    s.frequency_hz = n.double_in("start_hz", limits_->spindle_min_hz, limits_->spindle_max_hz);
    if (auto d = n.maybe("direction"))
      s.direction = d->as_choice({"cw", "ccw"}) == "cw" ? SpindleDirection::cw : SpindleDirection::ccw;
    return s;
  }

  Wait parse_wait(const YamlNode& n) {
    n.only_keys({"axis", "position_above_mm", "position_below_mm", "encoder", "spindle", "timeout_s"});
    Wait w;
    w.timeout_s = n.double_in("timeout_s", 0.001, 3600.0);
    int conditions = 0;
    if (auto a = n.maybe("position_above_mm")) {
      w.condition = Wait::Condition::position_above;
      w.threshold_mm = a->as_double();
      ++conditions;
    }
    if (auto a = n.maybe("position_below_mm")) {
      w.condition = Wait::Condition::position_below;
      w.threshold_mm = a->as_double();
      ++conditions;
    }
    if (auto e = n.maybe("encoder")) {
      (void)e->as_choice({"ready"});  // checked: `ready` is its only value
      w.condition = Wait::Condition::encoder_ready;
      ++conditions;
    }
    if (auto s = n.maybe("spindle")) {
      w.condition = s->as_choice({"at_speed", "at_rest"}) == "at_speed" ? Wait::Condition::spindle_at_speed
                                                                        : Wait::Condition::spindle_at_rest;
      ++conditions;
    }
    if (conditions != 1)
      n.fail("a wait needs exactly one condition: position_above_mm, position_below_mm, encoder or spindle");
    const bool positional =
        w.condition == Wait::Condition::position_above || w.condition == Wait::Condition::position_below;
    if (positional) {
      const auto axis = n.at("axis");
      w.axis = axis_index(axis, axis.as_string());
      const auto& ca = cell_.axes[static_cast<std::size_t>(w.axis)];
      const auto key =
          w.condition == Wait::Condition::position_above ? "position_above_mm" : "position_below_mm";
      w.threshold_mm = n.at(key).as_double_in(ca.min_mm, ca.max_mm);  // inside the axis's travel
    } else if (n.has("axis")) {
      n.at("axis").fail("only position conditions take an axis");
    }
    return w;
  }

  Require parse_require(const YamlNode& n) {
    n.only_keys({"homed", "encoder_ready", "spindle_at_rest"});
    Require r;
    if (auto h = n.maybe("homed")) r.homed_axes = homed_axes(*h);
    r.encoder_ready = n.bool_or("encoder_ready", false);
    r.spindle_at_rest = n.bool_or("spindle_at_rest", false);
    if (r.homed_axes.empty() && !r.encoder_ready && !r.spindle_at_rest)
      n.fail("require needs at least one of: homed, encoder_ready, spindle_at_rest");
    return r;
  }

  // A list of axes that each have a homing strategy in the cell config, none twice.
  std::vector<int> homed_axes(const YamlNode& list) const {
    std::vector<int> axes;
    const auto items = list.items();
    if (items.empty()) list.fail("name at least one axis");
    for (const auto& a : items) {
      const int idx = axis_index(a, a.as_string());
      const auto& axis = cell_.axes[static_cast<std::size_t>(idx)];
      if (axis.homing.strategy == config::HomingStrategy::none)
        a.fail(fmt::format("axis {} has no homing in the cell config (axes[].homing.strategy)", axis.name));
      if (std::find(axes.begin(), axes.end(), idx) != axes.end())
        a.fail(fmt::format("axis {} is named twice", axis.name));
      axes.push_back(idx);
    }
    return axes;
  }

  Repeat parse_repeat(const YamlNode& n, int depth) {
    n.only_keys({"times", "steps"});
    if (depth + 1 > kMaxRepeatDepth) n.fail(fmt::format("repeats nest at most {} deep", kMaxRepeatDepth));
    Repeat r;
    r.times = n.int_in<int>("times", 1, kMaxRepeatTimes);
    // Compared by division: the product of the counts is never formed beyond the limit.
    if (multiplier_ > kMaxInstructions / r.times)
      throw TooLong{
          make_error(n.at("times"), fmt::format("{} times inside repeats that run {} times unrolls to "
                                                "more than {} steps (the limit)",
                                                r.times, multiplier_, kMaxInstructions))};
    const auto steps = n.at("steps");
    if (steps.items().empty()) steps.fail("a repeat needs at least one step");
    const long outer = multiplier_;
    multiplier_ *= r.times;
    r.steps = parse_steps(steps, depth + 1);
    multiplier_ = outer;
    return r;
  }

  const CellCore& cell_;
  long checked_ = 0;     // step entries looked at, each alias use counted
  long unrolled_ = 0;    // instructions the recipe unrolls to so far
  long multiplier_ = 1;  // how often the enclosing repeats run the steps being parsed
  const Limits* limits_ = nullptr;
  bool has_spindle_limits_ = false;
  std::vector<ConfigError> errors_;
};

}  // namespace

RecipeErrors::RecipeErrors(std::vector<config::ConfigError> errors)
    : std::runtime_error(join_messages(errors)), errors_(std::move(errors)) {}

Recipe load_recipe(const std::filesystem::path& path, const config::CellCore& cell) {
  return parse_recipe(YamlNode::load_file(path), cell);
}

Recipe parse_recipe(const config::YamlNode& root, const config::CellCore& cell) {
  return Parser(cell).parse(root);
}

}  // namespace cellctl::recipe
