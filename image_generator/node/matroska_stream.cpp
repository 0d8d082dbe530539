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

// EBML writes every number big-endian
void store_big_endian(uint8_t* out, uint64_t value, std::size_t bytes) {
  for (std::size_t i = 0; i < bytes; ++i)
    out[i] = static_cast<uint8_t>(value >> (8 * (bytes - 1 - i)));
}

std::size_t id_bytes(uint32_t id) { return id > 0xFFFFFF ? 4 : id > 0xFFFF ? 3 : id > 0xFF ? 2 : 1; }

// 8-byte EBML size: a 0x01 marker byte, then 56 bits of value
void store_size(uint8_t* out, uint64_t size) {
  out[0] = 0x01;
  store_big_endian(out + 1, size, kSizeBytes - 1);
}

void put_element(Bytes& out, uint32_t id, const Bytes& payload) {
  const std::size_t at = out.size();
  out.resize(at + id_bytes(id) + kSizeBytes);
  store_big_endian(&out[at], id, id_bytes(id));
  store_size(&out[at + id_bytes(id)], payload.size());
  out.insert(out.end(), payload.begin(), payload.end());
}

void put_uint(Bytes& out, uint32_t id, uint64_t value) {
  Bytes payload(8);
  store_big_endian(payload.data(), value, payload.size());
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

  const std::size_t segment_at = out.size();
  out.resize(segment_at + 4 + kSizeBytes);
  store_big_endian(&out[segment_at], kSegment, 4);
  // unknown size (every value bit set): the stream ends when the pipe closes
  store_size(&out[segment_at + 4], (uint64_t{1} << 56) - 1);

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
  uint8_t* at = out.data();
  auto put = [&](uint64_t value, std::size_t bytes) {
    store_big_endian(at, value, bytes);
    at += bytes;
  };
  auto put_size = [&](uint64_t size) {
    store_size(at, size);
    at += kSizeBytes;
  };
  const uint64_t block_bytes = kBlockHeaderBytes + frame_bytes;
  const uint64_t timestamp_element_bytes = 1 + kSizeBytes + 8;
  const uint64_t block_element_bytes = 1 + kSizeBytes + block_bytes;
  put(kCluster, 4);
  put_size(timestamp_element_bytes + block_element_bytes);
  put(kClusterTimestamp, 1);
  put_size(8);
  put(static_cast<uint64_t>(timestamp_us), 8);
  put(kSimpleBlock, 1);
  put_size(block_bytes);
  put(kTrackNumberVint, 1);
  put(0, 2);  // the block at its cluster's timestamp (int16 offset 0)
  put(kKeyframeFlag, 1);
  return out;
}

}  // namespace vcockpit::image_generator
