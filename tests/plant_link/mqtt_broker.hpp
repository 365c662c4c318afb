#pragma once
// Debian's mosquitto as a test broker: a free loopback port, a generated password file (users
// cellctl, operator, viewer), an ACL (the controller reads and writes its tags, the operator may
// command, the viewer only reads), no anonymous clients. start() waits until the port accepts a
// connection; kill() is SIGKILL (the broker dies, as a crashed one does); start() again restarts it on
// the same port. Waits are on conditions, with time-outs.

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
#include <stdexcept>
#include <string>
#include <thread>

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

class MqttBroker {
 public:
  static constexpr const char* kPrefix = "plant-test";

  explicit MqttBroker(std::filesystem::path dir) : dir_(std::move(dir)), port_(free_loopback_port()) {
    std::filesystem::create_directories(dir_);
    const auto passwd = dir_ / "passwd";
    std::filesystem::remove(passwd);
    for (const auto& [user, pass] : {std::pair{"cellctl", "cell-secret"}, std::pair{"operator", "op-secret"},
                                     std::pair{"viewer", "view-secret"}}) {
      const auto cmd = "mosquitto_passwd -b " + std::string(std::filesystem::exists(passwd) ? "" : "-c ") +
                       passwd.string() + " " + user + " " + pass + " >/dev/null 2>&1";
      if (std::system(cmd.c_str()) != 0) throw std::runtime_error("mosquitto_passwd failed: " + cmd);
    }
    std::ofstream(dir_ / "acl") << "user cellctl\ntopic readwrite " << kPrefix << "/#\n"
                                << "user operator\ntopic read " << kPrefix << "/#\ntopic write " << kPrefix
                                << "/+/cmd/#\n"
                                << "user viewer\ntopic read " << kPrefix << "/#\n";
    std::ofstream conf(dir_ / "mosquitto.conf");
    conf << "listener " << port_ << " 127.0.0.1\nallow_anonymous false\npassword_file " << passwd.string()
         << "\nacl_file " << (dir_ / "acl").string()
         << "\npersistence false\nlog_dest stderr\nlog_type error\n";
    if (::geteuid() == 0) conf << "user root\n";
  }
  ~MqttBroker() { kill(); }

  [[nodiscard]] int port() const noexcept { return port_; }

  void start() {
    pid_ = ::fork();
    if (pid_ == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // a test that dies leaves no broker behind
      const auto conf = (dir_ / "mosquitto.conf").string();
      ::execlp("mosquitto", "mosquitto", "-c", conf.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (!port_accepts(port_)) {
      if (std::chrono::steady_clock::now() > until) throw std::runtime_error("mosquitto did not start");
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  void kill() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }

 private:
  std::filesystem::path dir_;
  int port_;
  pid_t pid_ = -1;
};

}  // namespace cellctl::testing
