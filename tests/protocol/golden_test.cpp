// Golden bytes of every protocol message: the fixed samples of protocol_test_util.hpp encode to
// tests/protocol/golden/<name>.bin byte for byte, and those files decode to <name>.json (the JSON
// web/protocol/decode.js must produce too). Regenerate after a deliberate format change with
//   THRONG_UPDATE_GOLDEN=1 ctest -R ProtocolGolden   (and bump kProtocolVersion if incompatible)
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>

#include "protocol_test_util.hpp"

namespace throng::protocol {
namespace {

const std::string kDir = std::string(THRONG_SOURCE_DIR) + "/tests/protocol/golden/";

bool updating() {
  const char* u = std::getenv("THRONG_UPDATE_GOLDEN");
  return u && std::string(u) == "1";
}

std::vector<std::uint8_t> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::string& path, const std::vector<std::uint8_t>& b) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

/// Compares (or, when updating, writes) the .bin and the .json of one golden message.
void checkGolden(const std::string& name, const std::vector<std::uint8_t>& encoded, const nlohmann::json& decoded) {
  const std::string bin = kDir + name + ".bin", js = kDir + name + ".json";
  if (updating()) {
    writeBytes(bin, encoded);
    std::ofstream(js) << decoded.dump(2) << "\n";
    return;
  }
  EXPECT_EQ(readBytes(bin), encoded) << name << ".bin differs from the encoder's output; if intended, run "
                                     << "THRONG_UPDATE_GOLDEN=1 ctest -R ProtocolGolden";
  std::ifstream in(js);
  ASSERT_TRUE(in) << js;
  EXPECT_EQ(nlohmann::json::parse(in), decoded) << name;
}

TEST(ProtocolGolden, EveryMessage) {
  for (const auto& [name, message] : test::goldenMessages()) {
    SCOPED_TRACE(name);
    const std::vector<std::uint8_t> bytes = encode(message);
    auto decoded = decodeAny(updating() ? bytes : readBytes(kDir + name + ".bin"));
    ASSERT_TRUE(decoded) << core::formatAll(decoded.errors());
    checkGolden(name, bytes, test::messageJson(decoded.value()));
    // Round trip: decode → encode gives the same bytes.
    EXPECT_EQ(encode(decoded.value()), bytes);
  }
}

TEST(ProtocolGolden, CrowdFrames) {
  for (const bool compressed : {false, true}) {
    const std::string suffix = compressed ? "_zstd" : "";
    const auto [key, delta] = test::goldenCrowdFrames(compressed);
    CrowdDecoder decoder;
    auto k = decoder.decode(updating() ? key : readBytes(kDir + "crowd_key" + suffix + ".bin"));
    ASSERT_TRUE(k) << core::formatAll(k.errors());
    EXPECT_EQ(k.value().header.compressed, compressed);
    checkGolden("crowd_key" + suffix, key, test::crowdJson(k.value()));
    auto d = decoder.decode(updating() ? delta : readBytes(kDir + "crowd_delta" + suffix + ".bin"));
    ASSERT_TRUE(d) << core::formatAll(d.errors());
    nlohmann::json dj = test::crowdJson(d.value());
    dj["base"] = "crowd_key" + suffix;  // the JavaScript test decodes the base first
    checkGolden("crowd_delta" + suffix, delta, dj);
    EXPECT_EQ(d.value().header.baseFrame, 1u);
    EXPECT_EQ(d.value().view, quantized(test::goldenCrowd(1), 4));
  }
}

}  // namespace
}  // namespace throng::protocol
