#include "cli/plant_facing.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "web/page_token.hpp"

namespace cellctl::cli {

void add_page_options(CLI::App* sub, PageArgs& args) {
  sub->add_option("--http", args.http_text,
                  "Serve the operator page (live state, commands, /metrics) on ADDR:PORT, or on\n"
                  "127.0.0.1:PORT given a port alone; it needs the token (--http-token-file, else\n"
                  "CELLCTL_HTTP_TOKEN, at least 16 bytes; else a random one printed at the start). A\n"
                  "non-loopback address needs --http-cert and --http-key (HTTPS), or --insecure-http")
      ->check(CLI::Validator(
          [&args](std::string& text) -> std::string {
            std::string why;
            args.http = web::parse_listen_address(text, why);
            return args.http ? std::string() : "'" + text + "': " + why;
          },
          "ADDR:PORT"));
  sub->add_option("--http-token-file", args.token_file, "File whose first line is the operator page's token");
  sub->add_option("--http-cert", args.cert_file,
                  "The operator page's TLS certificate (PEM, its chain after it)");
  sub->add_option("--http-key", args.key_file, "The private key of --http-cert (PEM)");
  sub->add_flag("--insecure-http", args.insecure_http,
                "Serve the page over plain HTTP on a non-loopback address: the token and the session cross\n"
                "the network in clear");
  sub->add_option("--http-allow-host", args.allow_hosts,
                  "A name the page answers to (its Host header) besides the address it is reached at\n"
                  "(repeatable): the controller's DNS name");
  sub->add_flag("--http-public-metrics", args.public_metrics, "/metrics without the token");
  sub->add_option("--http-streams", args.max_streams, "Live-event readers at once (pages open); more get 503")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
}

std::optional<PageSetup> page_setup(const PageArgs& args, std::string& problem) {
  if (!args.http) return std::nullopt;
  PageSetup setup{*args.http, {}};
  auto& o = setup.options;
  o.allowed_hosts = args.allow_hosts;
  o.cert_file = args.cert_file;
  o.key_file = args.key_file;
  o.insecure_http = args.insecure_http;
  o.public_metrics = args.public_metrics;
  o.max_streams = args.max_streams;
  problem = web::listen_problem(o);
  if (!problem.empty()) return std::nullopt;
  try {
    auto token = web::page_token(args.token_file);
    o.token = std::move(token.token);
    setup.token_origin = std::move(token.origin);
  } catch (const std::runtime_error& e) {
    problem = e.what();
    return std::nullopt;
  }
  return setup;
}

PlantFacing open_plant_facing(const config::CellCore& cell,
                              const std::optional<plant_link::LinkConfig>& link_config,
                              const std::optional<PageSetup>& page, const std::filesystem::path& recipes,
                              const plant_link::RunAccess& access,
                              const std::function<void(const std::string&)>& say) {
  PlantFacing f;
  if (link_config) {
    f.link = std::make_unique<plant_link::PlantLink>(*link_config, cell, access);
    say(fmt::format("  plant link: MQTT {}:{} as '{}', tags under {}", link_config->host, link_config->port,
                    link_config->client_id, link_config->topic("")));
  }
  if (page) {
    auto options = page->options;
    options.recipes = recipes;
    f.page = std::make_unique<web::OperatorPage>(options, cell, access);
    const bool generated = page->token_origin == "generated";
    say(fmt::format("  operator page: {}://{}:{}/ — token ({}): {}", options.tls() ? "https" : "http",
                    options.address, f.page->port(), page->token_origin,
                    generated ? options.token : "as given"));
  }
  return f;
}

}  // namespace cellctl::cli
