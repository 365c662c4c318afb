#pragma once
// The encoder side of the Teach-In routine (routines::TeachInPort) over the cell's encoder::Session:
// the parameter sets come from encoder/commissioning_parameters; a switch closes the DP session,
// gives it the new parameters and starts it up again (Set_Prm and Chk_Cfg go out again), stepped
// once per cycle. Distances are turned into the taught unit here, at the device boundary.

#include <cstdint>
#include <string_view>

#include "encoder/session.hpp"
#include "routines/teach_in_port.hpp"

namespace cellctl::runtime {

class TeachInEncoder final : public routines::TeachInPort {
 public:
  // `configured`: the cell config's session settings (what the session was built with).
  TeachInEncoder(encoder::Session& session, const encoder::SessionConfig& configured);

  // Each cycle after the sessions' receive(): carries out a switch once the session has closed.
  void step(link::TimePoint now);

  [[nodiscard]] std::string_view unavailable() const override;
  void switch_to(routines::EncoderSetting setting, link::TimePoint now) override;
  [[nodiscard]] bool start_teach_in() override;
  [[nodiscard]] bool end_teach_in(double distance_mm) override;
  void clear_command() override;
  [[nodiscard]] routines::EncoderView read() const override;

  // The taught unit: measuring units per mm after Teach-In (a power of ten, see
  // encoder::teach_in_units_per_mm).
  [[nodiscard]] double units_per_mm() const noexcept { return units_per_mm_; }
  // The session settings for the taught resolution (valid after end_teach_in succeeded).
  [[nodiscard]] encoder::SessionConfig taught(std::uint32_t total_resolution) const;

 private:
  [[nodiscard]] encoder::SessionConfig config_for(routines::EncoderSetting s) const;

  encoder::Session& session_;
  encoder::SessionConfig configured_;
  double configured_steps_per_mm_;
  double units_per_mm_;
  encoder::SessionConfig target_;
  bool pending_ = false;  // closing for a switch
  std::string_view failure_;
  std::uint32_t total_resolution_ = 0;  // of the last Teach-In end acknowledged
};

}  // namespace cellctl::runtime
