// Issue 22: no text is cut. Walks every message template the program composes into a fixed buffer
// (journal::Text::format, a session's enter_fault, link::assign_formatted) in the sources, renders it
// with fmt at its longest arguments and checks it fits: a message whole within
// Text::kLongestMessage, a message that quotes another (a reason, a failure, a source) adding at most
// Text::kLongestWrapping. Found in the sources, not listed here, so a new template is checked too.
// An argument's longest rendering is judged from its format spec and, for {}, from its expression:
// a literal or a choice of literals, a quoted text (a reason, failure, source, note: measured as a
// message of its own), a name, an enum's name, else a 32-bit number. CELLCTL_SHOW_MESSAGES=1 prints
// every template as rendered, with its length ("+": it quotes another text).

#include <fmt/args.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "config/axis_section.hpp"
#include "journal/event.hpp"
#include "link/fault_reason.hpp"

namespace cellctl::journal {
namespace {

struct Template {
  std::string where;  // file:line
  std::string text;   // the format string, literals joined
  std::vector<std::string> args;
};

// The longest rendering of each kind of argument.
constexpr std::size_t kEnumNameMax = 32;  // a state, rule, phase or strategy name (to_string)
constexpr std::size_t kNameMax = config::kAxisNameMax;

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// From just after an opening parenthesis: the top-level arguments up to its closing one.
std::vector<std::string> split_arguments(const std::string& s, std::size_t i) {
  std::vector<std::string> args(1);
  int depth = 0;
  for (; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '"' || c == '\'') {  // a literal, escapes and all
      const std::size_t start = i;
      for (++i; i < s.size() && s[i] != c; ++i)
        if (s[i] == '\\') ++i;
      args.back() += s.substr(start, i - start + 1);
      continue;
    }
    if (c == '(' || c == '[' || c == '{') ++depth;
    if (c == ')' || c == ']' || c == '}') {
      if (depth == 0) return args;
      --depth;
    }
    if (c == ',' && depth == 0) {
      args.emplace_back();
      continue;
    }
    args.back() += c;
  }
  return args;
}

// The string literals in an expression (adjacent literals are one string in C++), escapes undone.
std::vector<std::string> literals(const std::string& expr) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < expr.size(); ++i) {
    if (expr[i] == '\'') {  // a character literal: skip it whole
      for (++i; i < expr.size() && expr[i] != '\''; ++i)
        if (expr[i] == '\\') ++i;
      continue;
    }
    if (expr[i] != '"') continue;
    std::string v;
    for (++i; i < expr.size() && expr[i] != '"'; ++i) {
      if (expr[i] == '\\') ++i;
      if (i < expr.size()) v += expr[i];
    }
    out.push_back(v);
  }
  return out;
}

bool is_identifier_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

// Whether `expr` holds `word` as a whole identifier (or, for a word with punctuation, as written).
bool holds_word(const std::string& expr, std::string_view word) {
  for (auto at = expr.find(word); at != std::string::npos; at = expr.find(word, at + 1)) {
    const bool starts = at == 0 || !is_identifier_char(expr[at - 1]) || !is_identifier_char(word.front());
    const auto end = at + word.size();
    const bool ends =
        end == expr.size() || !is_identifier_char(expr[end]) || !is_identifier_char(word.back());
    if (starts && ends) return true;
  }
  return false;
}

bool is_literal(const std::string& expr) {
  const auto first = expr.find_first_not_of(" \n\t");
  return first != std::string::npos && expr[first] == '"';
}

std::vector<Template> templates_in_sources() {
  const std::filesystem::path root = CELLCTL_SOURCE_DIR;
  std::vector<Template> found;
  for (const char* dir : {"controller", "devices"})
    for (const auto& e : std::filesystem::recursive_directory_iterator(root / dir)) {
      const auto ext = e.path().extension();
      if (ext != ".cpp" && ext != ".hpp") continue;
      const std::string s = read(e.path());
      for (const std::string_view call : {"Text::format", "enter_fault", "assign_formatted"})
        for (auto at = s.find(call); at != std::string::npos; at = s.find(call, at + 1)) {
          if (at > 0 && is_identifier_char(s[at - 1])) continue;
          auto open = s.find_first_not_of(" \n", at + call.size());
          if (open == std::string::npos || s[open] != '(') continue;
          auto args = split_arguments(s, open + 1);
          if (call == "assign_formatted" && !args.empty()) args.erase(args.begin());  // the output
          if (args.empty() || !is_literal(args.front())) continue;  // a declaration or a forwarding call
          Template t;
          t.where = fmt::format("{}:{}", std::filesystem::relative(e.path(), root).string(),
                                std::count(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(at), '\n') + 1);
          for (const auto& l : literals(args.front())) t.text += l;
          t.args.assign(args.begin() + 1, args.end());
          found.push_back(std::move(t));
        }
    }
  return found;
}

