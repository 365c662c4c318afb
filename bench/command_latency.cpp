// Time from a stop sent to the stop telegram on the SCU's wire, through the real binaries, with and
// without load, in one run (issue 21). Not a test: the figures are printed, beside the no-load ones.
//
//   `cellctl emulate --trace`   the devices on pseudo-terminals; its trace stamps every telegram an
//                               emulator reads with the wall clock (microseconds): where the stop
//                               telegram arrives (the SCU's RS, or F20 after RE 0x13) is measured there;
//   `cellctl serve`             drives them as hardware (their ports are the pseudo-terminals), with
//                               the operator page (--http) and the plant link to
//   `mosquitto`                 started here on a free loopback port (anonymous, loopback only).
//
// Each sample: reset to Idle, start a recipe that moves x at 5 mm/s, wait until the SCU has read the
// move's RE and 300 ms more, send a stop and take the time; the sample ends at the trace's time of the
// first RS or F20 after it. Sources: the page (POST /cmd/stop with the token, one connection, as the
// page's button), the plant (cmd/stop over MQTT, QoS 1) and the terminal (Ctrl-C: SIGINT to serve,
// the stop a standing controller takes from its terminal — the monitor's operator stop, category
// stops.operator). Loads: none; N live-event readers (GET /events, reconnecting when refused or
// closed: serve keeps --http-streams of them, 16 by default, and answers the others 503) and a flood
// of starts over MQTT beside them (a recipe that does not exist, so that none is ever taken).
//
//   command_latency [--samples=20] [--readers=0,32,200] [--flood=1000] [--sources=page,plant,terminal]
//                   [--streams=16] [--cellctl=PATH] [--keep]
//
// Build (release): cmake --preset release && cmake --build --preset release --target command_latency cellctl
// Run:             build/release/bench/command_latency
// The clock of the trace and of this process is the same wall clock; a run across midnight is not
// measured right.

#include <arpa/inet.h>
#include <fcntl.h>
#include <mosquitto.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

extern char** environ;

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using Micros = long long;  // microseconds since local midnight: the trace's clock

constexpr const char* kToken = "command-latency-token-0123456789";
constexpr const char* kPrefix = "bench";
constexpr const char* kCell = "demo-cell";

struct Options {
  int samples = 20;
  std::vector<int> readers{0, 32, 200};
  int flood_per_s = 1000;
  std::vector<std::string> sources{"page", "plant", "terminal"};
  int streams = 16;
  fs::path cellctl = CELLCTL_BINARY;
  bool keep = false;
};

[[noreturn]] void die(const std::string& why) {
  std::fprintf(stderr, "command_latency: %s\n", why.c_str());
  std::exit(1);
}

std::vector<std::string> split(std::string_view s) {
  std::vector<std::string> out;
  std::stringstream in{std::string(s)};
  for (std::string part; std::getline(in, part, ',');) out.push_back(part);
  return out;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    const auto value = [&](std::string_view key) -> std::optional<std::string> {
      if (a.substr(0, key.size()) != key) return std::nullopt;
      return std::string(a.substr(key.size()));
    };
    if (auto v = value("--samples=")) {
      o.samples = std::stoi(*v);
    } else if (auto r = value("--readers=")) {
      o.readers.clear();
      for (const auto& n : split(*r)) o.readers.push_back(std::stoi(n));
    } else if (auto f = value("--flood=")) {
      o.flood_per_s = std::stoi(*f);
    } else if (auto s = value("--sources=")) {
      o.sources = split(*s);
    } else if (auto n = value("--streams=")) {
      o.streams = std::stoi(*n);
    } else if (auto c = value("--cellctl=")) {
      o.cellctl = *c;
    } else if (a == "--keep") {
      o.keep = true;
    } else {
      die("unknown option " + std::string(a));
    }
  }
  return o;
}

Micros now_of_day() {
  const auto now = std::chrono::system_clock::now();
  const auto t = std::chrono::system_clock::to_time_t(now);
  std::tm local{};
  localtime_r(&t, &local);
  const auto micros =
      std::chrono::duration_cast<std::chrono::microseconds>(now.time_since_epoch()).count() % 1'000'000;
  return ((local.tm_hour * 60LL + local.tm_min) * 60 + local.tm_sec) * 1'000'000 + micros;
}

int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) die("bind");
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(fd);
  return ntohs(a.sin_port);
}

