// SPDX-License-Identifier: Apache-2.0
// The codec table (codecs/codec_registry.h): each entry is found by its id, its name and its
// options, and its parameters survive being written and read back.
#include <gtest/gtest.h>

#include "codecs/codec_registry.h"

namespace animc {
namespace {

// A command line without options: every codec's defaults.
class NoOptions : public OptionValues {
 public:
  bool has(const std::string&) const override { return false; }
  std::string get(const std::string&, const std::string& fallback) const override { return fallback; }
};

TEST(CodecRegistry, EveryEntryIsFoundAndRoundTripsItsParameters) {
  ASSERT_EQ(allCodecs().size(), std::variant_size_v<CodecOptions>);
  for (const CodecEntry* codec : allCodecs()) {
    SCOPED_TRACE(codec->name);
    EXPECT_EQ(findCodec(uint8_t(codec->id)), codec);
    ASSERT_TRUE(findCodecByName(codec->name).ok());
    EXPECT_EQ(findCodecByName(codec->name).value(), codec);
    auto options = codec->fromFlags(NoOptions());
    ASSERT_TRUE(options.ok()) << options.status().message();
    EXPECT_EQ(&codecOf(options.value()), codec) << "the options type is not the codec's";
    EXPECT_TRUE(codec->validate(options.value()).ok());
    ByteWriter written;
    codec->write(options.value(), written);
    ByteReader reader(written.bytes().data(), written.size());
    auto read = codec->read(reader);
    ASSERT_TRUE(read.ok()) << read.status().message();
    ByteWriter again;
    codec->write(read.value(), again);
    EXPECT_EQ(again.bytes(), written.bytes());
    EXPECT_FALSE(codec->describe(options.value()).empty());
    EXPECT_FALSE(codec->settings(options.value()).empty());
  }
  EXPECT_EQ(findCodec(0), nullptr);
  EXPECT_EQ(findCodec(uint8_t(allCodecs().size() + 1)), nullptr);
  EXPECT_NE(findCodecByName("mpeg").status().message().find("affine-octree"), std::string::npos);
}

}  // namespace
}  // namespace animc