// The specs of the template's replacement fields, in order ("" for {}).
std::vector<std::string> field_specs(const std::string& text) {
  std::vector<std::string> specs;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '{' && i + 1 < text.size() && text[i + 1] == '{') {
      ++i;
      continue;
    }
    if (text[i] != '{') continue;
    const auto close = text.find('}', i);
    const auto field = text.substr(i + 1, close - i - 1);
    const auto colon = field.find(':');
    specs.push_back(colon == std::string::npos ? "" : field.substr(colon + 1));
    i = close;
  }
  return specs;
}

// An argument that is itself a composed text (another message, a device's reason, who commanded).
bool quotes_a_text(const std::string& expr) {
  for (const std::string_view part : {"failure", "reason", "why", "source", "note", "first_cause", "problem",
                                      "home_record", "view()", "std::string"})
    if (expr.find(part) != std::string::npos) return true;
  return holds_word(expr, "what") || holds_word(expr, ".text");
}

// Pushes the argument's longest rendering; returns whether it quotes a text (then it counts nothing:
// the wrapping is measured, the quoted text is a message of its own).
bool push_longest(fmt::dynamic_format_arg_store<fmt::format_context>& store, const std::string& spec,
                  const std::string& expr) {
  const char type = spec.empty() ? '\0' : spec.back();
  if (type == 'f' || type == 'g' || type == 'e') {
    // Positions, speeds and frequencies: a billion in any unit is beyond every device's range.
    store.push_back(type == 'f' ? -999999999.999999 : -1.23456789e-100);
  } else if (type == 'x' || type == 'd') {
    store.push_back(std::numeric_limits<std::uint32_t>::max());  // a device's word or count
  } else if (is_literal(expr) || expr.find('?') != std::string::npos) {
    std::size_t longest = 0;  // a literal, or a choice between literals
    for (const auto& l : literals(expr)) longest = std::max(longest, l.size());
    store.push_back(std::string(longest == 0 ? 20 : longest, 'w'));
  } else if (quotes_a_text(expr)) {
    store.push_back(std::string());
    return true;
  } else if (expr.find("name") != std::string::npos) {
    store.push_back(std::string(std::max(kNameMax, kEnumNameMax), 'n'));
  } else if (expr.find("to_string") != std::string::npos) {
    store.push_back(std::string(kEnumNameMax, 'e'));
  } else {
    // A count, an index, an offset: the devices' words are 32 bits at most.
    store.push_back(std::numeric_limits<std::int32_t>::min());
  }
  return false;
}

TEST(MessageLength, TheTemplatesAreFoundInTheSources) {
  const auto all = templates_in_sources();
  EXPECT_GT(all.size(), 100u);
  const bool preset_refusal = std::any_of(all.begin(), all.end(), [](const Template& t) {
    return t.text.find("which records the offset in the config") != std::string::npos;
  });
  EXPECT_TRUE(preset_refusal) << "the encoder's preset-offset refusal (issue 22) was not found";
}

TEST(MessageLength, EveryTemplateFitsAtItsLongestArguments) {
  for (const auto& t : templates_in_sources()) {
    const auto specs = field_specs(t.text);
    ASSERT_LE(specs.size(), t.args.size()) << t.where << ": " << t.text;
    fmt::dynamic_format_arg_store<fmt::format_context> store;
    bool wraps = false;
    for (std::size_t i = 0; i < specs.size(); ++i) wraps = push_longest(store, specs[i], t.args[i]) || wraps;
    const std::string rendered = fmt::vformat(t.text, store);
    const std::size_t limit = wraps ? Text::kLongestWrapping : Text::kLongestMessage;
    if (std::getenv("CELLCTL_SHOW_MESSAGES"))
      std::printf("%4zu%s %s: %s\n", rendered.size(), wraps ? "+" : " ", t.where.c_str(), rendered.c_str());
    EXPECT_LE(rendered.size(), limit)
        << t.where << (wraps ? " (without the text it quotes): " : ": ") << rendered;
  }
}

TEST(MessageLength, ThreeLayersOfTheLongestFitEveryFixedBuffer) {
  const std::size_t longest = Text::kLongestMessage + 3 * Text::kLongestWrapping;
  EXPECT_LE(longest, Text{}.chars.size());
  EXPECT_LE(longest, link::kFaultReasonCapacity);
}

TEST(MessageLength, TheLongestTextIsKeptWhole) {
  const std::string whole(Text::kLongestMessage + 3 * Text::kLongestWrapping, 'a');
  EXPECT_EQ(Text::format("{}", whole).view(), whole);
  std::string reason;
  reason.reserve(link::kFaultReasonCapacity);
  link::assign_formatted(reason, "{}", whole);
  EXPECT_EQ(reason, whole);
}

}  // namespace
}  // namespace cellctl::journal
