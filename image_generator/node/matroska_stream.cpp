#include "image_generator/node/matroska_stream.hpp"

#include <stdexcept>
#include <string>

namespace vcockpit::image_generator {
namespace {

// Element IDs (they carry their own length marker bits)
constexpr uint32_t kEbml = 0x1A45DFA3;
constexpr uint32_t kEbmlVersion = 0x4286;
constexpr uint32_t kEbmlReadVersion = 0x42F7;
constexpr uint32_t kEbmlMaxIdLength = 0x42F2;
constexpr uint32_t kEbmlMaxSizeLength = 0x42F3;
constexpr uint32_t kDocType = 0x4282;
constexpr uint32_t kDocTypeVersion = 0x4287;
constexpr uint32_t kDocTypeReadVersion = 0x4285;
constexpr uint32_t kSegment = 0x18538067;
constexpr uint32_t kInfo = 0x1549A966;
constexpr uint32_t kTimestampScale = 0x2AD7B1;
constexpr uint32_t kMuxingApp = 0x4D80;
constexpr uint32_t kWritingApp = 0x5741;
constexpr uint32_t kTracks = 0x1654AE6B;
constexpr uint32_t kTrackEntry = 0xAE;
constexpr uint32_t kTrackNumber = 0xD7;
constexpr uint32_t kTrackUid = 0x73C5;
constexpr uint32_t kTrackType = 0x83;
constexpr uint32_t kCodecId = 0x86;
constexpr uint32_t kFlagLacing = 0x9C;
constexpr uint32_t kVideo = 0xE0;
constexpr uint32_t kPixelWidth = 0xB0;
constexpr uint32_t kPixelHeight = 0xBA;
constexpr uint32_t kColourSpace = 0x2EB524;
constexpr uint32_t kCluster = 0x1F43B675;
constexpr uint32_t kClusterTimestamp = 0xE7;
constexpr uint32_t kSimpleBlock = 0xA3;

constexpr uint64_t kNanosecondsPerTick = 1000;  // timestamps in microseconds
constexpr uint8_t kVideoTrackType = 1;
constexpr uint8_t kTrackNumberVint = 0x81;  // track 1 as a 1-byte EBML integer
constexpr uint8_t kKeyframeFlag = 0x80;
constexpr std::size_t kSizeBytes = 8;
constexpr std::size_t kBlockHeaderBytes = 4;  // track number, int16 relative timestamp, flags

using Bytes = std::vector<uint8_t>;

void put_id(Bytes& out, uint32_t id) {
  int bytes = 4;
  while (bytes > 1 && (id >> (8 * (bytes - 1))) == 0)
    --bytes;
  for (int i = bytes - 1; i >= 0; --i)
    out.push_back(static_cast<uint8_t>(id >> (8 * i)));
}

// 8-byte EBML size: a 0x01 marker byte, then 56 bits of value
template <typename Out>
void put_size(Out out, uint64_t size) {
  out[0] = 0x01;
  for (std::size_t i = 1; i < kSizeBytes; ++i)
    out[i] = static_cast<uint8_t>(size >> (8 * (kSizeBytes - 1 - i)));
}

void put_element(Bytes& out, uint32_t id, const Bytes& payload) {
  put_id(out, id);
  const std::size_t at = out.size();
  out.resize(at + kSizeBytes);
  put_size(out.begin() + static_cast<std::ptrdiff_t>(at), payload.size());
  out.insert(out.end(), payload.begin(), payload.end());
}

void put_uint(Bytes& out, uint32_t id, uint64_t value) {
  Bytes payload;
  for (int i = 7; i >= 0; --i)
    payload.push_back(static_cast<uint8_t>(value >> (8 * i)));
  put_element(out, id, payload);
}

void put_string(Bytes& out, uint32_t id, const std::string& text) {
  put_element(out, id, Bytes(text.begin(), text.end()));
}

}  // namespace

std::vector<uint8_t> matroska_stream_header(int width_px, int height_px) {
  if (width_px <= 0 || height_px <= 0) throw std::invalid_argument("matroska: empty frame size");
  Bytes out;
  Bytes ebml;
  put_uint(ebml, kEbmlVersion, 1);
  put_uint(ebml, kEbmlReadVersion, 1);
  put_uint(ebml, kEbmlMaxIdLength, 4);
  put_uint(ebml, kEbmlMaxSizeLength, kSizeBytes);
  put_string(ebml, kDocType, "matroska");
  put_uint(ebml, kDocTypeVersion, 4);
  put_uint(ebml, kDocTypeReadVersion, 2);
  put_element(out, kEbml, ebml);

  put_id(out, kSegment);
  for (int i = 0; i < 8; ++i)  // unknown size: the stream ends when the pipe closes
    out.push_back(i == 0 ? 0x01 : 0xFF);

  Bytes info;
  put_uint(info, kTimestampScale, kNanosecondsPerTick);
  put_string(info, kMuxingApp, "vcockpit");
  put_string(info, kWritingApp, "vcockpit image_generator");
  put_element(out, kInfo, info);

  Bytes video;
  put_uint(video, kPixelWidth, static_cast<uint64_t>(width_px));
  put_uint(video, kPixelHeight, static_cast<uint64_t>(height_px));
  put_element(video, kColourSpace, Bytes{'R', 'G', 'B', 24});  // ffmpeg's raw RGB24 FourCC
  Bytes track;
  put_uint(track, kTrackNumber, 1);
  put_uint(track, kTrackUid, 1);
  put_uint(track, kTrackType, kVideoTrackType);
  put_string(track, kCodecId, "V_UNCOMPRESSED");
  put_uint(track, kFlagLacing, 0);
  put_element(track, kVideo, video);
  Bytes tracks;
  put_element(tracks, kTrackEntry, track);
  put_element(out, kTracks, tracks);
  return out;
}

std::array<uint8_t, kMatroskaFramePrefixBytes> matroska_frame_prefix(int64_t timestamp_us,
                                                                     std::size_t frame_bytes) {
  if (timestamp_us < 0) throw std::invalid_argument("matroska: negative timestamp");
  std::array<uint8_t, kMatroskaFramePrefixBytes> out{};
  std::size_t at = 0;
  auto put_byte = [&](uint32_t value) { out[at++] = static_cast<uint8_t>(value); };
  auto put_id4 = [&](uint32_t id) {
    for (int i = 3; i >= 0; --i) put_byte(id >> (8 * i));
  };
  auto put_size8 = [&](uint64_t size) {
    put_size(out.begin() + static_cast<std::ptrdiff_t>(at), size);
    at += kSizeBytes;
  };
  const uint64_t block_bytes = kBlockHeaderBytes + frame_bytes;
  const uint64_t timestamp_element_bytes = 1 + kSizeBytes + 8;
  const uint64_t block_element_bytes = 1 + kSizeBytes + block_bytes;
  put_id4(kCluster);
  put_size8(timestamp_element_bytes + block_element_bytes);
  put_byte(kClusterTimestamp);
  put_size8(8);
  for (int i = 7; i >= 0; --i) put_byte(static_cast<uint32_t>(static_cast<uint64_t>(timestamp_us) >> (8 * i)));
  put_byte(kSimpleBlock);
  put_size8(block_bytes);
  put_byte(kTrackNumberVint);
  put_byte(0);  // the block at its cluster's timestamp (int16 offset 0)
  put_byte(0);
  put_byte(kKeyframeFlag);
  return out;
}

}  // namespace vcockpit::image_generator
