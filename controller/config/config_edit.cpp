#include "config/config_edit.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "config/cell_config.hpp"

namespace cellctl::config {
namespace {

std::vector<std::string> split_lines(std::string_view text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const auto end = text.find('\n', start);
    lines.emplace_back(text.substr(start, end == std::string_view::npos ? text.size() - start : end - start));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return lines;
}

std::size_t indent_of(const std::string& line) {
  return line.find_first_not_of(' ');
}

bool blank_or_comment(const std::string& line) {
  const auto i = line.find_first_not_of(" \t");
  return i == std::string::npos || line[i] == '#';
}

std::string value_of(const std::string& line, std::size_t value_start) {
  std::string v = line.substr(value_start);
  if (const auto hash = v.find(" #"); hash != std::string::npos) v.resize(hash);
  const auto b = v.find_first_not_of(' ');
  const auto e = v.find_last_not_of(' ');
  return b == std::string::npos ? std::string{} : v.substr(b, e - b + 1);
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot be read", path.string()));
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_synced(const std::filesystem::path& path, std::string_view text) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) throw std::runtime_error(fmt::format("{}: cannot be written", path.string()));
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size() && std::fflush(f) == 0 &&
                  ::fsync(fileno(f)) == 0;
  if (std::fclose(f) != 0 || !ok) {
    std::filesystem::remove(path);
    throw std::runtime_error(fmt::format("{}: writing failed", path.string()));
  }
}

struct SectionLines {
  std::size_t head = 0;        // the "section:" line
  std::size_t end = 0;         // one past its last line
  std::size_t key_indent = 2;  // of its own keys
  [[nodiscard]] std::optional<std::size_t> find(const std::vector<std::string>& lines,
                                                const std::string& key) const {
    const std::string prefix = std::string(key_indent, ' ') + key + ":";
    for (std::size_t i = head + 1; i < end; ++i)
      if (lines[i].rfind(prefix, 0) == 0) return i;
    return std::nullopt;
  }
};

SectionLines find_section(const std::vector<std::string>& lines, std::string_view section) {
  const std::string header = std::string(section) + ":";
  SectionLines s;
  s.head = lines.size();
  for (std::size_t i = 0; i < lines.size() && s.head == lines.size(); ++i) {
    const auto& l = lines[i];
    if (l.rfind(header, 0) == 0 && (l.size() == header.size() || blank_or_comment(l.substr(header.size()))))
      s.head = i;
  }
  if (s.head == lines.size())
    throw std::runtime_error(fmt::format("no block-style top-level section '{}:' to change", section));
  // Its lines: everything indented (or blank, or a comment) up to the next top-level key.
  std::size_t first_indent = 0;
  for (s.end = s.head + 1; s.end < lines.size(); ++s.end) {
    const auto& l = lines[s.end];
    if (blank_or_comment(l)) continue;
    const auto ind = indent_of(l);
    if (ind == 0) break;
    if (first_indent == 0) first_indent = ind;
  }
  if (first_indent != 0) s.key_indent = first_indent;
  return s;
}

}  // namespace

std::string edit_section(std::string_view text, std::string_view section,
                         const std::vector<KeyChange>& changes) {
  auto lines = split_lines(text);
  auto s = find_section(lines, section);
  std::size_t added = 0;
  for (const auto& change : changes) {
    const std::string prefix = std::string(s.key_indent, ' ') + change.key + ":";
    const auto at = s.find(lines, change.key);
    if (!change.value) {
      if (at) {
        lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(*at));
        --s.end;
      }
    } else if (at) {
      // A comment on a changed value would describe the old one: kept only when the value stays.
      if (value_of(lines[*at], prefix.size()) != *change.value) lines[*at] = prefix + " " + *change.value;
    } else {
      lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(s.head + 1 + added),
                   prefix + " " + *change.value);
      ++added;
      ++s.end;
    }
  }
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

namespace {

// What `changes` change in `section` of `old_text`, one "section.key: before → after" per key.
std::vector<std::string> changed_keys(std::string_view old_text, std::string_view section,
                                      const std::vector<KeyChange>& changes) {
  std::vector<std::string> changed;
  const auto old_lines = split_lines(old_text);
  const auto old_section = find_section(old_lines, section);
  for (const auto& c : changes) {
    const auto at = old_section.find(old_lines, c.key);
    const std::string before =
        at ? value_of(old_lines[*at], old_section.key_indent + c.key.size() + 1) : std::string("(none)");
    const std::string after = c.value.value_or("(removed)");
    if (before != after) changed.push_back(fmt::format("{}.{}: {} → {}", section, c.key, before, after));
  }
  return changed;
}

// `text` into a temporary file beside `path` that the loader has accepted; the caller renames it.
std::filesystem::path checked_temp(const std::filesystem::path& path, std::string_view text) {
  auto temp = path;
  temp += fmt::format(".new-{}", ::getpid());
  write_synced(temp, text);
  try {
    (void)load_cell_config(temp);  // loaded to be checked: a ConfigError names what is wrong
  } catch (...) {
    std::filesystem::remove(temp);
    throw;
  }
  return temp;
}

void rename_over(const std::filesystem::path& temp, const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::rename(temp, path, ec);
  if (ec) {
    std::filesystem::remove(temp);
    throw std::runtime_error(fmt::format("{}: cannot be replaced: {}", path.string(), ec.message()));
  }
}

}  // namespace

ConfigChange change_config_file(const std::filesystem::path& path, std::string_view section,
                                const std::vector<KeyChange>& changes) {
  const std::string old_text = read_file(path);
  const std::string new_text = edit_section(old_text, section, changes);
  ConfigChange result;
  result.changed = changed_keys(old_text, section, changes);
  // Same folder, so the rename is atomic; the loader judges the new text before it counts.
  const auto temp = checked_temp(path, new_text);
  result.backup = path;
  result.backup += ".bak";
  try {
    write_synced(result.backup, old_text);
  } catch (...) {
    std::filesystem::remove(temp);
    throw;
  }
  rename_over(temp, path);
  return result;
}

ConfigChange change_config_copy(const std::filesystem::path& source, const std::filesystem::path& destination,
                                std::string_view section, const std::vector<KeyChange>& changes) {
  const std::string old_text = read_file(source);
  ConfigChange result;
  result.changed = changed_keys(old_text, section, changes);
  if (destination.has_parent_path()) std::filesystem::create_directories(destination.parent_path());
  rename_over(checked_temp(destination, edit_section(old_text, section, changes)), destination);
  return result;
}

void replace_file(const std::filesystem::path& path, std::string_view text) {
  auto temp = path;
  temp += fmt::format(".new-{}", ::getpid());
  write_synced(temp, text);
  rename_over(temp, path);
}

}  // namespace cellctl::config
