#include "journal/record_header.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <openssl/evp.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "journal/version.hpp"

namespace cellctl::journal {
namespace {

std::string host_name() {
  std::array<char, 256> name{};
  if (::gethostname(name.data(), name.size() - 1) != 0) return "unknown";
  return name.data();
}

}  // namespace

std::string file_sha256(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("cannot read {} to record its hash", file.string()));
  const std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), &EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("SHA-256 is not available");
  std::array<char, 8192> buf{};
  while (in.read(buf.data(), buf.size()) || in.gcount() > 0)
    EVP_DigestUpdate(ctx.get(), buf.data(), static_cast<std::size_t>(in.gcount()));
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int n = 0;
  EVP_DigestFinal_ex(ctx.get(), digest.data(), &n);
  std::string hex;
  for (unsigned int i = 0; i < n; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

schema::RecordHeader record_header(const RecordInfo& info) {
  schema::RecordHeader h;
  h.recipe_file = info.recipe_file.string();
  h.recipe_sha256 = file_sha256(info.recipe_file);
  h.recipe = info.recipe_name;
  h.recipe_version = info.recipe_version;
  h.config_file = info.config_file.string();
  h.config_sha256 = file_sha256(info.config_file);
  h.cell = info.cell;
  h.cellctl = std::string(cellctl_version());
  h.mode = info.mode;
  h.ports = info.ports;
  h.host = host_name();
  h.started_utc =
      fmt::format("{:%Y-%m-%dT%H:%M:%SZ}",
                  fmt::gmtime(std::chrono::system_clock::to_time_t(std::chrono::system_clock::now())));
  h.sample_s = info.sample_s;
  for (const auto& a : info.axes) h.axes.push_back({a.name, a.measured});
  for (const auto& s : info.steps) h.steps.push_back({s.label, s.kind, s.planned_s});
  return h;
}

}  // namespace cellctl::journal
