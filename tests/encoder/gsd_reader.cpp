#include "gsd_reader.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace cellctl::encoder::testing {
namespace {

[[noreturn]] void fail(std::size_t line, const std::string& what) {
  throw std::runtime_error("GSD line " + std::to_string(line) + ": " + what);
}

std::string trim(std::string s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

std::string lower(std::string s) {
  std::ranges::transform(s, s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

long long number(const std::string& text, std::size_t line) {
  const std::string t = trim(text);
  try {
    std::size_t used = 0;
    const long long v = std::stoll(t, &used, 0);  // 0x.. hexadecimal or decimal
    if (used != t.size()) fail(line, "not a number: '" + t + "'");
    return v;
  } catch (const std::logic_error&) {
    fail(line, "not a number: '" + t + "'");
  }
}

std::vector<std::uint8_t> byte_list(const std::string& text, std::size_t line) {
  std::vector<std::uint8_t> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const auto comma = std::min(text.find(',', start), text.size());
    const long long v = number(text.substr(start, comma - start), line);
    if (v < 0 || v > 255) fail(line, "byte out of range: " + std::to_string(v));
    out.push_back(static_cast<std::uint8_t>(v));
    start = comma + 1;
  }
  return out;
}

// "Key(offset) = value" → offset; nullopt without "(…)".
std::optional<std::size_t> offset_of(const std::string& key, std::size_t line) {
  const auto open = key.find('(');
  if (open == std::string::npos) return std::nullopt;
  const auto close = key.find(')', open);
  if (close == std::string::npos) fail(line, "missing ')'");
  const long long v = number(key.substr(open + 1, close - open - 1), line);
  if (v < 0) fail(line, "negative offset");
  return static_cast<std::size_t>(v);
}

std::string base_key(const std::string& key) {
  return lower(trim(key.substr(0, key.find('('))));
}

// Splits "\"name\" rest" into name and rest; false without a quoted name.
bool quoted(const std::string& text, std::string& name, std::string& rest) {
  if (text.empty() || text[0] != '"') return false;
  const auto close = text.find('"', 1);
  if (close == std::string::npos) return false;
  name = text.substr(1, close - 1);
  rest = trim(text.substr(close + 1));
  return true;
}

// `Type[(bit[-bit])] default min-max` (or a comma list of allowed values) of an ExtUserPrmData block.
void read_prm_type(GsdPrmDef& def, const std::string& text, std::size_t line) {
  std::istringstream words(text);
  std::string type_word, default_word, range;
  words >> type_word >> default_word;
  std::getline(words, range);
  range = trim(range);
  if (type_word.empty() || default_word.empty() || range.empty())
    fail(line, "unreadable parameter type: '" + text + "'");
  const auto paren = type_word.find('(');
  const std::string type = lower(type_word.substr(0, paren));
  static const std::map<std::string, GsdPrmDef::Type> types{{"bit", GsdPrmDef::Type::bit},
                                                            {"bitarea", GsdPrmDef::Type::bit_area},
                                                            {"unsigned8", GsdPrmDef::Type::unsigned8},
                                                            {"unsigned16", GsdPrmDef::Type::unsigned16},
                                                            {"unsigned32", GsdPrmDef::Type::unsigned32},
                                                            {"signed8", GsdPrmDef::Type::signed8},
                                                            {"signed16", GsdPrmDef::Type::signed16},
                                                            {"signed32", GsdPrmDef::Type::signed32}};
  const auto t = types.find(type);
  if (t == types.end()) fail(line, "unknown parameter type '" + type_word + "'");
  def.type = t->second;
  if (def.type == GsdPrmDef::Type::bit || def.type == GsdPrmDef::Type::bit_area) {
    const auto close = type_word.find(')');
    if (paren == std::string::npos || close == std::string::npos)
      fail(line, type_word + " needs its bit number(s)");
    const std::string bits = type_word.substr(paren + 1, close - paren - 1);
    const auto dash = bits.find('-');
    def.first_bit = static_cast<unsigned>(number(bits.substr(0, dash), line));
    def.last_bit = dash == std::string::npos ? def.first_bit
                                             : static_cast<unsigned>(number(bits.substr(dash + 1), line));
    if (def.last_bit < def.first_bit || def.last_bit > 7) fail(line, "bit numbers outside 0..7");
  }
  def.default_value = number(default_word, line);
  const auto dash = range.find('-', 1);
  if (dash != std::string::npos && range.find(',') == std::string::npos) {
    def.min = number(range.substr(0, dash), line);
    def.max = number(range.substr(dash + 1), line);
  } else {
    const auto allowed = byte_list(range, line);
    def.min = *std::ranges::min_element(allowed);
    def.max = *std::ranges::max_element(allowed);
  }
  if (def.default_value < def.min || def.default_value > def.max)
    fail(line, "default " + std::to_string(def.default_value) + " outside its range");
}

std::size_t width(GsdPrmDef::Type t) {
  switch (t) {
    case GsdPrmDef::Type::unsigned16:
    case GsdPrmDef::Type::signed16:
      return 2;
    case GsdPrmDef::Type::unsigned32:
    case GsdPrmDef::Type::signed32:
      return 4;
    default:
      return 1;
  }
}

void merge(std::vector<std::uint8_t>& data, const GsdConst& c, const std::string& where) {
  if (c.offset + c.bytes.size() > data.size())
    throw std::runtime_error(where + ": Ext_User_Prm_Data_Const(" + std::to_string(c.offset) +
                             ") reaches beyond the " + std::to_string(data.size()) + " octets declared");
  std::ranges::copy(c.bytes, data.begin() + static_cast<std::ptrdiff_t>(c.offset));
}

void write(std::vector<std::uint8_t>& data, const GsdRef& ref, const GsdPrmDef& def, long long value,
           const std::string& where) {
  if (value < def.min || value > def.max)
    throw std::runtime_error(where + ": '" + def.name + "' = " + std::to_string(value) + " outside " +
                             std::to_string(def.min) + "-" + std::to_string(def.max));
  if (ref.offset + width(def.type) > data.size())
    throw std::runtime_error(where + ": '" + def.name + "' at offset " + std::to_string(ref.offset) +
                             " reaches beyond the data");
  auto& octet = data[ref.offset];
  if (def.type == GsdPrmDef::Type::bit || def.type == GsdPrmDef::Type::bit_area) {
    const unsigned bits = def.last_bit - def.first_bit + 1;
    const auto mask = static_cast<std::uint8_t>(((1u << bits) - 1u) << def.first_bit);
    octet =
        static_cast<std::uint8_t>((octet & ~mask) | ((static_cast<unsigned>(value) << def.first_bit) & mask));
    return;
  }
  const auto u = static_cast<unsigned long long>(value);
  const std::size_t n = width(def.type);
  for (std::size_t i = 0; i < n; ++i)  // big-endian, as PROFIBUS sends multi-octet values
    data[ref.offset + i] = static_cast<std::uint8_t>(u >> (8 * (n - 1 - i)));
}

}  // namespace

const GsdModule& Gsd::module(std::string_view name) const {
  const auto it = std::ranges::find(modules, name, &GsdModule::name);
  if (it == modules.end()) throw std::runtime_error("GSD: no module \"" + std::string(name) + "\"");
  return *it;
}

Gsd read_gsd(std::istream& in) {
  Gsd gsd;
  enum class Block { global, prm_text, ext_user_prm, module } block = Block::global;
  GsdPrmDef* def = nullptr;
  bool def_typed = false;
  bool module_reference_due = false;
  std::string raw;
  std::size_t line_no = 0;
  std::string text;
  while (std::getline(in, raw)) {
    ++line_no;
    raw = trim(raw.substr(0, raw.find(';')));
    if (!raw.empty() && raw.back() == '\\') {  // continued on the next line
      text += raw.substr(0, raw.size() - 1);
      continue;
    }
    text += raw;
    const std::string line = trim(text);
    text.clear();
    if (line.empty()) continue;
    const auto eq = line.find('=');
    const std::string key = eq == std::string::npos ? lower(line) : base_key(line.substr(0, eq));
    const std::string value = eq == std::string::npos ? std::string{} : trim(line.substr(eq + 1));

    switch (block) {
      case Block::prm_text:
        if (key == "endprmtext") block = Block::global;
        continue;
      case Block::ext_user_prm:
        if (key == "endextuserprmdata") {
          if (!def_typed) fail(line_no, "ExtUserPrmData without its type line");
          block = Block::global;
        } else if (key == "prm_text_ref" || key == "changeable" || key == "visible") {
        } else if (!def_typed) {
          read_prm_type(*def, line, line_no);
          def_typed = true;
        } else {
          fail(line_no, "unexpected in ExtUserPrmData: '" + line + "'");
        }
        continue;
      case Block::module:
        if (module_reference_due && eq == std::string::npos && key != "endmodule") {
          (void)number(line, line_no);  // the module's reference number (GSD revision 3)
          module_reference_due = false;
          continue;
        }
        module_reference_due = false;
        if (key == "endmodule") {
          block = Block::global;
        } else if (key == "ext_module_prm_data_len") {
          gsd.modules.back().prm_length = static_cast<std::size_t>(number(value, line_no));
        } else if (key == "ext_user_prm_data_const") {
          const auto off = offset_of(line.substr(0, eq), line_no);
          if (!off) fail(line_no, "Ext_User_Prm_Data_Const needs its offset");
          gsd.modules.back().consts.push_back({*off, byte_list(value, line_no)});
        } else if (key == "ext_user_prm_data_ref") {
          const auto off = offset_of(line.substr(0, eq), line_no);
          if (!off) fail(line_no, "Ext_User_Prm_Data_Ref needs its offset");
          gsd.modules.back().refs.push_back({*off, static_cast<int>(number(value, line_no))});
        } else {
          fail(line_no, "unexpected in a module: '" + line + "'");
        }
        continue;
      case Block::global:
        break;
    }

    if (key == "prmtext") {
      block = Block::prm_text;
    } else if (key == "extuserprmdata") {
      const auto space = value.find_first_of(" \t");
      std::string name, rest;
      if (space == std::string::npos || !quoted(trim(value.substr(space)), name, rest) || !rest.empty())
        fail(line_no, "ExtUserPrmData needs: id \"name\"");
      const int id = static_cast<int>(number(value.substr(0, space), line_no));
      if (gsd.prm_defs.contains(id)) fail(line_no, "ExtUserPrmData " + std::to_string(id) + " defined twice");
      def = &gsd.prm_defs[id];
      def->id = id;
      def->name = name;
      def_typed = false;
      block = Block::ext_user_prm;
    } else if (key == "module") {
      std::string name, cfg;
      if (!quoted(value, name, cfg)) fail(line_no, "Module needs: \"name\" configuration bytes");
      gsd.modules.push_back(GsdModule{name, byte_list(cfg, line_no), 0, {}, {}});
      block = Block::module;
      module_reference_due = true;
    } else if (key == "ident_number") {
      gsd.ident = static_cast<std::uint16_t>(number(value, line_no));
    } else if (key == "user_prm_data_len") {
      gsd.user_prm_length = static_cast<std::size_t>(number(value, line_no));
    } else if (key == "user_prm_data") {
      gsd.user_prm = byte_list(value, line_no);
    } else if (key == "max_user_prm_data_len") {
      gsd.max_user_prm_length = static_cast<std::size_t>(number(value, line_no));
    } else if (key == "ext_user_prm_data_const") {
      const auto off = offset_of(line.substr(0, eq), line_no);
      if (!off) fail(line_no, "Ext_User_Prm_Data_Const needs its offset");
      gsd.consts.push_back({*off, byte_list(value, line_no)});
    } else if (key == "ext_user_prm_data_ref") {
      const auto off = offset_of(line.substr(0, eq), line_no);
      if (!off) fail(line_no, "Ext_User_Prm_Data_Ref needs its offset");
      gsd.refs.push_back({*off, static_cast<int>(number(value, line_no))});
    }
    // Other global keywords (baud rates, timing, texts) do not shape Set_Prm or Chk_Cfg.
  }
  if (block != Block::global) fail(line_no, "file ends inside a block");
  return gsd;
}

Gsd read_gsd_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("GSD: cannot open " + path);
  return read_gsd(in);
}

std::vector<std::uint8_t> user_prm_for(const Gsd& gsd, const GsdModule& module,
                                       const std::map<int, long long>& values) {
  const auto fill = [&](std::size_t length, const std::vector<std::uint8_t>& initial,
                        const std::vector<GsdConst>& consts, const std::vector<GsdRef>& refs,
                        const std::string& where) {
    std::vector<std::uint8_t> data(length, 0);
    std::copy_n(initial.begin(), std::min(initial.size(), length), data.begin());
    for (const auto& c : consts) merge(data, c, where);
    for (const auto& r : refs) {
      const auto d = gsd.prm_defs.find(r.id);
      if (d == gsd.prm_defs.end())
        throw std::runtime_error(where + ": Ext_User_Prm_Data_Ref to undefined " + std::to_string(r.id));
      const auto v = values.find(r.id);
      write(data, r, d->second, v == values.end() ? d->second.default_value : v->second, where);
    }
    return data;
  };
  std::vector<std::uint8_t> prm = fill(gsd.user_prm_length, gsd.user_prm, gsd.consts, gsd.refs, "global");
  const auto part = fill(module.prm_length, {}, module.consts, module.refs, "module \"" + module.name + "\"");
  prm.insert(prm.end(), part.begin(), part.end());
  if (gsd.max_user_prm_length > 0 && prm.size() > gsd.max_user_prm_length)
    throw std::runtime_error("module \"" + module.name + "\": " + std::to_string(prm.size()) +
                             " octets of User_Prm_Data, Max_User_Prm_Data_Len " +
                             std::to_string(gsd.max_user_prm_length));
  return prm;
}

IoLengths io_lengths(std::span<const std::uint8_t> cfg) {
  IoLengths io;
  // One length octet: bit 6 words (else bytes), bits 0..5 (special) or 0..3 (general) count − 1.
  const auto octets = [](std::uint8_t length_byte, unsigned count_mask) {
    const std::size_t n = (length_byte & count_mask) + 1u;
    return (length_byte & 0x40u) != 0 ? 2 * n : n;
  };
  for (std::size_t i = 0; i < cfg.size(); ++i) {
    const std::uint8_t id = cfg[i];
    const unsigned direction = (id >> 4) & 0x03u;
    if (direction != 0) {  // general format: 01 input, 10 output, 11 both
      if ((direction & 1u) != 0) io.input += octets(id, 0x0Fu);
      if ((direction & 2u) != 0) io.output += octets(id, 0x0Fu);
      continue;
    }
    // Special format: bits 6..7 say which length octets follow, bits 0..3 the manufacturer octets.
    const unsigned lengths = (id >> 6) & 0x03u;
    const std::size_t manufacturer = id & 0x0Fu;
    if ((lengths & 2u) != 0) {
      if (++i >= cfg.size()) throw std::runtime_error("configuration ends before its output length octet");
      io.output += octets(cfg[i], 0x3Fu);
    }
    if ((lengths & 1u) != 0) {
      if (++i >= cfg.size()) throw std::runtime_error("configuration ends before its input length octet");
      io.input += octets(cfg[i], 0x3Fu);
    }
    if (i + manufacturer >= cfg.size())
      throw std::runtime_error("configuration ends inside its manufacturer octets");
    i += manufacturer;
  }
  return io;
}

}  // namespace cellctl::encoder::testing
