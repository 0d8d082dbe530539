// The Matroska stream the video recorder pipes to ffmpeg: the header's EBML magic and track, and
// each frame's prefix sizing its Cluster and SimpleBlock to the pixels that follow. (Whether
// ffmpeg reads it, timestamps and all, is video_recorder_test's part.)

#include "image_generator/node/matroska_stream.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace vcockpit {
namespace {

using image_generator::kMatroskaFramePrefixBytes;
using image_generator::matroska_frame_prefix;
using image_generator::matroska_stream_header;

uint64_t read_size8(const uint8_t* at) {
  EXPECT_EQ(at[0], 0x01) << "8-byte EBML size";
  uint64_t value = 0;
  for (int i = 1; i < 8; ++i)
    value = (value << 8) | at[i];
  return value;
}

bool contains(const std::vector<uint8_t>& bytes, const std::string& text) {
  return std::search(bytes.begin(), bytes.end(), text.begin(), text.end()) != bytes.end();
}

TEST(MatroskaStream, HeaderIsEbmlWithOneRawRgbTrack) {
  const std::vector<uint8_t> header = matroska_stream_header(640, 360);
  ASSERT_GE(header.size(), 12u);
  EXPECT_EQ(header[0], 0x1A);
  EXPECT_EQ(header[1], 0x45);
  EXPECT_EQ(header[2], 0xDF);
  EXPECT_EQ(header[3], 0xA3);
  const std::size_t segment = 12 + read_size8(&header[4]);  // right after the EBML element
  ASSERT_LT(segment + 12, header.size());
  EXPECT_EQ(header[segment], 0x18);
  EXPECT_EQ(header[segment + 3], 0x67) << "the Segment follows the EBML header";
  EXPECT_EQ(header[segment + 4], 0x01);
  EXPECT_EQ(header[segment + 5], 0xFF) << "of unknown size: a stream";
  EXPECT_TRUE(contains(header, "matroska"));
  EXPECT_TRUE(contains(header, "V_UNCOMPRESSED"));
  EXPECT_TRUE(contains(header, std::string("RGB\x18", 4))) << "ffmpeg's RGB24 FourCC";
  EXPECT_THROW(matroska_stream_header(0, 360), std::invalid_argument);
}

TEST(MatroskaStream, FramePrefixSizesTheClusterAndBlockToThePixels) {
  const std::size_t pixels = 640 * 360 * 3;
  const int64_t timestamp_us = 3'600'000'000;  // an hour in: past 32 bits
  const auto prefix = matroska_frame_prefix(timestamp_us, pixels);
  ASSERT_EQ(prefix.size(), kMatroskaFramePrefixBytes);
  EXPECT_EQ(prefix[0], 0x1F);  // Cluster
  EXPECT_EQ(prefix[3], 0x75);
  EXPECT_EQ(read_size8(&prefix[4]), kMatroskaFramePrefixBytes - 12 + pixels)
      << "the cluster ends where the pixels do";
  EXPECT_EQ(prefix[12], 0xE7);  // its Timestamp, 8 bytes
  EXPECT_EQ(read_size8(&prefix[13]), 8u);
  uint64_t timestamp = 0;
  for (int i = 21; i < 29; ++i)
    timestamp = (timestamp << 8) | prefix[i];
  EXPECT_EQ(timestamp, uint64_t(timestamp_us));
  EXPECT_EQ(prefix[29], 0xA3);  // SimpleBlock
  EXPECT_EQ(read_size8(&prefix[30]), 4 + pixels);
  EXPECT_EQ(prefix[38], 0x81) << "track 1";
  EXPECT_EQ(prefix[41], 0x80) << "a keyframe";
  EXPECT_THROW(matroska_frame_prefix(-1, pixels), std::invalid_argument);
}

}  // namespace
}  // namespace vcockpit
