#include "plant_link/packml_tags.hpp"

#include <array>
#include <utility>

namespace cellctl::plant_link {

int packml_state_number(std::string_view s) noexcept {
  static constexpr std::array<std::pair<std::string_view, int>, 13> kNumbers{{{"Stopped", 2},
                                                                              {"Starting", 3},
                                                                              {"Idle", 4},
                                                                              {"Execute", 6},
                                                                              {"Stopping", 7},
                                                                              {"Aborting", 8},
                                                                              {"Aborted", 9},
                                                                              {"Holding", 10},
                                                                              {"Held", 11},
                                                                              {"Unholding", 12},
                                                                              {"Resetting", 15},
                                                                              {"Completing", 16},
                                                                              {"Complete", 17}}};
  for (const auto& [name, number] : kNumbers)
    if (name == s) return number;
  return 0;  // undefined
}

UnitMode unit_mode(std::string_view run_mode) noexcept {
  if (run_mode == "hardware") return {1, "production"};
  if (run_mode == "emulated") return {2, "dry-run emulated"};
  if (run_mode == "virtual-time") return {2, "dry-run virtual time"};
  return {0, "none"};
}

}  // namespace cellctl::plant_link
