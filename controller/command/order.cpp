#include "command/order.hpp"

#include <fmt/format.h>

#include <charconv>

namespace cellctl::command {
namespace {

bool digits(std::string_view s, std::size_t at, std::size_t n, int& out) {
  if (at + n > s.size()) return false;
  const auto r = std::from_chars(s.data() + at, s.data() + at + n, out);
  return r.ec == std::errc() && r.ptr == s.data() + at + n;
}

// Days since 1970-01-01 of a proleptic Gregorian date (H. Hinnant's days_from_civil).
long long days_from_civil(int y, unsigned m, unsigned d) {
  y -= m <= 2 ? 1 : 0;
  const int era = (y >= 0 ? y : y - 399) / 400;
  const auto yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3u : 9u)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return static_cast<long long>(era) * 146097 + static_cast<long long>(doe) - 719468;
}

double ms(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double, std::milli>(d).count();
}

}  // namespace

std::optional<UtcTime> parse_utc(std::string_view s) {
  int y = 0, mo = 0, d = 0, h = 0, mi = 0, sec = 0;
  if (s.size() < 20 || s.size() > 40 || s[4] != '-' || s[7] != '-' || (s[10] != 'T' && s[10] != 't') ||
      s[13] != ':' || s[16] != ':')
    return std::nullopt;
  if (!digits(s, 0, 4, y) || !digits(s, 5, 2, mo) || !digits(s, 8, 2, d) || !digits(s, 11, 2, h) ||
      !digits(s, 14, 2, mi) || !digits(s, 17, 2, sec))
    return std::nullopt;
  if (mo < 1 || mo > 12 || d < 1 || d > 31 || h > 23 || mi > 59 || sec > 60) return std::nullopt;
  std::size_t at = 19;
  long long nanos = 0;
  if (s[at] == '.') {
    long long scale = 100'000'000;
    std::size_t n = 0;
    for (++at; at < s.size() && s[at] >= '0' && s[at] <= '9'; ++at, ++n) {
      nanos += (s[at] - '0') * scale;
      scale /= 10;
    }
    if (n == 0) return std::nullopt;
  }
  const auto zone = s.substr(at);
  if (zone != "Z" && zone != "z" && zone != "+00:00") return std::nullopt;
  const long long seconds = days_from_civil(y, static_cast<unsigned>(mo), static_cast<unsigned>(d)) * 86400 +
                            h * 3600LL + mi * 60LL + sec;
  return UtcTime(std::chrono::duration_cast<UtcTime::duration>(std::chrono::seconds(seconds) +
                                                               std::chrono::nanoseconds(nanos)));
}

std::string expired(const Order& o, SteadyTime now, UtcTime utc_now, std::chrono::milliseconds max_age) {
  const auto waited = now - o.received;
  if (waited > max_age)
    return fmt::format("expired: it waited {:.0f} ms here, more than the {} ms a command may (not obeyed)",
                       ms(waited), max_age.count());
  if (o.issued_at) {
    const auto age = utc_now - *o.issued_at;
    if (age > max_age)
      return fmt::format(
          "expired: issued {:.0f} ms ago, more than the {} ms a command may wait (not obeyed; are the "
          "clocks in step?)",
          ms(std::chrono::duration_cast<std::chrono::steady_clock::duration>(age)), max_age.count());
    if (-age > max_age)
      return fmt::format(
          "its issue time lies {:.0f} ms ahead of this controller's clock: its age is unknown (not "
          "obeyed; set the clocks in step)",
          ms(std::chrono::duration_cast<std::chrono::steady_clock::duration>(-age)));
  }
  return {};
}

}  // namespace cellctl::command
