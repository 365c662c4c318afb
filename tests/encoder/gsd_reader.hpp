#pragma once
// A small reader for PROFIBUS DP GSD files — the part a DP master needs to parameterise and configure
// a modular slave: the ident number, the slave-global User_Prm_Data, the ExtUserPrmData definitions
// (Bit, BitArea, Unsigned8/16/32 and Signed8/16/32 with default and range), and per module its
// configuration bytes, Ext_Module_Prm_Data_Len, Ext_User_Prm_Data_Const and Ext_User_Prm_Data_Ref.
// It builds Set_Prm's User_Prm_Data as a master does: the global part (User_Prm_Data_Len octets,
// constants merged) followed by the chosen module's part (Ext_Module_Prm_Data_Len octets, constants
// merged, every referenced parameter written at its offset), never more than Max_User_Prm_Data_Len.
// Keywords are case-insensitive, ';' starts a comment, '\' continues a line. Whatever the reader does
// not understand in these keywords is an error naming the line: a test must not pass on a misread file.

#include <cstddef>
#include <cstdint>
#include <istream>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace cellctl::encoder::testing {

struct GsdPrmDef {
  enum class Type : std::uint8_t {
    bit,
    bit_area,
    unsigned8,
    unsigned16,
    unsigned32,
    signed8,
    signed16,
    signed32
  };
  int id = 0;
  std::string name;
  Type type = Type::unsigned8;
  unsigned first_bit = 0;  // bit / bit_area
  unsigned last_bit = 0;
  long long default_value = 0;
  long long min = 0;
  long long max = 0;
};

struct GsdConst {
  std::size_t offset = 0;
  std::vector<std::uint8_t> bytes;
};

struct GsdRef {
  std::size_t offset = 0;
  int id = 0;
};

struct GsdModule {
  std::string name;
  std::vector<std::uint8_t> cfg;
  std::size_t prm_length = 0;  // Ext_Module_Prm_Data_Len
  std::vector<GsdConst> consts;
  std::vector<GsdRef> refs;
};

struct Gsd {
  std::uint16_t ident = 0;
  std::size_t user_prm_length = 0;     // User_Prm_Data_Len (0 when absent)
  std::vector<std::uint8_t> user_prm;  // User_Prm_Data
  std::size_t max_user_prm_length = 0;
  std::vector<GsdConst> consts;  // global Ext_User_Prm_Data_Const
  std::vector<GsdRef> refs;      // global Ext_User_Prm_Data_Ref
  std::map<int, GsdPrmDef> prm_defs;
  std::vector<GsdModule> modules;

  [[nodiscard]] const GsdModule& module(std::string_view name) const;  // throws when absent
};

// Throws std::runtime_error "line N: …" for what it cannot read.
[[nodiscard]] Gsd read_gsd(std::istream& in);
[[nodiscard]] Gsd read_gsd_file(const std::string& path);

// Set_Prm octet 8 onwards for `module`, each referenced parameter at its default unless `values`
// (ExtUserPrmData id → value) says otherwise. Throws for a value outside the parameter's range, a
// reference outside the data, or more than Max_User_Prm_Data_Len octets.
[[nodiscard]] std::vector<std::uint8_t> user_prm_for(const Gsd& gsd, const GsdModule& module,
                                                     const std::map<int, long long>& values = {});

// Input and output octets the configuration identifiers describe (general and special formats).
struct IoLengths {
  std::size_t input = 0;
  std::size_t output = 0;
};
[[nodiscard]] IoLengths io_lengths(std::span<const std::uint8_t> cfg);

}  // namespace cellctl::encoder::testing