int connect_to(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

// --- child processes ------------------------------------------------------------------------------

struct Child {
  pid_t pid = -1;
  void stop() {
    if (pid > 0) {
      ::kill(pid, SIGTERM);
      ::waitpid(pid, nullptr, 0);
    }
    pid = -1;
  }
  ~Child() { stop(); }
};

// Starts argv with stdout and stderr to `out_fd`.
pid_t spawn(const std::vector<std::string>& args, int out_fd) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out_fd, 1);
  posix_spawn_file_actions_adddup2(&actions, out_fd, 2);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = -1;
  if (posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ) != 0)
    die("cannot start " + args[0]);
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

int log_file(const fs::path& p) {
  const int fd = ::open(p.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) die("cannot write " + p.string());
  return fd;
}

// --- the SCU's wire, as the emulator's trace tells it ---------------------------------------------

// Reads `cellctl emulate --trace` and keeps the times of the SCU's RS, F20 and move starts (RE).
class ScuWire {
 public:
  enum class Kind { stop, move };

  explicit ScuWire(int fd) : fd_(fd), reader_([this] { read(); }) {}
  // After the emulator ended: its end of the pipe closed, the reader sees the end.
  ~ScuWire() {
    reader_.join();
    ::close(fd_);
  }
  // The first telegram of `kind` read after `after`, within `timeout`.
  std::optional<Micros> wait(Kind kind, Micros after, std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    std::optional<Micros> found;
    arrived_.wait_for(lock, timeout, [&] {
      for (const auto& [k, t] : seen_)
        if (k == kind && t > after) return (found = t).has_value();
      return false;
    });
    return found;
  }
  bool said(std::string_view text) {
    std::lock_guard lock(mutex_);
    return banner_.find(text) != std::string::npos;
  }

 private:
  void read() {
    std::string buf;
    char chunk[65536];
    for (;;) {
      const auto n = ::read(fd_, chunk, sizeof chunk);
      if (n <= 0) return;
      buf.append(chunk, static_cast<std::size_t>(n));
      for (std::size_t end; (end = buf.find('\n')) != std::string::npos; buf.erase(0, end + 1))
        line(buf.substr(0, end));
    }
  }
  // "trace   12.345678 s 23:05:01.123456 scu RX 52 53 …"
  void line(const std::string& l) {
    const auto at = l.find(" scu RX 52 ");
    if (at == std::string::npos || at < 15) {
      std::lock_guard lock(mutex_);
      if (banner_.size() < 65536) banner_ += l + "\n";
      return;
    }
    const auto bytes = std::string_view(l).substr(at + 11);
    std::optional<Kind> kind;
    if (bytes.substr(0, 2) == "53" || bytes.substr(0, 5) == "45 13")
      kind = Kind::stop;
    else if (bytes.substr(0, 2) == "45")
      kind = Kind::move;
    if (!kind) return;
    const auto time = l.substr(at - 15, 15);  // HH:MM:SS.micros
    const Micros t = ((std::stoll(time.substr(0, 2)) * 60 + std::stoll(time.substr(3, 2))) * 60 +
                      std::stoll(time.substr(6, 2))) *
                         1'000'000 +
                     std::stoll(time.substr(9, 6));
    {
      std::lock_guard lock(mutex_);
      seen_.emplace_back(*kind, t);
      if (seen_.size() > 4096) seen_.erase(seen_.begin(), seen_.begin() + 2048);
    }
    arrived_.notify_all();
  }

  int fd_;
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::vector<std::pair<Kind, Micros>> seen_;
  std::string banner_;
  std::thread reader_;
};

// --- HTTP, as the page's script and a reader use it -----------------------------------------------

struct Reply {
  int status = 0;
  std::string body;
};

Reply http(int port, std::string_view method, std::string_view path, std::string_view body = {}) {
  const int fd = connect_to(port);
  if (fd < 0) return {};
  timeval tv{5, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  std::string req = std::string(method) + " " + std::string(path) +
                    " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                    "\r\nX-Cellctl-Token: " + kToken + "\r\n";
  if (method == "POST")
    req += "Content-Type: application/json\r\nContent-Length: " + std::to_string(body.size()) + "\r\n";
  req += "Connection: close\r\n\r\n" + std::string(body);
  (void)::send(fd, req.data(), req.size(), MSG_NOSIGNAL);
  std::string in;
  char chunk[16384];
  for (ssize_t n; (n = ::recv(fd, chunk, sizeof chunk, 0)) > 0;)
    in.append(chunk, static_cast<std::size_t>(n));
  ::close(fd);
  Reply r;
  if (in.size() > 12) r.status = std::atoi(in.c_str() + 9);
  if (const auto b = in.find("\r\n\r\n"); b != std::string::npos) r.body = in.substr(b + 4);
  return r;
}

std::string state_of(int port) {
  const auto m = http(port, "GET", "/metrics").body;
  const auto at = m.find("cellctl_state{state=\"");
  if (at == std::string::npos) return {};
  const auto from = at + 21;
  return m.substr(from, m.find('"', from) - from);
}

bool wait_state(int port, std::initializer_list<std::string_view> states, std::chrono::seconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end) {
    const auto s = state_of(port);
    if (std::find(states.begin(), states.end(), s) != states.end()) return true;
    std::this_thread::sleep_for(50ms);
  }
  return false;
}

