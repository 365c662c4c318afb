#include "web/run_history.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <system_error>
#include <utility>
#include <vector>

#include "journal/run_record.hpp"
#include "journal/run_report.hpp"

namespace cellctl::web {
namespace {

namespace fs = std::filesystem;

// A journal larger than this is reported by `cellctl report`, not by the page.
constexpr std::uintmax_t kMaxReportedJournal = 64u << 20;

// One line of the file, at most kMaxRecordLine long: the first line (from_end false) or the last
// complete one; none when there is none within the bound.
std::optional<std::string> record_line(const fs::path& file, bool from_end) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uintmax_t>(in.tellg());
  const auto take = std::min<std::uintmax_t>(size, kMaxRecordLine);
  in.seekg(from_end ? static_cast<std::streamoff>(size - take) : 0);
  std::string text(take, '\0');
  in.read(text.data(), static_cast<std::streamsize>(take));
  text.resize(static_cast<std::size_t>(in.gcount()));
  std::string_view line = text;
  if (from_end) {
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.remove_suffix(1);
    const auto start = line.rfind('\n');
    // Without a newline before it the line may begin before the bytes read: only a whole file will do.
    if (start == std::string_view::npos && take < size) return std::nullopt;
    if (start != std::string_view::npos) line.remove_prefix(start + 1);
  } else if (const auto end = line.find('\n'); end != std::string_view::npos) {
    line = line.substr(0, end);
  } else if (take < size) {
    return std::nullopt;
  }
  return std::string(line);
}

schema::RunEntry run_entry(const fs::path& dir) {
  const auto journal = dir / "journal.jsonl";
  schema::RunEntry run;
  run.run = dir.filename().string();
  if (const auto header = record_line(journal, false)) run.recipe = schema::header_recipe(*header);
  if (const auto summary = record_line(journal, true)) run.ended = schema::summary_end(*summary);
  std::error_code ec;
  run.plot = fs::is_regular_file(dir / "plot.html", ec);
  return run;
}

}  // namespace

bool plain_run_name(std::string_view name) noexcept {
  if (name.empty() || name.size() > 128 || name.front() == '.') return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
  });
}

schema::RunHistory run_history(const fs::path& folder) {
  std::vector<std::pair<fs::file_time_type, fs::path>> records;
  std::error_code ec;
  if (!folder.empty())
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
      const auto name = entry.path().filename().string();
      const auto journal = entry.path() / "journal.jsonl";
      std::error_code e;
      if (!plain_run_name(name) || !fs::is_regular_file(journal, e)) continue;
      const auto written = fs::last_write_time(journal, e);
      if (!e) records.emplace_back(written, entry.path());
    }
  std::sort(records.begin(), records.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  schema::RunHistory history;
  for (std::size_t i = 0; i < records.size() && i < kMaxListedRuns; ++i)
    history.runs.push_back(run_entry(records[i].second));
  history.more = records.size() > kMaxListedRuns;
  return history;
}

std::optional<std::string> run_report(const fs::path& folder, std::string_view name) {
  if (folder.empty() || !plain_run_name(name)) return std::nullopt;
  const auto journal = folder / name / "journal.jsonl";
  std::error_code ec;
  if (!fs::is_regular_file(journal, ec)) return std::nullopt;
  if (fs::file_size(journal, ec) > kMaxReportedJournal)
    return fmt::format("The record is larger than {} MiB: cellctl report {} prints it.\n",
                       kMaxReportedJournal >> 20, (folder / name).string());
  try {
    return journal::report_text(journal::RunRecord::load(folder / name));
  } catch (const std::exception& e) {
    return fmt::format("The record cannot be read: {}\n", e.what());
  }
}

}  // namespace cellctl::web
