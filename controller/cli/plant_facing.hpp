#pragma once
// What faces the plant while cellctl commands the cell: the MQTT plant link (the config's
// `plant_link:` section) and the operator page (--http). `cellctl run` opens them around its one run,
// `cellctl serve` for as long as it stands by; both the same way, with the same banner lines.

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "config/cell_config.hpp"
#include "plant_link/link_config.hpp"
#include "plant_link/plant_link.hpp"
#include "web/operator_page.hpp"

namespace cellctl::cli {

struct PlantFacing {
  std::unique_ptr<plant_link::PlantLink> link;
  std::unique_ptr<web::OperatorPage> page;

  // Every journal line to both (the journal's writer thread).
  void on_journal_line(const nlohmann::json& line) const {
    if (link) link->on_journal_line(line);
    if (page) page->on_journal_line(line);
  }
  // The link's last tags and goodbye, then the page closed.
  void close() {
    link.reset();
    page.reset();
  }
};

// Opens the link when `link_config` is given and the page when `http` is; `say` gets a banner line
// for each (the page's line carries a generated token). `recipes`: the folder a page's start names.
// Throws what PlantLink and OperatorPage throw (TLS options refused, an address that cannot be bound).
[[nodiscard]] PlantFacing open_plant_facing(const config::CellCore& cell,
                                            const std::optional<plant_link::LinkConfig>& link_config,
                                            const std::optional<web::PageOptions>& http,
                                            const std::string& http_token_file,
                                            const std::filesystem::path& recipes,
                                            const plant_link::RunAccess& access,
                                            const std::function<void(const std::string&)>& say);

}  // namespace cellctl::cli