// Live-event readers: each holds a stream as long as it is served, and asks again when refused.
class Readers {
 public:
  Readers(int port, int n) {
    for (int i = 0; i < n; ++i) threads_.emplace_back([this, port] { read(port); });
  }
  ~Readers() {
    stop_.store(true);
    for (auto& t : threads_) t.join();
  }

 private:
  void read(int port) {
    const std::string req = "GET /events HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                            "\r\nX-Cellctl-Token: " + kToken + "\r\n\r\n";
    while (!stop_.load()) {
      const int fd = connect_to(port);
      if (fd >= 0) {
        timeval tv{0, 200'000};
        ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
        (void)::send(fd, req.data(), req.size(), MSG_NOSIGNAL);
        char chunk[8192];
        while (!stop_.load()) {
          const auto n = ::recv(fd, chunk, sizeof chunk, 0);
          if (n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK)) break;
        }
        ::close(fd);
      }
      std::this_thread::sleep_for(200ms);
    }
  }
  std::atomic<bool> stop_{false};
  std::vector<std::thread> threads_;
};

// --- MQTT, as the plant sends -----------------------------------------------------------------------

class Plant {
 public:
  Plant(int port, const std::string& id) : m_(mosquitto_new(id.c_str(), true, nullptr)) {
    if (!m_ || mosquitto_connect(m_, "127.0.0.1", port, 10) != MOSQ_ERR_SUCCESS)
      die("cannot reach the broker");
    mosquitto_loop_start(m_);
  }
  ~Plant() {
    mosquitto_disconnect(m_);
    mosquitto_loop_stop(m_, true);
    mosquitto_destroy(m_);
  }
  void send(std::string_view word, std::string_view payload, int qos) {
    const auto topic = std::string(kPrefix) + "/" + kCell + "/cmd/" + std::string(word);
    (void)mosquitto_publish(m_, nullptr, topic.c_str(), static_cast<int>(payload.size()), payload.data(), qos,
                            false);
  }

 private:
  mosquitto* m_;
};

