#pragma once
// What faces the plant while cellctl commands the cell: the MQTT plant link (the config's
// `plant_link:` section) and the operator page (--http and its options). `cellctl run` opens them
// around its one run, `cellctl serve` for as long as it stands by; both the same way, with the same
// options and banner lines.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "config/cell_config.hpp"
#include "journal/event_listener.hpp"
#include "plant_link/link_config.hpp"
#include "plant_link/plant_link.hpp"
#include "web/operator_page.hpp"

namespace cellctl::cli {

// The operator page's command-line options, as given.
struct PageArgs {
  std::string http_text;
  std::optional<web::PageOptions> http;  // --http, parsed by its validator
  std::string token_file;
  std::vector<std::string> allow_hosts;
  std::string cert_file, key_file;
  bool insecure_http = false;
  bool public_metrics = false;
  std::size_t max_streams = 16;
};

// --http, --http-token-file, --http-cert, --http-key, --insecure-http, --http-allow-host,
// --http-public-metrics and --http-streams on `sub`.
void add_page_options(CLI::App* sub, PageArgs& args);

// The page as it will be served: its options and where its token came from.
struct PageSetup {
  web::PageOptions options;
  std::string token_origin;  // "file …", "CELLCTL_HTTP_TOKEN", "generated"
};

// Without --http: nullopt. Else the page's options with the token read (or made). `problem` says why
// they cannot be served (the command is refused with exit 2, before anything opens): plain HTTP on a
// non-loopback address without --insecure-http, a certificate without its key, a token file that
// cannot be read, a token shorter than 16 bytes.
[[nodiscard]] std::optional<PageSetup> page_setup(const PageArgs& args, std::string& problem);

struct PlantFacing final : journal::EventListener {
  std::unique_ptr<plant_link::PlantLink> link;
  std::unique_ptr<web::OperatorPage> page;

  // Every event of the run to both (the journal's writer thread).
  void on_event(const journal::Event& e) override {
    if (link) link->events().on_event(e);
    if (page) page->events().on_event(e);
  }
  void on_note(double t, std::string_view text) override {
    if (link) link->events().on_note(t, text);
    if (page) page->events().on_note(t, text);
  }
  // The link's last tags and goodbye, then the page closed.
  void close() {
    link.reset();
    page.reset();
  }
};

// Opens the link when `link_config` is given and the page when `page` is; `say` gets a banner line
// for each (the page's line carries a generated token). `recipes`: the folder a page's start names.
// Throws what PlantLink and OperatorPage throw (TLS options refused, an address that cannot be bound).
[[nodiscard]] PlantFacing open_plant_facing(const config::CellCore& cell,
                                            const std::optional<plant_link::LinkConfig>& link_config,
                                            const std::optional<PageSetup>& page,
                                            const std::filesystem::path& recipes,
                                            const plant_link::RunAccess& access,
                                            const std::function<void(const std::string&)>& say);

}  // namespace cellctl::cli
