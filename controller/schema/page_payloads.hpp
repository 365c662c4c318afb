#pragma once
// The operator page's own payloads (web/), typed, and their JSON: the "board" live event (axes,
// devices, the buttons the state allows) and the Start list (GET /recipes). The page fills these views
// from the run's status board, PackML's table and the recipes folder; the JSON is made here only.
//
// board: {"live":true,"t":…,"axes":[{"name":"x","target_mm":40.0|null,"scu_mm":…|null,
//   "encoder_mm":…|null,"homed":{"record":true,"scu":true}}],
//  "devices":[{"name":"scu","link":"up"|"lost"|"down","round_trip_ms":…,"last_good_s":…,"replies":…,
//   "timeouts":…,"bad_frames":…,"refusals":…,"safe":"observed"|"bounded"|"unknown" (once the run's stop
//   resolved it)}],"spindle":{"set_hz":…,"actual_hz":…},"read_at_start":true (only then),
//  "state":"Idle","state_current":4,"buttons":{"hold":{"enabled":false,"reason":"…"},…},"history":true}
// (without a view: {"live":false,"axes":[{"name":"x"}…],"devices":[],…}).
// recipes: {"recipes":[{"name":"demo","steps":12,"planned_s":34.5,"not_counted":1},
//   {"name":"bad","problem":"…"}],"more":false}

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cellctl::schema {

struct BoardAxis {
  std::string name;
  // What a run's view says of it; nullopt: no view (only the name is shown).
  struct Read {
    std::optional<double> target_mm, scu_mm, encoder_mm;  // none: not known
    bool homed_record = false;                            // the home record's entry
    bool homed_scu = false;                               // the SCU's initialised bit
  };
  std::optional<Read> read;
};

struct BoardDevice {
  std::string name;
  std::string link;  // "up", "lost", "down"
  double round_trip_ms = 0.0;
  double last_good_s = 0.0;
  std::uint64_t replies = 0, timeouts = 0, bad_frames = 0, refusals = 0;
  std::optional<std::string> safe;  // once the run's stop resolved it
};

// A command button: enabled when `refusal` is empty, else disabled with it.
struct CommandButton {
  std::string command;  // "hold", …, "teach-in"
  std::string refusal;
};

struct Board {
  bool live = false;
  std::optional<double> t;  // the view's time, when there is a view
  std::vector<BoardAxis> axes;
  std::vector<BoardDevice> devices;
  struct Spindle {
    double set_hz = 0.0;
    double actual_hz = 0.0;
  };
  std::optional<Spindle> spindle;  // when there is a view
  bool read_at_start = false;      // the view is the one `cellctl serve` read before any job
  std::string state;
  int state_current = 0;  // PackML's number
  std::vector<CommandButton> buttons;
  bool history = false;  // the page lists run records
};

[[nodiscard]] std::string board_json(const Board& board);

struct RecipeEntry {
  std::string name;
  // Valid for the cell: its steps (unrolled) and, with a timer, its planned time and the steps only
  // the run can time (shown when there are any); else the problem that keeps it from starting.
  std::optional<std::size_t> steps;
  std::optional<double> planned_s;
  std::size_t not_counted = 0;
  std::optional<std::string> problem;
};

struct RecipeList {
  std::vector<RecipeEntry> recipes;
  bool more = false;  // more recipes than listed
};

[[nodiscard]] std::string recipe_list_json(const RecipeList& list);

// The page's own replies that answer no command (a login, a logout, a request refused before any
// command is read, an internal error): {"ok":true,"outcome":…} or {"ok":false,"reason":…}, the shape
// of a command's answer (command_answer.hpp), so the page reads both alike.
[[nodiscard]] std::string page_reply_json(bool ok, std::string_view text);

}  // namespace cellctl::schema
