#pragma once
// A certificate authority, a broker certificate (for 127.0.0.1 and localhost) and a client
// certificate for the controller, made with `openssl` in the test's folder when the test runs: no key
// is ever committed. EC P-256 keys, valid for two days.

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace cellctl::testing {

struct TestCertificates {
  std::filesystem::path ca;  // the CA's certificate (PEM): what both sides trust
  std::filesystem::path server_cert, server_key;
  std::filesystem::path client_cert, client_key;  // CN cellctl
};

inline TestCertificates make_test_certificates(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  const auto at = [&](const char* name) { return (dir / name).string(); };
  const auto run = [](const std::string& cmd) {
    if (std::system((cmd + " >/dev/null 2>&1").c_str()) != 0)
      throw std::runtime_error("openssl failed: " + cmd);
  };
  const std::string key = "-newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes";
  run("openssl req -x509 " + key + " -keyout " + at("ca.key") + " -out " + at("ca.crt") +
      " -days 2 -subj /CN=cellctl-test-ca");
  std::ofstream(dir / "server.ext") << "subjectAltName=IP:127.0.0.1,DNS:localhost\n"
                                       "extendedKeyUsage=serverAuth\n";
  std::ofstream(dir / "client.ext") << "extendedKeyUsage=clientAuth\n";
  for (const std::string who : {"server", "client"}) {
    const auto cn = who == "server" ? "localhost" : "cellctl";
    run("openssl req " + key + " -keyout " + at("") + who + ".key -out " + at("") + who +
        ".csr -subj /CN=" + cn);
    run("openssl x509 -req -in " + at("") + who + ".csr -CA " + at("ca.crt") + " -CAkey " + at("ca.key") +
        " -CAcreateserial -days 2 -out " + at("") + who + ".crt -extfile " + at("") + who + ".ext");
  }
  return {dir / "ca.crt", dir / "server.crt", dir / "server.key", dir / "client.crt", dir / "client.key"};
}

}  // namespace cellctl::testing
