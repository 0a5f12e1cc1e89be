// SPDX-License-Identifier: Apache-2.0
// The error bound on real animations, both profiles, whole sequences (test_sequences.h says
// where they are looked for).
#include <gtest/gtest.h>

#include "codec_test_support.h"
#include "test_sequences.h"

namespace animc {
namespace {

using testing_support::decodeAll;
using testing_support::realSequence;
using testing_support::tempPath;
using testing_support::worstRelativeError;

struct RealCase {
  const char* sequence;
  Profile profile;
  double max_error;
};

class RealDataRoundTrip : public ::testing::TestWithParam<RealCase> {};

TEST_P(RealDataRoundTrip, EveryDecodedVertexIsWithinMaxError) {
  ANIMC_REQUIRE_SEQUENCE(GetParam().sequence);
  MemorySequence seq = realSequence(GetParam().sequence, 0);
  ASSERT_FALSE(HasFailure());  // the whole sequence was read
  EncodeSettings settings;
  settings.octree().profile = GetParam().profile;
  settings.octree().max_error = GetParam().max_error;
  const std::string path = tempPath(std::string(GetParam().sequence) + ".ams");
  auto report = encodeSequence(seq, settings, path);
  ASSERT_TRUE(report.ok()) << report.status().message();
  const auto decoded = decodeAll(path);
  ASSERT_EQ(decoded.size(), seq.frames().size());
  EXPECT_LE(worstRelativeError(seq.frames(), decoded), GetParam().max_error);
  // Far smaller than the raw floats, or something is badly wrong.
  EXPECT_LT(report.value().bytes * 5, 12ull * report.value().vertices * report.value().frames);
  std::remove(path.c_str());
}

INSTANTIATE_TEST_SUITE_P(
    SharedData, RealDataRoundTrip,
    ::testing::Values(RealCase{"chickenCrossing", Profile::kPaper, 0.01},
                      RealCase{"chickenCrossing", Profile::kPredictive, 0.01},
                      RealCase{"oa_angelyss_lower", Profile::kPredictive, 0.05},
                      RealCase{"oa_gargoyle_upper", Profile::kPaper, 0.05},
                      RealCase{"sydney_md2", Profile::kPredictive, 0.002},
                      RealCase{"sydney_md2", Profile::kPaper, 0.1}),
    [](const ::testing::TestParamInfo<RealCase>& info) {
      return std::string(info.param.sequence) + "_" + profileName(info.param.profile) + "_" +
             std::to_string(int(info.param.max_error * 1000));
    });

}  // namespace
}  // namespace animc