// Starts a recipe that does not exist, `per_s` a second, until destroyed: refused every one.
class StartFlood {
 public:
  StartFlood(int port, int per_s) : plant_(port, "bench-flood") {
    if (per_s > 0)
      thread_ = std::thread([this, per_s] {
        const auto period = std::chrono::nanoseconds(1'000'000'000LL / per_s);
        auto next = std::chrono::steady_clock::now();
        while (!stop_.load()) {
          plant_.send("start", R"({"recipe":"no-such-recipe","by":"flood"})", 0);
          next += period;
          std::this_thread::sleep_until(next);
        }
      });
  }
  ~StartFlood() {
    stop_.store(true);
    if (thread_.joinable()) thread_.join();
  }

 private:
  Plant plant_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// --- the cell ----------------------------------------------------------------------------------------

struct Bench {
  Options o;
  fs::path work;
  int broker_port = free_port();
  int page_port = free_port();
  Child broker, emulate, serve;
  std::unique_ptr<ScuWire> wire;
  std::unique_ptr<Plant> plant;
  int moves_out = 0;

  void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

  void set_up() {
    const fs::path src = CELLCTL_SOURCE_DIR;
    fs::create_directories(work / "recipes");
    write(work / "mosquitto.conf", "listener " + std::to_string(broker_port) +
                                       " 127.0.0.1\nallow_anonymous true\npersistence false\n");
    broker.pid =
        spawn({"mosquitto", "-c", (work / "mosquitto.conf").string()}, log_file(work / "mosquitto.log"));
    // The emulated cell and the cell that drives it as hardware, as the tests of `cellctl emulate` make them.
    const auto script =
        "set -e; work='" + work.string() + "'; fail() { echo \"$*\" >&2; exit 1; }; source '" +
        (src / "tests/cli/emulate_lib.sh").string() + "'; publish_config '" +
        (src / "config/cell.yaml").string() + "' \"$work/emulated.yaml\"; " +
        "sed -i -E '/^state_dir:/d' \"$work/emulated.yaml\"; echo \"state_dir: $work/state\" >> "
        "\"$work/emulated.yaml\"; " +
        "client_config \"$work/emulated.yaml\" \"$work/cell.yaml\"";
    if (std::system(("bash -c " + quoted(script)).c_str()) != 0) die("could not write the cell configs");
    std::ofstream(work / "cell.yaml", std::ios::app)
        << "plant_link:\n  host: 127.0.0.1\n  port: " << broker_port << "\n  topic_prefix: " << kPrefix
        << "\n  recipes: " << (work / "recipes").string() << "\n";
    const std::string limits = R"(limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
  timeouts: {move_s: 60}
)";
    write(work / "recipes/out.yaml", "recipe: {name: out, version: \"1\", cell: demo-cell}\n" + limits +
                                         "steps:\n  - move: {to: {x: 170}, speed_mm_s: 5}\n");
    write(work / "recipes/back.yaml", "recipe: {name: back, version: \"1\", cell: demo-cell}\n" + limits +
                                          "steps:\n  - move: {to: {x: 5}, speed_mm_s: 18}\n");
    write(work / "token", std::string(kToken) + "\n");

    int pipe_fds[2];
    if (::pipe2(pipe_fds, O_CLOEXEC) != 0) die("pipe");
    emulate.pid = spawn({o.cellctl.string(), "-c", (work / "emulated.yaml").string(), "--trace", "emulate"},
                        pipe_fds[1]);
    ::close(pipe_fds[1]);
    wire = std::make_unique<ScuWire>(pipe_fds[0]);
    for (int i = 0; i < 200 && !wire->said("Ctrl-C ends the emulation"); ++i)
      std::this_thread::sleep_for(50ms);
    if (!wire->said("Ctrl-C ends the emulation")) die("cellctl emulate did not start");

    serve.pid = spawn(
        {o.cellctl.string(), "-c", (work / "cell.yaml").string(), "serve", "--runs", (work / "runs").string(),
         "--recipes", (work / "recipes").string(), "--http", "127.0.0.1:" + std::to_string(page_port),
         "--http-token-file", (work / "token").string(), "--http-streams", std::to_string(o.streams)},
        log_file(work / "serve.log"));
    if (!wait_state(page_port, {"Idle"}, 30s)) die("cellctl serve did not come up (see serve.log)");
    plant = std::make_unique<Plant>(broker_port, "bench-plant");
    std::this_thread::sleep_for(1s);  // the link connected and subscribed
  }

  static std::string quoted(const std::string& s) {
    std::string q = "'";
    for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  }

  // Reset (clear first after an abort; stop first a job still running) until Idle: a reset while the
  // job that ended still closes its devices is refused, so it is asked again.
  void to_idle() {
    const auto end = std::chrono::steady_clock::now() + 30s;
    while (std::chrono::steady_clock::now() < end) {
      const auto s = state_of(page_port);
      if (s == "Idle") return;
      if (s == "Stopped" || s == "Complete") {
        (void)http(page_port, "POST", "/cmd/reset", "{}");
      } else if (s == "Aborted") {
        (void)http(page_port, "POST", "/cmd/clear", "{}");
      } else if (s == "Held" || s == "Execute" || s == "Holding" || s == "Starting") {
        (void)http(page_port, "POST", "/cmd/stop", "{}");
      }
      std::this_thread::sleep_for(50ms);
    }
    die("the cell does not come back to Idle: " + state_of(page_port));
  }

  // x back near its start every few samples, so that every sample's move is a long one.
  void bring_back() {
    to_idle();
    if (http(page_port, "POST", "/cmd/start", R"({"recipe":"back"})").status != 200)
      die("the back move was refused");
    (void)wait_state(page_port, {"Complete", "Stopped", "Aborted"}, 60s);
    moves_out = 0;
  }

  void send_stop(const std::string& source) {
    if (source == "page") {
      (void)http(page_port, "POST", "/cmd/stop", "{}");  // the answer comes later: the clock started before
    } else if (source == "plant") {
      plant->send("stop", R"({"by":"bench"})", 1);
    } else {
      ::kill(serve.pid, SIGINT);
    }
  }

  // One sample: ms from the stop sent to the SCU's reading of its RS or F20; nullopt when none came.
  std::optional<double> sample(const std::string& source) {
    if (moves_out >= 8) bring_back();
    to_idle();
    const auto before = now_of_day();
    const auto started = http(page_port, "POST", "/cmd/start", R"({"recipe":"out"})");
    if (started.status != 200) die("start refused: " + started.body);
    ++moves_out;
    if (!wire->wait(ScuWire::Kind::move, before, 20s)) die("the move never reached the SCU");
    std::this_thread::sleep_for(300ms);
    const auto sent = now_of_day();
    send_stop(source);
    const auto stopped = wire->wait(ScuWire::Kind::stop, sent, 5s);
    (void)wait_state(page_port, {"Stopped", "Held", "Aborted", "Complete"}, 20s);
    if (!stopped) return std::nullopt;
    return static_cast<double>(*stopped - sent) / 1000.0;
  }
};

struct Figures {
  std::size_t n = 0, missing = 0;
  double p50 = 0, p99 = 0, max = 0;
};

Figures figures(std::vector<double> v, std::size_t missing) {
  Figures f;
  f.n = v.size();
  f.missing = missing;
  if (v.empty()) return f;
  std::sort(v.begin(), v.end());
  const auto at = [&](double q) {
    const auto i = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size()))) - 1;
    return v[std::min(i, v.size() - 1)];
  };
  f.p50 = at(0.50);
  f.p99 = at(0.99);
  f.max = v.back();
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  Bench b;
  b.o = parse(argc, argv);
  mosquitto_lib_init();
  char tmpl[] = "/tmp/cellctl-command-latency.XXXXXX";
  if (!::mkdtemp(tmpl)) die("mkdtemp");
  b.work = tmpl;
  std::printf("command_latency: %s, %d samples per source and load, work in %s\n", b.o.cellctl.c_str(),
              b.o.samples, b.work.c_str());
  std::fflush(stdout);
  std::map<std::pair<int, std::string>, Figures> table;
  {
    b.set_up();
    for (const int readers : b.o.readers) {
      std::optional<Readers> live;
      std::optional<StartFlood> flood;
      if (readers > 0) {
        live.emplace(b.page_port, readers);
        flood.emplace(b.broker_port, b.o.flood_per_s);
        std::this_thread::sleep_for(1s);
      }
      for (const auto& source : b.o.sources) {
        std::vector<double> ms;
        std::size_t missing = 0;
        for (int i = 0; i < b.o.samples; ++i) {
          if (const auto s = b.sample(source))
            ms.push_back(*s);
          else
            ++missing;
        }
        table[{readers, source}] = figures(ms, missing);
        const auto& f = table[{readers, source}];
        std::printf("  %-8s %3d readers%s: p50 %.1f ms, p99 %.1f ms, max %.1f ms (%zu samples%s)\n",
                    source.c_str(), readers, readers > 0 ? " + starts" : "", f.p50, f.p99, f.max, f.n,
                    f.missing ? (", " + std::to_string(f.missing) + " without a stop telegram").c_str() : "");
        std::fflush(stdout);
      }
    }
  }
  std::printf(
      "\nstop sent -> the SCU reads its RS/F20 (ms); load: live-event readers (serve keeps %d) + %d MQTT "
      "starts/s; ratio: p99 / p99 with no load\n",
      b.o.streams, b.o.flood_per_s);
  std::printf("%-9s %-20s %8s %8s %8s %7s %s\n", "source", "load", "p50", "p99", "max", "ratio",
              "p99 <= 50 ms");
  bool met = true;
  for (const auto& [key, f] : table) {
    const auto& [readers, source] = key;
    const auto base = table.find({0, source});
    const double ratio = base != table.end() && base->second.p99 > 0 ? f.p99 / base->second.p99 : 0.0;
    const auto load = readers == 0 ? std::string("none") : std::to_string(readers) + " readers + starts";
    const bool ok = f.n > 0 && f.missing == 0 && f.p99 <= 50.0;
    met = met && ok;
    std::printf("%-9s %-20s %8.1f %8.1f %8.1f %7.2f %s\n", source.c_str(), load.c_str(), f.p50, f.p99, f.max,
                ratio, ok ? "yes" : "NO");
  }
  b.plant.reset();
  b.serve.stop();
  b.emulate.stop();
  b.wire.reset();
  b.broker.stop();
  std::printf("%s\n", met ? "target met: p99 <= 50 ms for every source and load"
                          : "target NOT met for every source and load");
  if (!b.o.keep) fs::remove_all(b.work);
  mosquitto_lib_cleanup();
  return met ? 0 : 1;
}
