#include "cli/plant_facing.hpp"

#include <fmt/format.h>

#include "web/page_token.hpp"

namespace cellctl::cli {

PlantFacing open_plant_facing(const config::CellCore& cell,
                              const std::optional<plant_link::LinkConfig>& link_config,
                              const std::optional<web::PageOptions>& http, const std::string& http_token_file,
                              const std::filesystem::path& recipes, const plant_link::RunAccess& access,
                              const std::function<void(const std::string&)>& say) {
  PlantFacing f;
  if (link_config) {
    f.link = std::make_unique<plant_link::PlantLink>(*link_config, cell, access);
    say(fmt::format("  plant link: MQTT {}:{} as '{}', tags under {}", link_config->host, link_config->port,
                    link_config->client_id, link_config->topic("")));
  }
  if (http) {
    auto page_options = *http;
    const auto token = web::page_token(http_token_file);
    page_options.token = token.token;
    page_options.recipes = recipes;
    f.page = std::make_unique<web::OperatorPage>(page_options, cell, access);
    say(fmt::format("  operator page: http://{}:{}/ — command token ({}): {}", page_options.address,
                    f.page->port(), token.origin, token.origin == "generated" ? token.token : "as given"));
  }
  return f;
}

}  // namespace cellctl::cli
