#include "routines/home_record_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace cellctl::routines {
namespace {

std::string utc(std::int64_t unix_time) {
  const auto t = static_cast<std::time_t>(unix_time);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

config::HomingStrategy strategy_from(const std::string& s) {
  for (auto k : {config::HomingStrategy::absolute_encoder, config::HomingStrategy::end_position,
                 config::HomingStrategy::scu_initialised})
    if (s == config::to_string(k)) return k;
  return config::HomingStrategy::none;
}

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what) {
  throw std::runtime_error("home record " + file.string() + ": " + what);
}

}  // namespace

std::filesystem::path home_record_path(const std::filesystem::path& state_dir,
                                       std::string_view dry_run_mode) {
  return state_dir /
         (dry_run_mode.empty() ? std::string("home.json") : "home." + std::string(dry_run_mode) + ".json");
}

HomeRecord load_home_record(const std::filesystem::path& file, const config::CellCore& cell,
                            const std::string& config_sha256, std::string* problem) {
  HomeRecord r;
  r.config_sha256 = config_sha256;
  std::ifstream in(file);
  if (!in) return r;
  try {
    const auto j = nlohmann::json::parse(in);
    const auto recorded = j.at("config_sha256").get<std::string>();
    r.config_changed = recorded != config_sha256;
    for (const auto& [name, a] : j.at("axes").items()) {
      for (std::size_t i = 0; i < cell.axes.size(); ++i) {
        if (cell.axes[i].name != name) continue;
        auto& h = r.axes[i];
        h.homed = true;
        h.strategy = strategy_from(a.at("strategy").get<std::string>());
        h.measured = a.contains("encoder_mm") && !a.at("encoder_mm").is_null();
        if (h.measured) h.encoder_mm = a.at("encoder_mm").get<double>();
        h.scu_mm = a.at("scu_mm").get<double>();
        h.unix_time = a.value("unix_time", std::int64_t{0});
      }
    }
  } catch (const nlohmann::json::exception& e) {
    if (problem) *problem = file.string() + " is no home record (" + e.what() + "); it counts as empty";
    r = {};
    r.config_sha256 = config_sha256;
  }
  return r;
}

void save_home_record(const std::filesystem::path& file, const HomeRecord& record,
                      const config::CellCore& cell) {
  nlohmann::json j;
  j["config_sha256"] = record.config_sha256;
  j["config"] = cell.source.string();
  j["axes"] = nlohmann::json::object();
  for (std::size_t i = 0; i < cell.axes.size(); ++i) {
    const auto& h = record.axes[i];
    if (!h.homed) continue;
    auto& a = j["axes"][cell.axes[i].name];
    a["strategy"] = config::to_string(h.strategy);
    a["encoder_mm"] = h.measured ? nlohmann::json(h.encoder_mm) : nlohmann::json(nullptr);
    a["scu_mm"] = h.scu_mm;
    a["unix_time"] = h.unix_time;
    a["time"] = utc(h.unix_time);
  }
  std::error_code ec;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
  if (ec) fail(file, "cannot create its folder: " + ec.message());
  const auto tmp = std::filesystem::path(file.string() + ".tmp");
  const std::string text = j.dump(2) + "\n";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail(file, std::string("cannot write ") + tmp.string() + ": " + std::strerror(errno));
  std::size_t done = 0;
  while (done < text.size()) {
    const auto n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = errno;
      ::close(fd);
      fail(file, std::string("write failed: ") + std::strerror(err));
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) fail(file, std::string("flush failed: ") + std::strerror(errno));
  if (std::rename(tmp.c_str(), file.c_str()) != 0)
    fail(file, std::string("rename failed: ") + std::strerror(errno));
}

}  // namespace cellctl::routines
