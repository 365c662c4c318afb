// The shipped GSD file, read as a DP master reads it, drives our DP master to data exchange with the
// emulated encoder for every module: the ident number, each module's configuration bytes and its own
// parameter data (Ext_Module_Prm_Data_Len, constants, ExtUserPrmData references at their defaults or
// at values a master chooses). The file is the only source of the master's Set_Prm and Chk_Cfg here.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <fstream>
#include <sstream>

#include "encoder/cyclic.hpp"
#include "encoder/emulator.hpp"
#include "encoder/functionality.hpp"
#include "encoder/parameters.hpp"
#include "gsd_reader.hpp"
#include "link/sim_link.hpp"
#include "plant/shaft.hpp"
#include "profibus/dp_master.hpp"
#include "virtual_line.hpp"

namespace cellctl::encoder::testing {
namespace {

using namespace std::chrono_literals;

constexpr std::uint8_t kStation = 5;

const std::pair<const char*, Functionality> kModules[] = {
    {"Class 1 Multiturn", Functionality::class1},        {"Class 2 Multiturn", Functionality::class2},
    {"Scancon 2.1 Multiturn", Functionality::scancon21}, {"Scancon 2.2 Multiturn", Functionality::scancon22},
    {"Scancon 3.0 Multiturn", Functionality::scancon30},
};

std::string gsd_text() {
  std::ifstream in(CELLCTL_ENCODER_GSD);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Gsd shipped_gsd() {
  std::istringstream in(gsd_text());
  return read_gsd(in);
}

// A DP master configured from the GSD alone, and the emulated encoder, on one simulated line.
struct GsdBus {
  GsdBus(const Gsd& gsd, const GsdModule& module, const std::map<int, long long>& values = {})
      : sim(clock, link::line_8e1(1'500'000)),
        shaft(plant::ShaftParams{4.0, 0.0, 0.0}, [] { return 10.0; }),
        emulator(sim.device(), emulator_config(), shaft),
        master(sim.master(), master_config(), setup(gsd, module, values)) {}

  static EmulatorConfig emulator_config() {
    EmulatorConfig c;
    c.address = kStation;
    return c;
  }
  static profibus::DpMasterConfig master_config() {
    profibus::DpMasterConfig c;
    c.master_address = 2;
    return c;
  }
  static profibus::DpSlaveSetup setup(const Gsd& gsd, const GsdModule& module,
                                      const std::map<int, long long>& values) {
    profibus::DpSlaveSetup s;
    s.station_address = kStation;
    s.ident = gsd.ident;
    const auto prm = user_prm_for(gsd, module, values);
    EXPECT_TRUE(s.user_prm.assign(prm));
    EXPECT_TRUE(s.cfg.assign(module.cfg));
    const IoLengths io = io_lengths(module.cfg);
    s.input_length = io.input;
    s.output_length = io.output;
    return s;
  }

  // Until data exchange or a refusal (or 200 ms); true in data exchange with a few inputs read.
  bool start() {
    master.activate(clock.now());
    (void)run_line_until(
        clock, sim,
        [&] { return master.lifecycle() == link::Lifecycle::fault || master.stats().data_exchanges >= 3; },
        200ms, master, emulator);
    return master.lifecycle() == link::Lifecycle::active && master.stats().data_exchanges >= 3;
  }

  link::VirtualClock clock;
  link::SimLink sim;
  plant::Shaft shaft;
  Emulator emulator;
  profibus::DpMaster master;
};

TEST(Gsd, OneModulePerFunctionalityWithItsOwnParameterData) {
  const Gsd gsd = shipped_gsd();
  EXPECT_EQ(gsd.ident, kIdentNumber);
  EXPECT_EQ(gsd.user_prm_length, 0u) << "every user parameter belongs to a module";
  ASSERT_EQ(gsd.modules.size(), std::size(kModules));
  for (const auto& [name, f] : kModules) {
    const GsdModule& m = gsd.module(name);
    const auto ids = config_identifiers(f);
    EXPECT_EQ(m.cfg, std::vector<std::uint8_t>(ids.begin(), ids.end())) << name;
    EXPECT_EQ(m.prm_length, user_prm_length(f)) << name;
    const IoLengths io = io_lengths(m.cfg);
    EXPECT_EQ(io.input, input_length(f)) << name;
    EXPECT_EQ(io.output, output_length(f)) << name;
    // At their defaults the module's parameters are what encode_user_prm() writes for the defaults.
    EncoderParameters p;
    p.functionality = f;
    std::array<std::uint8_t, 64> prm{};
    const std::size_t n = encode_user_prm(p, prm);
    EXPECT_EQ(user_prm_for(gsd, m),
              std::vector<std::uint8_t>(prm.begin(), prm.begin() + static_cast<long>(n)))
        << name;
  }
}

TEST(Gsd, OurMasterConfiguredFromTheFileReachesDataExchangeForEveryModule) {
  const Gsd gsd = shipped_gsd();
  for (const auto& [name, f] : kModules) {
    GsdBus bus(gsd, gsd.module(name));
    ASSERT_TRUE(bus.start()) << name << ": " << bus.master.fault_reason() << " / "
                             << bus.emulator.last_prm_reason() << bus.emulator.last_cfg_reason();
    EXPECT_EQ(bus.emulator.device().parameters().functionality, f) << name;
    EXPECT_EQ(bus.master.inputs().size(), input_length(f)) << name;
    // The shaft stands at 10 mm = 2.5 revolutions = 20480 steps; the input says so.
    const auto in = decode_input(f, is_scancon(f), bus.master.inputs());
    ASSERT_TRUE(std::holds_alternative<CyclicInput>(in)) << name;
    EXPECT_EQ(std::get<CyclicInput>(in).position(is_scancon(f)), 20480u) << name;
    EXPECT_EQ(bus.master.health().error_replies, 0u) << name;
  }
}

TEST(Gsd, TheEmulatorTakesTheParametersAMasterSetsFromTheFile) {
  const Gsd gsd = shipped_gsd();
  const auto id_of = [&](std::string_view parameter) {
    for (const auto& [id, def] : gsd.prm_defs)
      if (def.name == parameter) return id;
    ADD_FAILURE() << "no ExtUserPrmData \"" << parameter << "\"";
    return 0;
  };
  // Scaling on, 1000 units per revolution, range 1000 × 4096, velocity per 10 ms, counter-clockwise.
  const std::map<int, long long> values{{id_of("Scaling function control"), 1},
                                        {id_of("Measuring units per revolution / desired units"), 1000},
                                        {id_of("Total measuring range"), 1000 * 4096},
                                        {id_of("Time base for velocity"), 2},
                                        {id_of("Code sequence"), 1}};
  GsdBus bus(gsd, gsd.module("Scancon 3.0 Multiturn"), values);
  ASSERT_TRUE(bus.start()) << bus.master.fault_reason() << " / " << bus.emulator.last_prm_reason();
  const EncoderParameters& p = bus.emulator.device().parameters();
  EXPECT_TRUE(p.scaling);
  EXPECT_EQ(p.measuring_units, 1000u);
  EXPECT_EQ(p.total_range, 1000u * 4096u);
  EXPECT_EQ(p.time_base, TimeBase::steps_per_10ms);
  EXPECT_EQ(p.code_sequence, CodeSequence::ccw);
  // A value outside the GSD's range is refused before anything is sent.
  EXPECT_THROW(
      (void)user_prm_for(gsd, gsd.module("Scancon 3.0 Multiturn"), {{id_of("Time base for velocity"), 4}}),
      std::runtime_error);
}

TEST(Gsd, AGlobalUserPrmDataLenBesideTheModulesIsRefusedByTheEncoder) {
  // The file as it was: 32 global octets + 32 of the module = 64, which the encoder refuses.
  std::string text = gsd_text();
  text.insert(text.find("Max_User_Prm_Data_Len"), "User_Prm_Data_Len = 32\n");
  text.replace(text.find("Max_User_Prm_Data_Len = 32"), 26, "Max_User_Prm_Data_Len = 64");
  std::istringstream in(text);
  const Gsd gsd = read_gsd(in);
  GsdBus bus(gsd, gsd.module("Scancon 2.2 Multiturn"));
  EXPECT_FALSE(bus.start());
  EXPECT_EQ(bus.master.last_startup_fault().kind, profibus::StartupFault::Kind::prm_fault);
  EXPECT_EQ(
      bus.emulator.last_prm_reason(),
      "User_Prm_Data: 64 octets; the encoder takes 2 (Class 1), 18 (Class 2) or 32 (Scancon 2.1/2.2/3.0) "
      "(manual 4.1)");
}

TEST(GsdReader, ConfigurationIdentifiersInBothFormats) {
  EXPECT_EQ(io_lengths(std::array<std::uint8_t, 1>{0xD1}).input, 4u);   // general: 2 input words
  EXPECT_EQ(io_lengths(std::array<std::uint8_t, 1>{0xF1}).output, 4u);  // general: 2 in + 2 out words
  EXPECT_EQ(io_lengths(std::array<std::uint8_t, 1>{0x23}).output, 4u);  // general: 4 output bytes
  const IoLengths special = io_lengths(std::array<std::uint8_t, 4>{0xC1, 0xC1, 0xC3, 0x30});
  EXPECT_EQ(special.output, 4u);
  EXPECT_EQ(special.input, 8u);
  EXPECT_THROW((void)io_lengths(std::array<std::uint8_t, 2>{0xC1, 0xC1}), std::runtime_error);
}

TEST(GsdReader, RefusesWhatItCannotRead) {
  const auto read = [](const std::string& text) {
    std::istringstream in(text);
    return read_gsd(in);
  };
  EXPECT_THROW((void)read("ExtUserPrmData = 1 \"x\"\nFloat32 0 0-1\nEndExtUserPrmData\n"),
               std::runtime_error);
  EXPECT_THROW((void)read("ExtUserPrmData = 1 \"x\"\nUnsigned8 9 0-1\nEndExtUserPrmData\n"),
               std::runtime_error);
  EXPECT_THROW((void)read("Module = \"m\" 0xD1\n1\nSomething = 2\nEndModule\n"), std::runtime_error);
  EXPECT_THROW((void)read("Module = \"m\" 0xD1\n1\n"), std::runtime_error);
  // A constant beyond the module's declared parameter length is the file's error, not silently cut.
  const Gsd gsd = read(
      "Module = \"m\" 0xD1\n1\nExt_Module_Prm_Data_Len = 1\n"
      "Ext_User_Prm_Data_Const(0) = 0x00,0x01\nEndModule\n");
  EXPECT_THROW((void)user_prm_for(gsd, gsd.module("m")), std::runtime_error);
}

}  // namespace
}  // namespace cellctl::encoder::testing
