#pragma once
// What the video recorder pipes to ffmpeg: a Matroska stream of raw RGB24 frames, each with its
// own timestamp. Raw video alone has no timestamps, so a video that lasts as long as the run had
// to repeat the last image for every display period the render (or the encoder) missed; on a
// busy machine the low-priority encoder fell ever further behind on those repeats, and the
// backlog at the run's end outlasted the node's bounded stop. With timestamps a missed period
// costs nothing: the previous image just stays on longer in the video.
//
// The subset written (Matroska spec, RFC 9559): an EBML header, a Segment of unknown size (a
// stream), Info with a 1 microsecond timestamp scale, one uncompressed video track whose
// ColourSpace is the RGB24 FourCC ffmpeg maps raw Matroska video by, then one Cluster per frame
// holding one keyframe SimpleBlock. Every element size is written in the 8-byte form, so a
// frame's prefix has a fixed length.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vcockpit::image_generator {

// EBML header, Segment start, Info and Tracks for a width x height RGB24 video.
std::vector<uint8_t> matroska_stream_header(int width_px, int height_px);

constexpr std::size_t kMatroskaFramePrefixBytes = 42;
// The bytes before a frame's pixels: a Cluster at timestamp_us holding one SimpleBlock of
// frame_bytes (width * height * 3).
std::array<uint8_t, kMatroskaFramePrefixBytes> matroska_frame_prefix(int64_t timestamp_us,
                                                                     std::size_t frame_bytes);

}  // namespace vcockpit::image_generator
