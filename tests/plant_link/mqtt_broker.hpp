#pragma once
// Debian's mosquitto as a test broker, configured as the plant's example (config/examples/mosquitto/):
// its mosquitto.conf with the test's ports, paths and certificates (made at test time:
// test_certificates.hpp), its ACL file as it is, users cellctl, mes and dashboard with generated
// passwords. Both listeners on loopback and free ports: port() plain, tls_port() TLS with a client
// certificate required.
// start() waits until the port accepts a connection; kill() is SIGKILL (the broker dies, as a crashed
// one does, and keeps nothing); stop() is SIGTERM (a restart for maintenance: a persistent broker
// saves its retained messages); start() again restarts it on the same ports. Waits are on conditions,
// with time-outs.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "test_certificates.hpp"

namespace cellctl::testing {

inline int free_loopback_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) throw std::runtime_error("bind");
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(fd);
  return ntohs(a.sin_port);
}

inline bool port_accepts(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  const bool ok = ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  ::close(fd);
  return ok;
}

struct BrokerOptions {
  bool persistent = false;  // retained messages survive stop() and start()
  // Replaces the example's message_size_limit (a test of what reaches the link when the broker lets
  // a large message through).
  std::optional<std::size_t> message_size_limit;
};

class MqttBroker {
 public:
  // The example's topic prefix and cell (config/examples/mosquitto/cellctl.acl).
  static constexpr const char* kPrefix = "plant/area1";
  static constexpr const char* kMesPassword = "mes-secret";
  static constexpr const char* kDashboardPassword = "dashboard-secret";

  explicit MqttBroker(std::filesystem::path dir, BrokerOptions options = {})
      : dir_(std::move(dir)), port_(free_loopback_port()), tls_port_(free_loopback_port()) {
    while (tls_port_ == port_) tls_port_ = free_loopback_port();
    std::filesystem::create_directories(dir_);
    certificates_ = make_test_certificates(dir_ / "certs");
    const auto passwd = dir_ / "passwd";
    std::filesystem::remove(passwd);
    for (const auto& [user, pass] : {std::pair{"cellctl", "cell-secret"}, std::pair{"mes", kMesPassword},
                                     std::pair{"dashboard", kDashboardPassword}}) {
      const auto cmd = "mosquitto_passwd -b " + std::string(std::filesystem::exists(passwd) ? "" : "-c ") +
                       passwd.string() + " " + user + " " + pass + " >/dev/null 2>&1";
      if (std::system(cmd.c_str()) != 0) throw std::runtime_error("mosquitto_passwd failed: " + cmd);
    }
    const auto example = std::filesystem::path(CELLCTL_SOURCE_DIR) / "config/examples/mosquitto";
    std::ofstream(dir_ / "mosquitto.conf")
        << as_tested(example / "mosquitto.conf", example / "cellctl.acl", passwd, options)
        << "log_dest stderr\n"
        << "log_type error\n"
        << (options.persistent ? "persistence true\npersistence_location " + (dir_ / "db").string() + "/\n"
                               : std::string("persistence false\n"))
        << (::geteuid() == 0 ? "user root\n" : "");
    std::filesystem::create_directories(dir_ / "db");
  }
  ~MqttBroker() { kill(); }

  [[nodiscard]] int port() const noexcept { return port_; }
  [[nodiscard]] int tls_port() const noexcept { return tls_port_; }
  [[nodiscard]] const TestCertificates& certificates() const noexcept { return certificates_; }

  void start() {
    pid_ = ::fork();
    if (pid_ == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // a test that dies leaves no broker behind
      const auto conf = (dir_ / "mosquitto.conf").string();
      ::execlp("mosquitto", "mosquitto", "-c", conf.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (!port_accepts(port_) || !port_accepts(tls_port_)) {
      if (std::chrono::steady_clock::now() > until) throw std::runtime_error("mosquitto did not start");
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  void kill() { end(SIGKILL); }
  void stop() { end(SIGTERM); }

 private:
  // The example's configuration line by line, with the test's ports (its first listener plain, its
  // second TLS, both on loopback), certificates, password file and the example's own ACL file.
  std::string as_tested(const std::filesystem::path& example_conf, const std::filesystem::path& acl,
                        const std::filesystem::path& passwd, const BrokerOptions& options) const {
    std::ifstream in(example_conf);
    if (!in) throw std::runtime_error("no " + example_conf.string());
    std::ostringstream out;
    int listeners = 0;
    for (std::string line; std::getline(in, line);) {
      std::istringstream words(line);
      std::string key;
      words >> key;
      if (key == "listener")
        out << "listener " << (listeners++ == 0 ? port_ : tls_port_) << " 127.0.0.1\n";
      else if (key == "cafile")
        out << "cafile " << certificates_.ca.string() << "\n";
      else if (key == "certfile")
        out << "certfile " << certificates_.server_cert.string() << "\n";
      else if (key == "keyfile")
        out << "keyfile " << certificates_.server_key.string() << "\n";
      else if (key == "password_file")
        out << "password_file " << passwd.string() << "\n";
      else if (key == "acl_file")
        out << "acl_file " << acl.string() << "\n";
      else if (key == "message_size_limit" && options.message_size_limit)
        out << "message_size_limit " << *options.message_size_limit << "\n";
      else
        out << line << "\n";
    }
    if (listeners != 2) throw std::runtime_error(example_conf.string() + " has not two listeners");
    return out.str();
  }
  void end(int signal) {
    if (pid_ <= 0) return;
    ::kill(pid_, signal);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }

  std::filesystem::path dir_;
  int port_;
  int tls_port_;
  TestCertificates certificates_;
  pid_t pid_ = -1;
};

}  // namespace cellctl::testing
