// Writes the seed corpora of the binary targets from the codecs' own encoders, so that every seed
// is a well-formed telegram (the fuzzer mutates from there). Run once after a format change:
//   build/asan/fuzz/fuzz_make_seeds fuzz/corpus
// The YAML targets' seeds are the shipped config and recipes, copied by hand (fuzz/README.md).

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "encoder/cyclic.hpp"
#include "encoder/diagnosis.hpp"
#include "encoder/parameters.hpp"
#include "profibus/dp_diag.hpp"
#include "profibus/dp_services.hpp"
#include "profibus/fdl_frame.hpp"
#include "scu/codec.hpp"
#include "spindle/codec.hpp"

namespace {

using namespace cellctl;
using Bytes = std::vector<std::uint8_t>;

std::filesystem::path g_root;

void write(const std::string& target, const std::string& name, const Bytes& bytes) {
  const auto dir = g_root / target;
  std::filesystem::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

Bytes join(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

void scu_seeds() {
  const std::array<std::uint8_t, 4> value{0x30, 0x39, 0x30, 0x00};
  const std::vector<scu::Request> requests = {scu::OpenRequest{0},
                                              scu::AbortRequest{},
                                              scu::CyclicRequest{},
                                              scu::GetRequest{0x2000},
                                              scu::TransferRequest{0x2100, value},
                                              scu::ExecuteRequest{0, 1, 0},
                                              scu::StopRequest{0, 1},
                                              scu::ExecuteRequest{19, 0xFF, 0xFF}};
  Bytes all;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    scu::RequestBytes out;
    if (!scu::encode_request(requests[i], out)) continue;
    const Bytes telegram(out.view().begin(), out.view().end());
    // Piece size (1: byte by byte), gap between pieces (0), then the telegram.
    write("scu_request_stream", "request-" + std::to_string(i), join({{0x00, 0x00}, telegram}));
    all.insert(all.end(), telegram.begin(), telegram.end());

    const auto shape = scu::reply_shape(requests[i]);
    scu::Reply reply;
    reply.command = shape.command;
    reply.has_data = shape.has_data;
    const std::array<std::uint8_t, 4> data{0xb0, 0x01, 0x00, 0x00};
    if (shape.has_data) reply.data = data;
    scu::ReplyBytes reply_out;
    if (!scu::encode_reply(reply, reply_out)) continue;
    // The target's first byte: the command's index in its kCommands order, bit 7 = has data.
    const std::string order = "GTCESOA";
    const auto index = order.find(static_cast<char>(shape.command));
    const auto shape_byte = static_cast<std::uint8_t>(index | (shape.has_data ? 0x80u : 0u));
    write("scu_reply_stream", "reply-" + std::to_string(i),
          join({{shape_byte, static_cast<std::uint8_t>(i)},
                Bytes(reply_out.view().begin(), reply_out.view().end())}));
  }
  write("scu_request_stream", "several", join({{0x3f, 0x01}, all}));
}

void spindle_seeds() {
  const std::vector<spindle::Message> messages = {spindle::SetBasic{400, spindle::SpeedUnit::hz},
                                                  spindle::SetStart{},
                                                  spindle::Command{spindle::MsgId::cmd_start},
                                                  spindle::Request{spindle::MsgId::res_status},
                                                  spindle::Ack{spindle::MsgId::set_basic},
                                                  spindle::StatusValues{},
                                                  spindle::Identification{},
                                                  spindle::StatusOut{}};
  Bytes all;
  for (std::size_t i = 0; i < messages.size(); ++i) {
    std::array<std::uint8_t, spindle::kMaxFrameLength> frame{};
    const std::size_t n = spindle::Codec::encode(messages[i], frame);
    const Bytes bytes(frame.begin(), frame.begin() + static_cast<std::ptrdiff_t>(n));
    write("spindle_frames", "message-" + std::to_string(i), bytes);
    all.insert(all.end(), bytes.begin(), bytes.end());
  }
  write("spindle_frames", "several", all);
}

void fdl_seeds() {
  std::array<std::uint8_t, 8> eight{1, 2, 3, 4, 5, 6, 7, 8};
  std::array<std::uint8_t, 244> full{};
  const std::vector<profibus::FdlFrame> frames = {profibus::make_frame(5, 2, 0x49),
                                                  profibus::make_sap_frame(5, 2, 0x6d, 60, 62),
                                                  profibus::make_frame(2, 5, 0x08, std::span(eight).first(6)),
                                                  profibus::make_frame(2, 5, 0x08, eight),
                                                  profibus::make_sap_frame(2, 5, 0x08, 62, 60, full),
                                                  profibus::make_short_ack()};
  Bytes all;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    std::array<std::uint8_t, profibus::kMaxFrameSize> out{};
    const std::size_t n = profibus::encode(frames[i], out);
    const Bytes bytes(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n));
    write("fdl_frames", "frame-" + std::to_string(i), join({{static_cast<std::uint8_t>(i * 40)}, bytes}));
    all.insert(all.end(), bytes.begin(), bytes.end());
  }
  write("fdl_frames", "several", join({{0x10}, all}));
}

void encoder_seeds() {
  for (std::uint8_t f = 0; f < 5; ++f) {
    encoder::CyclicInput in;
    in.word = 0x0600'1234u;
    in.velocity = -120;
    in.acceleration = 3;
    std::array<std::uint8_t, 8> out{};
    const auto fn = static_cast<encoder::Functionality>(f);
    const std::size_t n = encoder::encode_input(fn, in, out);
    write("encoder_cyclic", "input-" + std::to_string(f),
          join({{static_cast<std::uint8_t>(f | 0x80)},
                Bytes(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n))}));

    encoder::EncoderParameters p;
    p.functionality = fn;
    std::array<std::uint8_t, 32> prm{};
    const std::size_t m = encoder::encode_user_prm(p, prm);
    profibus::PrmStandard standard;
    standard.ident = encoder::kIdentNumber;
    std::array<std::uint8_t, profibus::kPrmStandardSize> head{};
    (void)profibus::encode(standard, head);
    write("dp_parameters", "prm-" + std::to_string(f),
          join({{f, 0xd3, 0, 0, 0, 0, 0, 0, 0x12, 0x34},
                Bytes(head.begin(), head.end()),
                Bytes(prm.begin(), prm.begin() + static_cast<std::ptrdiff_t>(m))}));
  }
  for (const bool detailed : {false, true}) {
    encoder::EncoderDiagnosis d;
    d.singleturn_resolution = 8192;
    d.revolutions = 4096;
    if (detailed) d.detail = encoder::DiagnosisDetail{};
    std::array<std::uint8_t, encoder::kExtDiagLong> ext{};
    const std::size_t n = encoder::encode_diagnosis(d, ext);
    write("dp_diagnosis", detailed ? "extended-long" : "extended-short",
          Bytes(ext.begin(), ext.begin() + static_cast<std::ptrdiff_t>(n)));
    profibus::StandardDiag standard;
    standard.ext_diag = true;
    standard.ident = encoder::kIdentNumber;
    std::array<std::uint8_t, profibus::kStandardDiagSize> head{};
    (void)profibus::encode(standard, head);
    write("dp_diagnosis", detailed ? "slave-diag-long" : "slave-diag-short",
          join({Bytes(head.begin(), head.end()),
                Bytes(ext.begin(), ext.begin() + static_cast<std::ptrdiff_t>(n))}));
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_make_seeds <corpus directory>\n");
    return 2;
  }
  g_root = argv[1];
  scu_seeds();
  spindle_seeds();
  fdl_seeds();
  encoder_seeds();
  return 0;
}
